#pragma once
// A scene's built-in effects grouped by type: one std::vector per type, in the order of
// the type list, each keeping the file's order. Both effect lists build their bank on it
// (1-D: engine/effects/effect_types.hpp, 2-D: engine/effects/planar/planar_effect_types.hpp),
// so the tick loops over plain arrays with no per-effect dispatch.
#include <cstddef>
#include <cstdint>
#include <span>
#include <tuple>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

namespace hapscene {

template <typename... Types>
struct EffectGroups {
  // Read them through group<T>() or std::apply; effects are added only through append(),
  // which keeps `present` in step with them.
  std::tuple<std::vector<Types>...> groups;
  // Bit i set when the group of the i-th type has effects. The tick tests one bit for an
  // empty group rather than loading its bounds (a type added to a list costs every scene
  // that lacks it two instructions a tick, not four: callgrind, spring scene).
  std::uint32_t present{};
  static_assert(sizeof...(Types) <= 32, "one bit per type of the list");

  template <typename T>
  static constexpr std::uint32_t bit_of() noexcept {
    constexpr bool same[] = {std::is_same_v<T, Types>...};
    for (std::size_t i = 0; i < sizeof...(Types); ++i) {
      if (same[i]) return std::uint32_t{1} << i;
    }
    return 0;
  }
  template <typename T>
  bool has() const noexcept { return (present & bit_of<T>()) != 0; }

  template <typename T>
  const std::vector<T>& group() const noexcept { return std::get<std::vector<T>>(groups); }
  // The effects of a group, to change in place (not to add or remove: append()).
  template <typename T>
  std::span<T> group() noexcept { return std::get<std::vector<T>>(groups); }

  template <typename T>
  void append(T effect) {
    std::get<std::vector<T>>(groups).push_back(std::move(effect));
    present |= bit_of<T>();
  }

  // Appends the effect a variant of the list holds to its group; an alternative that is
  // not one of Types (a script, which runs in the Lua layer) adds nothing.
  template <typename Variant>
  void add(Variant effect) {
    std::visit(
        [&](auto&& e) {
          using Type = std::decay_t<decltype(e)>;
          if constexpr ((std::is_same_v<Type, Types> || ...)) append(std::move(e));
        },
        std::move(effect));
  }
};

}  // namespace hapscene

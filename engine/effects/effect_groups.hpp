#pragma once
// A scene's built-in effects grouped by type: one std::vector per type, in the order of
// the type list, each keeping the file's order. Both effect lists build their bank on it
// (1-D: engine/effects/effect_types.hpp, 2-D: engine/effects/planar/planar_effect_types.hpp),
// so the tick loops over plain arrays with no per-effect dispatch.
#include <tuple>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

namespace hapscene {

template <typename... Types>
struct EffectGroups {
  std::tuple<std::vector<Types>...> groups;

  template <typename T>
  std::vector<T>& group() noexcept { return std::get<std::vector<T>>(groups); }
  template <typename T>
  const std::vector<T>& group() const noexcept { return std::get<std::vector<T>>(groups); }

  // Appends the effect a variant of the list holds to its group; an alternative that is
  // not one of Types (a script, which runs in the Lua layer) adds nothing.
  template <typename Variant>
  void add(Variant effect) {
    std::visit(
        [&](auto&& e) {
          using Type = std::decay_t<decltype(e)>;
          if constexpr ((std::is_same_v<Type, Types> || ...)) group<Type>().push_back(std::move(e));
        },
        std::move(effect));
  }
};

}  // namespace hapscene

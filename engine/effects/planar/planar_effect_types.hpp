#pragma once
// The list of 2-D built-in effect types (the 1-D list: engine/effects/effect_types.hpp),
// for scenes of two axes (SceneParts<2>). A type is a struct with its declaration
// (engine/effects/effect_keys.hpp), kNeeds, kUsesProxy, can_act_within(min, max),
// open_loop_force_N(input) and either force_N(input) (a field) or force_N(input, state)
// (a shape with a proxy, kUsesProxy). The variant, the bank, its per-run proxy states and
// the table of "type" names follow from the list.
#include <array>
#include <cstddef>
#include <span>
#include <string>
#include <string_view>
#include <tuple>
#include <type_traits>
#include <variant>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "engine/effects/effect_groups.hpp"
#include "engine/effects/effect_input.hpp"
#include "engine/effects/effect_keys.hpp"
#include "engine/effects/magnet.hpp"
#include "engine/effects/planar/planar_fields.hpp"
#include "engine/effects/planar/planar_shapes.hpp"
#include "engine/effects/planar/proxy_state.hpp"
#include "engine/effects/script_effect.hpp"

namespace hapscene {

class ObjectReader;

template <typename... Types>
struct PlanarEffectTypeList {
  // One effect of any of the types, plus 2-D scripts (which run in the Lua layer, not
  // in the bank: the tick adds them after it, as in 1-D).
  using Variant = std::variant<Types..., ScriptEffect>;

  // Each type's declaration (engine/effects/effect_keys.hpp), in the order of the list.
  static constexpr std::array<EffectDeclaration, sizeof...(Types)> kDeclarations{declaration_of<Types>()...};

  // A scene's 2-D effects grouped by type (in the order of the list; within a group in
  // the order of the file). The shapes' proxies live outside, in the run: one
  // PlanarProxyState per shape effect, in the order the groups list them
  // (proxy_count() of them, value-initialised when a run starts).
  struct Bank : EffectGroups<Types...> {
    std::size_t proxy_count() const noexcept {
      return (std::size_t{0} + ... + (Types::kUsesProxy ? this->template group<Types>().size() : std::size_t{0}));
    }

    // What a run keeps of the effects: the shapes' proxies (TickStateOf<2>::effect_runs).
    using RunState = std::vector<PlanarProxyState>;
    RunState make_run_state() const { return RunState(proxy_count()); }

    // Closed loop: the sum of every effect's force, moving the shapes' proxies (`runs`
    // holds proxy_count() states). Inlined into the tick, loops and all, as in 1-D.
    [[gnu::always_inline]] Vec2 force_N(const PlanarInput& input, RunState& runs) const noexcept {
      return force_N(input, runs.data());
    }
    [[gnu::always_inline]] Vec2 force_N(const PlanarInput& input, PlanarProxyState* proxies) const noexcept {
      Vec2 force_N{};
      (add_group_N<Types>(input, &proxies, &force_N), ...);
      return force_N;
    }

    // Open loop: the same sum without history (each shape's proxy at the nearest point of
    // its boundary when the handle is in its solid).
    Vec2 open_loop_force_N(const PlanarInput& input) const noexcept {
      Vec2 force_N{};
      (add_open_group_N<Types>(input, &force_N), ...);
      return force_N;
    }

   private:
    // A group's forces; a shape takes the next proxy (`*proxy` moves past the group's).
    template <typename T>
    [[gnu::always_inline]] void add_group_N(const PlanarInput& input, PlanarProxyState** proxy,
                                            Vec2* force_N) const noexcept {
      if (!this->template has<T>()) return;
      for (const T& e : this->template group<T>()) {
        if constexpr (T::kUsesProxy) {
          *force_N += e.force_N(input, *(*proxy)++);
        } else {
          *force_N += e.force_N(input);
        }
      }
    }
    template <typename T>
    void add_open_group_N(const PlanarInput& input, Vec2* force_N) const noexcept {
      for (const T& e : this->template group<T>()) *force_N += e.open_loop_force_N(input);
    }
  };

  // Adds one built-in effect to its group (a script effect is not in the bank).
  static void add(Bank& bank, Variant effect) { bank.add(std::move(effect)); }
};

// The 2-D built-in effects, in the order the tick adds them up.
using PlanarBuiltInEffects =
    PlanarEffectTypeList<PlanarSpring, PlanarWall, PlanarBox, PlanarCircle, PlanarPolygon, PlanarDamper, PlanarTexture,
                         MagnetOf<2>>;
using PlanarEffect = PlanarBuiltInEffects::Variant;
using PlanarEffectBank = PlanarBuiltInEffects::Bank;

// The 2-D "type" names and their parsers, in the order of the list (like the 1-D
// loader's table), "script" last. parse reads the effect's own keys (a script effect
// also takes the environment's shared load budget, see plan_script_loads); the caller
// reads "type" and "enabled" and calls finish().
struct PlanarEffectType {
  std::string_view name;
  PlanarEffect (*parse)(ObjectReader& reader, ScriptLoadBudget* budget);
};
std::span<const PlanarEffectType> planar_effect_types();

// One element of a 2-D scene's "effects" at `pointer` of `file`: its "type" (unknown
// names are refused with a suggestion), "enabled" (a boolean, default true; a disabled
// effect is not parsed further), its keys, and no others. Returns false when disabled.
// A script's "file" is relative to `base_dir`; script effects charge `budget` (null: a
// budget of their own, as when one effect is parsed alone).
// Throws InputError with the file and the JSON pointer.
bool parse_planar_effect(const nlohmann::json& value, const std::string& pointer, const std::string& file,
                         PlanarEffect* effect, const std::string& base_dir = ".",
                         ScriptLoadBudget* budget = nullptr);

}  // namespace hapscene

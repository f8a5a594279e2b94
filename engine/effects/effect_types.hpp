#pragma once
// The one list of 1-D effect types. A new built-in effect is a header in this folder (a
// struct with its declaration, engine/effects/effect_keys.hpp, can_act_within() and
// force_N(input)) and one entry in BuiltInEffects: the Effect variant, the scene's
// EffectBank, the loader's table of "type" names, its parser, the sliders, Python and the
// schema all follow from that entry.
#include <array>
#include <tuple>
#include <type_traits>
#include <variant>
#include <vector>

#include "engine/effects/damper.hpp"
#include "engine/effects/effect_groups.hpp"
#include "engine/effects/effect_input.hpp"
#include "engine/effects/effect_keys.hpp"
#include "engine/effects/magnet.hpp"
#include "engine/effects/script_effect.hpp"
#include "engine/effects/spring.hpp"
#include "engine/effects/texture.hpp"
#include "engine/effects/wall.hpp"

namespace hapscene {

// The effect types of scenes with N axes (each type's force_N takes an EffectInputOf<N>
// and returns Axes<N>).
template <int N, typename... Types>
struct EffectTypeList {
  using Input = EffectInputOf<N>;

  // One effect of any of the types, plus scripts (which run in the Lua layer, not here).
  using Variant = std::variant<Types..., ScriptEffect>;

  // Each type's declaration (engine/effects/effect_keys.hpp), in the order of the list.
  static constexpr std::array<EffectDeclaration, sizeof...(Types)> kDeclarations{declaration_of<Types>()...};

  // A scene's built-in effects grouped by type, compiled once at load: the tick loops
  // over each group as a plain array, with no per-effect dispatch, so a scene pays only
  // for the groups it has (an empty group costs a bit test, EffectGroups::present).
  // Within a group effects keep their order in the file; the groups add up in the order
  // of the list, then the scene adds its scripts.
  struct Bank : EffectGroups<Types...> {
    // What a run keeps of these effects: nothing (the 1-D lab effects are fields). A list
    // of shapes keeps their proxies here (engine/effects/planar/planar_effect_types.hpp).
    struct RunState {};
    RunState make_run_state() const { return {}; }

    // The sum of every built-in effect's force for one input, group by group in the
    // order of the list. Inlined into the tick, loops and all (as a call it cost the
    // spring scene about 12 instructions a tick).
    [[gnu::always_inline]] Axes<N> force_N(const Input& input, RunState&) const noexcept {
      return force_N(input);
    }
    // Open loop (no history): the same, as the effects keep no state.
    Axes<N> open_loop_force_N(const Input& input) const noexcept { return force_N(input); }

    [[gnu::always_inline]] Axes<N> force_N(const Input& input) const noexcept {
      Axes<N> force_N{};
      (add_group_N<Types>(input, &force_N), ...);
      return force_N;
    }

   private:
    template <typename T>
    [[gnu::always_inline]] void add_group_N(const Input& input, Axes<N>* force_N) const noexcept {
      // Scenes have a few effects of a type: a vectorised loop's set-up cost more than
      // it saved (about 10 instructions a tick for one spring), so the loop stays scalar
      // (the empty asm hides the pointer's stride from the vectoriser; it emits nothing).
      if (!this->template has<T>()) return;
      for (const T* e = this->template group<T>().data(), *end = e + this->template group<T>().size(); e != end; ++e) {
        *force_N += e->force_N(input);
        asm("" : "+r"(e));
      }
    }
  };
};

// The built-in effects of 1-DOF scenes, in the order the tick adds them up.
using BuiltInEffects = EffectTypeList<1, Spring, Wall, Damper, Texture, MagnetOf<1>>;

// One effect as written in an environment file; the forces of all effects add up.
using Effect = BuiltInEffects::Variant;
using EffectBank = BuiltInEffects::Bank;

}  // namespace hapscene

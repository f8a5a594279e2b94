#pragma once
// A Lua script as an effect: `{"type": "script", "file": "../scripts/bumps.lua",
// "params": {...}, "limits": {...}}` or `{"type": "script", "source": "function force(s)
// ... end"}`. The compiled program is immutable and shared; each run creates its own
// sandboxed instance (TickState::scripts), so its state never leaks between runs.
#include <cstddef>
#include <memory>
#include <string>

#include <nlohmann/json_fwd.hpp>

#include "engine/effects/effect_input.hpp"
#include "engine/lua/script.hpp"

namespace hapscene {

class ObjectReader;

// Bounds on all the script effects of one environment together (docs/reference/
// lua.md, "Limits"): each has its own Lua state, and every run creates them all again.
inline constexpr std::size_t kMaxScriptEffects = 64;
// Their memory_bytes add up to at most this (the most one script may have).
inline constexpr std::size_t kMaxScriptMemoryBytesTotal = std::size_t{1} << 30;
// Their loads together take at most this, or the largest load_time among them if longer.
inline constexpr double kScriptLoadBudget_s = 10.0;

// The wall-clock time the script effects of one environment share while loading (each
// load is also within its own load_time).
struct ScriptLoadBudget {
  double total_s{};
  double used_s{};
};

struct ScriptEffect {
  static constexpr const char* kType = "script";

  std::shared_ptr<const ScriptProgram> program;
  std::string file;              // the script file (empty for inline source), for reloads
  std::size_t instance_index{};  // its instance in TickState::scripts, in scene order
  Needs needs;                   // what the script declared it reads

  // Reads and compiles one script effect for a scene of `axes` axes (1 or 2: the check
  // call at load refuses a script of the other dimension); its load takes no longer than
  // what is left of the environment's `budget`, and what it took is added to it.
  static ScriptEffect parse(ObjectReader& reader, ScriptLoadBudget& budget, int axes = 1);
};

// Checks the bounds on an environment's script effects together before any is loaded,
// and returns their shared load budget. `effects` is the environment's "effects" array at
// `pointer` in `file`. Throws InputError at the script effect that passes a bound. (A bad
// "limits" block is left for that effect's own parse to report, in order.)
ScriptLoadBudget plan_script_loads(const nlohmann::json& effects, const std::string& file,
                                   const std::string& pointer);

// Keys of a "limits" block, for documentation.
ScriptLimits parse_script_limits(ObjectReader& reader);

}  // namespace hapscene

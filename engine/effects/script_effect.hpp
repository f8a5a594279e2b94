#pragma once
// A Lua script as an effect: `{"type": "script", "file": "../scripts/bumps.lua",
// "params": {...}, "limits": {...}}` or `{"type": "script", "source": "function force(s)
// ... end"}`. The compiled program is immutable and shared; each run creates its own
// sandboxed instance (TickState::scripts), so its state never leaks between runs.
#include <cstddef>
#include <memory>
#include <string>

#include "engine/effects/effect_input.hpp"
#include "engine/lua/script.hpp"

namespace hapscene {

class ObjectReader;

struct ScriptEffect {
  static constexpr const char* kType = "script";

  std::shared_ptr<const ScriptProgram> program;
  std::string file;              // the script file (empty for inline source), for reloads
  std::size_t instance_index{};  // its instance in TickState::scripts, in scene order
  Needs needs;                   // what the script declared it reads

  static ScriptEffect parse(ObjectReader& reader);
};

// Keys of a "limits" block, for documentation.
ScriptLimits parse_script_limits(ObjectReader& reader);

}  // namespace hapscene

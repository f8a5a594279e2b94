// compile_script: everything that can be wrong with a script is found here, at load
// time, with a message naming the place; a run only ever sees a checked program.
#include <string>

#include "engine/core/errors.hpp"
#include "engine/lua/script_vm.hpp"

namespace hapscene {
namespace {

// Limits come from the environment file; the loader checks them with its own JSON
// pointers, this is the last line.
void check_limits(const ScriptLimits& limits, const std::string& error_context,
                  const std::string& display_name) {
  const auto fail = [&](const std::string& what) {
    throw InputError((error_context.empty() ? display_name : error_context) +
                     ": script limits: " + what);
  };
  if (limits.instructions_per_call < 100) fail("instructions_per_call must be at least 100");
  if (limits.instructions_at_load < 100) fail("instructions_at_load must be at least 100");
  if (limits.memory_bytes < (64u << 10)) fail("memory_bytes must be at least 65536 (64 KiB)");
  if (limits.allocation_bytes_per_call < 1024) fail("allocation_bytes_per_call must be at least 1024");
  if (limits.string_bytes < 256) fail("string_bytes must be at least 256");
  if (!(limits.wall_time_per_call_s >= 0.0)) fail("wall_time_per_call_s must be 0 (off) or positive");
  if (!(limits.load_time_s > 0.0 && limits.load_time_s <= 600.0)) {
    fail("load_time_s must be positive and at most 600 s");
  }
  if (!(limits.log_messages_per_s >= 0.0)) fail("log_messages_per_s must not be negative");
}

}  // namespace

ScriptProgram compile_script(std::string display_name, std::string source,
                             const nlohmann::json& params_override, std::string error_context,
                             std::string pointer_prefix, ScriptLimits limits) {
  check_limits(limits, error_context, display_name);
  ScriptProgram program;
  program.display_name = std::move(display_name);
  program.source = std::move(source);
  program.params_override = params_override.is_null() ? nlohmann::json::object() : params_override;
  program.error_context = std::move(error_context);
  program.pointer_prefix = std::move(pointer_prefix);
  program.limits = limits;

  // One throwaway instance loads and checks the script; what it found becomes the program.
  std::unique_ptr<ScriptInstance> instance = ScriptInstance::create(program);
  const detail::ScriptVm& vm = *instance->vm_;
  program.params = vm.params;
  program.needs_velocity = vm.needs_velocity;
  program.needs_time = vm.needs_time;
  program.has_reset = !lua_isnil(vm.L, detail::kSlotReset);

  // Run it once, as a run would start, so that errors inside reset() and force() on the
  // common path (typos, wrong needs, a missing return) fail the load, not the run.
  instance->reset();
  if (instance->disabled()) {
    throw InputError(std::string(instance->fault_message()) + " (while checking reset() at load)");
  }
  ScriptInput probe;
  probe.dt_s = 0.001;
  instance->force_N(probe);
  if (instance->disabled()) {
    throw InputError(std::string(instance->fault_message()) +
                     " (while checking force(s) at x = 0 m, v = 0 m/s, t = 0 s)");
  }
  return program;
}

}  // namespace hapscene

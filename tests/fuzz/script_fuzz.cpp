// Fuzz target: a Lua source through the sandbox's load (compile_script: syntax, top-level
// code, params, needs and the first check call), then one instance as a run uses it: reset,
// force at a sweep of positions and times, garbage collection between calls, the log
// drained, a second reset and more calls. Every force must be finite; the limits (budget,
// memory) are the defaults a user gets.
#include <memory>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/base/errors.hpp"
#include "engine/lua/script.hpp"
#include "tests/fuzz/fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace hapscene;
  ScriptProgram program;
  try {
    program = compile_script("fuzz.lua", std::string(fuzz::as_text(data, size)),
                             nlohmann::json::object(), "fuzz.json", "/effects/0/params");
  } catch (const InputError&) {
    return 0;
  }
  std::unique_ptr<ScriptInstance> instance = ScriptInstance::create(program);
  std::vector<std::string> log;
  for (int round = 0; round < 2; ++round) {
    instance->reset();
    for (int i = 0; i < 8; ++i) {
      ScriptInput in;
      in.x_m = -0.04 + 0.01 * i;
      in.v_m_per_s = (i % 3 - 1) * 0.1;
      in.t_s = 0.001 * (round * 8 + i);
      in.dt_s = 0.001;
      fuzz::fuzz_require(std::isfinite(instance->force_N(in)), "script force is not finite");
      instance->collect_garbage(4);
    }
    instance->drain_log(&log);
  }
  fuzz::fuzz_require(instance->disabled() == !instance->fault_message().empty(),
                     "a disabled script has no message, or a message without a fault");
  return 0;
}

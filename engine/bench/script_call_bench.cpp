#include "engine/bench/script_call_bench.hpp"

#include <cmath>
#include <numbers>
#include <utility>

#include "engine/bench/tick_loop_of.hpp"

namespace hapscene {
namespace {

// Owns the instance and the inputs; the callable keeps pointers to them.
template <typename Input, typename Call>
class ScriptCallLoop : public TickLoopOf<Call> {
 public:
  ScriptCallLoop(ScriptList scripts, std::vector<Input> inputs, Call call)
      : TickLoopOf<Call>(std::move(call)), scripts_(std::move(scripts)), inputs_(std::move(inputs)) {}
  const ScriptList* scripts() const override { return &scripts_; }

 private:
  ScriptList scripts_;
  std::vector<Input> inputs_;
};

template <typename Input, typename Force>
std::unique_ptr<TickLoop> make_call_loop(const ScriptProgram& program, std::vector<Input> inputs, Force force) {
  ScriptList scripts;
  scripts.push_back(ScriptInstance::create(program));
  scripts.back()->reset();
  ScriptInstance* script = scripts.back().get();
  const Input* data = inputs.data();  // a vector's buffer stays put when the vector moves
  auto call = [script, data, force](std::int32_t i) {
    const auto result = force(*script, data[i]);
    asm volatile("" : : "m"(result));
  };
  return std::make_unique<ScriptCallLoop<Input, decltype(call)>>(std::move(scripts), std::move(inputs), call);
}

}  // namespace

template <int N>
std::unique_ptr<TickLoop> script_call_tick_loop(const ScriptProgram& program, std::vector<ScriptInputOf<N>> inputs) {
  return make_call_loop(program, std::move(inputs),
                        [](ScriptInstance& script, const ScriptInputOf<N>& input) { return script.force_N(input); });
}

#define HAPSCENE_SCRIPT_CALL_LOOP(N) \
  template std::unique_ptr<TickLoop> script_call_tick_loop<N>(const ScriptProgram&, std::vector<ScriptInputOf<N>>);
HAPSCENE_FOR_EACH_AXES(HAPSCENE_SCRIPT_CALL_LOOP)
#undef HAPSCENE_SCRIPT_CALL_LOOP

std::vector<ScriptInput> swinging_script_inputs(std::size_t count) {
  std::vector<ScriptInput> inputs(count);
  for (std::size_t i = 0; i < count; ++i) {
    const double t_s = 0.001 * static_cast<double>(i);
    const double phase = 2.0 * std::numbers::pi * 0.5 * t_s;
    inputs[i].x_m = 0.02 * std::sin(phase);
    inputs[i].v_m_per_s = 0.02 * 2.0 * std::numbers::pi * 0.5 * std::cos(phase);
    inputs[i].t_s = t_s;
    inputs[i].dt_s = 0.001;
  }
  return inputs;
}

std::vector<PlanarScriptInput> swinging_planar_script_inputs(std::size_t count, double x0_m, double y0_m) {
  std::vector<PlanarScriptInput> inputs(count);
  for (std::size_t i = 0; i < count; ++i) {
    const double t_s = 0.001 * static_cast<double>(i);
    const double phase = 2.0 * std::numbers::pi * 0.5 * t_s;
    const double speed = 0.02 * 2.0 * std::numbers::pi * 0.5;
    inputs[i].x_m = Vec2{{x0_m + 0.02 * std::sin(phase), y0_m + 0.02 * std::cos(phase)}};
    inputs[i].v_m_per_s = Vec2{{speed * std::cos(phase), -speed * std::sin(phase)}};
    inputs[i].t_s = t_s;
    inputs[i].dt_s = 0.001;
  }
  return inputs;
}

}  // namespace hapscene

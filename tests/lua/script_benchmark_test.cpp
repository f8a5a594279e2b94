// Cost per call of a script in the tick: the lab spring and texture as shipped Lua, next
// to the same formulas in C++. Prints the medians (docs/reference/lua.md quotes them); the check is
// loose on purpose, to catch a regression by an order of magnitude, not machine noise.
#include <algorithm>
#include <chrono>
#include <cmath>

#include "tests/lua/script_test_support.hpp"

namespace hapscene::HAPSCENE_TEST_FILE {
namespace {

using test::at;

// Median ns per call over batches of calls along a slow sweep of the workspace.
template <typename Force>
double median_ns_per_call(Force&& force) {
  constexpr int kBatches = 31;
  constexpr int kCalls = 5000;
  std::vector<double> batches;
  double sink = 0.0;
  for (int b = 0; b < kBatches; ++b) {
    const auto start = std::chrono::steady_clock::now();
    for (int i = 0; i < kCalls; ++i) {
      const double t = (b * kCalls + i) * 0.001;
      sink += force(at(0.04 * std::sin(0.5 * t), 0.02 * std::cos(0.5 * t), t));
    }
    const auto stop = std::chrono::steady_clock::now();
    batches.push_back(std::chrono::duration<double, std::nano>(stop - start).count() / kCalls);
  }
  CHECK(std::isfinite(sink));
  std::sort(batches.begin(), batches.end());
  return batches[kBatches / 2];
}

TEST_CASE("benchmark: ns per call of the Lua lab spring and texture") {
  auto spring = ScriptInstance::create(test::compile_shipped("spring.lua"));
  auto texture = ScriptInstance::create(test::compile_shipped("texture.lua"));
  const double lua_spring = median_ns_per_call([&](const ScriptInput& s) {
    const double f = spring->force_N(s);
    spring->collect_garbage();
    return f;
  });
  const double lua_texture = median_ns_per_call([&](const ScriptInput& s) {
    const double f = texture->force_N(s);
    texture->collect_garbage();
    return f;
  });
  // The same formulas compiled in, as a floor (the sin/cos of the sweep included).
  const double cpp_spring = median_ns_per_call([](const ScriptInput& s) { return -100.0 * s.x_m; });
  const double cpp_texture = median_ns_per_call([](const ScriptInput& s) {
    const double phase = s.x_m - 0.01 * std::floor(s.x_m / 0.01);
    return phase < 0.005 ? -0.5 * s.v_m_per_s : 0.0;
  });
  MESSAGE("median ns per call: Lua spring " << lua_spring << ", Lua texture " << lua_texture
                                              << ", C++ spring " << cpp_spring << ", C++ texture "
                                              << cpp_texture << " (sweep included)");
  CHECK_FALSE(spring->disabled());
  CHECK_FALSE(texture->disabled());
  CHECK(lua_spring < 5000.0);
  CHECK(lua_texture < 5000.0);
}

}  // namespace
}  // namespace hapscene::HAPSCENE_TEST_FILE

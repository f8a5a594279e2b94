// Hot reload of a 2-DOF run, the loop's side: a planar scene offered through
// RunOptions::reload_planar replaces the running one at a tick boundary and cross-fades in
// (force vector and shape proxies) without a jolt.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "engine/devices/planar/simulated_planar.hpp"
#include "engine/load/environment.hpp"
#include "engine/run/observer_list.hpp"
#include "engine/run/runner.hpp"

// This file's own names, apart from its unity batch's neighbours (tests/CMakeLists.txt).
namespace HAPSCENE_TEST_FILE {

using namespace hapscene;

namespace {

// Made by hand, without the run state its box needs: offer() makes it (before, the loop
// stepped the box with no proxy and crashed).
std::unique_ptr<LoadedSceneOf<2>> loaded(const std::string& json) {
  auto next = std::make_unique<LoadedSceneOf<2>>();
  next->scene = load_planar_environment_text(json, "t.json");
  next->scripts = make_script_instances(next->scene);
  return next;
}

// The commanded force and what the effects asked for, every tick (reserved up front).
class ForceTrace final : public TickObserverOf<2> {
 public:
  ForceTrace() {
    output_N.reserve(4000);
    effects_N.reserve(4000);
  }
  void on_tick(const TickStateOf<2>& s) noexcept override {
    output_N.push_back(s.output_N);
    effects_N.push_back(s.effects_force_N);
  }
  std::vector<Vec2> output_N, effects_N;
};

}  // namespace

TEST_CASE("planar hot swap: an offered scene cross-fades in at a tick boundary, without a jolt") {
  // A spring 10 mm left of the haplink's home; the new version pulls 10 mm right of it and
  // adds a box the handle sits inside of (its proxy starts in the new run state).
  const PlanarScene first = load_planar_environment_text(
      R"({"device": "haplink", "effects": [{"type": "spring", "stiffness": "100 N/m", "center": ["-26.33 mm", "142.34 mm"]}]})",
      "t.json");
  SceneExchangeOf<2> exchange;
  auto second = loaded(R"({"device": "haplink", "effects": [
      {"type": "spring", "stiffness": "100 N/m", "center": ["-6.33 mm", "142.34 mm"]},
      {"type": "box", "min": ["-60 mm", "100 mm"], "max": ["30 mm", "160 mm"], "stiffness": "200 N/m", "solid": "outside"}]})");
  PlanarSimulationConfig config;
  config.start_q_rad = planar_joint_angles_at(first.device, first.device.home_m);
  config.hand.motion = PlanarHandMotion::hold;
  config.hand.hold_m = first.device.home_m;
  config.hand.stiffness_N_per_m = 5000.0;
  SimulatedPlanar device(first.device, config);
  ForceTrace trace;
  RunOptions options{.duration_s = 2.0, .pacing = Pacing::simulated_time};
  set_reload_exchange<2>(&options, &exchange);
  CHECK(reload_exchange<2>(options) == &exchange);
  CHECK(reload_exchange<1>(options) == nullptr);
  // Offered after the soft start, at 0.8 s.
  std::unique_ptr<LoadedSceneOf<2>> later = std::move(second);
  class Offer final : public TickObserverOf<2> {
   public:
    Offer(SceneExchangeOf<2>* exchange, std::unique_ptr<LoadedSceneOf<2>>* later) : exchange_(exchange), later_(later) {}
    void on_tick(const TickStateOf<2>& s) noexcept override {
      if (s.tick == 800 && *later_ != nullptr) exchange_->offer(*later_);
    }

   private:
    SceneExchangeOf<2>* exchange_;
    std::unique_ptr<LoadedSceneOf<2>>* later_;
  } offer(&exchange, &later);
  ObserverListOf<2> observers;
  observers.add(&trace);
  observers.add(&offer);
  const RunSummaryOf<2> summary = run_scene(first, device, options, &observers);

  CHECK(exchange.swaps() == 1);
  CHECK(summary.ticks == 2000);
  // About -1 N in x before the swap (toward the left centre), +1 N after the fade (0.5 s).
  CHECK(trace.effects_N[790][0] == doctest::Approx(-1.0).epsilon(0.1));
  CHECK(trace.effects_N[1900][0] == doctest::Approx(1.0).epsilon(0.1));
  double largest_step_N = 0.0;
  for (std::size_t i = 1; i < trace.output_N.size(); ++i) {
    largest_step_N = std::max(largest_step_N, norm(trace.output_N[i] - trace.output_N[i - 1]));
  }
  CHECK(largest_step_N < 0.02);
  // The first scene's carrier came back to be destroyed off the loop.
  CHECK(exchange.take_retired() != nullptr);
}

}  // namespace HAPSCENE_TEST_FILE

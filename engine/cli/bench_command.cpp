// `hapscene bench [ENV...]`: per-tick compute cost of each environment next to the
// hand-written Hapkit lab baseline, and a table of what each part of a scene costs, all
// measured in one run so the ratios compare like with like.
#include <cstdio>
#include <string>

#include "engine/bench/tick_bench.hpp"
#include "engine/cli/arguments.hpp"
#include "engine/cli/bench_modes.hpp"
#include "engine/cli/commands.hpp"
#include "engine/load/environment.hpp"

namespace hapscene {
namespace {

constexpr const char* kLabEnvironments[] = {"environments/spring.json", "environments/wall.json",
                                            "environments/damper.json", "environments/texture.json"};

// Scenes that differ in one part only: the difference in cost is that part's cost.
constexpr const char* kPartScenes[][2] = {
    {"no effect (sensor, safety, command)", R"({"effects": []})"},
    {"spring", R"({"effects": [{"type": "spring", "stiffness": 100}]})"},
    {"spring + 10 disabled effects", R"({"effects": [{"type": "spring", "stiffness": 100},
      {"type": "damper", "damping": 1, "enabled": false}, {"type": "damper", "damping": 1, "enabled": false},
      {"type": "damper", "damping": 1, "enabled": false}, {"type": "damper", "damping": 1, "enabled": false},
      {"type": "damper", "damping": 1, "enabled": false}, {"type": "texture", "width": 0.005, "damping": 1, "enabled": false},
      {"type": "texture", "width": 0.005, "damping": 1, "enabled": false}, {"type": "wall", "position": 0, "stiffness": 1, "solid": "above", "enabled": false},
      {"type": "wall", "position": 0, "stiffness": 1, "solid": "above", "enabled": false}, {"type": "wall", "position": 0, "stiffness": 1, "solid": "above", "enabled": false}]})"},
    {"damper (adds the velocity estimator)", R"({"effects": [{"type": "damper", "damping": 1}]})"},
    {"texture, 10 fields over the workspace", R"({"effects": [{"type": "texture", "width": 0.005, "damping": 1}]})"},
    {"texture, 10000 fields over the workspace", R"({"effects": [{"type": "texture", "width": "5 um", "damping": 1}]})"},
    {"10 built-in effects", R"({"effects": [{"type": "spring", "stiffness": 10}, {"type": "spring", "stiffness": 10},
      {"type": "damper", "damping": 0.1}, {"type": "damper", "damping": 0.1}, {"type": "texture", "width": 0.005, "damping": 0.1},
      {"type": "texture", "width": 0.004, "damping": 0.1}, {"type": "wall", "position": 0.02, "stiffness": 100, "solid": "above"},
      {"type": "wall", "position": -0.02, "stiffness": 100, "solid": "below"}, {"type": "wall", "position": 0.03, "stiffness": 100, "solid": "above"},
      {"type": "wall", "position": -0.03, "stiffness": 100, "solid": "below"}]})"},
};

void print_row(const char* scene, const char* implementation, const TickCost& cost, double baseline_ns) {
  std::printf("%-28s %-22s %8.1f %8.1f %8.1f %9.1f", scene, implementation, cost.median_ns, cost.p99_ns,
              cost.p999_ns, cost.max_ns);
  if (baseline_ns > 0.0) std::printf("  %6.2fx", cost.median_ns / baseline_ns);
  std::printf("\n");
}

}  // namespace

int bench_command(std::vector<std::string> args) {
  Arguments arguments(std::move(args), "hapscene bench");
  if (arguments.take_flag("accuracy")) return bench_accuracy(arguments);
  const double seconds = arguments.take_quantity("seconds", Quantity::time_s).value_or(20.0);
  const auto passes_text = arguments.take_value("passes").value_or("10");
  std::vector<std::string> files = arguments.positionals();
  int passes = 0;
  try {
    passes = std::stoi(passes_text);
  } catch (const std::exception&) {
    arguments.fail("--passes: expected a whole number, got \"" + passes_text + "\"");
  }
  if (passes < 1 || passes > 1000) arguments.fail("--passes: must be in [1, 1000]");
  if (!(seconds > 0.0 && seconds <= 600.0)) arguments.fail("--seconds: must be > 0 s and at most 600 s");
  if (files.empty()) files.assign(std::begin(kLabEnvironments), std::end(kLabEnvironments));

  std::vector<Scene> scenes;
  for (const std::string& file : files) scenes.push_back(load_environment_file(file));

  TickTimer timer;
  std::printf("tick compute in ns (read counts -> motor command, no I/O); %g s of recorded sensor "
              "readings x %d passes per row; ratios against the hand-written lab code, same run\n\n",
              seconds, passes);
  std::printf("%-28s %-22s %8s %8s %8s %9s  %7s\n", "environment", "implementation", "median", "p99",
              "p99.9", "max", "ratio");
  for (const Scene& scene : scenes) {
    const std::vector<std::int32_t> counts = record_sensor_counts(scene, seconds);
    TickCost baseline;
    double baseline_ns = 0.0;
    if (bench_lab_baseline(scene, counts, passes, &timer, &baseline)) {
      baseline_ns = baseline.median_ns;
      print_row(scene.name.c_str(), "hand-written C++", baseline, baseline_ns);
    }
    print_row(scene.name.c_str(), "built-in (JSON)", bench_scene(scene, counts, passes, &timer), baseline_ns);
  }

  std::printf("\nwhat each part of a scene costs (median ns per tick; the same sensor readings)\n\n");
  const std::vector<std::int32_t> counts = record_sensor_counts(
      load_environment_text(R"({"effects": [{"type": "wall", "position": 0.01, "stiffness": 500,
        "solid": "above"}]})", "bench"), seconds);
  for (const auto& [label, json] : kPartScenes) {
    const Scene scene = load_environment_text(json, "bench");
    const TickCost cost = bench_scene(scene, counts, passes, &timer);
    std::printf("%-44s %8.1f\n", label, cost.median_ns);
  }
  return 0;
}

}  // namespace hapscene

// `hapscene bench --soak [ENV...] [--ticks N] [--no-lua]`: 100 million simulated ticks
// (default) of each lab environment, as built-in JSON effects and as its Lua twin, with
// the sweeping hand: non-finite values, drift of position and energy from one sweep
// period to the next, and memory.
#include <cstdio>
#include <optional>
#include <string>

#include "engine/bench/lua_equivalent.hpp"
#include "engine/bench/soak.hpp"
#include "engine/cli/bench_modes.hpp"
#include "engine/cli/option_definitions.hpp"
#include "engine/cli/standard_output.hpp"
#include "engine/load/environment.hpp"

namespace hapscene {

int bench_soak(Arguments& arguments) {
  const unsigned long long ticks = arguments.take(option::soak_ticks).value_or(100'000'000);
  const std::string scripts_dir = arguments.take_value("scripts").value_or("scripts");
  const bool with_lua = !arguments.take_flag("no-lua");
  std::vector<std::string> files = arguments.positionals();
  if (files.empty()) {
    files = {"environments/spring.json", "environments/wall.json", "environments/damper.json",
             "environments/texture.json"};
  }
  std::vector<Scene> scenes;
  for (const std::string& file : files) {
    scenes.push_back(load_environment_file(file));
    if (with_lua) {
      if (std::optional<Scene> lua = lua_equivalent(scenes.back(), scripts_dir)) scenes.push_back(std::move(*lua));
    }
  }

  print_out("soak: %llu ticks per environment, sweeping hand (-40 .. +40 mm at 80 mm/s, period 2 s); drift = "
            "spread of the per-period means after the first period\n\n", ticks);
  print_out("%-16s %12s %9s %8s %13s %13s %15s %12s %8s %s\n", "environment", "ticks", "nonfinite", "periods",
            "x_spread_um", "E_spread_uJ", "RSS_kB", "Lua_bytes", "wall_s", "verdict");
  bool all_ok = true;
  for (const Scene& scene : scenes) {
    const SoakResult r = run_soak(scene, ticks);
    // No script error; no NaN; drift below a tenth of a sensor count and a microjoule; memory flat.
    const bool ok = r.script_errors == 0 && r.script_faults.empty() && r.nonfinite_ticks == 0 && r.position_spread_m < 1.2e-6 && r.energy_spread_J < 1e-6 &&
                    r.rss_end_kB - r.rss_start_kB < 1024 && r.lua_bytes_end <= r.lua_bytes_start + 65536;
    all_ok = all_ok && ok;
    char rss[40], lua[40];
    std::snprintf(rss, sizeof rss, "%ld->%ld", r.rss_start_kB, r.rss_end_kB);
    std::snprintf(lua, sizeof lua, "%zu->%zu", r.lua_bytes_start, r.lua_bytes_end);
    print_out("%-16s %12llu %9llu %8llu %13.3g %13.3g %15s %12s %8.1f %s\n", scene.name.c_str(),
              static_cast<unsigned long long>(r.ticks), static_cast<unsigned long long>(r.nonfinite_ticks),
              static_cast<unsigned long long>(r.windows), r.position_spread_m * 1e6, r.energy_spread_J * 1e6, rss,
              lua, r.wall_s, ok ? "ok" : "FAIL");
    flush_out();
    // A disabled script soaked 0 N: say why, once per script.
    for (const std::string& fault : r.script_faults) std::fprintf(stderr, "%s (while soaking %s)\n", fault.c_str(), scene.name.c_str());
  }
  return all_ok ? 0 : 1;
}

}  // namespace hapscene

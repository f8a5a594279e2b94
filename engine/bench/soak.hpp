#pragma once
// Soak: a lab environment run for a very long time on the simulated Hapkit with the
// sweeping hand (period 2 s), watched for non-finite values, drift (window by window, one
// window per sweep period: mean position and mean mechanical energy, which repeat once the
// start-up has passed) and memory (process RSS, Lua heap).
#include <cstdint>
#include <string>
#include <vector>

#include "engine/scene/safety.hpp"
#include "engine/scene/scene.hpp"

namespace hapscene {

struct SoakResult {
  std::uint64_t ticks{};
  std::uint64_t nonfinite_ticks{};      // position, velocity or command not finite
  std::uint64_t windows{};              // sweep periods watched (the first is skipped)
  double position_spread_m{};           // largest - smallest window mean position
  double energy_spread_J{};             // largest - smallest window mean energy
  double first_last_position_m{};       // last window mean - first window mean
  long rss_start_kB{};                  // process resident memory at the start and the end
  long rss_end_kB{};
  std::size_t lua_bytes_start{};        // Lua heap of the scene's scripts (0 without)
  std::size_t lua_bytes_end{};
  double wall_s{};
  SafetyCounters safety;
  std::uint64_t script_errors{};
  std::vector<std::string> script_faults;  // messages of the scripts a fault disabled
};

// Runs `scene` for `ticks` ticks in simulated time.
SoakResult run_soak(const Scene& scene, std::uint64_t ticks);

// Resident memory of this process in kB (0 where unknown).
long resident_kB();

}  // namespace hapscene

#pragma once
// Shared by the fuzz targets in tests/fuzz: each target is one file defining
// LLVMFuzzerTestOneInput. Built with clang++ -fsanitize=fuzzer (HAPSCENE_FUZZ=ON) each is a
// fuzzer; built by g++ into hapscene_fuzz_replay (the symbol renamed per file) the committed
// corpora replay through them in ctest.
//
// A target fails by aborting (libFuzzer and the replay driver both report it with the
// input): a crash, a sanitizer report, or a broken invariant checked with fuzz_require.
// InputError is the expected answer to bad input and is caught by the targets.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

#include "engine/scene/scene.hpp"
#include "engine/scene/step.hpp"
#include "engine/scene/tick_state.hpp"

namespace hapscene::fuzz {

// Aborts with a message when an invariant does not hold.
inline void fuzz_require(bool holds, const char* what) {
  if (holds) return;
  std::fprintf(stderr, "fuzz invariant broken: %s\n", what);
  std::abort();
}

inline std::string_view as_text(const std::uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

// A private folder for targets that must read from files (made once, removed at a normal
// exit; a crash leaves it for inspection).
inline std::filesystem::path*& scratch_dir_slot() {
  static std::filesystem::path* dir = nullptr;
  return dir;
}

inline const std::filesystem::path& scratch_dir() {
  std::filesystem::path*& dir = scratch_dir_slot();
  if (dir == nullptr) {
    std::string pattern = (std::filesystem::temp_directory_path() / "hapscene-fuzz-XXXXXX").string();
    fuzz_require(::mkdtemp(pattern.data()) != nullptr, "cannot make a scratch folder");
    dir = new std::filesystem::path(pattern);
    std::atexit([] {
      std::error_code ignored;
      std::filesystem::remove_all(*scratch_dir_slot(), ignored);
    });
  }
  return *dir;
}

inline std::string write_scratch_file(const std::string& name, std::string_view text) {
  const std::string path = (scratch_dir() / name).string();
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(text.data(), static_cast<std::streamsize>(text.size()));
  fuzz_require(static_cast<bool>(out), "cannot write a scratch file");
  return path;
}

// Whatever a loaded scene is, the tick's command stays finite and within the device's
// limits: sweeps the handle through the sensor's range (and a few garbage readings) and
// checks every command. Bounded: 96 ticks.
inline void check_scene_commands(const Scene& scene) {
  TickState state = make_tick_state(scene);
  const std::int32_t span = scene.device.sensor.span_counts;
  const std::int32_t low = scene.device.sensor.min_counts;
  for (int tick = 0; tick < 96; ++tick) {
    std::int32_t raw = low + static_cast<std::int32_t>((static_cast<std::int64_t>(tick) * 37) % span);
    if (tick == 50) raw = INT32_MIN;  // garbage readings must not matter either
    if (tick == 51) raw = INT32_MAX;
    step(scene, raw, &state);
    collect_script_garbage(&state);
    fuzz_require(std::isfinite(state.output_N), "commanded force is not finite");
    fuzz_require(std::abs(state.output_N) <= scene.safety.max_force_N,
                 "commanded force above the safety limit");
    fuzz_require(state.command.duty >= 0.0 && state.command.duty <= scene.device_model.kinematics.duty_max,
                 "duty outside [0, duty_max]");
  }
}

}  // namespace hapscene::fuzz

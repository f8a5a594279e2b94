// Fuzz target: an environment file (JSON, with the unit strings, inline Lua scripts and
// references to shipped profiles and scripts) through the loader; a scene that loads is
// ticked through the sensor's range and must command only finite forces within its limits.
#include "engine/base/errors.hpp"
#include "engine/load/environment.hpp"
#include "tests/fuzz/fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace hapscene;
  Scene scene;
  try {
    // Relative paths resolve as for a file in environments/ (devices/, ../scripts/).
    scene = load_environment_text(fuzz::as_text(data, size), "fuzz.json",
                                  HAPSCENE_SOURCE_DIR "/environments");
  } catch (const InputError&) {
    return 0;
  }
  fuzz::check_scene_commands(scene);
  return 0;
}

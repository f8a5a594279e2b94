// Fuzz target: a device profile through the profile loader, then as the device of a small
// environment, which must command only finite forces within the profile's limits.
#include "engine/base/errors.hpp"
#include "engine/devices/profile.hpp"
#include "engine/load/environment.hpp"
#include "tests/fuzz/fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace hapscene;
  const std::string_view text = fuzz::as_text(data, size);
  try {
    parse_device_profile(text, "fuzz_profile.json");
  } catch (const InputError&) {
    return 0;
  }
  // The same text as a file referenced by an environment: the path the commands take.
  fuzz::write_scratch_file("fuzz_profile.json", text);
  Scene scene;
  try {
    scene = load_environment_text(
        R"({"device": "fuzz_profile.json", "effects": [
              {"type": "spring", "stiffness": "300 N/m"},
              {"type": "wall", "position": "10 mm", "stiffness": "800 N/m", "solid": "above"},
              {"type": "damper", "damping": "2 N*s/m"}]})",
        "fuzz_environment.json", fuzz::scratch_dir().string());
  } catch (const InputError&) {
    return 0;
  }
  fuzz::check_scene_commands(scene);
  return 0;
}

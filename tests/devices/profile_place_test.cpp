// Every check of a device profile made after parsing (at device open, when a simulated
// plant is set up, in calibrate) names the profile's file and key, as a parse error does:
// the user can tell which file to edit. A compiled-in profile is named by its name.
#include <doctest/doctest.h>

#include <string>

#include "engine/base/errors.hpp"
#include "engine/devices/haply/haply_protocol.hpp"
#include "engine/devices/open_device.hpp"
#include "engine/devices/planar/board_pair.hpp"
#include "engine/devices/planar/simulated_planar.hpp"
#include "engine/devices/profile.hpp"
#include "engine/devices/simulated_hapkit.hpp"
#include "tests/scratch_folder.hpp"
#include "tests/support.hpp"

using namespace hapscene;
using test::ScratchFolder;

namespace {

// The message of the InputError `f` throws ("" when it throws none).
template <typename F>
std::string error_of(F f) {
  try {
    f();
  } catch (const InputError& error) {
    return error.what();
  }
  return "";
}

}  // namespace

TEST_CASE("profile place: a profile is named by its file, or as a built-in profile") {
  const ScratchFolder folder("profile_place_source");
  const std::string file = folder.write("mine.json", R"({"extends": "hapkit3", "name": "mine"})").string();
  CHECK(load_device_profile(file, ".").source == file + " (extends hapkit3)");
  CHECK(load_device_profile("hapkit3", ".").source == "hapkit3 (built-in profile)");
  CHECK(load_planar_profile("haply2diy_v3", ".").source == "haply2diy_v3 (built-in profile)");
}

TEST_CASE("profile place: a start position outside the home period of a profile file names the file") {
  const ScratchFolder folder("profile_place_home");
  // The sensor's angle offset moved by 15 deg: its home period is 11 to 18 mm, not around 0.
  const std::string file =
      folder.write("shifted.json", R"({"extends": "hapkit3", "name": "shifted", "sensor": {"counts_to_deg_offset": 20}})")
          .string();
  const DeviceProfile profile = load_device_profile(file, ".");
  const std::string message = error_of([&] { SimulatedHapkit device(profile, SimulationConfig{}); });
  CAPTURE(message);
  CHECK(message.starts_with("start position 0 m is outside the sensor's home period ["));
  CHECK(message.ends_with("where the board starts counting (the period from " + file + " (extends hapkit3): /sensor)"));
  // The same through open_device, as `run --device sim` opens it.
  CHECK(error_of([&] { (void)open_device("sim", profile, SimulationConfig{}, LinkOptions{}); }).find(file) !=
        std::string::npos);
}

TEST_CASE("profile place: a profile file the hapscene firmware cannot drive is named with its key") {
  const ScratchFolder folder("profile_place_firmware");
  // 1-DOF: an encoder (the MR sensor's period keys removed).
  const std::string encoder = folder
                                  .write("encoder.json", R"({"extends": "hapkit3", "name": "enc", "sensor": {"type": "encoder",
      "min_counts": null, "span_counts": null, "flip_threshold_counts": null}})")
                                  .string();
  const std::string one = error_of(
      [&] { (void)open_device("serial:/dev/null", load_device_profile(encoder, "."), SimulationConfig{}, LinkOptions{}); });
  CAPTURE(one);
  CHECK(one.find("profile \"enc\" has an encoder") != std::string::npos);
  CHECK(one.ends_with("(in " + encoder + " (extends hapkit3): /sensor/type)"));
  // 2-DOF: encoder joints on two Hapkit boards, and on a Haply board.
  const std::string haplink = folder.write("my_haplink.json", R"({"extends": "haplink", "name": "my haplink"})").string();
  const PlanarProfile planar = load_planar_profile(haplink, ".");
  const std::string pair = error_of([&] { require_hapkit_joints(planar, "--device serial"); });
  CAPTURE(pair);
  CHECK(pair.find("profile \"my haplink\" joint 1 reads an encoder") != std::string::npos);
  CHECK(pair.ends_with("; in " + haplink + " (extends haplink): /joints/0/sensor/type)"));
  const std::string haply = error_of([&] { (void)haply_setup_for(planar); });
  CAPTURE(haply);
  CHECK(haply.find("profile \"my haplink\", joint 1 is not a Haply-style joint") != std::string::npos);
  CHECK(haply.ends_with("; in " + haplink + " (extends haplink): /joints/0)"));
}

TEST_CASE("profile place: a handle position the linkage of a profile file cannot reach names the file") {
  const ScratchFolder folder("profile_place_reach");
  const std::string file = folder.write("short.json", R"({"extends": "haply2diy_v3", "name": "short"})").string();
  const PlanarProfile profile = load_planar_profile(file, ".");
  const std::string message = error_of([&] { (void)planar_joint_angles_at(profile, Vec2{{1.0, 1.0}}); });
  CAPTURE(message);
  CHECK(message.find(file + " (extends haply2diy_v3): /kinematics and /plant/end_stops") != std::string::npos);
}

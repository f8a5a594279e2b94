// A profile may extend another ("extends": a shipped name or a path relative to the
// file) and override a few keys: objects merge key by key, anything else is replaced.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "engine/base/errors.hpp"
#include "engine/devices/profile.hpp"
#include "engine/load/environment.hpp"
#include "tests/scratch_folder.hpp"

using namespace hapscene;
namespace fs = std::filesystem;

namespace {

void write(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream(path) << text;
}

std::string error_of(const std::string& name, const std::string& dir) {
  try {
    load_device_profile(name, dir);
  } catch (const InputError& error) {
    return error.what();
  }
  return "";
}

}  // namespace

TEST_CASE("profiles: extends a shipped profile by name and overrides a few keys") {
  const fs::path dir = fs::temp_directory_path() / ("hapscene_extends_" + std::to_string(::getpid()));
  write(dir / "kit.json", R"({"extends": "hapkit3", "name": "my kit",
    "drive": {"direction_sign": -1}, "limits": {"workspace": ["-40 mm", "40 mm"]}})");
  const DeviceProfile shipped = load_device_profile("hapkit3", ".");
  const DeviceProfile kit = load_device_profile("kit.json", dir.string());
  CHECK(kit.name == "my kit");
  CHECK(kit.drive.direction_sign == -1);
  CHECK(kit.limits.workspace_min_m == doctest::Approx(-0.040));
  CHECK(kit.limits.workspace_max_m == doctest::Approx(0.040));
  // Everything else is the parent's, sibling keys of an overridden one included.
  CHECK(kit.drive.handle_radius_m == shipped.drive.handle_radius_m);
  CHECK(kit.limits.max_force_N == shipped.limits.max_force_N);
  CHECK(kit.sensor.counts_to_deg_offset == shipped.sensor.counts_to_deg_offset);
  CHECK(kit.plant.mass_kg == shipped.plant.mass_kg);

  // A chain through a relative path; the environment refers to the last one.
  write(dir / "sub/lab.json", R"({"extends": "../kit.json", "name": "lab kit", "limits": {"max_force": "3 N"}})");
  write(dir / "env.json", R"({"device": "sub/lab.json", "effects": [{"type": "spring", "stiffness": 100}]})");
  const Environment environment = load_environment(( dir / "env.json").string());
  CHECK(environment.scene.device.name == "lab kit");
  CHECK(environment.scene.device.drive.direction_sign == -1);
  CHECK(environment.scene.device.limits.max_force_N == 3.0);
  CHECK(environment.scene.safety.max_force_N == 3.0);

  // A planar parent makes a planar profile: environment_axes follows the chain.
  write(dir / "pantograph.json", R"({"extends": "hapkit_pantograph", "name": "my pantograph"})");
  write(dir / "planar_env.json", R"({"device": "pantograph.json", "effects": []})");
  CHECK(environment_axes((dir / "planar_env.json").string()) == 2);
  fs::remove_all(dir);
}

TEST_CASE("profiles: a bad extends is an error naming the file") {
  const fs::path dir = fs::temp_directory_path() / ("hapscene_extends_bad_" + std::to_string(::getpid()));
  write(dir / "number.json", R"({"extends": 3, "name": "x"})");
  CHECK(error_of("number.json", dir.string()) ==
        (dir / "number.json").string() + ": /extends: expected the name or path of the profile to extend, got number");
  write(dir / "typo.json", R"({"extends": "hapkit33", "name": "x"})");
  CHECK(error_of("typo.json", dir.string()) ==
        (dir / "typo.json").string() + ": /extends: unknown device profile \"hapkit33\" (did you mean \"hapkit3\"?)");
  write(dir / "a.json", R"({"extends": "b.json", "name": "a"})");
  write(dir / "b.json", R"({"extends": "a.json", "name": "b"})");
  CHECK(error_of("a.json", dir.string()).find("/extends: more than 8 profiles extend each other (a loop?)") !=
        std::string::npos);
  // A merged value out of range names the file that extends, and what it extends.
  write(dir / "heavy.json", R"({"extends": "hapkit3", "name": "x", "plant": {"mass": "1000 kg"}})");
  CHECK(error_of("heavy.json", dir.string()).starts_with((dir / "heavy.json").string() + " (extends hapkit3): /plant/mass: "));
  fs::remove_all(dir);
}

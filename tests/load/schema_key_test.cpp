// A file's root may carry "$schema" (the URI of its JSON Schema in schemas/, so editors
// offer completion and checks): environments 1-D and 2-D, device profiles 1-D and planar,
// and test specs 1-D and 2-D accept it as a string and ignore it. Anything else about it
// is refused: a value that is not a string, and the key anywhere below the root.
#include <doctest/doctest.h>

#include <string>

#include "engine/devices/builtin_profiles.hpp"
#include "engine/devices/planar/planar_profile.hpp"
#include "engine/devices/profile.hpp"
#include "engine/harness/test_spec.hpp"
#include "engine/load/environment.hpp"
#include "tests/scratch_folder.hpp"
#include "tests/support.hpp"

using namespace hapscene;
using hapscene::test::input_error_of;
using hapscene::test::load_error;
using hapscene::test::scene_from;

namespace {

constexpr const char* kSchemaKey = R"("$schema": "https://example.org/hapscene/schemas/environment.schema.json", )";

// A shipped profile's text without its own "$schema" line (the shipped files carry one).
std::string builtin_text(std::string_view name) {
  for (const BuiltinProfile& profile : builtin_profiles()) {
    if (profile.name != name) continue;
    std::string text(profile.json_text);
    const auto key = text.find("\"$schema\"");
    if (key != std::string::npos) text.erase(key, text.find('\n', key) + 1 - key);
    return text;
  }
  FAIL("no built-in profile " << name);
  return {};
}

// `json` with "$schema": VALUE as its first key.
std::string with_schema(const std::string& json, const std::string& value) {
  const auto brace = json.find('{');
  return json.substr(0, brace + 1) + "\"$schema\": " + value + ", " + json.substr(brace + 1);
}

const std::string kPlanarEnvironment =
    R"({"device": "haplink", "effects": [{"type": "spring", "stiffness": "100 N/m", "center": ["0 mm", "120 mm"]}]})";

}  // namespace

TEST_CASE("$schema: a 1-D environment accepts it as a string and renders as without it") {
  const std::string plain = R"({"effects": [{"type": "spring", "stiffness": 100}]})";
  const Scene with = scene_from(std::string("{") + kSchemaKey + plain.substr(1));
  const Scene without = scene_from(plain);
  CHECK(with.effects.size() == without.effects.size());
  CHECK(with.name == without.name);
}

TEST_CASE("$schema: a 2-D environment accepts it") {
  const PlanarScene scene =
      load_planar_environment_text(with_schema(kPlanarEnvironment, R"("environment.schema.json")"), "test.json",
                                   HAPSCENE_SOURCE_DIR "/environments");
  CHECK(scene.effects.size() == 1);
}

TEST_CASE("$schema: refused when not a string, in 1-D and 2-D environments") {
  CHECK(load_error(R"({"$schema": 3, "effects": []})") ==
        "test.json: /$schema: expected a string (the URI of this file's JSON Schema), got number");
  CHECK(input_error_of([] {
          load_planar_environment_text(with_schema(kPlanarEnvironment, "{}"), "test.json",
                                       HAPSCENE_SOURCE_DIR "/environments");
        }) == "test.json: /$schema: expected a string (the URI of this file's JSON Schema), got object");
}

TEST_CASE("$schema: only at a file's root, below it, it is an unknown key as before") {
  CHECK(load_error(R"({"effects": [{"$schema": "x", "type": "spring", "stiffness": 100}]})") ==
        "test.json: /effects/0/$schema: unknown key \"$schema\"");
  CHECK(load_error(R"({"safety": {"$schema": "x"}, "effects": []})") ==
        "test.json: /safety/$schema: unknown key \"$schema\"");
  // A near miss at the root is still an unknown key.
  CHECK(load_error(R"({"schema": "x", "effects": []})").starts_with("test.json: /schema: unknown key \"schema\""));
}

TEST_CASE("$schema: device profiles, capstan and planar, accept it") {
  // The shipped ones carry it, and are compiled in with it.
  for (const BuiltinProfile& builtin : builtin_profiles()) {
    CHECK(std::string_view(builtin.json_text).find("\"$schema\": \"../../schemas/device-profile.schema.json\"") !=
          std::string_view::npos);
  }
  const std::string hapkit3 = with_schema(builtin_text("hapkit3"), R"("device-profile.schema.json")");
  CHECK(parse_device_profile(hapkit3, "hapkit3.json").name == "hapkit3");
  const std::string haplink = with_schema(builtin_text("haplink"), R"("device-profile.schema.json")");
  CHECK(parse_planar_profile(haplink, "haplink.json").name == "haplink");
  CHECK(input_error_of([] { parse_device_profile(with_schema(builtin_text("hapkit3"), "null"), "p.json"); }) ==
        "p.json: /$schema: expected a string (the URI of this file's JSON Schema), got null");
}

TEST_CASE("$schema: test specs, 1-D and 2-D, accept it") {
  const test::ScratchFolder folder("schema_key");
  folder.write("wall.json", with_schema(R"({"effects": [{"type": "wall", "position": "10 mm", "stiffness": "500 N/m", "solid": "above"}]})",
                                        R"("environment.schema.json")"));
  const auto wall_spec = folder.write(
      "wall.test.json", with_schema(R"({"forces": [{"x": "20 mm", "force": "-5 N", "tolerance": "1e-9 N"}]})",
                                    R"("test-spec.schema.json")"));
  const SpecResult wall = run_test_spec(wall_spec.string());
  CHECK(wall.pass);
  CHECK(wall.outcomes.size() >= 1);

  folder.write("field.json", with_schema(kPlanarEnvironment, R"("environment.schema.json")"));
  const auto field_spec = folder.write(
      "field.test.json",
      with_schema(R"({"forces": [{"at": ["10 mm", "120 mm"], "force": ["-1 N", "0 N"], "tolerance": "1e-9 N"}]})",
                  R"("test-spec.schema.json")"));
  const SpecResult field = run_test_spec(field_spec.string());
  CHECK(field.pass);

  const auto bad_spec = folder.write("bad.test.json", R"({"$schema": true, "environment": "wall.json"})");
  CHECK(input_error_of([&] { run_test_spec(bad_spec.string()); }) ==
        bad_spec.string() + ": /$schema: expected a string (the URI of this file's JSON Schema), got boolean");
}

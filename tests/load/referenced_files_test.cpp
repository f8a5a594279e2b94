// Errors caused by a file that another file refers to name both: the referring file and
// its JSON pointer first, then the referenced file's own place.
//   env.json: /device: profile.json:3:7: ...
//   env.json: /effects/0/file: bumps.lua:2: ...
#include <doctest/doctest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "engine/load/environment.hpp"
#include "tests/support.hpp"

using namespace hapscene;

namespace {

// A fresh directory with the given files in it.
std::filesystem::path make_dir(const std::string& name,
                               std::initializer_list<std::pair<std::string, std::string>> files) {
  const auto dir = std::filesystem::temp_directory_path() / ("hapscene_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  for (const auto& [file, text] : files) std::ofstream(dir / file) << text;
  return dir;
}

}  // namespace

TEST_CASE("referenced files: a profile's error names the environment, /device and the profile") {
  const auto dir = make_dir("ref_profile", {
      {"env.json", R"({"device": "profile.json", "effects": []})"},
      {"profile.json", "{\n  \"name\": \"x\",\n  \"sensor\" {}\n}"},
      {"values.json", R"({"device": "bad_value.json", "effects": []})"},
  });
  const std::string env = (dir / "env.json").string();
  const std::string profile = (dir / "profile.json").string();
  CHECK(test::input_error_of([&] { load_environment_file(env); }) ==
        env + ": /device: " + profile + ":3:12: syntax error while parsing object separator - unexpected '{'; "
              "expected ':'");

  // A value inside the profile: its own pointer after the profile's name.
  std::string hapkit3;
  {
    std::ifstream in(test::source_path("environments/devices/hapkit3.json"));
    hapkit3.assign(std::istreambuf_iterator<char>(in), {});
  }
  const std::size_t at = hapkit3.find("\"span_counts\"");
  REQUIRE(at != std::string::npos);
  const std::size_t colon = hapkit3.find(':', at);
  const std::size_t end = hapkit3.find_first_of(",}\n", colon);
  hapkit3.replace(colon + 1, end - colon - 1, " 99999999999999999999");
  std::ofstream(dir / "bad_value.json") << hapkit3;
  const std::string message = test::input_error_of([&] { load_environment_file((dir / "values.json").string()); });
  CHECK(message.starts_with((dir / "values.json").string() + ": /device: " + (dir / "bad_value.json").string() + ":"));
  CHECK(message.ends_with(": number out of range: 99999999999999999999 (whole numbers are limited to 64 bits)"));
  std::filesystem::remove_all(dir);
}

TEST_CASE("referenced files: a script file's error names the environment, /effects/N/file and the script") {
  const auto dir = make_dir("ref_script", {
      {"env.json", R"({"effects": [{"type": "spring", "stiffness": 10}, {"type": "script", "file": "bad.lua"}]})"},
      {"bad.lua", "function force(s)\n  return s.x +\nend\n"},
      {"params.json", R"({"effects": [{"type": "script", "file": "ok.lua", "params": {"k": "5 mm"}}]})"},
      {"ok.lua", "params = {k = 1}\nfunction force(s) return -params.k * s.x end\n"},
  });
  const std::string env = (dir / "env.json").string();
  const std::string message = test::input_error_of([&] { load_environment_file(env); });
  CHECK(message.starts_with(env + ": /effects/1/file: " + (dir / "bad.lua").string() + ":3: "));
  // An error in the environment's own overrides keeps its single place.
  const std::string params = test::input_error_of([&] { load_environment_file((dir / "params.json").string()); });
  CHECK(params.starts_with((dir / "params.json").string() + ": /effects/0/params/k: "));
  std::filesystem::remove_all(dir);
}

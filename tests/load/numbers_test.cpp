// Numbers at the edges of what the file formats can hold: out of range is said so, and a
// number is echoed as written (never wrapped to -1, never rounded into another number).
#include <doctest/doctest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "engine/base/json_source.hpp"
#include "engine/base/units.hpp"
#include "engine/devices/profile.hpp"
#include "engine/harness/test_spec.hpp"
#include "tests/support.hpp"

using namespace hapscene;
using hapscene::test::load_error;

TEST_CASE("numbers: unit strings past a double's range are out of range, not malformed") {
  CHECK(parse_quantity("1e400 N/m").error == "value out of range, got \"1e400 N/m\"");
  CHECK(parse_quantity("-1e400").error == "value out of range, got \"-1e400\"");
  CHECK(parse_quantity("1e-400 m").error == "value out of range, got \"1e-400 m\"");
  CHECK(load_error(R"({"effects": [{"type": "spring", "stiffness": "1e400 N/m"}]})") ==
        "test.json: /effects/0/stiffness: value out of range, got \"1e400 N/m\"");
}

TEST_CASE("numbers: bare JSON numbers past a double or 64 bits are located and echoed as written") {
  CHECK(load_error(R"({"effects": [{"type": "spring", "stiffness": -1e400}]})") ==
        "test.json:1:46: number out of range: -1e400");
  CHECK(load_error(R"({"effects": [{"type": "spring", "stiffness": 99999999999999999999999}]})") ==
        "test.json:1:46: number out of range: 99999999999999999999999 (whole numbers are limited to 64 bits)");
  CHECK(load_error(R"({"effects": [{"type": "spring", "stiffness": -9223372036854775809}]})") ==
        "test.json:1:46: number out of range: -9223372036854775809 (whole numbers are limited to 64 bits)");
  // Numbers inside strings are text; a tiny number is 0 as before.
  CHECK(load_error(R"({"name": "99999999999999999999999", "effects": [{"type": "spring", "stiffness": 1e-400}]})") ==
        "(no error)");
}

TEST_CASE("numbers: whole-number keys echo what was written, accept 1e6 and refuse 1.5") {
  const auto limits = [](const std::string& value) {
    return load_error(R"({"effects": [{"type": "script", "source": "function force(s) return 0 end",
      "limits": {"instructions_per_call": )" + value + "}}]}");
  };
  CHECK(limits("18446744073709551615") ==
        "test.json: /effects/0/limits/instructions_per_call: must be in [100, 100000000], got 18446744073709551615");
  CHECK(limits("9223372036854775808") ==
        "test.json: /effects/0/limits/instructions_per_call: must be in [100, 100000000], got 9223372036854775808");
  CHECK(limits("-5") == "test.json: /effects/0/limits/instructions_per_call: must be in [100, 100000000], got -5");
  CHECK(limits("1e6") == "(no error)");
  CHECK(limits("1.5") == "test.json: /effects/0/limits/instructions_per_call: expected a whole number, got 1.5");
  CHECK(limits("1e12") == "test.json: /effects/0/limits/instructions_per_call: must be in [100, 100000000], got 1e+12");
  CHECK(limits("\"many\"") == "test.json: /effects/0/limits/instructions_per_call: expected a whole number, got string");

  // The same reader serves profiles and validate blocks.
  CHECK(load_error(R"({"validate": {"max_slip_ticks": 18446744073709551615}, "effects": []})") ==
        "test.json: /validate/max_slip_ticks: must be in [0, 1000000000], got 18446744073709551615");
}

TEST_CASE("numbers: test specs read numbers the same way") {
  const auto dir = std::filesystem::temp_directory_path() / ("hapscene_numbers_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "wall.json") << R"({"effects": [{"type": "wall", "position": 0.01, "stiffness": 500, "solid": "above"}]})";
  std::ofstream(dir / "seed.test.json") << R"({"environment": "wall.json", "options": {"seed": 18446744073709551615}})";
  std::ofstream(dir / "force.test.json") << "{\"environment\": \"wall.json\",\n \"never_exceeds\": 1e400}";
  CHECK(test::input_error_of([&] { run_test_spec((dir / "seed.test.json").string()); }) ==
        (dir / "seed.test.json").string() + ": /options/seed: must be in [0, 9007199254740992], got 18446744073709551615");
  CHECK(test::input_error_of([&] { run_test_spec((dir / "force.test.json").string()); }) ==
        (dir / "force.test.json").string() + ":2:19: number out of range: 1e400");
  std::filesystem::remove_all(dir);
}

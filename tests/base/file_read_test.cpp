// Every file hapscene reads goes through read_text_file: a named pipe, a directory, a
// device or a file over the size cap is refused with a message naming the file, before
// anything is read, and nothing blocks (a FIFO with no writer would block a plain open).
#include <doctest/doctest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>

#include "engine/base/json_source.hpp"
#include "engine/devices/profile.hpp"
#include "engine/run/reload_watcher.hpp"
#include "tests/run/reload_support.hpp"
#include "tests/scratch_folder.hpp"
#include "tests/support.hpp"

using namespace hapscene;

namespace {

}  // namespace

TEST_CASE("file reading: named pipes, directories, devices and huge files are refused at once") {
  test::ScratchFolder scratch("files");
  const auto started = std::chrono::steady_clock::now();
  const std::string pipe = scratch.fifo("env.json");
  CHECK(test::input_error_of([&] { read_text_file(pipe, 1000); }) ==
        pipe + ": cannot read a named pipe, expected a regular file");
  CHECK(test::input_error_of([&] { read_text_file(scratch.dir.string(), 1000); }) ==
        scratch.dir.string() + ": cannot read a directory, expected a regular file");
  CHECK(test::input_error_of([&] { read_text_file("/dev/zero", 1000); }) ==
        "/dev/zero: cannot read a character device, expected a regular file");
  // A sparse 4 GiB file: refused by its size, not read.
  const auto huge = scratch.dir / "huge.json";
  std::ofstream(huge).put('{');
  std::filesystem::resize_file(huge, 4ull << 30);
  CHECK(test::input_error_of([&] { read_text_file(huge.string(), 1u << 20); }) ==
        huge.string() + ": file larger than 1048576 bytes");
  CHECK(std::chrono::steady_clock::now() - started < std::chrono::seconds(2));
}

TEST_CASE("file reading: every kind of file hapscene loads refuses a named pipe") {
  test::ScratchFolder scratch("files");
  // An environment, a .lua environment, a script file, a device profile, a test spec.
  const std::string env = scratch.fifo("env.json");
  CHECK(test::input_error_of([&] { load_environment_file(env); }).ends_with("env.json: cannot read a named pipe, expected a regular file"));
  const std::string lua = scratch.fifo("field.lua");
  CHECK(test::input_error_of([&] { load_environment_file(lua); }).ends_with("field.lua: cannot read a named pipe, expected a regular file"));
  scratch.fifo("push.lua");
  const auto with_script = scratch.dir / "script.json";
  std::ofstream(with_script) << R"({"effects": [{"type": "script", "file": "push.lua"}]})";
  CHECK(test::input_error_of([&] { load_environment_file(with_script.string()); })
            .ends_with("push.lua: cannot read a named pipe, expected a regular file"));
  scratch.fifo("device.json");
  CHECK(test::input_error_of([&] { load_device_profile("device.json", scratch.dir.string()); })
            .ends_with("device.json: cannot read a named pipe, expected a regular file"));
  const std::string spec = scratch.fifo("x.test.json");
  CHECK(test::input_error_of([&] { read_json_file(spec); }).ends_with("x.test.json: cannot read a named pipe, expected a regular file"));
}

TEST_CASE("reload watcher: an environment file replaced by a named pipe is reported, not waited on" * doctest::test_suite("threaded")) {
  test::ScratchFolder scratch("files");
  const auto env = scratch.dir / "env.json";
  std::ofstream(env) << R"({"effects": []})";
  const Scene running = load_environment_file(env.string());
  SceneExchange exchange;
  std::vector<std::string> reports;
  ReloadWatcher watcher(env.string(), running, &exchange,
                        [&](const std::string& message) { reports.push_back(message); },
                        test::manual_polling());
  std::filesystem::remove(env);
  scratch.fifo("env.json");
  const auto started = std::chrono::steady_clock::now();
  watcher.poll();
  CHECK(std::chrono::steady_clock::now() - started < std::chrono::seconds(2));
  CHECK(exchange.take_offer() == nullptr);
  REQUIRE(reports.size() == 1);
  CHECK(reports[0] == "reload failed, keeping the running version: " + env.string() +
                          ": cannot read a named pipe, expected a regular file");
}

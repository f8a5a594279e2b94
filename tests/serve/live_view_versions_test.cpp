// The live view follows the version the loop runs: after the environment file or a script
// it names is edited during a run, every endpoint (the scene, validate, the parameters)
// describes the new version; and a script run as an environment of its own (a .lua file)
// gets the same view, with save refused since it has no environment file.
#include <doctest/doctest.h>

#include <chrono>
#include <string>
#include <thread>

#include "tests/cli/cli_support.hpp"
#include "tests/scratch_folder.hpp"
#include "tests/serve/live_view_support.hpp"

namespace hapscene {
namespace {

using nlohmann::json;

std::string spring_at(const char* stiffness) {
  return std::string(R"({"name": "edited spring", "effects": [{"type": "spring", "stiffness": ")") + stiffness +
         R"(", "center": "0 mm"}]})" + "\n";
}

// A scripted spring whose stiffness is a parameter with a default.
std::string scripted_spring(const char* stiffness) {
  return std::string("params = {stiffness = \"") + stiffness +
         "\"}\n"
         "needs = {velocity = false, time = false}\n"
         "local K = params.stiffness\n"
         "function force(s) return -K * s.x end\n";
}

json get_scene(const test::LiveRun<1>& run) {
  httplib::Client client = run.client();
  const auto answer = client.Get(run.with_token("/api/scene"));
  REQUIRE(answer);
  REQUIRE(answer->status == 200);
  return json::parse(answer->body);
}

json post_validate(const test::LiveRun<1>& run) {
  httplib::Client client = run.client();
  client.set_read_timeout(120, 0);
  const auto answer = client.Post(run.with_token("/api/validate"), "", "application/json");
  REQUIRE(answer);
  REQUIRE(answer->status == 200);
  return json::parse(answer->body);
}

// Waits (up to 10 s) until the watcher has taken `count` versions from the files.
bool wait_for_file_versions(const test::LiveRun<1>& run, std::uint64_t count) {
  for (int i = 0; i < 200 && run.watcher->file_versions() < count; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return run.watcher->file_versions() >= count;
}

}  // namespace

TEST_SUITE("threaded") {

TEST_CASE("live view: after the file is edited during a run, the scene, validate and save follow the new version") {
  test::ScratchFolder folder("live_versions_file");
  const std::string file = folder.write("spring.json", spring_at("100 N/m")).string();
  test::LiveRun<1> run(file, 60.0);
  CHECK(post_validate(run)["pass"] == true);
  // 3000 N/m: past the passivity bound 2b/T = 800 N/m at 1 kHz, so validate fails it.
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  folder.write("spring.json", spring_at("3000 N/m"));
  REQUIRE(wait_for_file_versions(run, 1));
  CHECK(post_validate(run)["pass"] == false);
  const json scene = get_scene(run);
  CHECK(scene["parameters"][0]["value"] == 3000.0);
  CHECK(scene["unsaved"] == false);
  // A change and a save start from the new version, not the one the view was opened on.
  int status = 0;
  (void)run.post_params({{"effect", 0}, {"parameter", "center"}, {"value", 0.005}}, &status);
  REQUIRE(status == 200);
  httplib::Client client = run.client();
  const auto saved = client.Post(run.with_token("/api/save"), "", "application/json");
  REQUIRE(saved);
  CHECK(saved->status == 200);
  CHECK(test::slurp_file(file).find("\"stiffness\": \"3000 N/m\"") != std::string::npos);
  CHECK(test::slurp_file(file).find("\"center\": \"5 mm\"") != std::string::npos);
}

TEST_CASE("live view: a script's edited default reaches the page's parameters") {
  test::ScratchFolder folder("live_versions_script");
  folder.write("spring.lua", scripted_spring("100 N/m"));
  const std::string file =
      folder.write("scripted.json", R"({"name": "scripted", "effects": [{"type": "script", "file": "spring.lua"}]})")
          .string();
  test::LiveRun<1> run(file, 60.0);
  CHECK(get_scene(run)["parameters"][0]["value"] == 100.0);
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  folder.write("spring.lua", scripted_spring("250 N/m"));
  REQUIRE(wait_for_file_versions(run, 1));
  const json scene = get_scene(run);
  CHECK(scene["parameters"][0]["parameter"] == "params/stiffness");
  CHECK(scene["parameters"][0]["value"] == 250.0);
}

TEST_CASE("live view: a .lua file runs with the view like any environment, and save says why it cannot write it") {
  test::ScratchFolder folder("live_versions_lua");
  const std::string script = folder.write("bump.lua", scripted_spring("100 N/m")).string();
  test::LiveRun<1> run(script, 60.0);
  const json scene = get_scene(run);
  CHECK(scene["name"] == "bump");
  CHECK(scene["effects"][0]["type"] == "script");
  CHECK(scene["effects"][0]["file"] == "bump.lua");
  CHECK(scene["parameters"][0]["value"] == 100.0);
  CHECK(post_validate(run)["pass"] == true);
  int status = 0;
  const json changed = run.post_params({{"effect", 0}, {"parameter", "params/stiffness"}, {"value", 300}}, &status);
  CHECK(status == 200);
  CHECK(changed["parameters"][0]["value"] == 300.0);
  CHECK(changed["unsaved"] == true);
  httplib::Client client = run.client();
  const auto saved = client.Post(run.with_token("/api/save"), "", "application/json");
  REQUIRE(saved);
  CHECK(saved->status == 409);
  CHECK(json::parse(saved->body)["error"].get<std::string>().starts_with(script + ": a script run as an environment"));
  CHECK(test::slurp_file(script) == scripted_spring("100 N/m"));
  // Validate judges the changed values: 300 N/m across the sweep asks more than 6 N.
  CHECK(post_validate(run)["pass"] == false);
}

TEST_CASE("live view: a POST with no body at all is an empty body (curl -X POST)") {
  test::ScratchFolder folder("live_versions_nobody");
  test::LiveRun<1> run(folder.write("spring.json", spring_at("100 N/m")).string(), 60.0);
  const std::string head = " HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n";
  test::RawConnection validate(run.view->port());
  REQUIRE(validate.send("POST " + run.with_token("/api/validate") + head));
  const std::string verdict = validate.read_to_close(120000);
  CHECK(verdict.rfind("HTTP/1.1 200", 0) == 0);
  CHECK(verdict.find("\"pass\":true") != std::string::npos);
  test::RawConnection params(run.view->port());
  REQUIRE(params.send("POST " + run.with_token("/api/params") + head));
  const std::string refused = params.read_to_close(10000);
  CHECK(refused.rfind("HTTP/1.1 400", 0) == 0);
  CHECK(refused.find("{\"error\":\"request: expected a JSON object") != std::string::npos);
}

}  // TEST_SUITE("threaded")

}  // namespace hapscene

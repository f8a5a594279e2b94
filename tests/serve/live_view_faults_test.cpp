// The live view shows a script's fault: the message the script VM stored when it
// disabled the script ("boom.lua:3: boom", located), its kind and time, once per fault
// in the stream (the event's "script_faults"), counted in status.script_faults, and kept
// in GET /api/scene's "script_faults" for a page opened later.
#include <doctest/doctest.h>

#include <string>

#include "tests/scratch_folder.hpp"
#include "tests/serve/live_view_support.hpp"

namespace hapscene {
namespace {

using nlohmann::json;

// A script that runs 50 ms, then raises.
const char* kBoomScript = R"(-- faults after 50 ms
function force(s)
  if s.t > 0.05 then error('boom') end
  return 0
end
)";

const char* kBoomScene = R"({
  "name": "live boom",
  "effects": [
    {"type": "spring", "stiffness": "100 N/m"},
    {"type": "script", "file": "boom.lua"}
  ]
}
)";

}  // namespace

TEST_SUITE("threaded") {

TEST_CASE("live view: a script fault inside the loop reaches the page with its located message, once") {
  test::ScratchFolder folder("live_faults");
  folder.write("boom.lua", kBoomScript);
  const std::string file = folder.write("boom.json", kBoomScene).string();
  test::LiveRun<1> run(file, 1.0);
  const std::vector<test::SseEvent> events = run.stream_for(3.0);
  REQUIRE(events.size() > 10);
  std::vector<json> faults;
  std::uint64_t last_count = 0;
  json last_disabled;
  for (const test::SseEvent& event : events) {
    if (event.event != "message") continue;
    const json data = json::parse(event.data);
    REQUIRE(data.contains("script_faults"));
    for (const json& fault : data["script_faults"]) faults.push_back(fault);
    last_count = data["status"]["script_faults"].get<std::uint64_t>();
    last_disabled = data["status"]["scripts_disabled"];
  }
  // One fault, sent once, with the script's own located message.
  REQUIRE(faults.size() == 1);
  const json& fault = faults[0];
  CHECK(fault["number"] == 1);
  CHECK(fault["script"] == 0);
  CHECK(fault["kind"] == "error");
  CHECK(fault["t_s"].get<double>() == doctest::Approx(0.051).epsilon(0.02));
  const std::string message = fault["message"].get<std::string>();
  CHECK_MESSAGE(message.find("boom.lua:3: boom") != std::string::npos, message);
  CHECK(last_count == 1);
  CHECK(last_disabled == json::array({0}));
  // A page opened later gets it from the scene.
  httplib::Client client = run.client();
  const json scene = json::parse(client.Get(run.with_token("/api/scene"))->body);
  REQUIRE(scene["script_faults"].size() == 1);
  CHECK(scene["script_faults"][0] == fault);
  // The run's own summary says the same.
  run.stop.store(true);
  run.loop.join();
  REQUIRE(run.summary.scripts.size() == 1);
  CHECK(run.summary.scripts[0].fault == message);
}

TEST_CASE("live view: a fault in each version of a script is its own fault (a parameter change makes new instances)") {
  test::ScratchFolder folder("live_faults_versions");
  folder.write("boom.lua", kBoomScript);
  const std::string file = folder.write("boom.json", kBoomScene).string();
  test::LiveRun<1> run(file, 3.0);
  std::this_thread::sleep_for(std::chrono::milliseconds(400));
  // A new version (the spring's stiffness changed) has new script instances; the run's
  // time is past 0.05 s, so the new one faults at its first call.
  int status = 0;
  (void)run.post_params({{"effect", 0}, {"parameter", "stiffness"}, {"value", 120}}, &status);
  REQUIRE(status == 200);
  std::this_thread::sleep_for(std::chrono::milliseconds(900));
  httplib::Client client = run.client();
  const json scene = json::parse(client.Get(run.with_token("/api/scene"))->body);
  REQUIRE(scene["script_faults"].size() == 2);
  CHECK(scene["script_faults"][0]["number"] == 1);
  CHECK(scene["script_faults"][1]["number"] == 2);
  CHECK(scene["script_faults"][1]["message"].get<std::string>().find("boom.lua:3: boom") != std::string::npos);
}

}  // TEST_SUITE("threaded")

}  // namespace hapscene

// The live view's endpoints against a real simulated run in real time (`run --ui` as a
// library): the token on every request, the stream's format and that it carries every
// tick, parameter changes taken (the loop's force follows) and refused (the loader's
// located message, nothing changes), and saving that keeps the file's layout.
#include <doctest/doctest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <thread>

#include "tests/cli/cli_support.hpp"
#include "tests/scratch_folder.hpp"
#include "tests/serve/live_view_support.hpp"

namespace hapscene::HAPSCENE_TEST_FILE {
namespace {

using nlohmann::json;

// A spring held 20 mm out by the hand: its force shows its stiffness.
const char* kSpring = R"({
  "name": "live spring",
  "effects": [
    {"type": "spring", "stiffness": "100 N/m", "center": "0 mm"}
  ]
}
)";

// The force the stream shows at the end of `events` (the last tick's output_N).
double last_output_N(const std::vector<test::SseEvent>& events) {
  for (auto it = events.rbegin(); it != events.rend(); ++it) {
    if (it->event != "message") continue;
    const json event = json::parse(it->data);
    if (!event["output_N"].empty()) return event["output_N"].back().get<double>();
  }
  return std::nan("");
}

}  // namespace

TEST_SUITE("threaded") {

TEST_CASE("live view: every request needs the token, a wrong or missing one is refused with 403") {
  test::ScratchFolder folder("live_token");
  test::LiveRun<1> run(folder.write("spring.json", kSpring).string(), 2.0);
  httplib::Client client = run.client();
  for (const char* path : {"/", "/api/scene", "/api/stream"}) {
    CAPTURE(path);
    const auto none = client.Get(path);
    REQUIRE(none);
    CHECK(none->status == 403);
    CHECK(none->body.find("token") != std::string::npos);
    const auto wrong = client.Get(std::string(path) + "?token=" + std::string(run.view->token().size(), '0'));
    REQUIRE(wrong);
    CHECK(wrong->status == 403);
  }
  const auto post = client.Post("/api/params", R"({"effect": 0, "parameter": "stiffness", "value": 1})", "application/json");
  REQUIRE(post);
  CHECK(post->status == 403);
  for (const char* path : {"/api/save", "/api/validate"}) {
    const auto refused = client.Post(path, "", "application/json");
    REQUIRE(refused);
    CHECK(refused->status == 403);
  }
  // The right token, in the query or as a bearer token.
  const auto page = client.Get(run.with_token("/"));
  REQUIRE(page);
  CHECK(page->status == 200);
  CHECK(page->get_header_value("Content-Type").find("text/html") == 0);
  CHECK(page->body.find("hapscene live view") != std::string::npos);
  CHECK(page->body.find("EventSource") != std::string::npos);  // the script is inlined
  CHECK(page->body.find("HAPSCENE_APP_JS") == std::string::npos);
  httplib::Headers bearer{{"Authorization", "Bearer " + run.view->token()}};
  const auto scene = client.Get("/api/scene", bearer);
  REQUIRE(scene);
  CHECK(scene->status == 200);
  // The loopback address, a port, and 32 hex digits of token.
  CHECK(run.view->url().rfind("http://127.0.0.1:" + std::to_string(run.view->port()) + "/?token=", 0) == 0);
  CHECK(run.view->token().size() == 32);
}

TEST_CASE("live view: GET /api/scene lists the device, the effects and every parameter with its unit and range") {
  test::ScratchFolder folder("live_scene");
  test::LiveRun<1> run(folder.write("spring.json", kSpring).string(), 1.0);
  httplib::Client client = run.client();
  const auto response = client.Get(run.with_token("/api/scene"));
  REQUIRE(response);
  REQUIRE(response->status == 200);
  const json scene = json::parse(response->body);
  CHECK(scene["name"] == "live spring");
  CHECK(scene["axes"] == 1);
  CHECK(scene["rate_hz"] == 1000.0);
  CHECK(scene["device"]["name"] == "hapkit3");
  CHECK(scene["device"]["max_force_N"] == 6.0);
  CHECK(scene["stream"]["stride"] == 1);
  CHECK(scene["stream"]["events_per_s"] == 50.0);
  CHECK(scene["unsaved"] == false);
  REQUIRE(scene["parameters"].size() == 2);
  const json& stiffness = scene["parameters"][0];
  CHECK(stiffness["effect"] == 0);
  CHECK(stiffness["parameter"] == "stiffness");
  CHECK(stiffness["unit"] == "N/m");
  CHECK(stiffness["value"] == 100.0);
  CHECK(stiffness["min"] == 0.0);
  CHECK(stiffness["max"].get<double>() > 100.0);  // the passivity bound
  const json& center = scene["parameters"][1];
  CHECK(center["parameter"] == "center");
  CHECK(center["unit"] == "m");
  CHECK(center["min"] == scene["device"]["workspace_min_m"]);
  CHECK(center["max"] == scene["device"]["workspace_max_m"]);
}

TEST_CASE("live view: GET /api/scene sketches a 1-D scene: the walls' solid sides, the textures' fields, the force at rest") {
  test::ScratchFolder folder("live_sketch");
  test::LiveRun<1> run(folder.write("sketch.json", R"({"effects": [
    {"type": "wall", "position": "10 mm", "stiffness": "200 N/m", "solid": "below"},
    {"type": "texture", "width": "5 mm", "spacing": "5 mm", "damping": "2 N*s/m", "offset": "0 mm"},
    {"type": "spring", "stiffness": "50 N/m", "enabled": false}]})").string(), 1.0);
  httplib::Client client = run.client();
  const auto response = client.Get(run.with_token("/api/scene"));
  REQUIRE(response);
  const json scene = json::parse(response->body);
  // The enabled walls and textures, in the file's order.
  REQUIRE(scene["shapes"].size() == 2);
  CHECK(scene["shapes"][0] == json{{"kind", "wall"}, {"position_m", 0.01}, {"solid", "below"}});
  const json& fields = scene["shapes"][1]["fields_m"];
  CHECK(scene["shapes"][1]["kind"] == "texture");
  CHECK_FALSE(scene["shapes"][1].contains("more_fields"));
  // 5 mm fields every 10 mm from 0, across [-50, 45] mm: [-50,-45], ..., [40, 45].
  REQUIRE(fields.size() == 10);
  CHECK(fields[5][0].get<double>() == doctest::Approx(0.0).epsilon(1e-9));
  CHECK(fields[5][1].get<double>() == doctest::Approx(0.005).epsilon(1e-3));
  for (const json& field : fields) {
    CHECK(field[1].get<double>() - field[0].get<double>() == doctest::Approx(0.005).epsilon(0.02));
  }
  // The force at rest every 0.5 mm: the wall's -K (x - xw) below it, nothing above (the
  // texture damps motion only), clamped at the device's 6 N.
  const json& curve = scene["force_curve"];
  REQUIRE(curve["x_m"].size() == 191);
  for (std::size_t i = 0; i < curve["x_m"].size(); ++i) {
    const double x_m = curve["x_m"][i].get<double>();
    const double asked_N = x_m < 0.01 ? -200.0 * (x_m - 0.01) : 0.0;
    CHECK(curve["force_N"][i].get<double>() == doctest::Approx(asked_N).epsilon(1e-12));
    CHECK(curve["output_N"][i].get<double>() == doctest::Approx(std::min(asked_N, 6.0)).epsilon(1e-12));
  }
}

TEST_CASE("live view: the stream is Server-Sent Events, 30 to 120 a second, carrying every tick once and in order") {
  test::ScratchFolder folder("live_stream");
  test::LiveRun<1> run(folder.write("spring.json", kSpring).string(), 1.5);
  const std::vector<test::SseEvent> events = run.stream_for(3.0);
  REQUIRE(events.size() > 10);
  std::uint64_t next_tick = 0;
  bool first = true;
  std::size_t ticks = 0;
  std::size_t data_events = 0;
  double first_t = 0.0, last_t = 0.0;
  std::uint64_t previous_id = 0;
  // First the log so far (nothing has been logged in this run).
  CHECK(events.front().event == "log");
  CHECK(json::parse(events.front().data) == json{{"log", json::array()}});
  for (const test::SseEvent& event : events) {
    if (event.event == "end" || event.event == "log") continue;
    CHECK(event.event == "message");
    const json data = json::parse(event.data);
    // The fields, all there, the columns of one length.
    for (const char* field : {"seq", "tick", "stride", "t_s", "x_m", "force_N", "output_N", "status", "log", "dropped_events"}) {
      CHECK_MESSAGE(data.contains(field), field);
    }
    CHECK(std::stoull(event.id) == data["seq"].get<std::uint64_t>());
    if (data_events > 0) CHECK(data["seq"].get<std::uint64_t>() == previous_id + 1);
    previous_id = data["seq"].get<std::uint64_t>();
    ++data_events;
    const std::size_t n = data["t_s"].size();
    CHECK(data["x_m"].size() == n);
    CHECK(data["force_N"].size() == n);
    CHECK(data["output_N"].size() == n);
    CHECK(data["stride"] == 1);
    CHECK(data["dropped_events"] == 0);
    CHECK(data["status"]["dropped_ticks"] == 0);
    for (const char* field : {"ticks", "t_s", "loop_rate_hz", "deadline_misses", "wake_late_max_us", "compute_max_us",
                              "energy_J", "safety", "scripts_disabled", "finished"}) {
      CHECK_MESSAGE(data["status"].contains(field), field);
    }
    if (n == 0) continue;
    // Every tick: the first tick of this event follows the last of the one before.
    const std::uint64_t tick = data["tick"].get<std::uint64_t>();
    if (!first) CHECK(tick == next_tick);
    CHECK(data["t_s"][0].get<double>() == doctest::Approx(static_cast<double>(tick) * 0.001));
    if (first) first_t = data["t_s"][0].get<double>();
    first = false;
    next_tick = tick + n;
    ticks += n;
    for (std::size_t i = 1; i < n; ++i) CHECK(data["t_s"][i].get<double>() == doctest::Approx(data["t_s"][i - 1].get<double>() + 0.001));
    last_t = data["t_s"].back().get<double>();
  }
  // The run's ticks from the stream's first to its end, none missing; "event: end" last.
  CHECK(events.back().event == "end");
  CHECK(ticks == static_cast<std::size_t>(std::llround((last_t - first_t) / 0.001)) + 1);
  CHECK(next_tick == 1500);
  // 50 events a second over the run (the first and last partial).
  const double events_per_s = static_cast<double>(data_events) / 1.5;
  CHECK(events_per_s >= 30.0);
  CHECK(events_per_s <= 120.0);
}

TEST_CASE("live view: a stream opened late starts with the log so far, and no line comes twice") {
  // (The run's script log() lines reach add_log through the status thread of `run`; the
  // browser test shows one logged before the page opened. Here the server alone.)
  test::ScratchFolder folder("live_log_history");
  test::LiveRun<1> run(folder.write("spring.json", kSpring).string(), 1.5);
  run.view->add_log("scripts/hello.lua:3: hello (t = 0.000 s)");
  std::this_thread::sleep_for(std::chrono::milliseconds(300));  // sent in an event to nobody
  run.view->add_log("a line after");  // a race with the stream's opening, on purpose
  const std::vector<test::SseEvent> events = run.stream_for(0.5);
  REQUIRE_FALSE(events.empty());
  REQUIRE(events.front().event == "log");
  const json history = json::parse(events.front().data)["log"];
  REQUIRE_FALSE(history.empty());
  CHECK(history[0] == "scripts/hello.lua:3: hello (t = 0.000 s)");
  // Each line comes once: the later one in the history or in a data event, whichever it
  // was sent in when the stream opened; the first never again.
  std::size_t hellos = 0;
  std::size_t afters = 0;
  for (const test::SseEvent& event : events) {
    hellos += test::occurrences(event.data, "hello (t =");
    afters += test::occurrences(event.data, "a line after");
  }
  CHECK(hellos == 1);
  CHECK(afters == 1);
}

TEST_CASE("live view: a parameter change goes through load, check and cross-fade, a bad one gets the loader's message and changes nothing") {
  test::ScratchFolder folder("live_params");
  const std::string file = folder.write("spring.json", kSpring).string();
  test::LiveRun<1> run(file, 4.0);
  // Before: the hand holds the handle where 100 N/m and its own 200 N/m balance.
  std::this_thread::sleep_for(std::chrono::milliseconds(700));
  const double before_N = last_output_N(run.stream_for(0.2));
  CHECK(before_N == doctest::Approx(-100.0 * 0.02 * 200.0 / 300.0).epsilon(0.05));

  // Refused: a negative stiffness. 400, the loader's located message, and nothing changes.
  int status = 0;
  json refused = run.post_params({{"effect", 0}, {"parameter", "stiffness"}, {"value", -5}}, &status);
  CHECK(status == 400);
  CHECK(refused["error"] == file + ": /effects/0/stiffness: must be >= 0, got -5 N/m");
  refused = run.post_params({{"effect", 0}, {"parameter", "stiffness"}, {"value", "50 mm"}}, &status);
  CHECK(status == 400);
  CHECK(refused["error"] == file + ": /effects/0/stiffness: expected a stiffness (N/m), got a length (\"50 mm\")");
  refused = run.post_params({{"effect", 3}, {"parameter", "stiffness"}, {"value", 1}}, &status);
  CHECK(status == 400);
  CHECK(refused["error"] == "/effects/3/stiffness: no such parameter (GET /api/scene lists them)");
  refused = run.post_params({{"effect", 0}, {"parameter", "stiffness"}, {"value", true}}, &status);
  CHECK(status == 400);
  httplib::Client client = run.client();
  const auto malformed = client.Post(run.with_token("/api/params"), "{not json", "application/json");
  REQUIRE(malformed);
  CHECK(malformed->status == 400);
  const json unchanged = json::parse(client.Get(run.with_token("/api/scene"))->body);
  CHECK(unchanged["parameters"][0]["value"] == 100.0);
  CHECK(unchanged["unsaved"] == false);
  CHECK(run.exchange.swaps() == 0);

  // Taken: 200 N/m (in N/m, as written: a number in SI), then the force follows after the cross-fade.
  const json taken = run.post_params({{"effect", 0}, {"parameter", "stiffness"}, {"value", 200}}, &status);
  CHECK(status == 200);
  CHECK(taken["parameters"][0]["value"] == 200.0);
  CHECK(taken["unsaved"] == true);
  std::this_thread::sleep_for(std::chrono::milliseconds(1200));  // 0.5 s of fade, and the hand settles
  const double after_N = last_output_N(run.stream_for(0.2));
  CHECK(after_N == doctest::Approx(-200.0 * 0.02 * 200.0 / 400.0).epsilon(0.05));
  CHECK(run.exchange.swaps() == 1);
  // The file is not touched until saved.
  CHECK(test::slurp_file(file) == kSpring);
}

TEST_CASE("live view: save writes the values back keeping the file's layout, units and all") {
  test::ScratchFolder folder("live_save");
  const std::string file = folder.write("spring.json", kSpring).string();
  test::LiveRun<1> run(file, 3.0);
  int status = 0;
  (void)run.post_params({{"effect", 0}, {"parameter", "stiffness"}, {"value", 250}}, &status);
  REQUIRE(status == 200);
  (void)run.post_params({{"effect", 0}, {"parameter", "center"}, {"value", 0.0125}}, &status);
  REQUIRE(status == 200);
  httplib::Client client = run.client();
  const auto saved = client.Post(run.with_token("/api/save"), "", "application/json");
  REQUIRE(saved);
  CHECK(saved->status == 200);
  // Only the two values changed, each in the unit it was written in.
  std::string expected = kSpring;
  expected.replace(expected.find("100 N/m"), 7, "250 N/m");
  expected.replace(expected.find("0 mm"), 4, "12.5 mm");
  CHECK(test::slurp_file(file) == expected);
  const json scene = json::parse(client.Get(run.with_token("/api/scene"))->body);
  CHECK(scene["unsaved"] == false);
  // The watcher does not take the saved file for an edit: one cross-fade per change only.
  std::this_thread::sleep_for(std::chrono::milliseconds(400));
  CHECK(run.exchange.swaps() <= 2);
}

TEST_CASE("live view: validate runs the harness on the current values, off the loop, and gives the verdict table") {
  test::ScratchFolder folder("live_validate");
  const std::string file = folder.write("spring.json", kSpring).string();
  test::LiveRun<1> run(file, 30.0);
  int status = 0;
  (void)run.post_params({{"effect", 0}, {"parameter", "stiffness"}, {"value", 150}}, &status);
  REQUIRE(status == 200);
  httplib::Client client = run.client();
  client.set_read_timeout(60, 0);
  const auto result = client.Post(run.with_token("/api/validate"), "", "application/json");
  REQUIRE(result);
  CHECK(result->status == 200);
  const json verdict = json::parse(result->body);
  CHECK(verdict["pass"] == true);
  // The table as `validate` prints it, of the values running (150 N/m), and the JSON report.
  CHECK(verdict["table"].get<std::string>().rfind("validate live spring (" + file + ")", 0) == 0);
  CHECK(verdict["report"]["schema"] == "hapscene-validate/2");
  // The sweep's largest force is 150 N/m's (4.016 N at 26.77 mm), not the file's 100 N/m
  // (validate runs in simulated time: the same values give the same table).
  const std::string table = verdict["table"].get<std::string>();
  CHECK_MESSAGE(table.find("at -26.77 mm, t 2.626 s (asked up to 4.016 N)") != std::string::npos, table);
}

TEST_CASE("live view: a 2-D run streams x and y, both forces per axis and the shapes' proxies") {
  test::ScratchFolder folder("live_planar");
  const std::string text = test::slurp_file(std::string(HAPSCENE_SOURCE_DIR) + "/environments/planar/haplink_box_inside.json");
  const std::string file = folder.write("box.json", text).string();
  test::LiveRun<2> run(file, 1.0);
  httplib::Client client = run.client();
  const json scene = json::parse(client.Get(run.with_token("/api/scene"))->body);
  CHECK(scene["axes"] == 2);
  REQUIRE(scene["shapes"].size() == 1);
  CHECK(scene["shapes"][0]["kind"] == "box");
  CHECK(scene["shapes"][0]["points_m"].size() == 4);
  // min x, min y, max x, max y, stiffness.
  REQUIRE(scene["parameters"].size() == 5);
  CHECK(scene["parameters"][0]["parameter"] == "min/0");
  CHECK(scene["parameters"][0]["label"] == "min x");
  CHECK(scene["parameters"][1]["parameter"] == "min/1");
  CHECK(scene["parameters"][1]["value"].get<double>() == doctest::Approx(0.110));
  const std::vector<test::SseEvent> events = run.stream_for(2.0);
  REQUIRE(events.size() > 5);
  const json data = json::parse(events[events.size() / 2].data);
  for (const char* field : {"t_s", "x_m", "y_m", "force_x_N", "force_y_N", "output_x_N", "output_y_N", "proxies_m"}) {
    CHECK_MESSAGE(data.contains(field), field);
  }
  CHECK(data["proxies_m"].size() == 1);
  CHECK(data["y_m"].size() == data["t_s"].size());
  // A change to the box's corner is taken and written in the file's unit.
  int status = 0;
  (void)run.post_params({{"effect", 0}, {"parameter", "min/1"}, {"value", 0.112}}, &status);
  CHECK(status == 200);
}

}  // TEST_SUITE("threaded")

}  // namespace hapscene::HAPSCENE_TEST_FILE

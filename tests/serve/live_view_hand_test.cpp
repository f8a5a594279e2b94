// The live view's pointer on a simulated device (POST /api/hand): the hand pulls the
// handle to the pointer while it is held and goes back to its motion when let go; bad
// requests are refused with a located message and change nothing.
#include <doctest/doctest.h>

#include <chrono>
#include <cmath>
#include <string>
#include <thread>

#include "tests/scratch_folder.hpp"
#include "tests/serve/live_view_support.hpp"

namespace hapscene {
namespace {

using nlohmann::json;

// A scene that pushes nowhere at rest: the handle goes where the hand takes it.
constexpr const char* kDamper = R"({"name": "damper", "effects": [{"type": "damper", "damping": "1 N*s/m"}]})";
constexpr const char* kPlanarDamper =
    R"({"name": "planar damper", "device": "haplink", "effects": [{"type": "damper", "damping": "1 N*s/m"}]})";

struct HandAnswer {
  int status{};
  json body;
};

template <int N>
HandAnswer post_hand(const test::LiveRun<N>& run, const std::string& body) {
  httplib::Client client = run.client();
  const auto result = client.Post(run.with_token("/api/hand"), body, "application/json");
  return result ? HandAnswer{result->status, json::parse(result->body)} : HandAnswer{-1, json()};
}

// The handle's position at the end of 0.3 s of the stream (x, and y on a 2-DOF device).
json handle_after(const std::vector<test::SseEvent>& events) {
  for (auto it = events.rbegin(); it != events.rend(); ++it) {
    if (it->event != "message") continue;
    const json data = json::parse(it->data);
    if (data["x_m"].empty()) continue;
    json out{{"x_m", data["x_m"].back()}};
    if (data.contains("y_m")) out["y_m"] = data["y_m"].back();
    return out;
  }
  return nullptr;
}

}  // namespace

TEST_SUITE("threaded") {

TEST_CASE("live view hand: on a simulated 1-D device the pointer takes the handle, and letting go gives it back") {
  test::ScratchFolder folder("live_hand");
  test::LiveRun<1> run(folder.write("damper.json", kDamper).string(), 3.0, 0.02);  // the hand holds at 20 mm
  const json scene = json::parse(run.client().Get(run.with_token("/api/scene"))->body);
  CHECK(scene["device"]["hand_pointer"] == true);
  // Held at -30 mm: the hand's spring takes the handle there.
  const HandAnswer taken = post_hand(run, R"({"x_m": -0.03})");
  REQUIRE(taken.status == 200);
  CHECK(taken.body == json{{"hand", "pointer"}, {"x_m", -0.03}});
  std::this_thread::sleep_for(std::chrono::milliseconds(600));
  const json held = handle_after(run.stream_for(0.3));
  REQUIRE(held.is_object());
  CHECK(held["x_m"].get<double>() == doctest::Approx(-0.03).epsilon(0.05));
  // Let go: the hand's own motion (hold at 20 mm) again.
  const HandAnswer released = post_hand(run, R"({"release": true})");
  REQUIRE(released.status == 200);
  CHECK(released.body == json{{"hand", "released"}});
  std::this_thread::sleep_for(std::chrono::milliseconds(600));
  const json back = handle_after(run.stream_for(0.3));
  REQUIRE(back.is_object());
  CHECK(back["x_m"].get<double>() == doctest::Approx(0.02).epsilon(0.05));
}

TEST_CASE("live view hand: on a simulated 2-D device the pointer takes the handle in the plane") {
  test::ScratchFolder folder("live_hand_planar");
  test::LiveRun<2> run(folder.write("damper.json", kPlanarDamper).string(), 3.0);
  const HandAnswer taken = post_hand(run, R"({"x_m": -0.02, "y_m": 0.12})");
  REQUIRE(taken.status == 200);
  std::this_thread::sleep_for(std::chrono::milliseconds(800));
  const json held = handle_after(run.stream_for(0.3));
  REQUIRE(held.is_object());
  CHECK(held["x_m"].get<double>() == doctest::Approx(-0.02).epsilon(0.1));
  CHECK(held["y_m"].get<double>() == doctest::Approx(0.12).epsilon(0.1));
  CHECK(post_hand(run, R"({"release": true})").status == 200);
}

TEST_CASE("live view hand: a bad request is refused with what is wrong, and the hand stays as it was") {
  test::ScratchFolder folder("live_hand_bad");
  test::LiveRun<2> run(folder.write("damper.json", kPlanarDamper).string(), 2.0);
  const std::string object = R"({"x_m": X, "y_m": Y} or {"release": true})";
  const std::string form = "expected a JSON object " + object;
  const std::string not_metres = " must be a finite number of metres (" + object + ")";
  for (const std::pair<std::string, std::string>& request : {
           std::pair<std::string, std::string>{"not json", "request: " + form},
           {"[0.01, 0.1]", "request: " + form},
           {R"({"x_m": 0.01})", "request: " + form},
           {R"({"x_m": 0.01, "z_m": 0.1})", R"(request: "y_m")" + not_metres},
           {R"({"x_m": "1 mm", "y_m": 0.1})", R"(request: "x_m")" + not_metres},
           {R"({"x_m": 1e999, "y_m": 0.1})", "request: " + form},  // out of a double's range: not JSON we read
           {R"({"release": false})", R"(request: expected {"release": true} alone)"},
           {R"({"release": true, "x_m": 0})", R"(request: expected {"release": true} alone)"}}) {
    CAPTURE(request.first);
    const HandAnswer answer = post_hand(run, request.first);
    CHECK(answer.status == 400);
    CHECK(answer.body["error"] == request.second);
  }
  // Outside the workspace, named with its bounds.
  const HandAnswer outside = post_hand(run, R"({"x_m": 0.5, "y_m": 0.1})");
  CHECK(outside.status == 400);
  CHECK(outside.body["error"].get<std::string>().starts_with("x_m: 0.5 m is outside the workspace ["));
  CHECK(run.device->hand_pointer()->read().active == false);
}

}  // TEST_SUITE

}  // namespace hapscene

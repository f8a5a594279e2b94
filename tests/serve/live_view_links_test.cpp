// The live view's link health for a device on boards: `--device hil` (the firmware on
// simulated ATmega328Ps, talking through the same BoardLink as a real board on a serial
// port), 1-D and the 2-DOF pair. status.links carries each board's counters, taken by the
// tap on the loop's thread, and they move as the run goes. A simulated device has none.
#include <doctest/doctest.h>

#include <string>

#include "tests/scratch_folder.hpp"
#include "tests/serve/live_view_support.hpp"

namespace hapscene::HAPSCENE_TEST_FILE {
namespace {

using nlohmann::json;

const char* kSpring = R"({"name": "live link", "effects": [{"type": "spring", "stiffness": "100 N/m"}]})";

// status.links of each data event that has ticks.
std::vector<json> links_of(const std::vector<test::SseEvent>& events) {
  std::vector<json> out;
  for (const test::SseEvent& event : events) {
    if (event.event != "message") continue;
    const json data = json::parse(event.data);
    if (data["t_s"].empty()) continue;
    out.push_back(data["status"]["links"]);
  }
  return out;
}

// The counters of one board move between an early and a late event, with no errors on a clean link.
void check_moving(const json& early, const json& late) {
  CHECK(late["state"] == "running");
  CHECK(late["protocol"] == "hapscene");
  CHECK(late["commands"].get<std::uint64_t>() > early["commands"].get<std::uint64_t>() + 100);
  CHECK(late["replies"].get<std::uint64_t>() > early["replies"].get<std::uint64_t>() + 100);
  CHECK(late["round_trip_us"]["replies"].get<std::uint64_t>() > early["round_trip_us"]["replies"].get<std::uint64_t>());
  CHECK(late["round_trip_us"]["mean"].get<double>() > 0.0);
  CHECK(late["round_trip_us"]["max"].get<double>() >= late["round_trip_us"]["mean"].get<double>());
  CHECK(late["crc_errors"] == 0);
  CHECK(late["board_resets"] == 0);
  CHECK(late["connects"] == 1);
  for (const char* field : {"length_errors", "bytes_skipped", "lost_frames", "unanswered", "frames_not_sent",
                            "stale_reads", "board_timeouts", "implausible", "resyncs", "silences", "vanished"}) {
    CHECK_MESSAGE(late.contains(field), field);
  }
  // The board's own counters come every 100 ms (its STATS frame).
  REQUIRE(late["board_saw"].is_object());
  CHECK(late["board_saw"]["frames"].get<std::uint64_t>() > 100);
}

}  // namespace

TEST_SUITE("threaded") {

TEST_CASE("live view: a simulated device has no links") {
  test::ScratchFolder folder("live_links_sim");
  test::LiveRun<1> run(folder.write("spring.json", kSpring).string(), 0.5);
  const std::vector<json> links = links_of(run.stream_for(2.0));
  REQUIRE_FALSE(links.empty());
  CHECK(links.back() == json::array());
}

#if HAPSCENE_HAVE_HIL

TEST_CASE("live view: --device hil shows the board's link counters, live") {
  test::ScratchFolder folder("live_links_hil");
  test::LiveRun<1> run(folder.write("spring.json", kSpring).string(), 2.0, 0.02, "hil");
  httplib::Client client = run.client();
  const json scene = json::parse(client.Get(run.with_token("/api/scene"))->body);
  CHECK(scene["device"]["links"] == json::array({"simulated board"}));
  // The board's hand is not the page's to move (the live view's pointer: simulated devices).
  CHECK(scene["device"]["hand_pointer"] == false);
  const auto hand = client.Post(run.with_token("/api/hand"), R"({"x_m": 0.0})", "application/json");
  REQUIRE(hand);
  CHECK(hand->status == 409);
  CHECK(json::parse(hand->body)["error"] == "this device's hand is not the page's to move (only --device sim's is): on a real device it is yours");
  const std::vector<json> links = links_of(run.stream_for(4.0));
  REQUIRE(links.size() > 20);
  REQUIRE(links[2].size() == 1);
  REQUIRE(links.back().size() == 1);
  CHECK(links.back()[0]["board"] == "simulated board");
  CHECK(links.back()[0]["joint"] == nullptr);
  check_moving(links[2][0], links.back()[0]);
}

TEST_CASE("live view: --device hil on a 2-DOF pantograph shows both boards' links, per joint") {
  test::ScratchFolder folder("live_links_hil_pair");
  const std::string file =
      folder
          .write("pantograph.json",
                 R"({"name": "pantograph", "device": "hapkit_pantograph", "effects": [{"type": "box",
                    "min": ["55 mm", "115 mm"], "max": ["100 mm", "150 mm"], "stiffness": "300 N/m", "solid": "inside"}]})")
          .string();
  test::LiveRun<2> run(file, 2.0, 0.0, "hil");
  const std::vector<json> links = links_of(run.stream_for(4.0));
  REQUIRE(links.size() > 20);
  REQUIRE(links[2].size() == 2);
  REQUIRE(links.back().size() == 2);
  for (std::size_t joint = 0; joint < 2; ++joint) {
    CAPTURE(joint);
    CHECK(links.back()[joint]["joint"] == joint + 1);
    CHECK(links.back()[joint]["board"] == "simulated board " + std::to_string(joint + 1));
    check_moving(links[2][joint], links.back()[joint]);
  }
}

#else

TEST_CASE("live view: --device hil link counters need simavr and the firmware" * doctest::skip()) {}

#endif

}  // TEST_SUITE("threaded")

}  // namespace hapscene::HAPSCENE_TEST_FILE

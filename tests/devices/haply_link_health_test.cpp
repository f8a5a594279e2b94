// A Haply 2DIY's link counters as the live view takes them (DeviceStatus::link_health):
// the Haply protocol's own counts (frames sent, replies, resyncs), named by the port.
#include <doctest/doctest.h>

#include <chrono>
#include <string>
#include <thread>
#include <vector>

#include "engine/devices/haply/haply_device.hpp"
#include "tests/devices/pty_haply_board.hpp"

using namespace hapscene;

TEST_SUITE("threaded") {

TEST_CASE("haply device: link_health gives the link's own counters, and they move as it runs") {
  test::PtyHaplyBoard board;
  HaplyConfig config;
  config.path = board.path();
  config.handshake_timeout_s = 2.0;
  HaplyDevice device(load_planar_profile("haply2diy_v3", "."), config);
  CHECK(device.link_names() == std::vector<std::string>{board.path()});
  DeviceLinkHealth before;
  device.link_health(&before);
  REQUIRE(before.links == 1);
  PlanarMotorCommand command;
  for (int i = 0; i < 50; ++i) {
    (void)device.read();
    device.write(command);
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  DeviceLinkHealth after;
  device.link_health(&after);
  REQUIRE(after.links == 1);
  const LinkHealth& h = after.link[0];
  const HaplyLinkCounters& c = device.link().counters();
  CHECK(std::string(h.protocol) == "haply");
  CHECK(h.commands == c.frames_sent);
  CHECK(h.replies == c.replies);
  CHECK(h.resyncs == c.resyncs);
  CHECK(h.frames_not_sent == c.frames_dropped);
  CHECK(h.bytes_skipped == c.bytes_dropped);
  CHECK(h.commands > before.link[0].commands);
  CHECK(h.replies > before.link[0].replies);
  // No CRC, sequence numbers or STATS in this protocol.
  CHECK(h.crc_errors == 0);
  CHECK_FALSE(h.board_stats);
}

}  // TEST_SUITE("threaded")

#pragma once
// The handshake of one or more boards on links, before the loop starts: HELLO (and a
// motor-off COMMAND) every millisecond until each board answers, all boards at once, so
// two Uno-style boards that reset when their ports open wait out their boot together.
// Shared by the 1-DOF serial Hapkit and the two-board 2-DOF device.
#include <span>
#include <string>

#include "engine/devices/board_link.hpp"

namespace hapscene {

struct BoardToOpen {
  BoardLink* link{};
  std::string name;  // for the message, e.g. "--device serial:/dev/ttyACM0"
};

// Returns when every link is running; throws std::runtime_error naming the first board that
// did not answer within `timeout_s` (why, from what it sent, and the baud rate to check).
void complete_handshakes(std::span<const BoardToOpen> boards, double timeout_s, int baud);

}  // namespace hapscene

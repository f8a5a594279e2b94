#pragma once
// The run summary's lines about a board link: identity, frames, faults, round-trip
// latency and the firmware's own timing in CPU cycles.
#include <string>

#include "engine/devices/board_link.hpp"

namespace hapscene {

// Event times are shown in seconds since `start_ns` (the clock of the link).
std::string board_report(const BoardLink& link, std::int64_t start_ns);

// Why the handshake did not complete, from what the board sent: another protocol version
// (and its identity), a REFUSED, frames of other types, undecodable bytes, or nothing.
std::string handshake_failure(const BoardLink& link);

}  // namespace hapscene

#pragma once
// A device's link counters as one fixed-size value: what the run summary's link report
// says at the end, taken while the run goes (the live view shows them). A device on
// boards fills one entry per board (a 2-DOF pair: joint 1's, then joint 2's); taking them
// copies counters and never allocates, locks or blocks, but it reads what the loop
// writes, so it is called on the loop's thread (a tick observer) and the copy is handed
// on from there.
#include <array>
#include <cstddef>
#include <cstdint>

namespace hapscene {

struct LinkHealth {
  const char* protocol{"hapscene"};  // "hapscene" (the firmware's protocol) or "haply"
  const char* state{"running"};      // "handshaking", "running", "silent", "vanished"
  std::uint64_t commands{};          // frames sent (COMMANDs; Haply: torque frames)
  std::uint64_t replies{};           // STATEs (Haply: replies) accepted
  std::uint64_t crc_errors{};        // frames the host dropped for a bad CRC
  std::uint64_t length_errors{};     // ... for a bad length
  std::uint64_t bytes_skipped{};     // bytes dropped while hunting for a frame
  std::uint64_t lost_frames{};       // board frames missing by sequence number
  std::uint64_t unanswered{};        // commands whose reply never came
  std::uint64_t frames_not_sent{};   // frames the port would not take whole
  std::uint64_t stale_reads{};       // reads with no new reply since the previous one
  std::uint64_t board_timeouts{};    // replies saying the board's command timeout fired
  std::uint64_t implausible{};       // replies rejected as impossible positions
  std::uint64_t resyncs{};           // Haply: the stream resynchronised
  std::uint64_t connects{};          // handshakes completed (1: no reconnection)
  std::uint64_t board_resets{};      // the board was reset (it refused a command as unarmed)
  std::uint64_t silences{};          // the board went quiet for the silence timeout
  std::uint64_t vanished{};          // the port failed (unplugged)
  std::uint64_t round_trip_count{};  // replies timed
  std::uint64_t round_trip_sum_ns{};
  std::uint64_t round_trip_max_ns{};
  bool board_stats{};                // the board's own counters below are known
  std::uint64_t board_frames{};      // ... frames it took
  std::uint64_t board_crc_errors{};
  std::uint64_t board_length_errors{};
  std::uint64_t board_bytes_skipped{};
  std::uint64_t board_lost_frames{};
  std::uint64_t board_command_timeouts{};
};

// At most two links per device (a 2-DOF pair of boards).
inline constexpr std::size_t kMaxDeviceLinks = 2;

struct DeviceLinkHealth {
  std::size_t links{};  // 0: a device without a link (simulated)
  std::array<LinkHealth, kMaxDeviceLinks> link{};
};

}  // namespace hapscene

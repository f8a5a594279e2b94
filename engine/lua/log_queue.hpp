#pragma once
// Messages from a script's log()/print(): written inside the tick, read off the loop.
// A single-producer single-consumer ring of fixed-size slots, so writing never blocks
// and never allocates; a token bucket on run time (s.t) limits the rate, so a script
// that logs every tick cannot flood the terminal or slow the loop.
#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace hapscene::detail {

class LogQueue {
 public:
  static constexpr std::size_t kSlots = 64;
  static constexpr std::size_t kTextBytes = 240;

  // Messages per second of run time and burst size (at most kSlots).
  void configure(double messages_per_s, std::size_t burst);

  // Producer side (the thread running the script).
  // True when a message at run time t_s is within the rate; otherwise counts it dropped.
  bool admit(double t_s) noexcept;
  // A free slot's text buffer (kTextBytes long), or nullptr (then counts a drop).
  char* begin_write() noexcept;
  // Publishes the slot returned by begin_write.
  void commit(double t_s, std::size_t length) noexcept;

  // Consumer side (any one thread): appends "<text> (t = 0.500 s)" per message (the text
  // starts with its place, "scripts/x.lua:7: "), then "<script_name>: N log messages
  // dropped (...)" if any were.
  void drain(std::string_view script_name, std::vector<std::string>* out);

 private:
  struct Slot {
    double t_s{};
    std::size_t length{};
    char text[kTextBytes]{};
  };
  std::array<Slot, kSlots> slots_{};
  std::atomic<std::uint64_t> head_{0};     // next slot the producer writes
  std::atomic<std::uint64_t> tail_{0};     // next slot the consumer reads
  std::atomic<std::uint64_t> dropped_{0};  // messages dropped since the last drain
  double rate_per_s_{10.0};
  double burst_{20.0};
  double tokens_{20.0};
  double last_t_s_{0.0};
};

}  // namespace hapscene::detail

#pragma once
// Instructions retired by this thread in user space, from the CPU's performance counters
// (Linux perf_event_open). Many virtual machines and containers do not expose them: then
// available() is false and reason() says why ("perf_event_open: No such file or
// directory"), and the bench says so and points at its --callgrind mode instead.
#include <cstdint>
#include <string>

namespace hapscene {

class InstructionCounter {
 public:
  InstructionCounter();
  ~InstructionCounter();
  InstructionCounter(const InstructionCounter&) = delete;
  InstructionCounter& operator=(const InstructionCounter&) = delete;

  bool available() const noexcept { return fd_ >= 0; }
  const std::string& reason() const noexcept { return reason_; }

  // Counting between start() and stop(); stop() returns the instructions in between
  // (0 when not available).
  void start() noexcept;
  std::uint64_t stop() noexcept;

 private:
  int fd_{-1};
  std::string reason_;
};

}  // namespace hapscene

#pragma once
// Real-time conditions for the loop's thread, when the system permits them: SCHED_FIFO
// (so ordinary processes cannot preempt a tick) and locked memory (so no page fault
// stalls one). Without the privilege (CAP_SYS_NICE / an rtprio limit, CAP_IPC_LOCK / a
// memlock limit) the loop runs as it is and note() says so in one line. Everything is
// restored when the guard goes out of scope.
#include <string>

namespace hapscene {

class RealtimeGuard {
 public:
  // SCHED_FIFO at kPriority. Does nothing when `enabled` is false.
  explicit RealtimeGuard(bool enabled);
  ~RealtimeGuard();
  RealtimeGuard(const RealtimeGuard&) = delete;
  RealtimeGuard& operator=(const RealtimeGuard&) = delete;

  // One line for the summary: what was obtained, or why not.
  const std::string& note() const noexcept { return note_; }
  // When the system refused SCHED_FIFO or the memory lock for lack of privilege: how to
  // allow them (limits.conf or a capability) and what running without them costs. Empty
  // otherwise.
  const std::string& hint() const noexcept { return hint_; }

  // Above ordinary processes and most kernel threads, below the watchdogs (1..99).
  static constexpr int kPriority = 80;

 private:
  bool enabled_{};
  bool fifo_{};
  bool locked_{};
  int old_policy_{};
  int old_priority_{};
  std::string note_;
  std::string hint_;
};

// The hint above for a refused SCHED_FIFO (`fifo_refused`) and/or memory lock, naming the
// running binary (`executable`, for setcap) and the user (for limits.conf).
std::string realtime_permission_hint(bool fifo_refused, bool lock_refused, const std::string& executable,
                                     const std::string& user);

}  // namespace hapscene

#pragma once
// Real-time conditions for the loop's thread, when the system permits them: SCHED_FIFO
// (so ordinary processes cannot preempt a tick) and locked memory (so no page fault
// stalls one). Without the privilege (CAP_SYS_NICE / an rtprio limit, CAP_IPC_LOCK / a
// memlock limit) the loop runs as it is and note() says so in one line. Everything is
// restored when the guard goes out of scope.
//
// Processes that compute in lock-step with the loop (a simulated board's, which the loop
// waits on inside its tick: Device::lockstep_processes) get the same SCHED_FIFO priority
// when the loop got it: otherwise any busy process on the machine delays the loop's tick
// through them. They are given back their own scheduling at the end.
#include <string>
#include <vector>

namespace hapscene {

class RealtimeGuard {
 public:
  // SCHED_FIFO at kPriority, for this thread and for `lockstep_processes` (process ids).
  // Does nothing when `enabled` is false.
  explicit RealtimeGuard(bool enabled, const std::vector<int>& lockstep_processes = {});
  ~RealtimeGuard();
  RealtimeGuard(const RealtimeGuard&) = delete;
  RealtimeGuard& operator=(const RealtimeGuard&) = delete;

  // One line for the summary: what was obtained, or why not (the lock-step processes
  // included).
  const std::string& note() const noexcept { return note_; }
  // When the system refused SCHED_FIFO or the memory lock for lack of privilege: how to
  // allow them (limits.conf or a capability) and what running without them costs. Empty
  // otherwise.
  const std::string& hint() const noexcept { return hint_; }

  // Above ordinary processes and most kernel threads, below the watchdogs (1..99).
  static constexpr int kPriority = 80;

 private:
  // A lock-step process and the scheduling it had.
  struct Follower {
    int pid{};
    int old_policy{};
    int old_priority{};
  };
  std::vector<Follower> followers_;

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

#pragma once
// Real-time conditions for the loop's thread, when the system permits them: SCHED_FIFO
// (so ordinary processes cannot preempt a tick) and locked memory (so no page fault
// stalls one). Without the privilege (CAP_SYS_NICE / an rtprio limit, CAP_IPC_LOCK / a
// memlock limit) the loop runs as it is and note() says so in one line. Everything is
// restored when the guard goes out of scope.
//
// Processes and threads that must keep pace with the loop (a simulated board's process and
// the thread that paces it: Device::realtime_peers) get nice -20 when the loop got
// SCHED_FIFO, so that busy processes on the machine do not make the simulated board fall
// behind real time, while the loop still preempts them at once. They are given back their
// own niceness at the end.
#include <string>
#include <vector>

namespace hapscene {

class RealtimeGuard {
 public:
  // SCHED_FIFO at kPriority for this thread, kPeerNice for `peers` (process or thread ids).
  // Does nothing when `enabled` is false.
  explicit RealtimeGuard(bool enabled, const std::vector<int>& peers = {});
  ~RealtimeGuard();
  RealtimeGuard(const RealtimeGuard&) = delete;
  RealtimeGuard& operator=(const RealtimeGuard&) = delete;

  // One line for the summary: what was obtained, or why not (the peers included).
  const std::string& note() const noexcept { return note_; }
  // When the system refused SCHED_FIFO or the memory lock for lack of privilege: how to
  // allow them (limits.conf or a capability) and what running without them costs. Empty
  // otherwise.
  const std::string& hint() const noexcept { return hint_; }

  // Above ordinary processes and most kernel threads, below the watchdogs (1..99).
  static constexpr int kPriority = 80;
  // The peers' niceness: the most CPU among ordinary tasks.
  static constexpr int kPeerNice = -20;

 private:
  // A peer and the niceness it had.
  struct Follower {
    int pid{};
    int old_nice{};
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

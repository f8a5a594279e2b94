#pragma once
// The live view's pointer on a simulated device: while the user drags on the page, the
// simulated hand grips the handle and pulls it toward the pointer (its spring and damper,
// the reference still), in place of its scripted motion; released, the motion goes on.
// A mailbox between the live view's request threads (writers, one at a time) and the
// simulated plant on the loop's thread (reader): reads never wait and never allocate.
// Never active in a run without --ui, so simulated runs stay deterministic.
#include <mutex>

#include "engine/base/axes.hpp"
#include "engine/base/published.hpp"

namespace hapscene {

template <int N>
class HandPointerOf {
 public:
  struct Target {
    bool active{};
    Axes<N> x_m{};
  };

  // The hand takes the handle toward x (a point within the workspace).
  void take(const Axes<N>& x_m) {
    std::lock_guard lock(write_mutex_);
    target_.store(Target{true, x_m});
  }
  // The hand lets the pointer go: its scripted motion again.
  void release() {
    std::lock_guard lock(write_mutex_);
    target_.store(Target{});
  }
  Target read() const noexcept { return target_.load(); }

 private:
  std::mutex write_mutex_;  // the request threads, one store at a time (Published has one writer)
  Published<Target> target_;
};

}  // namespace hapscene

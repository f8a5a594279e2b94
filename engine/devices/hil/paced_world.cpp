#include "engine/devices/hil/paced_world.hpp"

#include <sys/prctl.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>

#include "engine/base/clock.hpp"
#include "engine/base/format.hpp"

namespace hapscene {

void PacedWorld::start(double h_s) {
  stop();
  h_ns_ = std::max<std::int64_t>(1, std::llround(h_s * 1e9));
  substeps_ = 0;
  substeps_behind_1ms_ = 0;
  most_behind_ns_ = 0;
  stop_.store(false, std::memory_order_relaxed);
  gone_.store(false, std::memory_order_relaxed);
  thread_id_.store(0, std::memory_order_relaxed);
  start_ns_ = monotonic_now_ns();
  thread_ = std::thread([this] { run(); });
  running_ = true;
  // The thread's id, so the loop's real-time scheduling can cover it from the start.
  while (thread_id() == 0 && !gone()) std::this_thread::yield();
}

void PacedWorld::stop() noexcept {
  if (!running_) return;
  stop_.store(true, std::memory_order_release);
  thread_.join();
  running_ = false;
}

std::int64_t PacedWorld::elapsed_ns() const noexcept { return monotonic_now_ns() - start_ns_; }

void PacedWorld::run() noexcept {
  // Wake-ups exactly when asked (the default 50 us slack is half a substep).
  prctl(PR_SET_TIMERSLACK, 1UL, 0UL, 0UL, 0UL);
  thread_id_.store(static_cast<int>(gettid()), std::memory_order_release);
  std::int64_t world_ns = 0;  // the world's time: substeps done times h
  while (!stop_.load(std::memory_order_acquire)) {
    // Substep k covers [k h, (k + 1) h]: it runs once the wall clock is past its end.
    const std::int64_t due_ns = world_ns + h_ns_;
    const std::int64_t now_ns = elapsed_ns();
    if (now_ns < due_ns) {
      const std::int64_t wake_ns = start_ns_ + due_ns;
      const timespec wake{static_cast<time_t>(wake_ns / 1'000'000'000), static_cast<long>(wake_ns % 1'000'000'000)};
      clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &wake, nullptr);
      continue;
    }
    const std::int64_t behind_ns = now_ns - due_ns;
    most_behind_ns_ = std::max(most_behind_ns_, behind_ns);
    if (behind_ns > 1'000'000) ++substeps_behind_1ms_;
    if (!substep_(context_, static_cast<double>(h_ns_) * 1e-9)) {
      gone_.store(true, std::memory_order_release);
      break;
    }
    world_ns = due_ns;
    ++substeps_;
  }
}

std::string PacedWorld::report() const {
  if (substeps_ == 0 && !gone()) return {};
  // Behind by more than the firmware's command timeout (20 ms), the board's own watchdog
  // can have cut its motor for commands that a real board would have had in time: say so.
  const bool late_board = most_behind_ns_ > 20'000'000;
  return printf_string(
      "  world pace       %llu substeps of %.3g ms beside the loop, in real time: at most %.3f ms behind it, "
      "%llu substeps more than 1 ms behind%s\n",
      static_cast<unsigned long long>(substeps_), static_cast<double>(h_ns_) * 1e-6,
      static_cast<double>(most_behind_ns_) * 1e-6, static_cast<unsigned long long>(substeps_behind_1ms_),
      late_board ? " (more than the board's command timeout: the machine did not give the simulated board its "
                   "pace, and the run's timing is not a real board's)"
                 : "");
}

}  // namespace hapscene

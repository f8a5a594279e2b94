#pragma once
// The simulated world of a firmware-in-the-loop device (its boards' processes and the
// plant), run on a thread of its own at the wall clock's pace during a real-time run,
// beside the loop, as a real board runs beside its host. The loop's tick then never waits
// for a simulated CPU: a deadline it misses is its own (Device::begin_real_time).
//
// The world is stepped in substeps of h_s; substep k runs once the wall clock has passed
// (k + 1) h_s since start(), so the world is never ahead of real time. When it falls
// behind (its processes were not scheduled, or compute slower than real time) it catches
// up without sleeping, and report() says how far behind it fell. Outside a real-time run
// the device steps the same world in lock-step inside advance(), deterministically.
#include <atomic>
#include <cstdint>
#include <string>
#include <thread>

namespace hapscene {

class PacedWorld {
 public:
  // One substep of the world, on the world's thread; false when the world is gone for
  // good (a board's process was lost): the thread stops stepping and gone() says so.
  using Substep = bool (*)(void* context, double h_s) noexcept;

  PacedWorld(Substep substep, void* context) noexcept : substep_(substep), context_(context) {}
  ~PacedWorld() { stop(); }
  PacedWorld(const PacedWorld&) = delete;
  PacedWorld& operator=(const PacedWorld&) = delete;

  // Starts the thread, stepping from now (std::system_error when no thread can start).
  // Only the thread that calls start() calls stop(), running() and elapsed_ns().
  void start(double h_s);
  // Stops the thread and waits for it (at most a substep and the one in progress).
  void stop() noexcept;
  bool running() const noexcept { return running_; }
  // The world ended itself (from any thread).
  bool gone() const noexcept { return gone_.load(std::memory_order_acquire); }
  // The world's thread, for real-time scheduling (Linux thread id; 0 before it ran).
  int thread_id() const noexcept { return thread_id_.load(std::memory_order_acquire); }
  // Wall-clock time since start().
  std::int64_t elapsed_ns() const noexcept;

  // After stop(): one summary line ("" when the world never ran paced), and how far
  // behind the wall clock a substep began at most.
  std::string report() const;
  std::int64_t most_behind_ns() const noexcept { return most_behind_ns_; }

 private:
  void run() noexcept;

  Substep substep_;
  void* context_;
  std::thread thread_;
  bool running_{};
  std::int64_t h_ns_{};
  std::int64_t start_ns_{};
  std::atomic<bool> stop_{};
  std::atomic<bool> gone_{};
  std::atomic<int> thread_id_{};

  // Written by the world's thread, read after stop().
  std::uint64_t substeps_{};
  std::uint64_t substeps_behind_1ms_{};  // began more than 1 ms after their time
  std::int64_t most_behind_ns_{};
};

}  // namespace hapscene

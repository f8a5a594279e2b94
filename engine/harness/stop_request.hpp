#pragma once
// A request, made on another thread, that the harness work running on this thread stop:
// Python's Ctrl-C during Scene.probe, validate or test (the command line never makes
// one). The caller installs its flag for the working thread with a StopRequestScope; the
// open-loop scans (every block of calls and every creation of instances), the pace
// check's calls and validate's closed-loop runs (every tick, through PaceWatch) look at
// it, and the work ends with CheckInterrupted within a few script calls or one tick.
#include <atomic>
#include <stdexcept>

namespace hapscene {

// The work stopped on request; nothing it computed is meaningful.
class CheckInterrupted : public std::runtime_error {
 public:
  CheckInterrupted() : std::runtime_error("the check was interrupted") {}
};

// Installs `stop` for the calling thread until destroyed (then the previous one again).
class StopRequestScope {
 public:
  explicit StopRequestScope(const std::atomic<bool>* stop) noexcept;
  ~StopRequestScope();
  StopRequestScope(const StopRequestScope&) = delete;
  StopRequestScope& operator=(const StopRequestScope&) = delete;

 private:
  const std::atomic<bool>* previous_;
};

// Whether a stop was requested for the calling thread's work. No allocation, no lock.
bool stop_requested() noexcept;
// Throws CheckInterrupted when stop_requested().
void throw_if_stop_requested();

}  // namespace hapscene

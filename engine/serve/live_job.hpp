#pragma once
// The live view's slow work (a load, a validate: seconds, maybe) runs on a thread of its
// own while the HTTP handler waits for it, so that stopping the view never waits for it.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>

namespace hapscene {

// Counts a job given up on because the view stopped (abandoned_live_view_jobs() reads it).
void count_abandoned_live_view_job() noexcept;

// The state a job's thread shares with the handler waiting for it (either may go first).
template <class T>
struct JobState {
  std::mutex mutex;
  std::condition_variable done_wake;
  bool done{};
  std::optional<T> result;
  std::optional<std::string> error;  // what `work` threw: its message
};

// Runs `work` (a load, a validate: seconds, maybe) on a thread of its own and waits for
// it until it is done or `stopping` is set; then it is abandoned (nullopt): its thread
// finishes alone on the copies it captured, and the process ends with std::_Exit
// (abandoned_live_view_jobs()). So no handler keeps the view from stopping. `work`
// must capture only copies. Throws std::runtime_error with the message of what `work`
// threw: only the text crosses threads, never the exception object (whose reference count
// lives in the uninstrumented C++ runtime: ThreadSanitizer saw its release on the job's
// thread race with the handler's read of its message).
template <class T, class Work>
std::optional<T> run_job(Work work, const std::atomic<bool>& stopping) {
  if (stopping.load()) return std::nullopt;
  auto state = std::make_shared<JobState<T>>();
  std::thread([state, work = std::move(work)]() mutable {
    std::optional<T> result;
    std::optional<std::string> error;
    try {
      result.emplace(work());
    } catch (const std::exception& thrown) {
      error = thrown.what();
    } catch (...) {
      error = "an unknown error";
    }
    std::lock_guard lock(state->mutex);
    state->result = std::move(result);
    state->error = std::move(error);
    state->done = true;
    state->done_wake.notify_all();
  }).detach();
  std::unique_lock lock(state->mutex);
  while (!state->done) {
    if (stopping.load()) {
      count_abandoned_live_view_job();
      return std::nullopt;
    }
    state->done_wake.wait_for(lock, std::chrono::milliseconds(20));
  }
  if (state->error) throw std::runtime_error(*state->error);
  return std::move(state->result);
}

}  // namespace hapscene

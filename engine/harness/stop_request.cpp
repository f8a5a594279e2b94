#include "engine/harness/stop_request.hpp"

namespace hapscene {
namespace {

// The flag installed for this thread (null: none, nothing can ask it to stop).
thread_local const std::atomic<bool>* installed_stop = nullptr;

}  // namespace

StopRequestScope::StopRequestScope(const std::atomic<bool>* stop) noexcept : previous_(installed_stop) {
  installed_stop = stop;
}

StopRequestScope::~StopRequestScope() { installed_stop = previous_; }

bool stop_requested() noexcept {
  return installed_stop != nullptr && installed_stop->load(std::memory_order_relaxed);
}

void throw_if_stop_requested() {
  if (stop_requested()) throw CheckInterrupted();
}

}  // namespace hapscene

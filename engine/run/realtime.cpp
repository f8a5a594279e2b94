#include "engine/run/realtime.hpp"

#include <pthread.h>
#include <sched.h>
#include <sys/mman.h>
#include <sys/resource.h>

#include <cerrno>
#include <cstring>

namespace hapscene {

RealtimeGuard::RealtimeGuard(bool enabled) : enabled_(enabled) {
  constexpr int priority = kPriority;
  if (!enabled) {
    note_ = "off (simulated time)";
    return;
  }
  // SCHED_FIFO for this thread, remembering what it had.
  sched_param old_param{};
  pthread_getschedparam(pthread_self(), &old_policy_, &old_param);
  old_priority_ = old_param.sched_priority;
  sched_param param{};
  param.sched_priority = priority;
  const int fifo_error = pthread_setschedparam(pthread_self(), SCHED_FIFO, &param);
  fifo_ = fifo_error == 0;

  // Lock memory; future mappings too only when the lock limit cannot make them fail.
  rlimit limit{};
  getrlimit(RLIMIT_MEMLOCK, &limit);
  const int flags = limit.rlim_cur == RLIM_INFINITY ? (MCL_CURRENT | MCL_FUTURE) : MCL_CURRENT;
  const bool lock_ok = mlockall(flags) == 0;
  const int lock_error = errno;
  locked_ = lock_ok;

  // One line either way.
  if (fifo_ && locked_) {
    note_ = "SCHED_FIFO priority " + std::to_string(priority) + ", memory locked";
  } else {
    note_ = std::string(fifo_ ? "SCHED_FIFO priority " + std::to_string(priority)
                              : "normal scheduling (SCHED_FIFO not permitted: " +
                                    std::string(std::strerror(fifo_error)) + ")") +
            (locked_ ? ", memory locked"
                     : ", memory not locked (" + std::string(std::strerror(lock_error)) + ")");
  }
}

RealtimeGuard::~RealtimeGuard() {
  if (!enabled_) return;
  if (locked_) munlockall();
  if (fifo_) {
    sched_param param{};
    param.sched_priority = old_priority_;
    pthread_setschedparam(pthread_self(), old_policy_, &param);
  }
}

}  // namespace hapscene

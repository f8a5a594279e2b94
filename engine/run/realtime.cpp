#include "engine/run/realtime.hpp"

#include <pthread.h>
#include <sched.h>
#include <sys/mman.h>
#include <sys/resource.h>

#include <pwd.h>
#include <unistd.h>

#include <cerrno>
#include <climits>
#include <cstring>

namespace hapscene {
namespace {

// The running binary and the user, for the hint.
std::string executable_path() {
  char path[PATH_MAX];
  const ssize_t n = ::readlink("/proc/self/exe", path, sizeof path - 1);
  return n > 0 ? std::string(path, static_cast<std::size_t>(n)) : std::string("hapscene");
}

std::string user_name() {
  const passwd* entry = ::getpwuid(::geteuid());
  return entry != nullptr && entry->pw_name != nullptr ? std::string(entry->pw_name) : std::string("$USER");
}

}  // namespace


RealtimeGuard::RealtimeGuard(bool enabled, const std::vector<int>& lockstep_processes) : enabled_(enabled) {
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

  // Refused for lack of privilege (not for another reason): say how to allow it.
  const bool fifo_refused = !fifo_ && fifo_error == EPERM;
  const bool lock_refused = !locked_ && (lock_error == EPERM || lock_error == ENOMEM || lock_error == EAGAIN);
  hint_ = realtime_permission_hint(fifo_refused, lock_refused, executable_path(), user_name());

  // The lock-step processes: the loop's priority too, when the loop has it.
  std::string followers_note;
  std::size_t followed = 0;
  for (const int pid : fifo_ ? lockstep_processes : std::vector<int>{}) {
    if (pid <= 0) continue;
    Follower follower{pid, sched_getscheduler(pid), 0};
    sched_param old{};
    if (follower.old_policy < 0 || sched_getparam(pid, &old) != 0) continue;  // already gone
    follower.old_priority = old.sched_priority;
    if (sched_setscheduler(pid, SCHED_FIFO, &param) != 0) {
      followers_note = std::string("; not the board process (") + std::strerror(errno) + ")";
      continue;
    }
    followers_.push_back(follower);
    ++followed;
  }
  if (followed > 0) followers_note = followed == 1 ? "; the board process too" : "; the board processes too";

  // One line either way.
  if (fifo_ && locked_) {
    note_ = "SCHED_FIFO priority " + std::to_string(priority) + ", memory locked" + followers_note;
  } else {
    note_ = std::string(fifo_ ? "SCHED_FIFO priority " + std::to_string(priority)
                              : "normal scheduling (SCHED_FIFO not permitted: " +
                                    std::string(std::strerror(fifo_error)) + ")") +
            (locked_ ? ", memory locked"
                     : ", memory not locked (" + std::string(std::strerror(lock_error)) + ")") +
            followers_note;
  }
}

std::string realtime_permission_hint(bool fifo_refused, bool lock_refused, const std::string& executable,
                                     const std::string& user) {
  if (!fifo_refused && !lock_refused) return {};
  std::string limits = fifo_refused ? "\"" + user + " - rtprio 95\"" : "";
  if (lock_refused) limits += std::string(limits.empty() ? "" : " and ") + "\"" + user + " - memlock unlimited\"";
  std::string caps = fifo_refused ? "cap_sys_nice" : "";
  if (lock_refused) caps += std::string(caps.empty() ? "" : ",") + "cap_ipc_lock";
  return "add " + limits + " to /etc/security/limits.d/hapscene.conf and log in again, or run `sudo setcap " + caps +
         "+ep " + executable + "`; without " + (fifo_refused ? "it other processes can preempt the loop" :
         "it a page fault can stall a tick") + " (docs/explanation/loop.md: on a busy 2-core machine runs without "
         "SCHED_FIFO ended on overrun faults in 4 of 4 tries)";
}


RealtimeGuard::~RealtimeGuard() {
  if (!enabled_) return;
  for (const Follower& follower : followers_) {  // a process gone since is no error
    sched_param param{};
    param.sched_priority = follower.old_priority;
    sched_setscheduler(follower.pid, follower.old_policy, &param);
  }
  if (locked_) munlockall();
  if (fifo_) {
    sched_param param{};
    param.sched_priority = old_priority_;
    pthread_setschedparam(pthread_self(), old_policy_, &param);
  }
}

}  // namespace hapscene

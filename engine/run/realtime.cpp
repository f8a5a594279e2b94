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


RealtimeGuard::RealtimeGuard(bool enabled, const std::vector<int>& peers) : enabled_(enabled) {
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

  // The peers: the most CPU an ordinary task can have, when the loop has SCHED_FIFO. Not
  // SCHED_FIFO themselves: a simulated board's world can take most of a core, and real-time
  // tasks past 95% of a core's second are throttled for the rest of it (the kernel's
  // sched_rt_runtime_us) together with a loop sharing that core: stalls of 50 ms.
  std::string followers_note;
  std::size_t followed = 0;
  for (const int pid : fifo_ ? peers : std::vector<int>{}) {
    if (pid <= 0) continue;
    errno = 0;
    const int old_nice = getpriority(PRIO_PROCESS, static_cast<id_t>(pid));
    if (old_nice == -1 && errno != 0) continue;  // already gone
    if (setpriority(PRIO_PROCESS, static_cast<id_t>(pid), kPeerNice) != 0) {
      followers_note = std::string("; not the simulated world (") + std::strerror(errno) + ")";
      continue;
    }
    followers_.push_back(Follower{pid, old_nice});
    ++followed;
  }
  if (followed > 0) {
    followers_note = "; the simulated world at nice " + std::to_string(kPeerNice) + " (" + std::to_string(followed) +
                     " processes and threads)";
  }

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
    setpriority(PRIO_PROCESS, static_cast<id_t>(follower.pid), follower.old_nice);
  }
  if (locked_) munlockall();
  if (fifo_) {
    sched_param param{};
    param.sched_priority = old_priority_;
    pthread_setschedparam(pthread_self(), old_policy_, &param);
  }
}

}  // namespace hapscene

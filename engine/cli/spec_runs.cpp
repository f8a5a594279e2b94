#include "engine/cli/spec_runs.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <optional>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "engine/base/errors.hpp"
#include "engine/base/format.hpp"
#include "engine/base/object_reader.hpp"
#include "engine/cli/per_file.hpp"
#include "engine/cli/standard_output.hpp"

namespace hapscene {
namespace {

SpecVerdict verdict_of(int exit_code) {
  return exit_code == kExitOk ? SpecVerdict::pass : exit_code == kExitInvalidInput ? SpecVerdict::invalid : SpecVerdict::fail;
}

}  // namespace

SpecRun run_spec_here(const std::string& spec) {
  SpecRun run;
  SpecRecord& record = run.record;
  record.spec_path = printable(spec);
  const auto start = std::chrono::steady_clock::now();
  run.exit_code = run_for_file(
      [&] {
        SpecResult result = run_test_spec(spec);
        record.environment_path = printable(result.environment_path);
        for (SpecOutcome& outcome : result.outcomes) {
          outcome.what = printable(outcome.what);
          outcome.message = printable(outcome.message);
        }
        record.outcomes = std::move(result.outcomes);
        return result.pass ? kExitOk : kExitFailure;
      },
      &record.error);
  record.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  record.verdict = verdict_of(run.exit_code);
  return run;
}

namespace {

using SpecClock = std::chrono::steady_clock;

// A run as the child hands it to the parent.
nlohmann::json run_to_json(const SpecRun& run) {
  nlohmann::json outcomes = nlohmann::json::array();
  for (const SpecOutcome& o : run.record.outcomes) outcomes.push_back({o.what, o.pass, o.message});
  return {{"environment", run.record.environment_path}, {"error", run.record.error},
          {"seconds", run.record.seconds}, {"code", run.exit_code}, {"outcomes", outcomes}};
}

std::optional<SpecRun> run_from_json(const std::string& spec, const std::string& text) {
  try {
    const nlohmann::json j = nlohmann::json::parse(text);
    SpecRun run;
    run.record.spec_path = printable(spec);
    run.record.environment_path = j.at("environment").get<std::string>();
    run.record.error = j.at("error").get<std::string>();
    run.record.seconds = j.at("seconds").get<double>();
    run.exit_code = j.at("code").get<int>();
    for (const nlohmann::json& o : j.at("outcomes")) {
      run.record.outcomes.push_back({o.at(0).get<std::string>(), o.at(1).get<bool>(), o.at(2).get<std::string>()});
    }
    run.record.verdict = verdict_of(run.exit_code);
    return run;
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

// Writes all of `text` to `fd` (a child's pipe); false when the reader is gone.
bool write_all(int fd, const std::string& text) {
  std::size_t at = 0;
  while (at < text.size()) {
    const ssize_t n = ::write(fd, text.data() + at, text.size() - at);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    at += static_cast<std::size_t>(n);
  }
  return true;
}

// The child: stdout and stderr into `output_fd`, the result into `result_fd`; never returns.
[[noreturn]] void child_main(const std::string& spec, int result_fd, int output_fd) {
  ::dup2(output_fd, STDOUT_FILENO);
  ::dup2(output_fd, STDERR_FILENO);
  ::close(output_fd);
  int code = 0;
  try {
    const SpecRun run = run_spec_here(spec);
    std::fflush(stdout);
    std::fflush(stderr);
    code = write_all(result_fd, run_to_json(run).dump()) ? 0 : 3;
  } catch (...) {
    code = 4;
  }
  ::close(result_fd);
  ::_exit(code);
}

// A child at work: its pid, its two pipes (-1 once closed) and what came through them.
struct Child {
  std::size_t index{};
  pid_t pid{-1};
  int result_fd{-1};
  int output_fd{-1};
  std::string result;
  std::string output;
  SpecClock::time_point start;
  bool timed_out{};
};

void set_cloexec(int fd) { ::fcntl(fd, F_SETFD, FD_CLOEXEC); }

Child start_child(const std::string& spec, std::size_t index) {
  int result_pipe[2];
  int output_pipe[2];
  if (::pipe(result_pipe) != 0) throw std::runtime_error(std::string("--jobs: cannot make a pipe (") + std::strerror(errno) + ")");
  if (::pipe(output_pipe) != 0) {
    ::close(result_pipe[0]);
    ::close(result_pipe[1]);
    throw std::runtime_error(std::string("--jobs: cannot make a pipe (") + std::strerror(errno) + ")");
  }
  set_cloexec(result_pipe[0]);
  set_cloexec(output_pipe[0]);
  flush_out();
  std::fflush(stderr);
  const pid_t pid = ::fork();
  if (pid < 0) {
    for (int fd : {result_pipe[0], result_pipe[1], output_pipe[0], output_pipe[1]}) ::close(fd);
    throw std::runtime_error(std::string("--jobs: cannot start a process (") + std::strerror(errno) + ")");
  }
  if (pid == 0) {
    ::close(result_pipe[0]);
    ::close(output_pipe[0]);
    child_main(spec, result_pipe[1], output_pipe[1]);
  }
  ::close(result_pipe[1]);
  ::close(output_pipe[1]);
  Child child;
  child.index = index;
  child.pid = pid;
  child.result_fd = result_pipe[0];
  child.output_fd = output_pipe[0];
  child.start = SpecClock::now();
  return child;
}

// Reads what is there; closes the pipe at its end.
void drain(int* fd, std::string* into) {
  char buffer[4096];
  const ssize_t n = ::read(*fd, buffer, sizeof buffer);
  if (n > 0) {
    into->append(buffer, static_cast<std::size_t>(n));
  } else if (n == 0 || (errno != EINTR && errno != EAGAIN)) {
    ::close(*fd);
    *fd = -1;
  }
}

// The child's run once both pipes are closed and it has been reaped.
SpecRun finish_child(const std::string& spec, Child& child, double timeout_s) {
  int status = 0;
  while (::waitpid(child.pid, &status, 0) < 0 && errno == EINTR) {
  }
  std::optional<SpecRun> run;
  if (!child.timed_out && WIFEXITED(status) && WEXITSTATUS(status) == 0) run = run_from_json(spec, child.result);
  if (!run) {
    run.emplace();
    run->record.spec_path = printable(spec);
    run->record.verdict = SpecVerdict::fail;
    run->exit_code = kExitFailure;
    const std::string why =
        child.timed_out ? "ran longer than --spec-timeout " + format_number(timeout_s) + " s: stopped"
        : WIFSIGNALED(status)
            ? printf_string("its process ended on signal %d (%s) before its verdict", WTERMSIG(status),
                            strsignal(WTERMSIG(status)))
            : printf_string("its process ended (status %d) before its verdict", WIFEXITED(status) ? WEXITSTATUS(status) : -1);
    run->record.error = printable(spec) + ": " + why;
    run->record.seconds = std::chrono::duration<double>(SpecClock::now() - child.start).count();
    child.output += "hapscene: " + run->record.error + "\n";
  }
  run->stderr_text = std::move(child.output);
  return std::move(*run);
}

}  // namespace

void run_specs_in_processes(const std::vector<std::string>& specs, int jobs, double timeout_s,
                            const std::function<void(std::size_t, SpecRun&)>& done) {
  std::vector<std::optional<SpecRun>> finished(specs.size());
  std::vector<Child> running;
  std::size_t next_to_start = 0;
  std::size_t next_to_report = 0;
  while (next_to_report < specs.size()) {
    while (next_to_start < specs.size() && static_cast<int>(running.size()) < jobs) {
      running.push_back(start_child(specs[next_to_start], next_to_start));
      ++next_to_start;
    }
    std::vector<pollfd> fds;
    for (const Child& child : running) {
      if (child.result_fd >= 0) fds.push_back({child.result_fd, POLLIN, 0});
      if (child.output_fd >= 0) fds.push_back({child.output_fd, POLLIN, 0});
    }
    if (!fds.empty()) ::poll(fds.data(), fds.size(), 50);
    for (Child& child : running) {
      for (const pollfd& p : fds) {
        if (p.revents == 0) continue;
        if (p.fd == child.result_fd) drain(&child.result_fd, &child.result);
        if (p.fd == child.output_fd) drain(&child.output_fd, &child.output);
      }
      // Past the limit: stopped; its pipes end with it.
      if (timeout_s > 0.0 && !child.timed_out &&
          std::chrono::duration<double>(SpecClock::now() - child.start).count() > timeout_s) {
        child.timed_out = true;
        ::kill(child.pid, SIGKILL);
      }
    }
    for (std::size_t i = 0; i < running.size();) {
      Child& child = running[i];
      if (child.result_fd >= 0 || child.output_fd >= 0) {
        ++i;
        continue;
      }
      finished[child.index] = finish_child(specs[child.index], child, timeout_s);
      running.erase(running.begin() + static_cast<std::ptrdiff_t>(i));
    }
    while (next_to_report < specs.size() && finished[next_to_report]) {
      done(next_to_report, *finished[next_to_report]);
      finished[next_to_report].reset();
      ++next_to_report;
    }
  }
}

}  // namespace hapscene

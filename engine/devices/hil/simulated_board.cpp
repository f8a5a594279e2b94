#include "engine/devices/hil/simulated_board.hpp"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include "engine/base/errors.hpp"
#include "engine/base/format.hpp"
#include "engine/devices/hil/channel_io.hpp"
#include "engine/devices/hil/firmware_image.hpp"
#include "engine/devices/installed_files.hpp"

extern char** environ;

namespace hapscene {
namespace {

using namespace board_protocol;
using board_channel::read_exactly;
using board_channel::write_exactly;

// The board process loads and trial-boots within 10 s of its own clock (then it ends
// itself with SIGALRM); this bounds the wait for its first reply from this side.
constexpr int kStartTimeout_ms = 15'000;

// hapscene-board: next to the running executable (a build tree), where `cmake --install`
// put it, or where this build made it (the tests run from another folder); or
// $HAPSCENE_BOARD (engine/devices/installed_files.hpp).
std::string board_executable() {
  const std::string found = find_board_program();
  if (!found.empty()) return found;
  if (const char* chosen = std::getenv("HAPSCENE_BOARD"); chosen != nullptr && *chosen != '\0') {
    throw std::runtime_error(std::string("--device hil: HAPSCENE_BOARD=") + chosen +
                             " is not an executable file (it names the board simulator, hapscene-board)");
  }
  throw std::runtime_error("--device hil: the board simulator hapscene-board was not found (looked for " +
                           board_places_text() + "; build it with cmake, which needs simavr)");
}

}  // namespace

SimulatedBoard::SimulatedBoard(const std::string& firmware_elf) : firmware_elf_(firmware_elf) {
  // Check the firmware image before simavr sees it.
  if (!std::filesystem::is_regular_file(firmware_elf)) {
    throw InputError("--device hil: firmware " + firmware_elf + " not found (build it with cmake; "
                     "it needs gcc-avr and avr-libc)");
  }
  check_avr_firmware(firmware_elf);

  // Start the board process: the channel on its descriptor 3, its stderr into a pipe.
  const std::string executable = board_executable();
  int channel[2];
  if (socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, channel) != 0) {
    throw std::runtime_error(std::string("--device hil: no channel to the board process: ") + std::strerror(errno));
  }
  int errors[2];
  if (pipe2(errors, O_CLOEXEC) != 0) {
    close(channel[0]);
    close(channel[1]);
    throw std::runtime_error(std::string("--device hil: no pipe for the board process: ") + std::strerror(errno));
  }
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, channel[1], kChannelFd);
  posix_spawn_file_actions_adddup2(&actions, errors[1], STDERR_FILENO);
  std::string argument = firmware_elf;
  char* argv[] = {const_cast<char*>(executable.c_str()), argument.data(), nullptr};
  const int spawned = posix_spawn(&child_, executable.c_str(), &actions, nullptr, argv, environ);
  posix_spawn_file_actions_destroy(&actions);
  close(channel[1]);
  close(errors[1]);
  channel_ = channel[0];
  stderr_pipe_ = errors[0];
  if (spawned != 0) {
    child_ = -1;
    close(channel_);
    close(stderr_pipe_);
    throw std::runtime_error("--device hil: could not start " + executable + ": " + std::strerror(spawned));
  }

  // Its first reply says the firmware is loaded and booted; anything else is the
  // firmware's fault (the process checked nothing but what simavr makes of the file).
  Reply first;
  bool timed_out = false;
  if (read_exactly(channel_, &first, sizeof first, kStartTimeout_ms, &timed_out) &&
      first.byte_count <= to_host_.size() &&
      read_exactly(channel_, to_host_.data(), first.byte_count, kReplyTimeout_ms, &timed_out)) {
    to_host_count_ = first.byte_count;
    cycle_ = first.cycle;
    motor_duty_ = first.motor_duty;
    direction_high_ = first.direction_high != 0;
    return;
  }
  lose(timed_out ? Loss::timed_out : Loss::channel);
  const std::string text = said();
  const std::string detail = text.empty() ? "" : " (simavr said: " + text + ")";
  const std::string prefix = "--device hil:" + firmware_elf + ": ";
  if (loss_ == Loss::signalled && WTERMSIG(wait_status_) != SIGALRM && WTERMSIG(wait_status_) != SIGKILL) {
    throw InputError(prefix + "not a valid ATmega328P firmware: it crashed simavr while loading (" +
                     std::string(strsignal(WTERMSIG(wait_status_))) + ")" + detail);
  }
  if (loss_ == Loss::signalled || loss_ == Loss::timed_out) {
    throw InputError(prefix + "not a valid ATmega328P firmware: simavr did not finish loading it" + detail);
  }
  if (loss_ == Loss::exited && WEXITSTATUS(wait_status_) == 3) {
    throw InputError(prefix + "not a readable AVR firmware image" + detail);
  }
  throw InputError(prefix + "simavr could not load it" + detail);
}

SimulatedBoard::~SimulatedBoard() {
  // Closing the channel ends the process; wait for it (kill it if it does not end).
  if (channel_ >= 0) close(channel_);
  if (child_ > 0 && !lost_) {
    int status = 0;
    for (int i = 0; i < 200; ++i) {  // up to 1 s
      if (waitpid(child_, &status, WNOHANG) == child_) {
        child_ = -1;
        break;
      }
      usleep(5000);
    }
    if (child_ > 0) {
      kill(child_, SIGKILL);
      while (waitpid(child_, &status, 0) < 0 && errno == EINTR) {
      }
    }
  }
  if (stderr_pipe_ >= 0) close(stderr_pipe_);
}

void SimulatedBoard::run_until(std::uint64_t cycle) noexcept {
  start_run_until(cycle);
  finish_run();
}

void SimulatedBoard::start_run_until(std::uint64_t cycle) noexcept {
  running_to_ = cycle;
  if (!send_request(Op::run_until, cycle)) cycle_ = std::max(cycle_, cycle);  // a lost board: time passes
}

void SimulatedBoard::finish_run() noexcept {
  if (!receive_reply()) cycle_ = std::max(cycle_, running_to_);
}

void SimulatedBoard::reset() noexcept { exchange(Op::reset, 0); }

bool SimulatedBoard::send_byte(std::uint8_t byte) noexcept {
  if (to_board_count_ + to_board_pending_ >= kQueueBytes) return false;
  request_message_[kRequestHeaderBytes + to_board_count_++] = byte;
  return true;
}

std::size_t SimulatedBoard::take_bytes(std::uint8_t* out, std::size_t capacity) noexcept {
  std::size_t n = 0;
  while (n < capacity && to_host_count_ > 0) {
    out[n++] = to_host_[to_host_head_];
    to_host_head_ = (to_host_head_ + 1) % to_host_.size();
    --to_host_count_;
  }
  return n;
}

bool SimulatedBoard::exchange(Op op, std::uint64_t cycle) noexcept { return send_request(op, cycle) && receive_reply(); }

bool SimulatedBoard::send_request(Op op, std::uint64_t cycle) noexcept {
  if (lost_) return false;
  // The request: sensor, host bytes, what to do, as one message.
  Request request;
  request.op = op;
  request.byte_count = static_cast<std::uint16_t>(to_board_count_);
  request.sensor_counts = sensor_counts_;
  request.cycle = cycle;
  std::memcpy(request_message_.data(), &request, kRequestHeaderBytes);
  if (!write_exactly(channel_, request_message_.data(), kRequestHeaderBytes + to_board_count_)) {
    lose(Loss::channel);
    return false;
  }
  to_board_count_ = 0;
  return true;
}

bool SimulatedBoard::receive_reply() noexcept {
  if (lost_) return false;
  // The reply: pins, cycle, the board's bytes (kept in order; dropped past a full queue,
  // as the board's own queue would).
  Reply reply;
  bool timed_out = false;
  if (!read_exactly(channel_, &reply, sizeof reply, kReplyTimeout_ms, &timed_out) ||
      reply.byte_count > reply_bytes_.size() ||
      !read_exactly(channel_, reply_bytes_.data(), reply.byte_count, kReplyTimeout_ms, &timed_out)) {
    lose(timed_out ? Loss::timed_out : Loss::channel);
    return false;
  }
  for (std::size_t i = 0; i < reply.byte_count && to_host_count_ < to_host_.size(); ++i) {
    to_host_[(to_host_head_ + to_host_count_++) % to_host_.size()] = reply_bytes_[i];
  }
  cycle_ = reply.cycle;
  motor_duty_ = reply.motor_duty;
  direction_high_ = reply.direction_high != 0;
  to_board_pending_ = reply.to_board_pending;
  return true;
}

// The process is gone or useless: make sure it is gone, learn how it ended, and leave
// the pins at zero.
void SimulatedBoard::lose(Loss why) noexcept {
  lost_ = true;
  lost_at_cycle_ = cycle_;
  motor_duty_ = 0.0;
  direction_high_ = false;
  to_board_count_ = 0;
  if (child_ <= 0) {
    loss_ = why;
    return;
  }
  // A process that closed the channel is usually dying: give it a moment to say how.
  int status = 0;
  pid_t ended = 0;
  if (why == Loss::channel) {
    for (int i = 0; i < 100 && ended == 0; ++i) {  // up to 0.5 s
      ended = waitpid(child_, &status, WNOHANG);
      if (ended == 0) usleep(5000);
    }
  }
  if (ended != child_) {
    kill(child_, SIGKILL);
    while (waitpid(child_, &status, 0) < 0 && errno == EINTR) {
    }
    if (why == Loss::channel) why = Loss::timed_out;  // it broke the channel, then hung
  } else if (WIFSIGNALED(status)) {
    why = Loss::signalled;
  } else {
    why = Loss::exited;
  }
  wait_status_ = status;
  loss_ = why;
  child_ = -1;
}

std::string SimulatedBoard::said() const {
  if (stderr_pipe_ >= 0) {
    const int flags = fcntl(stderr_pipe_, F_GETFL);
    fcntl(stderr_pipe_, F_SETFL, flags | O_NONBLOCK);
    char buffer[512];
    for (;;) {
      const ssize_t n = read(stderr_pipe_, buffer, sizeof buffer);
      if (n <= 0) break;
      if (said_.size() < 2000) said_.append(buffer, static_cast<std::size_t>(n));
    }
  }
  std::string text = said_;
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
  return text;
}

std::string SimulatedBoard::failure() const {
  if (!lost_) return {};
  std::string how;
  switch (loss_) {
    case Loss::signalled:
      how = "was killed by signal " + std::to_string(WTERMSIG(wait_status_)) + " (" +
            strsignal(WTERMSIG(wait_status_)) + ")";
      break;
    case Loss::exited: how = "exited with status " + std::to_string(WEXITSTATUS(wait_status_)); break;
    case Loss::timed_out:
      how = "did not answer within " + printf_string("%g", kReplyTimeout_ms * 1e-3) + " s (killed)";
      break;
    case Loss::channel:
    case Loss::none: how = "broke its channel"; break;
  }
  const std::string text = said();
  return "the simulated board process (hapscene-board on " + firmware_elf_ + ") " + how + " at board time " +
         printf_string("%.4f", static_cast<double>(lost_at_cycle_) / kClock_Hz) + " s" +
         (text.empty() ? "" : " (simavr said: " + text + ")");
}

}  // namespace hapscene

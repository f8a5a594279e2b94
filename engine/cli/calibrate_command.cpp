// `hapscene calibrate --device SPEC [--profile NAME|FILE] [--output FILE] [--yes]`: the
// checks people otherwise do by trial and error on a new kit, in three steps, with the
// motor off except for one small, slow, force-limited pulse:
//   1. centre: the handle held upright; its reading gives the sensor's angle offset
//   2. travel: the handle moved from end to end; the sensor is read and unwrapped every
//      millisecond as the loop does, and the travel found (counts and metres) narrows the
//      workspace when the kit cannot reach the profile's
//   3. direction: with the handle let go, a force ramped slowly up to --pulse-force each
//      way, stopped as soon as the handle has moved 3 mm: moving against the force means
//      the direction sign is the other one
// The result is a profile file that "extends" the one calibrated and overrides only the
// keys the measurement changed. Prompts read standard input (Enter to go on); --yes asks
// nothing and gives each step a fixed time. On sim and hil the simulated hand plays the
// user: it holds the handle centred, moves it end to end and lets go (--simulated-kit
// FILE builds the simulated Hapkit from another profile, to rehearse on a kit that differs).
// A board that stops giving positions during a step (no fresh reading for kSilentTicks) is
// named as such, not measured as a handle that did not move.
#include <nlohmann/json.hpp>
#include <poll.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "engine/base/clock.hpp"
#include "engine/base/errors.hpp"
#include "engine/base/format.hpp"
#include "engine/base/object_reader.hpp"
#include "engine/cli/arguments.hpp"
#include "engine/cli/commands.hpp"
#include "engine/cli/option_definitions.hpp"
#include "engine/cli/output_file.hpp"
#include "engine/cli/standard_output.hpp"
#include "engine/devices/device_model.hpp"
#include "engine/devices/open_device.hpp"
#include "engine/devices/profile.hpp"

namespace hapscene {
namespace {

std::atomic<bool> g_calibrate_stop{false};
extern "C" void on_calibrate_interrupt(int /*signal*/) { g_calibrate_stop.store(true); }

constexpr double kTick_s = 1e-3;
constexpr double kCentreTolerance_m = 0.5e-3;  // a centre reading farther off: new offset
constexpr double kTravelMargin_m = 3e-3;       // workspace kept this far inside the travel
constexpr double kMinTravel_m = 20e-3;         // less: the handle was not moved end to end
constexpr double kPulseTravel_m = 3e-3;        // the pulse stops once the handle moved this far
constexpr double kPulseRamp_N_per_s = 1.0;     // slow: from 0 to 0.5 N in half a second
constexpr int kSilentTicks = 100;              // no fresh reading for this long (ms) in a step: the board stopped

// The simulated user on sim and hil: centre, then end to end, then let go.
constexpr double kCentre_s = 0.5;
HandConfig scripted_hand(const DeviceProfile& kit, double travel_s) {
  HandConfig hand;
  hand.motion = HandMotion::path;
  const double low_m = kit.plant.end_stop_min_m - 5e-3, high_m = kit.plant.end_stop_max_m + 5e-3;
  const double leg_s = (travel_s - 0.4) / 3.0;  // to one end, to the other (twice as far), back
  hand.path = {{0.0, 0.0, true},
               {kCentre_s + 0.2, 0.0, true},
               {kCentre_s + 0.2 + leg_s * 0.9, low_m, true},
               {kCentre_s + 0.2 + leg_s * 2.5, high_m, true},
               {kCentre_s + travel_s - 0.2, 0.0, true},
               {kCentre_s + travel_s, 0.0, false}};
  return hand;
}

// Ticks the device at 1 kHz: real time for a board, simulated time otherwise. Reads the
// sensor through the profile's device model, as every tick of the loop does.
class Ticker {
 public:
  Ticker(Device& device, const DeviceProfile& profile, bool simulated)
      : device_(device), model_(compile_device_model(profile)), sensor_(make_sensor_state(model_)),
        simulated_(simulated), next_ns_(monotonic_now_ns()) {}

  // One tick with `force_N` on the handle (0: motor off). Returns the position.
  double tick(double force_N) {
    if (simulated_) {
      device_.advance(kTick_s);
    } else {
      next_ns_ += static_cast<std::int64_t>(kTick_s * 1e9);
      std::int64_t wait_ns = next_ns_ - monotonic_now_ns();
      if (wait_ns < -10'000'000) {  // far behind (the machine was busy): no burst to catch up
        next_ns_ -= wait_ns;
        wait_ns = 0;
      }
      if (wait_ns > 0) std::this_thread::sleep_for(std::chrono::nanoseconds(wait_ns));
    }
    x_m_ = sense_position_m(model_, device_.read(), &sensor_);
    device_.write(force_N == 0.0 ? MotorCommand{} : motor_command(model_, sensor_, force_N));
    t_s_ += kTick_s;
    // How long the device has given no fresh position (a silent board, not a still handle).
    gap_ticks_ = fresh() ? 0 : gap_ticks_ + 1;
    longest_gap_ticks_ = std::max(longest_gap_ticks_, gap_ticks_);
    return x_m_;
  }
  // A measuring step begins: gaps before it do not count against it.
  void begin_step() { longest_gap_ticks_ = gap_ticks_; }
  // The longest run of ticks without a fresh position since begin_step().
  int longest_gap_ticks() const { return longest_gap_ticks_; }
  // Ticks for `duration_s` with the motor off, or until Enter on an interactive input.
  template <typename Each>
  void idle(double duration_s, bool until_enter, Each each) {
    for (double t0 = t_s_; t_s_ - t0 < duration_s && !g_calibrate_stop.load();) {
      each(tick(0.0));
      if (until_enter && enter_pressed()) return;
    }
  }
  bool fresh() const { return device_.position_status() == PositionStatus::fresh; }
  std::int32_t counts() const { return sensor_.unwrapped_counts; }
  double t_s() const { return t_s_; }

 private:
  // Whether a line arrived on standard input (checked every 50 ticks, never waiting).
  bool enter_pressed() {
    if (++polls_ % 50 != 0) return false;
    pollfd fd{STDIN_FILENO, POLLIN, 0};
    if (::poll(&fd, 1, 0) <= 0) return false;
    char buffer[256];
    const ssize_t n = ::read(STDIN_FILENO, buffer, sizeof buffer);
    return n <= 0 || std::find(buffer, buffer + n, '\n') != buffer + n;
  }

  Device& device_;
  DeviceModel model_;
  SensorState sensor_;
  bool simulated_;
  std::int64_t next_ns_;
  int gap_ticks_{};
  int longest_gap_ticks_{};
  double x_m_{};
  double t_s_{};
  std::uint64_t polls_{};
};

// Waits for Enter (interactive; the device keeps ticking with the motor off) or says what
// happens next (--yes).
void prompt(Ticker& ticker, bool interactive, const std::string& text) {
  print_out(interactive ? "%s [Enter] " : "%s\n", text.c_str());
  flush_out();
  if (interactive) ticker.idle(3600.0, true, [](double) {});
  if (g_calibrate_stop.load()) throw std::runtime_error("calibrate: interrupted (nothing written)");
}

struct PulseResult {
  double moved_m{};  // signed, from where the pulse started to where it stopped
  double force_N{};  // the force reached
};

// A force ramped slowly from 0 toward `direction * max_N`, ended as soon as the handle has
// moved kPulseTravel_m, then the motor off while the handle settles.
PulseResult pulse(Ticker& ticker, double direction, double max_N) {
  const double start_m = ticker.tick(0.0);
  PulseResult result;
  double force_N = 0.0;
  for (int i = 0; i < 4000 && !g_calibrate_stop.load(); ++i) {
    force_N = std::min(max_N, force_N + kPulseRamp_N_per_s * kTick_s);
    const double x_m = ticker.tick(direction * force_N);
    result.moved_m = x_m - start_m;
    result.force_N = force_N;
    if (std::abs(result.moved_m) >= kPulseTravel_m) break;
  }
  ticker.idle(0.4, false, [](double) {});
  return result;
}

// After a measuring step: whether the device stopped giving positions in it (then it says
// so, with the device's link report, and nothing is measured from the step).
bool board_stopped(const Ticker& ticker, const Device& device, const char* step) {
  if (ticker.longest_gap_ticks() < kSilentTicks) return false;
  DeviceLinkHealth health;
  device.link_health(&health);
  const std::string link = health.links > 0 ? std::string(", its link ") + health.link[0].state : std::string();
  print_out("FAIL the board stopped answering after the handshake (no reading for %d ms in the %s step%s): "
            "check its cable and power and run again (nothing written)\n%s",
            ticker.longest_gap_ticks(), step, link.c_str(), device.report().c_str());
  return true;
}

// "-1.2 mm" (never "-0.0 mm").
std::string mm(double x_m) { return printf_string("%.1f mm", std::round(x_m * 1e4) / 10.0 + 0.0); }

// The default output name: NAME-calibrated.json in the working folder.
std::string default_output(const DeviceProfile& profile) { return profile.name + "-calibrated.json"; }

}  // namespace

int calibrate_command(std::vector<std::string> args) {
  Arguments arguments(std::move(args), "hapscene calibrate");
  const std::string spec = arguments.take_value("device").value_or("sim");
  const std::string profile_name = arguments.take_value("profile").value_or("hapkit3");
  const std::optional<std::string> output_option = arguments.take_value("output");
  const std::optional<std::string> kit_name = arguments.take_value("simulated-kit");
  const bool yes = arguments.take_flag("yes");
  LinkOptions link;
  if (const auto baud = arguments.take(option::baud)) link.baud = static_cast<int>(*baud);
  const std::optional<double> travel_option = arguments.take(option::calibrate_travel_time);
  const double pulse_max_N = arguments.take(option::calibrate_pulse_force).value_or(0.5);
  if (!arguments.positionals().empty()) arguments.fail("takes no files (the profile is --profile NAME|FILE)");

  const bool simulated = spec == "sim" || spec == "hil" || spec.starts_with("hil:");
  if (kit_name && !simulated) arguments.fail("--simulated-kit: only for --device sim or hil (a real kit is what it is)");
  const DeviceProfile profile = load_device_profile(profile_name, ".");
  const DeviceProfile kit = kit_name ? load_device_profile(*kit_name, ".") : profile;
  const std::string output = output_option.value_or(default_output(profile));
  if (const std::string problem = output_path_problem({{"output", output}}, {}); !problem.empty()) arguments.fail(problem);
  if (std::filesystem::exists(output) && !yes && !output_option) {
    arguments.fail(output + " exists: name another with --output, or give --yes to replace it");
  }
  const double pulse_limit_N = std::min(2.0, profile.limits.max_force_N);
  if (pulse_max_N > pulse_limit_N) {
    arguments.fail("--pulse-force: at most " + format_number(pulse_limit_N) + " N for profile " +
                   profile_place(profile.source, "/limits/max_force") + " (and never above 2 N), got " +
                   format_number(pulse_max_N) + " N");
  }
  const double travel_s = travel_option.value_or(simulated ? 4.0 : 15.0);
  const bool interactive = !yes && !simulated;

  // The device, with the simulated user's motions on sim and hil.
  SimulationConfig simulation;
  simulation.hand = scripted_hand(kit, travel_s);
  std::unique_ptr<Device> device;
  try {
    device = open_device(spec, kit, simulation, link);
  } catch (const InputError& error) {
    arguments.fail(error.what());
  }
  std::signal(SIGINT, on_calibrate_interrupt);
  Ticker ticker(*device, profile, simulated);
  print_out("hapscene calibrate: profile %s on --device %s\n", printable(profile.name).c_str(), printable(spec).c_str());
  const Kinematics kinematics = compile_kinematics(profile);

  // 1. Centre: the reading with the handle upright gives the angle offset.
  prompt(ticker, interactive, "step 1 of 3, centre: hold the handle upright, in the middle of its travel (as at power-up)");
  double centre_sum_counts = 0.0;
  int centre_samples = 0;
  ticker.begin_step();
  ticker.idle(simulated ? kCentre_s : 1.0, false, [&](double) {
    if (!ticker.fresh()) return;
    centre_sum_counts += ticker.counts();
    ++centre_samples;
  });
  if (g_calibrate_stop.load()) throw std::runtime_error("calibrate: interrupted (nothing written)");
  if (board_stopped(ticker, *device, "centre")) return kExitFailure;
  if (centre_samples == 0) throw std::runtime_error("calibrate: the device gave no position (see its report below)\n" + device->report());
  const double centre_counts = centre_sum_counts / centre_samples;
  const double centre_m = counts_to_position_m(kinematics, centre_counts);
  print_out("  centre reads %.1f counts: %s with %s's offset\n", centre_counts + 0.0, mm(centre_m).c_str(),
            printable(profile.name).c_str());

  // 2. Travel: end to end, unwrapped as the loop does.
  prompt(ticker, interactive, printf_string("step 2 of 3, travel: move the handle slowly to one end, to the other end and "
                                    "back to the middle (%g s%s)",
                                    travel_s, interactive ? ", Enter when done" : ""));
  std::int32_t low_counts = ticker.counts(), high_counts = ticker.counts();
  ticker.begin_step();
  ticker.idle(travel_s, interactive, [&](double) {
    if (!ticker.fresh()) return;
    low_counts = std::min(low_counts, ticker.counts());
    high_counts = std::max(high_counts, ticker.counts());
  });
  if (g_calibrate_stop.load()) throw std::runtime_error("calibrate: interrupted (nothing written)");
  if (board_stopped(ticker, *device, "travel")) {
    device->write(MotorCommand{});
    return kExitFailure;
  }
  const double span = std::max(1, profile.sensor.span_counts);
  // Positions with the offset the centre step found (the slope is the profile's).
  const double offset_m = std::abs(centre_m) > kCentreTolerance_m ? centre_m : 0.0;
  const double end_a = counts_to_position_m(kinematics, low_counts) - offset_m;
  const double end_b = counts_to_position_m(kinematics, high_counts) - offset_m;
  const double travel_low_m = std::min(end_a, end_b), travel_high_m = std::max(end_a, end_b);
  print_out("  travel found: counts %d to %d (%d counts, %.2f sensor periods unwrapped), %s to %s (%s)\n", low_counts,
            high_counts, high_counts - low_counts, (high_counts - low_counts) / span, mm(travel_low_m).c_str(),
            mm(travel_high_m).c_str(), mm(travel_high_m - travel_low_m).c_str());
  if (travel_high_m - travel_low_m < kMinTravel_m) {
    device->write(MotorCommand{});
    print_out("FAIL the handle moved only %s: move it from one end of its travel to the other (nothing written)\n",
              mm(travel_high_m - travel_low_m).c_str());
    return kExitFailure;
  }

  // 3. Direction: a slow, small push each way with the handle let go.
  prompt(ticker, interactive, printf_string("step 3 of 3, motor direction: let go of the handle; the motor pushes it gently "
                                    "(at most %s N, about 3 mm) one way, then the other",
                                    format_number(pulse_max_N).c_str()));
  ticker.idle(simulated ? 0.3 : 1.0, false, [](double) {});
  ticker.begin_step();
  const PulseResult forward = pulse(ticker, +1.0, pulse_max_N);
  const PulseResult backward = pulse(ticker, -1.0, pulse_max_N);
  device->write(MotorCommand{});
  if (g_calibrate_stop.load()) throw std::runtime_error("calibrate: interrupted (nothing written)");
  if (board_stopped(ticker, *device, "motor direction")) return kExitFailure;
  print_out("  +%.2f N moved the handle %+.2f mm, -%.2f N moved it %+.2f mm\n", forward.force_N, forward.moved_m * 1e3,
            backward.force_N, backward.moved_m * 1e3);
  const bool moved = std::abs(forward.moved_m) >= kPulseTravel_m * 0.5 && std::abs(backward.moved_m) >= kPulseTravel_m * 0.5;
  const bool with_force = forward.moved_m > 0 && backward.moved_m < 0;
  const bool against_force = forward.moved_m < 0 && backward.moved_m > 0;
  if (!moved || (!with_force && !against_force)) {
    print_out("FAIL the handle did not follow the pushes (held, or friction above %s N?): let go of it and run "
              "again, or raise --pulse-force (nothing written)\n",
              format_number(pulse_max_N).c_str());
    return kExitFailure;
  }
  const int direction_sign = with_force ? profile.drive.direction_sign : -profile.drive.direction_sign;
  print_out("  the handle moves %s the force: direction_sign %d\n", with_force ? "with" : "against", direction_sign);

  // The derived profile: only what differs from the one calibrated.
  nlohmann::ordered_json derived;
  derived["extends"] = profile_name;
  derived["name"] = profile.name + "-calibrated";
  derived["description"] = "Written by hapscene calibrate on --device " + spec + ": travel " + mm(travel_low_m) + " to " +
                           mm(travel_high_m) + ".";
  std::vector<std::string> changed;
  if (offset_m != 0.0) {
    // Sector angle 0 at the centre reading: offset = -slope * counts.
    const double offset_deg = std::round(-profile.sensor.counts_to_deg_slope * centre_counts * 1e4) / 1e4;
    derived["sensor"]["counts_to_deg_offset"] = offset_deg;
    changed.push_back("sensor.counts_to_deg_offset " + format_number(offset_deg));
  }
  if (direction_sign != profile.drive.direction_sign) {
    derived["drive"]["direction_sign"] = direction_sign;
    changed.push_back("drive.direction_sign " + std::to_string(direction_sign));
  }
  // The workspace: the profile's, kept kTravelMargin_m inside the travel found (0.1 mm steps, inward).
  const double ws_low_m = std::max(profile.limits.workspace_min_m, std::ceil((travel_low_m + kTravelMargin_m) * 1e4) / 1e4);
  const double ws_high_m = std::min(profile.limits.workspace_max_m, std::floor((travel_high_m - kTravelMargin_m) * 1e4) / 1e4);
  if (ws_low_m != profile.limits.workspace_min_m || ws_high_m != profile.limits.workspace_max_m) {
    derived["limits"]["workspace"] = {printf_string("%.1f mm", ws_low_m * 1e3), printf_string("%.1f mm", ws_high_m * 1e3)};
    changed.push_back("limits.workspace [" + mm(ws_low_m) + ", " + mm(ws_high_m) + "]");
  }
  write_output_file(output, derived.dump(2) + "\n");
  // It must load as any profile does (ranges and all).
  load_device_profile(std::filesystem::absolute(output).string(), ".");
  std::string list;
  for (const std::string& item : changed) list += (list.empty() ? "" : ", ") + item;
  print_out("wrote %s: extends %s, %s\n", printable(output).c_str(), printable(profile_name).c_str(),
            changed.empty() ? "nothing differs (the shipped profile fits this kit)" : ("overrides " + list).c_str());
  print_out("use it with \"device\": \"%s\" in an environment\n", printable(output).c_str());
  return kExitOk;
}

}  // namespace hapscene

#pragma once
// What the haptic loop needs of a device with N joints: the raw sensor readings of its
// joints and a motor command per joint (DeviceIo<N> names the types; the scene's device
// model turns readings into the handle position and a force into commands). Simulated
// devices also advance their physics by one tick period.
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "engine/base/axes.hpp"
#include "engine/devices/hand_pointer.hpp"
#include "engine/devices/kinematics.hpp"
#include "engine/devices/link_health.hpp"

namespace hapscene {

// How far the latest reading can be trusted. Devices on a link report it each tick; the
// loop commands force only on a fresh one (see SafetyState::position_hold).
enum class PositionStatus : std::uint8_t {
  fresh,        // measured recently enough
  unmeasured,   // nothing measured since the device (re)connected: no force
  stale,        // the newest measurement is older than the device's bound: ramp out
  implausible,  // the latest measurement was rejected as impossible: no force
};

// Whether the device model's pose lets force be rendered (multi-joint linkages; a 1-DOF
// device's pose is always trusted): near a singular pose force ramps out, at a pose the
// linkage cannot take (or from a non-finite reading) it is cut.
enum class PoseTrust : std::uint8_t { trusted, near_singular, invalid };

// What a simulator knows and a real device cannot: the plant's true state, read by
// observers (the harness recorder, `run --plot`, the soak) beside what the host measured.
// Simulated devices implement it; for a real device Device::truth() is null.
// Handle values are Axes<N> in the device's task frame.
template <int N>
class SimulationTruthOf {
 public:
  virtual ~SimulationTruthOf() = default;
  virtual Axes<N> x_m() const noexcept = 0;           // handle position
  virtual Axes<N> v_m_per_s() const noexcept = 0;     // handle velocity
  virtual Axes<N> motor_force_N() const noexcept = 0; // what the motors apply now, at the handle
  virtual Axes<N> hand_force_N() const noexcept = 0;  // the hand's force on the handle
  // Where the virtual hand is pulling the handle now (its target motion), NaN while it
  // does not grip; devices without a hand keep this default.
  virtual Axes<N> hand_target_m() const noexcept {
    Axes<N> none{};
    if constexpr (N == 1) {
      none = std::nan("");
    } else {
      for (int i = 0; i < N; ++i) none[i] = std::nan("");
    }
    return none;
  }
};

using SimulationTruth = SimulationTruthOf<1>;

// What a device with N joints reads and takes each tick.
template <int N>
struct DeviceIo;

// The tick stages of a compiled device model (the scene's SceneParts<N>::DeviceModel), as
// step() calls them, and the variants of them it compiles ahead: a model family whose
// sensor, linkage and drive branches are decided at compile time. Each model's header
// specialises it with:
//   Variant, kGeneral           the variants; kGeneral decides the family at run time
//   kVariantsAhead              whether any other variant is compiled (step() asks first)
//   dispatch(model, f)          calls f.template operator()<V>() with the variant compiled
//                               for the model's family and returns true; false when there
//                               is none (the general tick runs)
//   sense<V>, command<V>        the model's sense_position_m and motor_command for V
//   kSteadyTick, steady_reading whether step() has a call-free tick for a steady reading
//                               (one that cannot need the sensor's rare paths), and the test
// so that step<N> names no device kind.
template <typename Model>
struct TickStages;

// One joint (the Hapkit): the sensor's counts (an MR sensor's raw, wrapping counts, or
// counts already unwrapped by the board, or an encoder's; the device model tells them
// apart) and one duty and direction.
template <>
struct DeviceIo<1> {
  using Reading = std::int32_t;
  using Command = MotorCommand;
};

// What every device answers, whatever its number of joints.
class DeviceStatus {
 public:
  virtual ~DeviceStatus() = default;
  // Lets `dt_s` of device time pass. Real devices move on their own and ignore it.
  virtual void advance(double dt_s) noexcept { (void)dt_s; }
  // True once after the device's link came back (or first came up): the loop ramps
  // force in again, as at the start of a run.
  virtual bool take_restart() noexcept { return false; }
  // The trust in the latest read() (always fresh for simulated devices).
  virtual PositionStatus position_status() const noexcept { return PositionStatus::fresh; }
  // True when the device saw a fault that should fail the run (exit 1); its report()
  // says what.
  virtual bool fault_seen() const noexcept { return false; }
  // True when the device is gone for good (a simulated board's process died): the loop
  // commands zero force and the run ends; fault_seen() is true and report() says why.
  virtual bool lost() const noexcept { return false; }
  // Whether a missed deadline can hurt: a motor keeps pushing its last command while the
  // loop is late (a firmware-in-the-loop board rehearses exactly that). A simulated
  // device's world waits for the loop, so a late tick changes nothing but the wall clock:
  // its real-time runs report overruns instead of stopping on them (RunOptions::overruns).
  virtual bool deadlines_matter() const noexcept { return true; }
  // Lines for the run summary (link health, latency, board timing); called outside the
  // loop. Empty for devices with nothing to add.
  virtual std::string report() const { return {}; }
  // The link counters so far, one entry per board (links 0 for a device without one).
  // Never allocates or blocks; reads what read() and write() change, so it is called on
  // the loop's thread (or when the loop is not running).
  virtual void link_health(DeviceLinkHealth* out) const noexcept { out->links = 0; }
  // A name per link, in link_health()'s order ("/dev/ttyACM0", "simulated board 1").
  virtual std::vector<std::string> link_names() const { return {}; }
  // A real-time run starts, and ends (called on the loop's thread, outside the loop, around
  // it). A device whose world is simulated in processes of its own (firmware-in-the-loop)
  // runs that world on a thread of its own at the wall clock's pace in between, as real
  // hardware runs beside its host, so that the loop's tick never waits for a simulated CPU;
  // its advance() then does nothing. Other devices ignore both.
  virtual void begin_real_time(double period_s) { (void)period_s; }
  virtual void end_real_time() noexcept {}
  // The processes and threads of the device's own that must keep pace with the loop
  // between begin_real_time() and end_real_time() (a simulated board's process, the thread
  // that paces it, or boards the loop waits on in lock-step), which the loop's real-time
  // scheduling covers too (RealtimeGuard). None for other devices.
  virtual std::vector<int> realtime_peers() const { return {}; }
};

template <int N>
class DeviceOf : public DeviceStatus {
 public:
  using Reading = typename DeviceIo<N>::Reading;
  using Command = typename DeviceIo<N>::Command;

  // The joints' raw readings, for the tick about to run.
  virtual Reading read() noexcept = 0;
  // The motor commands, held until the next write (sample-and-hold).
  virtual void write(const Command& command) noexcept = 0;
  // The simulator's true state, or null for a real device.
  virtual const SimulationTruthOf<N>* truth() const noexcept { return nullptr; }
  // The mailbox through which the live view's pointer takes a simulated hand
  // (hand_pointer.hpp), or null: a real device's hand is the user's own.
  virtual HandPointerOf<N>* hand_pointer() const noexcept { return nullptr; }
};

// A 1-DOF device (the Hapkit, simulated, on a serial link or firmware-in-the-loop).
using Device = DeviceOf<1>;

}  // namespace hapscene

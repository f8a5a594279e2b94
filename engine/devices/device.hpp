#pragma once
// What the haptic loop needs of a device: a raw sensor reading and a motor command.
// Simulated devices also advance their physics by one tick period.
#include <cstdint>
#include <string>

#include "engine/devices/kinematics.hpp"

namespace hapscene {

// How far the latest reading can be trusted. Devices on a link report it each tick; the
// loop commands force only on a fresh one (see SafetyState::position_hold).
enum class PositionStatus : std::uint8_t {
  fresh,        // measured recently enough
  unmeasured,   // nothing measured since the device (re)connected: no force
  stale,        // the newest measurement is older than the device's bound: ramp out
  implausible,  // the latest measurement was rejected as impossible: no force
};

// What a simulator knows and a real device cannot: the plant's true state, read by
// observers (the harness recorder, `run --plot`, the soak) beside what the host measured.
// Simulated devices implement it; for a real device Device::truth() is null.
class SimulationTruth {
 public:
  virtual ~SimulationTruth() = default;
  virtual double x_m() const noexcept = 0;           // handle position
  virtual double v_m_per_s() const noexcept = 0;     // handle velocity
  virtual double motor_force_N() const noexcept = 0;      // what the motor applies now
  virtual double hand_force_N() const noexcept = 0;       // the hand's force on the handle
};

class Device {
 public:
  virtual ~Device() = default;
  // The sensor reading in counts of the MR sensor: raw (wrapping) or already unwrapped by
  // the board; the loop's flip counter leaves a continuous reading as it is.
  virtual std::int32_t read_counts() noexcept = 0;
  // The motor command, held until the next write (sample-and-hold).
  virtual void write(const MotorCommand& command) noexcept = 0;
  // Lets `dt_s` of device time pass. Real devices move on their own and ignore it.
  virtual void advance(double dt_s) noexcept { (void)dt_s; }
  // True once after the device's link came back (or first came up): the loop ramps
  // force in again, as at the start of a run.
  virtual bool take_restart() noexcept { return false; }
  // The trust in the reading of the latest read_counts() (always fresh for simulated
  // devices).
  virtual PositionStatus position_status() const noexcept { return PositionStatus::fresh; }
  // True when the device saw a fault that should fail the run (exit 1); its report()
  // says what.
  virtual bool fault_seen() const noexcept { return false; }
  // True when the device is gone for good (a simulated board's process died): the loop
  // commands zero force and the run ends; fault_seen() is true and report() says why.
  virtual bool lost() const noexcept { return false; }
  // Lines for the run summary (link health, latency, board timing); called outside the
  // loop. Empty for devices with nothing to add.
  virtual std::string report() const { return {}; }
  // The simulator's true state, or null for a real device.
  virtual const SimulationTruth* truth() const noexcept { return nullptr; }
};

}  // namespace hapscene

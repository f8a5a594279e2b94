#pragma once
// A simple virtual hand for simulated runs: a spring-damper (with an optional mass that
// moves with the paddle while the hand grips it) pulling the handle toward a reference
// motion. "sweep" moves slowly across the workspace and back (pushing into whatever is
// there), "hold" holds one position, "release" holds it and lets go at release_s (does
// the spring oscillate?), "shake" oscillates fast and small around hold_m, "path"
// follows timed waypoints (the harness's press scenario), "none" leaves the handle alone.
#include <string_view>
#include <vector>

#include "engine/devices/hand_pointer.hpp"

namespace hapscene {

enum class HandMotion { none, hold, sweep, release, shake, path };

inline constexpr std::string_view kHandMotionNames[] = {"none",    "hold",  "sweep",
                                                        "release", "shake", "path"};

// One point of a "path" motion: the reference is linear in time between points; the
// hand grips from this point to the next when `grip` is true, and is off otherwise.
struct HandWaypoint {
  double t_s{};
  double x_m{};
  bool grip{true};
};

struct HandConfig {
  HandMotion motion{HandMotion::sweep};
  double stiffness_N_per_m{200.0};  // grip stiffness of a relaxed hand on the paddle
  double damping_N_s_per_m{2.0};
  double mass_kg{0.0};              // hand mass moving with the paddle while gripping
  double speed_m_per_s{0.08};       // sweep speed
  double sweep_min_m{-0.04};
  double sweep_max_m{0.04};
  double hold_m{0.0};               // hold, release and shake position
  double release_s{0.5};            // release: when the hand lets go
  double shake_amplitude_m{0.002};  // shake: reference hold_m + A sin(2 pi f t)
  double shake_frequency_Hz{8.0};
  std::vector<HandWaypoint> path;   // path: at least one point, times increasing
};

class VirtualHand {
 public:
  VirtualHand(const HandConfig& config, double start_x_m);

  // Force of the hand on the handle at time t for handle position x and velocity v.
  double force_N(double t_s, double x_m, double v_m_per_s) const noexcept;
  // Where the hand wants the handle at time t, and how fast that point moves.
  double reference_m(double t_s) const noexcept;
  double reference_velocity_m_per_s(double t_s) const noexcept;
  // Whether the hand touches the paddle at time t.
  bool gripping(double t_s) const noexcept;
  // The mass the hand adds to the handle at time t.
  double added_mass_kg(double t_s) const noexcept {
    return gripping(t_s) ? config_.mass_kg : 0.0;
  }
  // While `pointer` is active (the live view's user dragging), the hand grips and its
  // reference is the pointer, still (hand_pointer.hpp). Null: the scripted motion only.
  void follow(const HandPointerOf<1>* pointer) noexcept { pointer_ = pointer; }
  // Reads the pointer once for the plant's next step: every call until the next refresh
  // sees the same target (a take or release mid-step cannot tear the step).
  void refresh_pointer() noexcept {
    if (pointer_ != nullptr) pointer_now_ = pointer_->read();
  }

 private:
  double sweep_phase_m(double t_s) const noexcept;
  // Index of the path segment containing t (the last point once past it).
  std::size_t path_segment(double t_s) const noexcept;

  HandConfig config_;
  double start_x_m_;
  const HandPointerOf<1>* pointer_{};
  HandPointerOf<1>::Target pointer_now_{};  // the pointer as the step in progress saw it
};

}  // namespace hapscene

#pragma once
// A simple virtual hand for simulated runs: a spring-damper pulling the handle toward a
// reference motion. "sweep" moves slowly across the workspace and back (pushing into
// whatever is there), "hold" holds one position, "release" holds it and lets go at
// release_s (does the spring oscillate?), "none" leaves the handle alone.
#include <string_view>

namespace hapscene {

enum class HandMotion { none, hold, sweep, release };

inline constexpr std::string_view kHandMotionNames[] = {"none", "hold", "sweep", "release"};

struct HandConfig {
  HandMotion motion{HandMotion::sweep};
  double stiffness_N_per_m{200.0};  // grip stiffness of a relaxed hand on the paddle
  double damping_N_s_per_m{2.0};
  double speed_m_per_s{0.08};       // sweep speed
  double sweep_min_m{-0.04};
  double sweep_max_m{0.04};
  double hold_m{0.0};               // hold and release position
  double release_s{0.5};            // release: when the hand lets go
};

class VirtualHand {
 public:
  VirtualHand(const HandConfig& config, double start_x_m);

  // Force of the hand on the handle at time t for handle position x and velocity v.
  double force_N(double t_s, double x_m, double v_m_per_s) const noexcept;
  // Where the hand wants the handle at time t, and how fast that point moves.
  double reference_m(double t_s) const noexcept;
  double reference_velocity_m_per_s(double t_s) const noexcept;

 private:
  double sweep_phase_m(double t_s) const noexcept;

  HandConfig config_;
  double start_x_m_;
};

}  // namespace hapscene

#include "engine/devices/virtual_hand.hpp"

#include <algorithm>
#include <cmath>

namespace hapscene {

VirtualHand::VirtualHand(const HandConfig& config, double start_x_m)
    : config_(config), start_x_m_(start_x_m) {}

// The sweep is a triangle wave between sweep_min_m and sweep_max_m that starts at the
// start position and moves up first: the distance travelled, folded onto one period
// [0, 2 L). Below L the hand moves up, above it down.
double VirtualHand::sweep_phase_m(double t_s) const noexcept {
  const double length_m = config_.sweep_max_m - config_.sweep_min_m;
  const double start_m = std::clamp(start_x_m_, config_.sweep_min_m, config_.sweep_max_m);
  const double travelled_m = (start_m - config_.sweep_min_m) + config_.speed_m_per_s * t_s;
  return std::fmod(travelled_m, 2.0 * length_m);
}

double VirtualHand::reference_m(double t_s) const noexcept {
  switch (config_.motion) {
    case HandMotion::none: return start_x_m_;
    case HandMotion::hold:
    case HandMotion::release: return config_.hold_m;
    case HandMotion::sweep: {
      const double length_m = config_.sweep_max_m - config_.sweep_min_m;
      const double phase_m = sweep_phase_m(t_s);
      return phase_m <= length_m ? config_.sweep_min_m + phase_m
                                 : config_.sweep_max_m - (phase_m - length_m);
    }
  }
  return start_x_m_;
}

double VirtualHand::reference_velocity_m_per_s(double t_s) const noexcept {
  if (config_.motion != HandMotion::sweep) return 0.0;
  const double length_m = config_.sweep_max_m - config_.sweep_min_m;
  return sweep_phase_m(t_s) <= length_m ? config_.speed_m_per_s : -config_.speed_m_per_s;
}

double VirtualHand::force_N(double t_s, double x_m, double v_m_per_s) const noexcept {
  if (config_.motion == HandMotion::none) return 0.0;
  if (config_.motion == HandMotion::release && t_s >= config_.release_s) return 0.0;
  return config_.stiffness_N_per_m * (reference_m(t_s) - x_m) +
         config_.damping_N_s_per_m * (reference_velocity_m_per_s(t_s) - v_m_per_s);
}

}  // namespace hapscene

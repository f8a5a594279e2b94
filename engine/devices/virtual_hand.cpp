#include "engine/devices/virtual_hand.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

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

// Paths are short (tens of points): a linear scan from the start is cheap enough.
std::size_t VirtualHand::path_segment(double t_s) const noexcept {
  std::size_t i = 0;
  while (i + 1 < config_.path.size() && config_.path[i + 1].t_s <= t_s) ++i;
  return i;
}

double VirtualHand::reference_m(double t_s) const noexcept {
  if (pointer_now_.active) return pointer_now_.x_m;
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
    case HandMotion::shake:
      return config_.hold_m + config_.shake_amplitude_m *
                                  std::sin(2.0 * std::numbers::pi * config_.shake_frequency_Hz * t_s);
    case HandMotion::path: {
      if (config_.path.empty()) return start_x_m_;
      const std::size_t i = path_segment(t_s);
      const HandWaypoint& a = config_.path[i];
      if (i + 1 >= config_.path.size() || t_s <= a.t_s) return a.x_m;
      const HandWaypoint& b = config_.path[i + 1];
      return a.x_m + (b.x_m - a.x_m) * (t_s - a.t_s) / (b.t_s - a.t_s);
    }
  }
  return start_x_m_;
}

double VirtualHand::reference_velocity_m_per_s(double t_s) const noexcept {
  if (pointer_now_.active) return 0.0;
  switch (config_.motion) {
    case HandMotion::sweep: {
      const double length_m = config_.sweep_max_m - config_.sweep_min_m;
      return sweep_phase_m(t_s) <= length_m ? config_.speed_m_per_s : -config_.speed_m_per_s;
    }
    case HandMotion::shake: {
      const double w_rad_per_s = 2.0 * std::numbers::pi * config_.shake_frequency_Hz;
      return config_.shake_amplitude_m * w_rad_per_s * std::cos(w_rad_per_s * t_s);
    }
    case HandMotion::path: {
      if (config_.path.empty()) return 0.0;
      const std::size_t i = path_segment(t_s);
      if (i + 1 >= config_.path.size() || t_s < config_.path[i].t_s) return 0.0;
      const HandWaypoint& a = config_.path[i];
      const HandWaypoint& b = config_.path[i + 1];
      return (b.x_m - a.x_m) / (b.t_s - a.t_s);
    }
    default: return 0.0;
  }
}

bool VirtualHand::gripping(double t_s) const noexcept {
  if (pointer_now_.active) return true;
  switch (config_.motion) {
    case HandMotion::none: return false;
    case HandMotion::release: return t_s < config_.release_s;
    case HandMotion::path:
      return !config_.path.empty() && config_.path[path_segment(t_s)].grip;
    default: return true;
  }
}

double VirtualHand::force_N(double t_s, double x_m, double v_m_per_s) const noexcept {
  if (!gripping(t_s)) return 0.0;
  return config_.stiffness_N_per_m * (reference_m(t_s) - x_m) +
         config_.damping_N_s_per_m * (reference_velocity_m_per_s(t_s) - v_m_per_s);
}

}  // namespace hapscene

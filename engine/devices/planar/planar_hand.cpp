#include "engine/devices/planar/planar_hand.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "engine/base/errors.hpp"

namespace hapscene {
namespace {

void require(bool ok, const char* field, const char* what) {
  if (!ok) throw InputError(std::string("hand ") + field + ": " + what);
}

bool finite(const Vec2& v) { return all_finite(v); }

}  // namespace

PlanarHand::PlanarHand(const PlanarHandConfig& config, const Vec2& start_m)
    : config_(config), start_m_(start_m) {
  const PlanarHandConfig& c = config_;
  require(finite(start_m), "start", "must be finite");
  require(std::isfinite(c.stiffness_N_per_m) && c.stiffness_N_per_m >= 0.0, "stiffness", "must be finite and >= 0");
  require(std::isfinite(c.damping_N_s_per_m) && c.damping_N_s_per_m >= 0.0, "damping", "must be finite and >= 0");
  require(std::isfinite(c.mass_kg) && c.mass_kg >= 0.0, "mass", "must be finite and >= 0");
  switch (c.motion) {
    case PlanarHandMotion::none: break;
    case PlanarHandMotion::hold: require(finite(c.hold_m), "hold", "must be finite"); break;
    case PlanarHandMotion::release:
      require(finite(c.hold_m), "hold", "must be finite");
      require(std::isfinite(c.release_s), "release time", "must be finite");
      break;
    case PlanarHandMotion::shake:
      require(finite(c.hold_m), "hold", "must be finite");
      require(unit_vector(c.shake_direction, &config_.shake_direction), "shake direction",
              "must be a finite, non-zero vector");
      require(std::isfinite(c.shake_amplitude_m) && std::isfinite(c.shake_frequency_Hz), "shake", "amplitude and frequency must be finite");
      break;
    case PlanarHandMotion::line:
    case PlanarHandMotion::circle:
    case PlanarHandMotion::sweep:
      require(std::isfinite(c.speed_m_per_s) && c.speed_m_per_s > 0.0, "speed", "must be finite and > 0");
      if (c.motion == PlanarHandMotion::line) {
        require(finite(c.line_from_m) && finite(c.line_to_m), "line", "ends must be finite");
      } else if (c.motion == PlanarHandMotion::circle) {
        require(finite(c.circle_center_m), "circle centre", "must be finite");
        require(std::isfinite(c.circle_radius_m) && c.circle_radius_m > 0.0, "circle radius", "must be finite and > 0");
        require(std::isfinite(c.circle_start_rad), "circle start angle", "must be finite");
      } else {
        require(finite(c.sweep_min_m) && finite(c.sweep_max_m), "sweep box", "must be finite");
        require(c.sweep_min_m[0] < c.sweep_max_m[0] && c.sweep_min_m[1] <= c.sweep_max_m[1], "sweep box",
                "min must be below max in x (and not above it in y)");
        require(std::isfinite(c.sweep_pitch_m) && c.sweep_pitch_m > 0.0, "sweep pitch", "must be finite and > 0");
        require((c.sweep_max_m[1] - c.sweep_min_m[1]) / c.sweep_pitch_m < 1e5, "sweep pitch", "gives more than 100000 rows");
      }
      build_polyline();
      break;
    case PlanarHandMotion::path:
      require(!c.path.empty(), "path", "needs at least one point");
      for (std::size_t i = 0; i < c.path.size(); ++i) {
        require(std::isfinite(c.path[i].t_s) && finite(c.path[i].p_m), "path", "points must be finite");
        require(i == 0 || c.path[i].t_s > c.path[i - 1].t_s, "path", "times must increase");
      }
      break;
  }
}

// The polyline's points: the start, then the motion's own points. Line and sweep walk it
// at the speed; the circle uses only the lead-in (start to its first point).
void PlanarHand::build_polyline() {
  const PlanarHandConfig& c = config_;
  points_.push_back(start_m_);
  switch (c.motion) {
    case PlanarHandMotion::line:
      points_.push_back(c.line_from_m);
      points_.push_back(c.line_to_m);
      back_and_forth_ = c.line_back_and_forth;
      break;
    case PlanarHandMotion::circle: {
      const double a = c.circle_start_rad;
      points_.push_back(c.circle_center_m + c.circle_radius_m * Vec2{{std::cos(a), std::sin(a)}});
      break;
    }
    case PlanarHandMotion::sweep: {
      const auto rows = static_cast<int>(std::ceil((c.sweep_max_m[1] - c.sweep_min_m[1]) / c.sweep_pitch_m - 1e-9));
      for (int row = 0; row <= rows; ++row) {
        const double y = std::min(c.sweep_min_m[1] + row * c.sweep_pitch_m, c.sweep_max_m[1]);
        const bool rightward = row % 2 == 0;
        points_.push_back(Vec2{{rightward ? c.sweep_min_m[0] : c.sweep_max_m[0], y}});
        points_.push_back(Vec2{{rightward ? c.sweep_max_m[0] : c.sweep_min_m[0], y}});
      }
      back_and_forth_ = true;
      break;
    }
    default: break;
  }
  loop_begin_ = 1;
  distance_m_.assign(points_.size(), 0.0);
  for (std::size_t i = 1; i < points_.size(); ++i) {
    distance_m_[i] = distance_m_[i - 1] + norm(points_[i] - points_[i - 1]);
  }
  lead_in_m_ = distance_m_[1];
}

// Distance s = speed t along the polyline: the lead-in once, then the loop part once or
// folded back and forth. The point is found by bisection on the cumulative distances.
void PlanarHand::polyline_at(double t_s, Vec2* p_m, Vec2* v_m_per_s) const noexcept {
  const double speed = config_.speed_m_per_s;
  double s = std::max(0.0, speed * t_s);
  double direction = 1.0;
  const double loop_start = distance_m_[loop_begin_];
  const double loop_length = distance_m_.back() - loop_start;
  if (s > loop_start) {
    if (back_and_forth_ && loop_length > 0.0) {
      const double phase = std::fmod(s - loop_start, 2.0 * loop_length);
      if (phase <= loop_length) {
        s = loop_start + phase;
      } else {
        s = loop_start + 2.0 * loop_length - phase;
        direction = -1.0;
      }
    } else if (s >= distance_m_.back()) {
      *p_m = points_.back();
      *v_m_per_s = Vec2{};
      return;
    }
  }
  // The segment [i, i + 1] holding s (moving forward: the later one at a shared point).
  const auto it = std::upper_bound(distance_m_.begin(), distance_m_.end(), s);
  std::size_t i = static_cast<std::size_t>(it - distance_m_.begin());
  i = i == 0 ? 0 : i - 1;
  if (i + 1 >= points_.size()) i = points_.size() - 2;
  // Skip zero-length segments (the start on the path's first point).
  while (i + 2 < points_.size() && distance_m_[i + 1] - distance_m_[i] <= 0.0) ++i;
  const double length = distance_m_[i + 1] - distance_m_[i];
  if (!(length > 0.0)) {
    *p_m = points_[i + 1];
    *v_m_per_s = Vec2{};
    return;
  }
  const Vec2 along = (points_[i + 1] - points_[i]) / length;
  *p_m = points_[i] + (s - distance_m_[i]) * along;
  *v_m_per_s = direction * speed * along;
}

void PlanarHand::circle_at(double t_s, Vec2* p_m, Vec2* v_m_per_s) const noexcept {
  const PlanarHandConfig& c = config_;
  const double s = std::max(0.0, c.speed_m_per_s * t_s);
  if (s < lead_in_m_) {
    polyline_at(t_s, p_m, v_m_per_s);
    return;
  }
  const double turn = c.circle_clockwise ? -1.0 : 1.0;
  const double angle = c.circle_start_rad + turn * (s - lead_in_m_) / c.circle_radius_m;
  const Vec2 radial{{std::cos(angle), std::sin(angle)}};
  *p_m = c.circle_center_m + c.circle_radius_m * radial;
  *v_m_per_s = turn * c.speed_m_per_s * Vec2{{-radial[1], radial[0]}};
}

std::size_t PlanarHand::path_segment(double t_s) const noexcept {
  const auto& path = config_.path;
  const auto it = std::upper_bound(path.begin(), path.end(), t_s,
                                   [](double t, const PlanarHandWaypoint& w) { return t < w.t_s; });
  const auto i = static_cast<std::size_t>(it - path.begin());
  return i == 0 ? 0 : i - 1;
}

Vec2 PlanarHand::reference_m(double t_s) const noexcept {
  if (pointer_now_.active) return pointer_now_.x_m;
  Vec2 p{}, v{};
  switch (config_.motion) {
    case PlanarHandMotion::none: return start_m_;
    case PlanarHandMotion::hold:
    case PlanarHandMotion::release: return config_.hold_m;
    case PlanarHandMotion::shake:
      return config_.hold_m + config_.shake_amplitude_m *
                                  std::sin(2.0 * std::numbers::pi * config_.shake_frequency_Hz * t_s) *
                                  config_.shake_direction;
    case PlanarHandMotion::line:
    case PlanarHandMotion::sweep: polyline_at(t_s, &p, &v); return p;
    case PlanarHandMotion::circle: circle_at(t_s, &p, &v); return p;
    case PlanarHandMotion::path: {
      const auto& path = config_.path;
      const std::size_t i = path_segment(t_s);
      if (i + 1 >= path.size() || t_s <= path[i].t_s) return path[i].p_m;
      const PlanarHandWaypoint& a = path[i];
      const PlanarHandWaypoint& b = path[i + 1];
      return a.p_m + (t_s - a.t_s) / (b.t_s - a.t_s) * (b.p_m - a.p_m);
    }
  }
  return start_m_;
}

Vec2 PlanarHand::reference_velocity_m_per_s(double t_s) const noexcept {
  if (pointer_now_.active) return Vec2{};
  Vec2 p{}, v{};
  switch (config_.motion) {
    case PlanarHandMotion::shake: {
      const double w = 2.0 * std::numbers::pi * config_.shake_frequency_Hz;
      return config_.shake_amplitude_m * w * std::cos(w * t_s) * config_.shake_direction;
    }
    case PlanarHandMotion::line:
    case PlanarHandMotion::sweep: polyline_at(t_s, &p, &v); return v;
    case PlanarHandMotion::circle: circle_at(t_s, &p, &v); return v;
    case PlanarHandMotion::path: {
      const auto& path = config_.path;
      const std::size_t i = path_segment(t_s);
      if (i + 1 >= path.size() || t_s < path[i].t_s) return Vec2{};
      return (path[i + 1].p_m - path[i].p_m) / (path[i + 1].t_s - path[i].t_s);
    }
    default: return Vec2{};
  }
}

bool PlanarHand::gripping(double t_s) const noexcept {
  if (pointer_now_.active) return true;
  switch (config_.motion) {
    case PlanarHandMotion::none: return false;
    case PlanarHandMotion::release: return t_s < config_.release_s;
    case PlanarHandMotion::path: return config_.path[path_segment(t_s)].grip;
    default: return true;
  }
}

Vec2 PlanarHand::force_N(double t_s, const Vec2& p_m, const Vec2& v_m_per_s) const noexcept {
  if (!gripping(t_s)) return Vec2{};
  return config_.stiffness_N_per_m * (reference_m(t_s) - p_m) +
         config_.damping_N_s_per_m * (reference_velocity_m_per_s(t_s) - v_m_per_s);
}

// Corners of the polyline as distances along the walk: the lead-in's points once, then the
// loop's points, unfolded (forward, then backward) period after period when it goes back
// and forth.
double PlanarHand::next_polyline_corner_s(double t_s) const noexcept {
  // A corner within a picometre of s (rounding) is the one just passed.
  const double speed = config_.speed_m_per_s;
  const double s = std::max(0.0, speed * t_s) + 1e-12;
  const double loop_start = distance_m_[loop_begin_];
  const double loop_length = distance_m_.back() - loop_start;
  if (s < loop_start || !back_and_forth_ || !(loop_length > 0.0)) {
    for (std::size_t i = 1; i < distance_m_.size(); ++i) {
      if (distance_m_[i] > s) return distance_m_[i] / speed;
    }
    return INFINITY;
  }
  const double cycle = 2.0 * loop_length;
  const double cycle_start = loop_start + std::floor((s - loop_start) / cycle) * cycle;
  const double phase = s - cycle_start;
  double best = INFINITY;
  for (std::size_t i = loop_begin_; i < distance_m_.size(); ++i) {
    const double forward = distance_m_[i] - loop_start;
    for (const double corner : {forward, cycle - forward, cycle + forward}) {
      if (corner > phase && corner < best) best = corner;
    }
  }
  return (cycle_start + best) / speed;
}

double PlanarHand::next_break_s(double t_s) const noexcept {
  t_s += 1e-12;  // a break within a picosecond of t (rounding) is the one just passed
  switch (config_.motion) {
    case PlanarHandMotion::line:
    case PlanarHandMotion::sweep: return next_polyline_corner_s(t_s);
    case PlanarHandMotion::circle: {
      const double corner_s = lead_in_m_ / config_.speed_m_per_s;
      return corner_s > t_s ? corner_s : INFINITY;
    }
    case PlanarHandMotion::release: return config_.release_s > t_s ? config_.release_s : INFINITY;
    case PlanarHandMotion::path: {
      for (const PlanarHandWaypoint& w : config_.path) {
        if (w.t_s > t_s) return w.t_s;
      }
      return INFINITY;
    }
    default: return INFINITY;
  }
}

}  // namespace hapscene

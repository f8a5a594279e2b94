#pragma once
// The 2-D virtual hand for simulated 2-DOF runs: an isotropic spring-damper (with an
// optional mass that moves with the handle while the hand grips it) pulling the handle
// toward a reference path p_ref(t), as the 1-D VirtualHand does along one axis:
//   F = K (p_ref - p) + B (v_ref - v) while gripping, 0 otherwise.
// Reference paths (all start where the handle starts; the moving ones first travel at
// their speed from there to where their path begins, so the hand never jumps):
//   none     no grip: the handle is left alone
//   hold     hold one point
//   line     from line_from_m to line_to_m at speed_m_per_s, then hold there (or go back
//            and forth between the two when line_back_and_forth)
//   circle   around circle_center_m at radius circle_radius_m and speed_m_per_s, from
//            the angle circle_start_rad, counter-clockwise unless circle_clockwise
//   sweep    a raster that covers the box [sweep_min_m, sweep_max_m]: rows along x spaced
//            sweep_pitch_m apart from the bottom row to the top one, serpentine, at
//            speed_m_per_s, then back the same way, forever
//   release  hold hold_m (a displaced pose) until release_s, then let go
//   shake    hold_m + shake_amplitude_m sin(2 pi f t) along shake_direction
//   path     timed waypoints, linear in time between them; the hand grips from a point
//            to the next while that point's grip is true (the harness's press scenarios)
// Deterministic; no allocation after construction.
#include <cstdint>
#include <string_view>
#include <vector>

#include "engine/base/axes.hpp"
#include "engine/devices/hand_pointer.hpp"

namespace hapscene {

enum class PlanarHandMotion : std::uint8_t { none, hold, line, circle, sweep, release, shake, path };

inline constexpr std::string_view kPlanarHandMotionNames[] = {"none",  "hold",    "line",  "circle",
                                                              "sweep", "release", "shake", "path"};

struct PlanarHandWaypoint {
  double t_s{};
  Vec2 p_m{};
  bool grip{true};
};

struct PlanarHandConfig {
  PlanarHandMotion motion{PlanarHandMotion::none};
  double stiffness_N_per_m{200.0};  // grip stiffness, the same in every direction
  double damping_N_s_per_m{2.0};
  double mass_kg{0.0};              // moves with the handle while gripping
  double speed_m_per_s{0.05};       // line, circle, sweep and their lead-in from the start
  Vec2 hold_m{};                    // hold, release, shake
  Vec2 line_from_m{};
  Vec2 line_to_m{};
  bool line_back_and_forth{false};
  Vec2 circle_center_m{};
  double circle_radius_m{0.01};
  double circle_start_rad{0.0};
  bool circle_clockwise{false};
  Vec2 sweep_min_m{};
  Vec2 sweep_max_m{};
  double sweep_pitch_m{0.005};
  double release_s{0.5};
  Vec2 shake_direction{{1.0, 0.0}};
  double shake_amplitude_m{0.002};
  double shake_frequency_Hz{8.0};
  std::vector<PlanarHandWaypoint> path;  // path: at least one point, times increasing
};

class PlanarHand {
 public:
  // Throws InputError naming the field when the configuration cannot describe a path
  // (a non-positive speed, radius or pitch, an empty box, an unordered path, non-finite
  // numbers).
  PlanarHand(const PlanarHandConfig& config, const Vec2& start_m);

  // Where the hand wants the handle at time t, and how fast that point moves.
  Vec2 reference_m(double t_s) const noexcept;
  Vec2 reference_velocity_m_per_s(double t_s) const noexcept;
  // Whether the hand touches the handle at time t.
  bool gripping(double t_s) const noexcept;
  double added_mass_kg(double t_s) const noexcept { return gripping(t_s) ? config_.mass_kg : 0.0; }
  // The hand's force on the handle at time t for handle position p and velocity v.
  Vec2 force_N(double t_s, const Vec2& p_m, const Vec2& v_m_per_s) const noexcept;
  // The first time after t where the force jumps (a corner of the path, where the
  // reference velocity changes at once; a waypoint; a release), or infinity. The plant ends
  // its integration steps there so that no step straddles a jump.
  double next_break_s(double t_s) const noexcept;
  // While `pointer` is active (the live view's user dragging), the hand grips and its
  // reference is the pointer, still (hand_pointer.hpp). Null: the scripted motion only.
  void follow(const HandPointerOf<2>* pointer) noexcept { pointer_ = pointer; }
  // Reads the pointer once for the plant's next step: every call until the next refresh
  // sees the same target (a take or release mid-step cannot tear the step).
  void refresh_pointer() noexcept {
    if (pointer_ != nullptr) pointer_now_ = pointer_->read();
  }

  const PlanarHandConfig& config() const noexcept { return config_; }

 private:
  // A polyline walked at constant speed: the lead-in points [0, loop_begin_] once, then
  // the rest once (holding the last point) or back and forth.
  void build_polyline();
  void polyline_at(double t_s, Vec2* p_m, Vec2* v_m_per_s) const noexcept;
  void circle_at(double t_s, Vec2* p_m, Vec2* v_m_per_s) const noexcept;
  std::size_t path_segment(double t_s) const noexcept;
  double next_polyline_corner_s(double t_s) const noexcept;

  PlanarHandConfig config_;
  const HandPointerOf<2>* pointer_{};
  HandPointerOf<2>::Target pointer_now_{};  // the pointer as the step in progress saw it
  Vec2 start_m_;
  std::vector<Vec2> points_;
  std::vector<double> distance_m_;  // along the polyline to each point
  std::size_t loop_begin_{};
  bool back_and_forth_{};
  double lead_in_m_{};              // circle: distance from the start to the circle
};

}  // namespace hapscene

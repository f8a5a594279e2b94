#pragma once
// The scenarios `hapscene validate` runs on a 2-DOF (planar) scene, each named,
// deterministic and built from the scene (its workspace box, its shapes as
// planar_shape_list gives them) and the harness options. The hand is the 2-D virtual hand
// (engine/devices/planar/planar_hand.hpp) with the options' grip; every run starts at the
// profile's home (free: at --start X,Y when given).
//   sweep    the plot's raster: 7 rows over the middle 80 % of the workspace box at 100 mm/s
//   press    into every shape's edges along their normals (a box's and polygon's edge
//            midpoints, a circle's rim at 0, 90, 180 and 270 deg, a wall's point nearest
//            home) and corners (box corners, polygon vertices, along the bisector of the
//            two edges' normals): from 3 mm in front, press_force / hand stiffness deep
//            (15 mm by default, less where the workspace ends) at 20, 80 and 200 mm/s, a
//            0.3 s hold each, back out; at most 16 places, spread over the boundary. The
//            hand travels between places round the shapes, never through a solid. Not
//            applicable without a shape (or with no place inside the workspace).
//   swipe    across every thin place of a shape (an edge, or rim point, whose solid is
//            at most 10 mm thick along its normal): from 10 mm in front to 10 mm beyond
//            the far side at 500 mm/s, a 0.3 s hold, back at 100 mm/s. Not applicable
//            without a thin place.
//   release  the hand takes the handle a quarter of release_from (5 mm) into the shape
//            nearest home (without a shape: release_from along +x), holds 0.5 s, lets go;
//            the free motion is watched for 1.5 s
//   hold     the hand holds still 2 mm into the shape nearest home (without a shape:
//            half release_from along +x); watched after 0.5 s, for 1 s
//   shake    +/-2 mm at 8 Hz around home, toward the nearest shape (or along x), 1.5 s
//   free     no hand; the handle starts at the free start, watched 1.5 s
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "engine/devices/planar/planar_hand.hpp"
#include "engine/harness/planar_shape_list.hpp"
#include "engine/harness/scenario.hpp"
#include "engine/scene/scene.hpp"

namespace hapscene {

enum class PlanarValidateKind { sweep, press, swipe, release, hold, shake, free };

inline constexpr std::string_view kPlanarValidateNames[] = {"sweep", "press", "swipe", "release",
                                                            "hold",  "shake", "free"};

// Parses a 2-D validate scenario name; empty when unknown.
std::optional<PlanarValidateKind> planar_validate_kind_named(std::string_view name);

// A solid's thickness at most this along an edge's normal makes the place "thin" (swiped).
inline constexpr double kThinWidth_m = 0.010;

struct PlanarValidateScenario {
  PlanarValidateKind kind{};
  std::string name;
  std::string description;       // what the hand does, with numbers
  bool applicable{true};         // false: nothing to do (press or swipe without a place)
  double duration_s{};
  Vec2 start_m{};                // where the handle starts
  PlanarHandConfig hand;
  std::optional<double> watch_from_s;  // oscillation is watched from here to the end
};

// Builds one scenario for `scene`.
PlanarValidateScenario build_planar_validate_scenario(PlanarValidateKind kind, const PlanarScene& scene,
                                                      const HarnessOptions& options);

// A place of a shape's boundary the harness presses (or swipes): the point, the unit
// normal out of the solid there, and what it is ("edge", "corner", "rim").
struct PlanarPressPlace {
  int shape{};                   // planar_shape_list index
  Vec2 surface_m{};
  Vec2 outward{};
  std::string what;
  double thickness_m{};          // the solid's thickness along -outward (infinity: more than 20 mm)
};

// Every place of every shape, in boundary order (before the cap of 16).
std::vector<PlanarPressPlace> planar_press_places(const std::vector<PlanarShapeGeometry>& shapes,
                                                  const Vec2& home_m);

}  // namespace hapscene

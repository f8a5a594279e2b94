#include "engine/harness/planar_shape_list.hpp"

#include <cmath>
#include <variant>

#include "engine/effects/script_effect.hpp"

namespace hapscene {

const char* planar_shape_kind_name(PlanarShapeKind kind) noexcept {
  switch (kind) {
    case PlanarShapeKind::wall: return "wall";
    case PlanarShapeKind::box: return "box";
    case PlanarShapeKind::circle: return "circle";
    case PlanarShapeKind::polygon: return "polygon";
  }
  return "shape";
}

Vec2 PlanarShapeGeometry::nearest_boundary_m(const Vec2& p_m) const noexcept {
  switch (kind) {
    case PlanarShapeKind::wall: {
      const double d = dot(point_m - p_m, normal);
      return p_m + d * normal;
    }
    case PlanarShapeKind::circle: {
      const Vec2 offset = p_m - center_m;
      const double distance = norm(offset);
      if (!(distance > 0.0)) return center_m + Vec2{{radius_m, 0.0}};
      return center_m + offset * (radius_m / distance);
    }
    case PlanarShapeKind::box:
    case PlanarShapeKind::polygon: return outline->nearest_point(p_m);
  }
  return p_m;
}

double PlanarShapeGeometry::depth_m(const Vec2& p_m) const noexcept {
  switch (kind) {
    case PlanarShapeKind::wall: return dot(point_m - p_m, normal);
    case PlanarShapeKind::circle: {
      const double inside_m = radius_m - norm(p_m - center_m);
      return solid_inside ? inside_m : -inside_m;
    }
    case PlanarShapeKind::box:
    case PlanarShapeKind::polygon: {
      const double distance_m = norm(outline->nearest_point(p_m) - p_m);
      return outline->in_solid(p_m) ? distance_m : -distance_m;
    }
  }
  return 0.0;
}

std::vector<PlanarShapeGeometry> planar_shape_list(const PlanarScene& scene) {
  std::vector<PlanarShapeGeometry> shapes;
  const auto& bank = scene.bank;
  for (const PlanarWall& wall : bank.group<PlanarWall>()) {
    PlanarShapeGeometry g;
    g.kind = PlanarShapeKind::wall;
    g.point_m = wall.point_m;
    g.normal = wall.normal;
    g.stiffness_N_per_m = wall.stiffness_N_per_m;
    shapes.push_back(std::move(g));
  }
  for (const PlanarBox& box : bank.group<PlanarBox>()) {
    PlanarShapeGeometry g;
    g.kind = PlanarShapeKind::box;
    g.solid_inside = box.solid_inside;
    g.stiffness_N_per_m = box.stiffness_N_per_m;
    g.points_m = {box.min_m, Vec2{{box.max_m[0], box.min_m[1]}}, box.max_m, Vec2{{box.min_m[0], box.max_m[1]}}};
    g.outline = &box.outline;
    shapes.push_back(std::move(g));
  }
  for (const PlanarCircle& circle : bank.group<PlanarCircle>()) {
    PlanarShapeGeometry g;
    g.kind = PlanarShapeKind::circle;
    g.solid_inside = circle.solid_inside;
    g.stiffness_N_per_m = circle.stiffness_N_per_m;
    g.center_m = circle.center_m;
    g.radius_m = circle.radius_m;
    shapes.push_back(std::move(g));
  }
  for (const PlanarPolygon& polygon : bank.group<PlanarPolygon>()) {
    PlanarShapeGeometry g;
    g.kind = PlanarShapeKind::polygon;
    g.solid_inside = polygon.outline.solid_inside();
    g.stiffness_N_per_m = polygon.stiffness_N_per_m;
    for (int i = 0; i < polygon.outline.edge_count(); ++i) g.points_m.push_back(polygon.outline.vertex(i));
    g.outline = &polygon.outline;
    shapes.push_back(std::move(g));
  }
  return shapes;
}

std::vector<PlanarShapeGeometry> planar_scenario_shapes(const PlanarScene& scene) {
  std::vector<PlanarShapeGeometry> shapes = planar_shape_list(scene);
  for (const auto& effect : scene.effects) {
    const auto* script = std::get_if<ScriptEffect>(&effect);
    if (script == nullptr) continue;
    for (const ScriptShape& declared : script->program->shapes) {
      PlanarShapeGeometry g;
      g.declared = true;
      g.solid_inside = declared.solid_inside;
      if (declared.kind == ScriptShape::Kind::box) {
        g.kind = PlanarShapeKind::box;
        const Vec2 low{{declared.min_m[0], declared.min_m[1]}};
        const Vec2 high{{declared.max_m[0], declared.max_m[1]}};
        // As the built-in box's outline: corners counter-clockwise from min.
        g.points_m = {low, Vec2{{high[0], low[1]}}, high, Vec2{{low[0], high[1]}}};
        g.owned_outline = std::make_shared<const PolygonOutline>(g.points_m, g.solid_inside);
        g.outline = g.owned_outline.get();
      } else {
        g.kind = PlanarShapeKind::circle;
        g.center_m = Vec2{{declared.center_m[0], declared.center_m[1]}};
        g.radius_m = declared.radius_m;
      }
      shapes.push_back(std::move(g));
    }
  }
  return shapes;
}

int nearest_shape_index(const std::vector<PlanarShapeGeometry>& shapes, const Vec2& p_m) noexcept {
  int best = -1;
  double best_m = INFINITY;
  for (std::size_t i = 0; i < shapes.size(); ++i) {
    const double distance_m = norm(shapes[i].nearest_boundary_m(p_m) - p_m);
    if (distance_m < best_m) {
      best_m = distance_m;
      best = static_cast<int>(i);
    }
  }
  return best;
}

}  // namespace hapscene

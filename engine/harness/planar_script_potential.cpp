#include "engine/harness/planar_script_potential.hpp"

#include <algorithm>
#include <cmath>

#include "engine/base/errors.hpp"
#include "engine/base/format.hpp"
#include "engine/harness/planar_open_loop.hpp"
#include "engine/scene/safety.hpp"
#include "engine/scene/step.hpp"

namespace hapscene {
namespace {

// A grid over the workspace box with nodes on its edges, spaced at most `step_m`.
PlanarScriptPotential empty_grid(const PlanarScene& scene, double step_m) {
  PlanarScriptPotential grid;
  const Vec2& low = scene.safety.workspace_min_m;
  const Vec2 span = scene.safety.workspace_max_m - low;
  const auto intervals = [&](int axis) {
    return std::max<std::size_t>(1, static_cast<std::size_t>(std::ceil(span[axis] / step_m - 1e-9)));
  };
  // One spacing for both axes (the larger of the two that fit the box's sides).
  grid.step_m = std::max(span[0] / static_cast<double>(intervals(0)), span[1] / static_cast<double>(intervals(1)));
  grid.columns = static_cast<std::size_t>(std::ceil(span[0] / grid.step_m - 1e-9)) + 1;
  grid.rows = static_cast<std::size_t>(std::ceil(span[1] / grid.step_m - 1e-9)) + 1;
  grid.min_m = low;
  return grid;
}

std::vector<Vec2> node_points(const PlanarScriptPotential& grid) {
  std::vector<Vec2> points;
  points.reserve(grid.columns * grid.rows);
  for (std::size_t r = 0; r < grid.rows; ++r) {
    for (std::size_t c = 0; c < grid.columns; ++c) {
      points.push_back(grid.min_m + Vec2{{static_cast<double>(c) * grid.step_m, static_cast<double>(r) * grid.step_m}});
    }
  }
  return points;
}

// The scripts' part of the scanned force at each node: less the built-in effects' open
// loop, non-finite as 0, clamped to the force limit.
std::vector<Vec2> scripts_part_N(const PlanarScene& scene, const std::vector<Vec2>& points,
                                 const std::vector<Vec2>& scanned_N) {
  std::vector<Vec2> force_N(points.size());
  ScriptList none;
  EffectInputOf<2> input;
  input.dt_s = scene.period_s;
  for (std::size_t i = 0; i < points.size(); ++i) {
    input.x_m = points[i];
    Vec2 f = scanned_N[i] - sum_effects_N(scene, input, none);
    if (!all_finite(f)) f = Vec2{};
    if (exceeds_magnitude(f, scene.safety.max_force_N)) f = limit_magnitude(f, scene.safety.max_force_N);
    force_N[i] = f;
  }
  return force_N;
}

// The work along each edge a -> b, U(b) - U(a) = -integral of F . dl: horizontal edges
// then vertical.
struct Edges {
  std::vector<std::size_t> from;
  std::vector<std::size_t> to;
  std::vector<double> work_J;
};

// One stretch [t0, t1] of an edge (t from 0 at a to 1 at b) whose integral is not settled,
// with the force along the edge at its ends.
struct Stretch {
  std::size_t edge{};
  double t0{};
  double t1{};
  double f0_N{};
  double f1_N{};
  int depth{};
};

// The edges' work by adaptive Simpson: each edge is split in halves where Simpson's rule
// and the trapezoid disagree by more than kEdgeTolerance_J (per edge) (a kink or a jump of the
// field, at a shape's outline or where its push flips side), down to 1/64 of the step,
// each round's new points scanned together by `sample`. Where a jump remains, the error
// is at most the jump times the last stretch's length.
constexpr double kEdgeTolerance_J = 1e-7;
constexpr int kEdgeMaxDepth = 7;

template <typename Sample>
Edges edge_work(const PlanarScriptPotential& g, const Sample& sample) {
  Edges e;
  std::vector<Stretch> open;
  const auto add = [&](std::size_t a, std::size_t b, int axis) {
    open.push_back({e.work_J.size(), 0.0, 1.0, g.force_N[a][axis], g.force_N[b][axis], 0});
    e.from.push_back(a);
    e.to.push_back(b);
    e.work_J.push_back(0.0);
  };
  for (std::size_t r = 0; r < g.rows; ++r) {
    for (std::size_t c = 0; c + 1 < g.columns; ++c) add(r * g.columns + c, r * g.columns + c + 1, 0);
  }
  const std::size_t horizontal = e.work_J.size();
  for (std::size_t r = 0; r + 1 < g.rows; ++r) {
    for (std::size_t c = 0; c < g.columns; ++c) add(r * g.columns + c, (r + 1) * g.columns + c, 1);
  }
  // The point at t along edge k, and the axis it runs along.
  const auto point_at = [&](const Stretch& s, double t) {
    const Vec2& a = g.min_m;
    const std::size_t node = e.from[s.edge];
    const Vec2 start = a + Vec2{{static_cast<double>(node % g.columns) * g.step_m,
                                 static_cast<double>(node / g.columns) * g.step_m}};
    return s.edge < horizontal ? start + Vec2{{t * g.step_m, 0.0}} : start + Vec2{{0.0, t * g.step_m}};
  };
  while (!open.empty()) {
    std::vector<Vec2> midpoints;
    midpoints.reserve(open.size());
    for (const Stretch& s : open) midpoints.push_back(point_at(s, 0.5 * (s.t0 + s.t1)));
    const std::vector<Vec2> mid_N = sample(midpoints);
    std::vector<Stretch> next;
    for (std::size_t i = 0; i < open.size(); ++i) {
      const Stretch& s = open[i];
      const double fm_N = mid_N[i][s.edge < horizontal ? 0 : 1];
      const double length_m = (s.t1 - s.t0) * g.step_m;
      const double trapezoid_J = -0.5 * (s.f0_N + s.f1_N) * length_m;
      const double simpson_J = -(s.f0_N + 4.0 * fm_N + s.f1_N) * length_m / 6.0;
      const double tolerance_J = kEdgeTolerance_J * (s.t1 - s.t0);
      if (std::fabs(simpson_J - trapezoid_J) <= tolerance_J || s.depth + 1 >= kEdgeMaxDepth) {
        e.work_J[s.edge] += simpson_J;
        continue;
      }
      const double tm = 0.5 * (s.t0 + s.t1);
      next.push_back({s.edge, s.t0, tm, s.f0_N, fm_N, s.depth + 1});
      next.push_back({s.edge, tm, s.t1, fm_N, s.f1_N, s.depth + 1});
    }
    open = std::move(next);
  }
  return e;
}

// The graph Laplacian of the grid times u (each node: its degree times u, less its neighbours').
void laplacian(const PlanarScriptPotential& g, const std::vector<double>& u, std::vector<double>* out) {
  for (std::size_t r = 0; r < g.rows; ++r) {
    for (std::size_t c = 0; c < g.columns; ++c) {
      const std::size_t i = r * g.columns + c;
      double sum = 0.0;
      if (c > 0) sum += u[i] - u[i - 1];
      if (c + 1 < g.columns) sum += u[i] - u[i + 1];
      if (r > 0) sum += u[i] - u[i - g.columns];
      if (r + 1 < g.rows) sum += u[i] - u[i + g.columns];
      (*out)[i] = sum;
    }
  }
}

double degree(const PlanarScriptPotential& g, std::size_t i) {
  const std::size_t r = i / g.columns;
  const std::size_t c = i % g.columns;
  return static_cast<double>((c > 0) + (c + 1 < g.columns) + (r > 0) + (r + 1 < g.rows));
}

// The least squares potential: L U = D^T w by conjugate gradients (Jacobi preconditioned)
// from the line integral along the bottom row and up each column.
void fit_potential(PlanarScriptPotential* g, const Edges& e) {
  const std::size_t n = g->columns * g->rows;
  std::vector<double>& u = g->potential_J;
  u.assign(n, 0.0);
  for (std::size_t c = 1; c < g->columns; ++c) u[c] = u[c - 1] + e.work_J[c - 1];
  const std::size_t vertical = g->rows * (g->columns - 1);
  for (std::size_t r = 1; r < g->rows; ++r) {
    for (std::size_t c = 0; c < g->columns; ++c) {
      u[r * g->columns + c] = u[(r - 1) * g->columns + c] + e.work_J[vertical + (r - 1) * g->columns + c];
    }
  }
  std::vector<double> rhs(n, 0.0);
  for (std::size_t k = 0; k < e.work_J.size(); ++k) {
    rhs[e.to[k]] += e.work_J[k];
    rhs[e.from[k]] -= e.work_J[k];
  }
  std::vector<double> residual(n);
  std::vector<double> product(n);
  laplacian(*g, u, &product);
  double rhs_norm2 = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    residual[i] = rhs[i] - product[i];
    rhs_norm2 += rhs[i] * rhs[i];
  }
  std::vector<double> z(n);
  std::vector<double> direction(n);
  double rz = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    z[i] = residual[i] / degree(*g, i);
    direction[i] = z[i];
    rz += residual[i] * z[i];
  }
  const double tolerance2 = rhs_norm2 * 1e-24;
  const std::size_t max_iterations = 20 * (g->columns + g->rows);
  for (std::size_t iteration = 0; iteration < max_iterations; ++iteration) {
    double residual2 = 0.0;
    for (const double r : residual) residual2 += r * r;
    if (!(residual2 > tolerance2)) break;
    laplacian(*g, direction, &product);
    double dAd = 0.0;
    for (std::size_t i = 0; i < n; ++i) dAd += direction[i] * product[i];
    if (!(dAd > 0.0)) break;
    const double alpha = rz / dAd;
    double rz_next = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      u[i] += alpha * direction[i];
      residual[i] -= alpha * product[i];
      z[i] = residual[i] / degree(*g, i);
      rz_next += residual[i] * z[i];
    }
    const double beta = rz_next / rz;
    rz = rz_next;
    for (std::size_t i = 0; i < n; ++i) direction[i] = z[i] + beta * direction[i];
  }
  const double origin_J = u[0];
  for (double& value : u) value -= origin_J;

  // How much of the edges' work the potential leaves unexplained.
  double work2 = 0.0;
  double unexplained2 = 0.0;
  for (std::size_t k = 0; k < e.work_J.size(); ++k) {
    const double left_J = e.work_J[k] - (u[e.to[k]] - u[e.from[k]]);
    work2 += e.work_J[k] * e.work_J[k];
    unexplained2 += left_J * left_J;
  }
  g->rotational_fraction = work2 > 0.0 ? std::sqrt(unexplained2 / work2) : 0.0;
}

// Scans the scripts at the grid's nodes and fits their potential.
void scan_and_fit(const PlanarScene& scene, PlanarOpenLoop* open_loop, PlanarScriptPotential* grid) {
  const std::vector<Vec2> points = node_points(*grid);
  PlanarOpenLoopScan scan = open_loop->scan(points, Vec2{});
  grid->behaviour = scan.behaviour;
  grid->force_N = scripts_part_N(scene, points, scan.force_N);
  const auto sample = [&](const std::vector<Vec2>& at_m) {
    return scripts_part_N(scene, at_m, open_loop->scan(at_m, Vec2{}).force_N);
  };
  fit_potential(grid, edge_work(*grid, sample));
}

}  // namespace

double PlanarScriptPotential::at_J(const Vec2& x_m) const noexcept {
  if (potential_J.empty() || columns < 2 || rows < 2) return 0.0;
  // The cell and p's place in it (0..1 on each axis), clamped to the grid.
  const auto locate = [&](int axis, std::size_t count, std::size_t* cell, double* fraction) {
    const double position = std::clamp((x_m[axis] - min_m[axis]) / step_m, 0.0, static_cast<double>(count - 1));
    *cell = std::min(static_cast<std::size_t>(position), count - 2);
    *fraction = position - static_cast<double>(*cell);
  };
  std::size_t c = 0;
  std::size_t r = 0;
  double u = 0.0;
  double v = 0.0;
  locate(0, columns, &c, &u);
  locate(1, rows, &r, &v);
  const std::size_t corner[4] = {r * columns + c, r * columns + c + 1, (r + 1) * columns + c, (r + 1) * columns + c + 1};
  const double corner_u[4] = {0.0, 1.0, 0.0, 1.0};
  const double corner_v[4] = {0.0, 0.0, 1.0, 1.0};
  // The force bilinear over the cell, at (a, b) in cell units.
  const auto force_at = [&](double a, double b) {
    return (1 - a) * (1 - b) * force_N[corner[0]] + a * (1 - b) * force_N[corner[1]] +
           (1 - a) * b * force_N[corner[2]] + a * b * force_N[corner[3]];
  };
  const Vec2 at_p = force_at(u, v);
  double energy_J = 0.0;
  for (int k = 0; k < 4; ++k) {
    const double weight = (corner_u[k] == 0.0 ? 1 - u : u) * (corner_v[k] == 0.0 ? 1 - v : v);
    if (weight == 0.0) continue;
    const Vec2 along_m{{(u - corner_u[k]) * step_m, (v - corner_v[k]) * step_m}};
    const Vec2 mid = force_at(0.5 * (u + corner_u[k]), 0.5 * (v + corner_v[k]));
    const double work_J = -dot(force_N[corner[k]] + 4.0 * mid + at_p, along_m) / 6.0;
    energy_J += weight * (potential_J[corner[k]] + work_J);
  }
  return energy_J;
}

PlanarScriptPotential planar_script_potential(const PlanarScene& scene) {
  if (scene.script_count == 0) return {};
  const Vec2 span = scene.safety.workspace_max_m - scene.safety.workspace_min_m;
  const double coarse_step_m =
      std::max(kScriptPotentialStep_m, std::sqrt(span[0] * span[1] / static_cast<double>(kScriptPotentialCoarseNodes)));
  PlanarOpenLoop open_loop(scene);
  try {
    // First the coarse grid: it says whether the scripts render a fixed field, and is the
    // estimate when they do not; a fixed field is then scanned again on the fine grid.
    PlanarScriptPotential coarse = empty_grid(scene, coarse_step_m);
    scan_and_fit(scene, &open_loop, &coarse);
    if (!coarse.behaviour.static_field() || coarse_step_m <= kScriptPotentialStep_m) return coarse;
    PlanarScriptPotential fine = empty_grid(scene, kScriptPotentialStep_m);
    scan_and_fit(scene, &open_loop, &fine);
    return fine;
  } catch (const InputError& error) {
    // The creation budget refused the scan: no potential, and the check says why.
    PlanarScriptPotential none;
    none.not_estimated = error.what();
    return none;
  }
}

std::string describe_script_potential(const PlanarScene& scene, const PlanarScriptPotential& potential) {
  if (scene.script_count == 0) return "";
  const std::string whose = scene.script_count == 1 ? "the script" : "the scripts";
  if (potential.empty()) {
    return "; no stored energy credited to " + whose + " (" + potential.not_estimated + ")";
  }
  std::string text = "; stored energy of " + whose + " from " + (scene.script_count == 1 ? "its" : "their") +
                     " field at rest (";
  if (!potential.behaviour.static_field()) text += potential.behaviour.note + "; ";
  text += printf_string("%.3g mm grid; %.1f %% of its work rotational, shown as created)", potential.step_m * 1e3,
                        potential.rotational_fraction * 100.0);
  return text;
}

}  // namespace hapscene

#pragma once
// The per-run state of one shape effect's god-object proxy (wall, box, circle, polygon).
// The caller owns one per shape effect per run and value-initialises it at the start of
// the run; the closed-loop force updates it each tick without allocating.
#include <cstdint>

#include "engine/base/axes.hpp"

namespace hapscene {

// Where the proxy rests.
enum class ProxyContact : std::uint8_t {
  none,     // free: the proxy is at the handle (or follows it through a solid it started in)
  edge,     // on the interior of edge `feature` of an outline
  vertex,   // on vertex `feature` of an outline (held in a corner, or stuck there by friction)
  surface,  // on a wall's line or a circle
};

struct PlanarProxyState {
  Vec2 proxy_m{};             // the proxy's position; F = K (proxy - x)
  std::int32_t feature{-1};   // edge or vertex index for ProxyContact::edge and ::vertex
  // An outline's proxy on a vertex: the edge whose normal bounds its slides (it never
  // slides onto an edge turned more than a quarter turn from it): the edge it came to
  // rest on, or met on its way to the handle, last. (On an edge: that edge.)
  std::int32_t reference_edge{-1};
  ProxyContact contact{ProxyContact::none};
  bool sliding{};             // friction: the proxy slides (dynamic cone) rather than sticks
  bool started{};             // false until the first tick of the run
  bool passive{};             // wall and circle: the run started with the handle in the solid
};

// Coulomb friction on a proxy's surface (both zero: frictionless).
struct FrictionCoefficients {
  double static_mu{};
  double dynamic_mu{};

  bool any() const noexcept { return static_mu > 0.0 || dynamic_mu > 0.0; }
};

}  // namespace hapscene

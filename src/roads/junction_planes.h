#pragma once
// Private to the roads module: the lanes at a junction lie on its plane. The profile fit gives
// each junction a tangent plane (its gradient); the part of it the junction's roads determine
// tilts the roads' cross-sections (superelevation): a road's ends take the roll of their
// junction's plane, eased to level within 50 m, and a road inside a junction lies across it.

#include <optional>
#include <vector>

#include <Eigen/Core>

#include "relief/geometry/cubic_profile.h"
#include "relief/geometry/plan_view.h"
#include "relief/geometry/types.h"
#include "relief/roads/road_network.h"

namespace relief::detail {

/// The part of a junction plane's gradient G its roads determine, as the linear map S (the
/// determined gradient is S G): with M = sum of u u^T over the roads' unit directions u leaving
/// the junction, each eigen-direction e of M keeps the share of G . e its eigenvalue lambda says:
/// all from lambda = 0.5, none under 0.05, a smoothstep between (junction_planes).
[[nodiscard]] Eigen::Matrix2d determined_share(const RoadNetwork& network, const Junction& j);

/// Per network junction, the gradient of its plane that the roads build on: of
/// `junction_gradient` (parallel to network.junctions, or empty for level junctions), the share
/// its roads determine. With M = sum of u u^T over the roads' unit directions u leaving the
/// junction, each eigen-direction e of M keeps the share of G . e its eigenvalue lambda says:
/// all from lambda = 0.5 (a T junction across its through road, a fork at 45 degrees), none
/// under 0.05 (across a road straight through, a fork at 13 degrees), a smoothstep between.
[[nodiscard]] std::vector<Vec2> junction_planes(const RoadNetwork& network,
                                                const std::vector<Vec2>& junction_gradient);

/// Superelevation (roll, radians) that lays a cross-section of the given heading on a plane of
/// gradient g: the surface rises by tan(roll) per metre to the left (road_surface.h).
[[nodiscard]] double plane_roll(const Vec2& g, double heading);

/// A road's roll: at each end the roll r0, r1 of its junction's plane, eased to level with zero
/// slope at both ends of the ease within 50 m; a road shorter than two eases turns from r0 to r1
/// in one. A dead end (nullopt: no plane to meet) takes what the other end's ease has left at
/// that distance, with its slope: a 1 m stub off a junction plane rolled 0.33 rad keeps 0.33
/// rad instead of twisting to level within 1 m.
[[nodiscard]] CubicProfile end_rolls(double length, std::optional<double> r0, std::optional<double> r1);

/// Roll along a road inside a junction: at every station the roll that lays its cross-section
/// on the junction's plane, the gradient blended from g0 at its start to g1 at its end (they
/// differ where the ends belong to different intersections joined into one junction). Its ends
/// take exactly the rolls of the roads they join.
[[nodiscard]] CubicProfile plane_rolls(const PlanView& plan, const Vec2& g0, const Vec2& g1);

}  // namespace relief::detail

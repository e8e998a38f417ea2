#pragma once
// Private to the roads module: points of different roads that lie near each other, found on a
// grid so that the cost grows with the length of road, not with its square. Used to find roads
// drawn closer than their widths (close_roads.h, road_separation.h).

#include <functional>
#include <vector>

#include "relief/roads/road_network.h"

namespace relief::detail {

/// A point on a road's centre line: its station s (metres from the road's first point), its
/// position and the unit direction of the segment it lies on.
struct RoadSample {
  int road = -1;
  double s = 0.0;
  Vec2 p, dir;
};

/// Every road's centre line sampled at most `step_m` apart (each segment in equal parts, its
/// last point left to the next segment).
[[nodiscard]] std::vector<RoadSample> sample_roads(const RoadNetwork& network, double step_m);

/// Calls visit(a, b) for every ordered pair of samples of different roads at most `reach_m`
/// apart in each coordinate (and possibly a few farther: the caller measures).
void for_each_near_pair(const std::vector<RoadSample>& samples, double reach_m,
                        const std::function<void(const RoadSample&, const RoadSample&)>& visit);

/// The largest half width of the network's roads (lane_layout.h's half_width).
[[nodiscard]] double widest_half_width(const RoadNetwork& network);

/// Whether either sample lies within `reach_m` of a junction both their roads end at (where
/// two roads split or merge, what lies close is the junction's).
[[nodiscard]] bool near_shared_junction(const RoadNetwork& network, const RoadSample& a, const RoadSample& b,
                                        double reach_m);

/// Whether b's point lies beside a's (within half of `step_m` along a's direction); if so,
/// `across` is its signed distance across a's direction, positive when b lies on a's left.
[[nodiscard]] bool beside(const RoadSample& a, const RoadSample& b, double step_m, double& across);

}  // namespace relief::detail

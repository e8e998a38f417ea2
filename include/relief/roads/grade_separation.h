#pragma once
// Grade separations: places where two roads on different layers cross without a junction
// (a bridge over a street, a tunnel under one). Found with a uniform grid over the segments,
// so the cost is linear in the network size.

#include <vector>

#include "relief/roads/elevation_sampling.h"
#include "relief/roads/road_network.h"

namespace relief {

struct GradeSeparation {
  int upper_road = -1;  ///< the road on the higher layer
  int lower_road = -1;
  double s_upper = 0.0;  ///< arc length of the crossing on each road (m)
  double s_lower = 0.0;
  Vec2 xy = Vec2::Zero();
  double clearance_m = 0.0;      ///< z_upper - z_lower of the profiles given last
  double raw_clearance_m = 0.0;  ///< the same on the profiles the crossing was found with
};

/// The layer used to order crossings: the `layer` tag, else +1 for a bridge and -1 for a
/// tunnel (OSM's implied values), else 0.
[[nodiscard]] int effective_layer(const WayAttributes& attributes);

/// Crossings of roads whose effective layers differ; one per crossing point (crossings of the
/// same two roads closer than 1 m are merged). Heights (raw_clearance_m, clearance_m) from
/// `profiles`.
[[nodiscard]] std::vector<GradeSeparation> find_grade_separations(const RoadNetwork& network,
                                                                  const std::vector<RoadProfile>& profiles);

/// Recomputes clearance_m from `profiles` (e.g. after a fit).
void update_clearances(std::vector<GradeSeparation>& separations, const std::vector<RoadProfile>& profiles);

}  // namespace relief

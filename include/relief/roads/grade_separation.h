#pragma once
// Grade separations: places where two roads on different layers cross without a junction
// (a bridge over a street, a tunnel under one) or run one over the other (a viaduct along the
// street beneath it). Found with a uniform grid over the segments, so the cost is linear in the
// network size.

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
  /// Not a crossing: the upper road runs along over the lower one, their paved widths
  /// overlapping in plan (a viaduct over the street beneath it); one every 5 m of the overlap.
  bool alongside = false;
  /// Alongside where no clearance fits: near a road's end (a tunnel's approach beside a street
  /// at its portal) or beyond the fan of a junction the two share. The upper one only has to
  /// stay kOrderingGap_m above the other, so that the two surfaces never cross.
  bool ordering_only = false;
  /// Two bridges (or two tunnels) of one layer crossing without a shared node: the data does not
  /// say which is above (a layer tag missing; joining them would invent a connection, a freeway
  /// ramp to the street it flies over). The upper one is the one whose straight span between its
  /// ends lies higher at the crossing (at equal height the lower road id).
  bool guessed_order = false;
};

/// What an ordering-only separation asks of the upper road (m): more than twice the scene's
/// 0.02 m meshing tolerance plus a crossfall's difference over the overlap.
inline constexpr double kOrderingGap_m = 0.1;

/// The layer used to order crossings: the `layer` tag, else +1 for a bridge and -1 for a
/// tunnel (OSM's implied values), else 0.
[[nodiscard]] int effective_layer(const WayAttributes& attributes);

/// Crossings of roads whose effective layers differ, and of two bridges or two tunnels of one
/// layer (guessed_order); one per crossing point (crossings of the same two roads closer than
/// 1 m are merged). Also, every 5 m, the places where such roads run
/// within 25 degrees of parallel with their paved widths (lanes x lane width) overlapping
/// (`alongside`): at least 20 m from the two roads' ends and away from a junction they share
/// with the full clearance, otherwise `ordering_only`; none where the two fan out of a junction
/// they share (within their half widths over sin 10 degrees of it); not for guessed_order
/// crossings. Other roads on one layer are never separated: where their pavements overlap (ways
/// closer than their widths) neither is above.
/// Heights (raw_clearance_m, clearance_m) from `profiles`.
[[nodiscard]] std::vector<GradeSeparation> find_grade_separations(const RoadNetwork& network,
                                                                  const std::vector<RoadProfile>& profiles);

/// Recomputes clearance_m from `profiles` (e.g. after a fit).
void update_clearances(std::vector<GradeSeparation>& separations, const std::vector<RoadProfile>& profiles);

}  // namespace relief

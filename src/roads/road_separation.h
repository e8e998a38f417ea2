#pragma once
// Private to the roads module: roads on one level drawn so close that their pavements overlap,
// moved apart. OSM draws a ramp, a frontage road or a service road beside a main road where a
// mapper's eye put it, often a metre or two closer than the lanes are wide (Portland's
// McLoughlin Boulevard and the trunk link beside it: 5.4 m apart for 7 m of pavement, over
// 85 m). Overlapping pavements at nearly one height cut through each other in the road mesh and
// stack two lanes in one place in OpenDRIVE and SUMO. The lesser road of such a pair is moved
// sideways, away from the other, just far enough that their pavements meet a margin apart,
// with smooth tapers on either side; its ends stay where they are (they belong to junctions).
// Carriageways of one road drawn too close are narrowed first instead (close_roads.h).

#include <cstddef>

#include "relief/core/diagnostics.h"
#include "relief/roads/road_network.h"

namespace relief::detail {

struct SeparationOptions {
  double margin_m = 0.2;       ///< left between the two pavements
  double sample_step_m = 2.0;  ///< roads are compared at points this far apart
  /// Of a pair, at least this length of each must lie too close: a brief approach (a kink drawn
  /// near a neighbour) is left to the mesh checks.
  double min_overlap_m = 6.0;
  /// A road is moved at most this far; a pair needing more (one road drawn over the other) is
  /// left alone, and to the mesh checks.
  double max_shift_m = 3.0;
  /// A shift of d metres comes in and goes out over taper_per_shift * d metres of road, and
  /// at least min_taper_m: 1.8 m over 30 m bends the road no tighter than a 100 m radius.
  double taper_per_shift = 15.0;
  double min_taper_m = 30.0;
};

/// For every pair of roads on one level (equal layer, both or neither a tunnel) whose centre lines
/// run within 30 degrees of parallel (either way) closer than their half widths' sum, over at
/// least min_overlap_m of each, away from any junction they share (where they split or merge is
/// the junction's to trim: farther than their half widths' sum over sin 10 degrees), moves the
/// lesser road (the lower highway class; then the narrower; then the later id) away from the
/// other until they are half widths' sum + margin apart. The shift follows the moved road's own
/// normal, rises and falls with cosine tapers, and is held to zero at the road's ends (taken in
/// over min_taper_m); new centre-line points are inserted every sample step where it moves
/// (their OSM node id is 0). Pairs drawn less than a quarter of that sum apart (one road drawn
/// twice), needing more than max_shift_m, or pushing a road to both sides, are left alone. Each
/// moved road is reported (codes::kNetworkRoadsMoved, a warning, with its way, its neighbour
/// and the shift). Returns the number of roads moved.
std::size_t separate_close_roads(RoadNetwork& network, Diagnostics& diagnostics,
                                 const SeparationOptions& options = {});

}  // namespace relief::detail

#pragma once
// Private to the roads module: the carriageways of a dual carriageway drawn closer than their
// widths. OSM draws each carriageway as its own one-way; where the two lie closer than their
// lanes are wide (Portland's Naito Parkway: 6 m apart for two 7 m carriageways) the pavements
// overlap in plan, and at different heights their meshes cut through each other. Both get
// narrower lanes, so that their pavements meet instead. Other roads drawn close (a ramp beside a
// freeway before it merges, a service road beside a boulevard) keep their widths: narrowing a
// freeway over its whole length for a ramp's gore would be wrong; the lesser of the two is moved
// aside instead (road_separation.h).

#include <cstddef>

#include "relief/core/diagnostics.h"
#include "relief/roads/road_network.h"

namespace relief::detail {

struct CloseRoadOptions {
  double min_lane_width_m = 2.5;  ///< lanes are never made narrower than this
  double margin_m = 0.2;          ///< left between the two pavements
  double sample_step_m = 2.0;     ///< roads are compared at points this far apart
  /// Of a pair, at least this length of each must lie too close: a brief approach (a kink drawn
  /// near a neighbour) is left to the mesh checks.
  double min_overlap_m = 6.0;
};

/// For every pair of carriageways (one-ways of the same name on one level: neither a bridge nor a
/// tunnel, equal layer) whose centre lines run against each other within 30 degrees closer than
/// the sum of their half widths, over at least min_overlap_m of each, away from any junction they
/// share (where they split or merge is the junction's to trim: farther than their half widths'
/// sum over sin 10 degrees), scales both roads' lane widths by (distance - margin) / (sum of half
/// widths) at their closest, when that leaves lanes of at least min_lane_width_m. Pairs drawn
/// less than a quarter of that sum apart (one road drawn twice) or needing narrower lanes are
/// left alone. Each narrowed road is reported (codes::kNetworkRoadsNarrowed, a warning, with its
/// way, its neighbour and the widths). Points are bucketed on a grid: the cost grows with the
/// length of road, not with its square. Returns the number of roads narrowed.
std::size_t narrow_close_roads(RoadNetwork& network, Diagnostics& diagnostics,
                               const CloseRoadOptions& options = {});

}  // namespace relief::detail

#pragma once
// Private to the roads module: how far each road end is trimmed back from its junction's node.
// A junction that takes room (an intersection, two roads needing a transition road, two one-ways
// without passage) trims its roads by its radius; where road ends at a junction still overlap
// (forks at a small angle), their trims grow in steps until the ends lie apart, and a road the
// trims use up joins its two junctions into one (junction_joining.h), after which the trims run
// again. An end lying between two others, where their connecting roads run (inside the convex
// hull of their end lines), grows as well (and may use its road up, as above), without making
// its junction level.
// Dead ends lying on another road's pavement are trimmed back as well (stray_ends.h).

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "relief/core/diagnostics.h"
#include "relief/geometry/types.h"
#include "relief/roads/road_model.h"
#include "relief/roads/road_model_builder.h"
#include "relief/roads/road_network.h"
#include "roads/junction_ends.h"

namespace relief::detail {

/// Per network junction, the room it takes (m from its node; 0 for none): the widest half-width
/// of its roads plus junction_margin_m at an intersection, at an attribute change that needs a
/// transition road (`transition`, per network junction) and where two one-ways without passage
/// between them end apart; a transition road reaches further where its bend needs it
/// (transition_reach, which weighs the roads' `profiles`).
[[nodiscard]] std::vector<double> junction_radii(const RoadNetwork& network,
                                                 const std::vector<RoadProfile>& profiles,
                                                 const RoadModelOptions& options,
                                                 const std::vector<std::uint8_t>& transition);

struct EndTrimResult {
  /// Junctions whose road ends still overlap at the largest trims allowed, with their network roads.
  std::vector<std::pair<int, std::vector<int>>> overlaps;
  std::size_t ends_trimmed = 0;  ///< road ends trimmed beyond the junction radius
};

/// Grows `ends.trim` apart at every junction (in 0.5 m steps, up to 400 per junction, keeping
/// min_kept_length_m of each road), and joins junctions across the roads it uses up (up to 8
/// rounds, each starting again from the radii). A junction whose ends still overlap is made
/// level: its entry of `planes` (per network junction, and its members') becomes zero.
[[nodiscard]] EndTrimResult grow_end_trims(JunctionEnds& ends, std::vector<Vec2>& planes);

/// Trims back the dead ends that lie on another road's pavement (clear_stray_ends) and, when
/// `report`, reports each (codes::kModelStrayEndTrimmed, codes::kModelStrayEndOverlap) and counts it.
void trim_stray_ends(JunctionEnds& ends, bool report, Diagnostics& diagnostics, RoadModelStats& stats);

/// Reports the junctions whose ends still overlap (codes::kModelJunctionEndsOverlap), naming the
/// model roads (`model_road_of`, per network road) that were built.
void report_end_overlaps(const RoadNetwork& network, const EndTrimResult& trims, const RoadModel& model,
                         const std::vector<int>& model_road_of, Diagnostics& diagnostics,
                         RoadModelStats& stats);

}  // namespace relief::detail

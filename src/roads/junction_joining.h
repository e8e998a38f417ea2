#pragma once
// Private to the roads module: junctions joined across the roads their trims use up. A road
// that the trims at its two junctions leave no longer than min_kept_length_m cannot hold both:
// when its ends still overlap others, when it is no more than 10 m longer than the two radii,
// or when the two junctions' areas meet across it, the two become one junction (netconvert's
// join-dist) and the road lies inside it. The joining itself is junction_clusters.h's.

#include <array>
#include <cstdint>
#include <vector>

#include "relief/core/diagnostics.h"
#include "relief/roads/road_model_builder.h"
#include "roads/junction_ends.h"

namespace relief::detail {

/// Marks in `used_up` (per network road) the roads whose two junctions the current trims
/// (`ends.trim`) join: roads that are not loops, with height, not yet absorbed, left no more
/// than min_kept_length_m, and either `stuck` (per network road: their ends still overlap at
/// their cap), or no more than 10 m longer than their radii's trims (`radius_trim`), or between
/// two intersections whose areas meet across them (unless the join would leave a loop through
/// the joined junction). Returns whether any road was marked.
[[nodiscard]] bool mark_used_up_roads(const JunctionEnds& ends,
                                      const std::vector<std::array<double, 2>>& radius_trim,
                                      const std::vector<std::uint8_t>& stuck,
                                      std::vector<std::uint8_t>& used_up);

/// Reports every joined junction (codes::kModelJunctionsJoined: its OSM nodes and the OSM ways
/// inside it) and counts the intersections joined and the roads absorbed.
void report_joined_junctions(const JunctionEnds& ends, Diagnostics& diagnostics, RoadModelStats& stats);

}  // namespace relief::detail

#pragma once
// Private to the roads module: ways that cross in plan on one level without a shared node (the
// "crossing ways" JOSM's validator flags: a node missing, or a bridge or tunnel not tagged).
// Their pavements would lie through each other at the same height; a node at the crossing makes
// it a junction, reported as a data defect.

#include <cstddef>

#include "relief/core/diagnostics.h"
#include "relief/roads/osm_reader.h"

namespace relief::detail {

/// Finds every pair of segments of different ways that cross (interiors, in a local metric
/// approximation of WGS84 about the data's centre) where both ways are on one level (neither a
/// bridge nor a tunnel, equal layer), and puts one node at the crossing into both ways: an
/// existing end node of one segment when the crossing lies within 1 cm of it, else a new node
/// with a negative id below every id in `osm`; two end nodes within 1 cm of each other (one
/// place drawn twice) are merged into the first. Each crossing is reported once
/// (codes::kOsmCrossingWithoutNode, a warning, with both way ids and the position). Segments are
/// bucketed on a grid, so the cost grows with the number of segments, not with its square.
/// Returns the number of crossings joined.
std::size_t join_crossing_ways(OsmRoads& osm, Diagnostics& diagnostics);

}  // namespace relief::detail

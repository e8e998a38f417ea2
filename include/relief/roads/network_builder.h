#pragma once
// Builds the road network from OSM ways: projection to the local frame, splitting at shared
// nodes, merging pieces with identical attributes, junction classification.

#include "relief/core/diagnostics.h"
#include "relief/roads/osm_reader.h"
#include "relief/roads/road_network.h"

namespace relief {

/// Builds the network in `frame`.
/// - Each way is projected (PROJ, WGS84 -> frame CRS, minus origin) and split at every node
///   shared with another way (or used twice by the same way).
/// - Consecutive pieces that meet at a node used by exactly two pieces and have equal
///   attributes are merged into one road (their way ids concatenated).
/// - Every road end becomes a junction: 1 end -> dead_end, 2 ends -> attribute_change, 3+ ->
///   intersection. Traffic signals and roundabout membership are carried over.
/// - Consecutive duplicate points are removed; a piece shorter than 1 cm is dropped and reported
///   ("network.degenerate_way").
/// Throws InvalidInput when no road is left.
[[nodiscard]] RoadNetwork build_network(const OsmRoads& osm, const GeoFrame& frame,
                                        Diagnostics& diagnostics);

}  // namespace relief

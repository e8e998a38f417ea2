#pragma once
// Builds the road network from OSM ways: projection to the local frame, splitting at shared
// nodes, merging pieces with identical attributes, junction classification.

#include "relief/core/diagnostics.h"
#include "relief/roads/osm_reader.h"
#include "relief/roads/road_network.h"

namespace relief {

/// Builds the network in `frame`.
/// - A way folding back onto its own pavement at a node (a hairpin drawn to one node, its legs'
///   pavements overlapping all along the shorter one) is built once there (detail::split_folds,
///   codes::kOsmWayTurnsBack).
/// - Ways crossing on one level without a shared node get a node at the crossing
///   (detail::join_crossing_ways, codes::kOsmCrossingWithoutNode).
/// - Each way is projected (PROJ, WGS84 -> frame CRS, minus origin) and split at every node
///   shared with another way (or used twice by the same way).
/// - Consecutive pieces that meet at a node used by exactly two pieces and have equal
///   attributes are merged into one road (their way ids concatenated). A two-way piece may be
///   reversed for this (its lanes swapped); a one-way never is, so one-ways merge only head to
///   tail. A closed way stays one loop road; a ring of pieces is cut at its first piece.
/// - Every road end becomes a junction: 1 end -> dead_end, 2 ends -> attribute_change, 3+ ->
///   intersection. Traffic signals and roundabout membership are carried over.
/// - Consecutive duplicate points are removed; a piece shorter than 1 cm is dropped and reported
///   ("network.degenerate_way").
/// - Roads are ordered by their first piece in the input (which keeps its direction), junctions
///   by first appearance along the roads; ids are indices. Runs in linear time.
/// Throws InvalidInput when no road is left, ProjectionError when a node cannot be projected.
[[nodiscard]] RoadNetwork build_network(const OsmRoads& input, const GeoFrame& frame,
                                        Diagnostics& diagnostics);

}  // namespace relief

#pragma once
// Private to the roads module: ways that fold back onto their own pavement at one node (a
// hairpin drawn to a single node whose legs lie closer than the road is wide all along the
// shorter one, JOSM's "sharp angles" at their worst). No reference line with the lanes' radius
// turns there, and the two legs' lanes would lie through each other: the stretch is built once,
// like a way drawn out to a node and straight back (the reader's split of X-Y-X).

#include <cstddef>

#include "relief/core/diagnostics.h"
#include "relief/roads/osm_reader.h"

namespace relief::detail {

/// Least turn (degrees) at a node for its two segments to count as a fold.
inline constexpr double kFoldMinTurn_deg = 150.0;

/// At every inner node Y of a way where the way turns by kFoldMinTurn_deg or more between X and
/// Z, and the shorter leg's far end lies within the road's width (lane width x total lanes) of
/// the longer leg, so that the two legs' pavements overlap along all of the shorter one (in a
/// local metric approximation of WGS84 at Y), the shorter leg's
/// far end N (X or Z) and Y become a way of their own (N to Y), and the way runs X-Z past it:
/// the stretch is built once, with every node kept, so that junctions at X, Y and Z stay. Folds
/// uncovered by a removal (the way now turning back at X) are removed in turn. Each fold is
/// reported (codes::kOsmWayTurnsBack, a warning, with the way, the node and the legs'
/// distance). Returns the number of folds removed.
std::size_t split_folds(OsmRoads& osm, Diagnostics& diagnostics);

}  // namespace relief::detail

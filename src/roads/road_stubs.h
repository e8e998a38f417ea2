#pragma once
// Private to the roads module: dead-end stubs that lie on the road they leave. A way cut by a
// clip box a metre past a junction (--bbox, a tile's edge), or a driveway drawn a metre long,
// leaves a road whose whole pavement lies on the other road's or the junction's: it adds no lane
// anyone can drive, its end cannot be trimmed clear of the other pavement (stray_ends.h keeps
// a metre of every road), and its mesh cuts through the junction's. Such stubs are dropped.

#include <cstddef>
#include <vector>

#include "relief/core/diagnostics.h"
#include "relief/roads/road_network.h"

namespace relief::detail {

/// Drops every road with one dead end (an end node no other road ends at) whose other end
/// joins other roads, when the road is shorter than its own half width plus the widest half
/// width of the others there (its pavement cannot reach past theirs). Where the roads that stay
/// at that node would make a corner once all its stubs are gone (more than 30 degrees from
/// straight through: a bend of wide roads, which a junction builds better), the longest stub
/// stays if it is at least 1 m long (shorter, no end trim can clear it) and its pavement reaches
/// clear of every road staying there (at an acute angle it lies on theirs). A dead end forking
/// off another road at a junction of three ends or more is dropped too where, at its far end,
/// their centre lines lie closer than their half widths plus the separation margin by more than
/// road_separation moves a road (SeparationOptions::max_shift_m): no trim or move can part the
/// two (of two such branches, the narrower is judged first). Runs before the junctions are built
/// (ends are matched by their OSM node ids); renumbers the kept roads' ids in order. Each drop
/// is reported (codes::kNetworkStubDropped, a warning). Returns the number dropped.
std::size_t drop_stubs(std::vector<Road>& roads, Diagnostics& diagnostics);

}  // namespace relief::detail

#pragma once
// Elevation-aware routing: the time a vehicle class needs on each edge of the net, given the
// edge's grade. Uphill a vehicle goes no faster than its power carries the climb (the ego
// vehicles' table, cosim/ego_world.h: a loaded truck crawls up 15 % at 7.8 m/s), downhill and on
// the level at the limit. Written as SUMO edge weights (`traveltime`), which duarouter routes
// on (--weight-files): trucks then avoid the steep streets cars take.

#include <ostream>
#include <string>
#include <vector>

#include "relief/demand/net_edges.h"

namespace relief {

/// Seconds a vehicle of `vclass` (SUMO's default size for it) needs on the edge: its length over
/// min(limit, the speed its power holds on the edge's mean grade).
[[nodiscard]] double grade_travel_time(const NetEdge& edge, const std::string& vclass);

/// The weights of every edge for `vclass` (edges the class may not use are left out).
void write_grade_weights(std::ostream& out, const std::vector<NetEdge>& edges, const std::string& vclass);

}  // namespace relief

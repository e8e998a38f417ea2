#pragma once
// Private to the roads module: intersections joined into one junction where the road between
// them is too short to hold both (netconvert's --junctions.join for OSM data). Divided streets
// crossing each other give such clusters: four nodes a few metres apart joined by one-way
// stubs that no lane can be fitted on once both junctions have taken their room.

#include <cstdint>
#include <vector>

#include "relief/roads/road_network.h"

namespace relief::detail {

struct JunctionClusters {
  /// Per network junction: the junction that stands for its cluster (its first intersection);
  /// itself when it was not joined.
  std::vector<int> representative;
  /// Per network junction: the members of the cluster it represents (itself first); empty for
  /// junctions represented by another.
  std::vector<std::vector<int>> members;
  /// Per network road: 1 where the road lies inside a joined junction.
  std::vector<std::uint8_t> absorbed;

  /// Whether traffic can drive from member junction `from` to member junction `to` of one
  /// cluster over its absorbed roads, each in its direction of travel.
  [[nodiscard]] bool reachable(const RoadNetwork& network, int from, int to) const;
};

/// Joins the two junctions at the ends of every road (not a loop, with height) that is shorter
/// than the two junctions' radii plus `min_kept_length_m`, where one is an intersection and the
/// other an intersection or an attribute change that takes room (a bend or lane change, which
/// then needs no transition road). `radius` is per network junction (0 where a junction takes no
/// room); `length` and `has_height` per network road. `used_up` (per network road, or empty)
/// marks roads joined whatever their length: roads the junctions' trims used up. A road between
/// two members of one cluster shorter than their radii + min_kept_length_m + 10 m is absorbed
/// too (left out, it would be a loop through the joined junction).
[[nodiscard]] JunctionClusters join_junctions(const RoadNetwork& network, const std::vector<double>& radius,
                                              const std::vector<double>& length,
                                              const std::vector<std::uint8_t>& has_height,
                                              double min_kept_length_m,
                                              const std::vector<std::uint8_t>& used_up);

/// Whether joining the two junctions at the ends of `road` would leave another road between
/// them too long to lie inside the joined junction (see join_junctions): a loop through it
/// whose two ends its outline cannot hold apart. Arguments as for join_junctions, `clusters`
/// its current result.
[[nodiscard]] bool join_leaves_loop(const RoadNetwork& network, const JunctionClusters& clusters,
                                    const std::vector<double>& radius, const std::vector<double>& length,
                                    const std::vector<std::uint8_t>& has_height, double min_kept_length_m,
                                    const Road& road);

}  // namespace relief::detail

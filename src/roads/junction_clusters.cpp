#include "roads/junction_clusters.h"

#include <algorithm>
#include <numeric>

namespace relief::detail {
namespace {

constexpr double kInsideSlack = 10.0;  // m more than a joined road a road inside a cluster may have

int find(std::vector<int>& parent, int j) {
  while (parent[j] != j) {
    parent[j] = parent[parent[j]];
    j = parent[j];
  }
  return j;
}

}  // namespace

JunctionClusters join_junctions(const RoadNetwork& network, const std::vector<double>& radius,
                                const std::vector<double>& length,
                                const std::vector<std::uint8_t>& has_height, double min_kept_length_m,
                                const std::vector<std::uint8_t>& used_up) {
  const std::size_t n = network.junctions.size();
  JunctionClusters out;
  out.absorbed.assign(network.roads.size(), 0);
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  for (const Road& road : network.roads) {
    const int a = road.start_junction, b = road.end_junction;
    if (a < 0 || b < 0 || a == b || !has_height[road.id]) continue;
    // Two intersections, or an intersection and a bend or lane change that takes room.
    const bool ia = network.junctions[a].kind == JunctionKind::intersection;
    const bool ib = network.junctions[b].kind == JunctionKind::intersection;
    if (!(ia || ib) || !(radius[a] > 0.0) || !(radius[b] > 0.0)) continue;
    const bool used = !used_up.empty() && used_up[road.id];
    if (!used && length[road.id] >= radius[a] + radius[b] + min_kept_length_m) continue;
    out.absorbed[road.id] = 1;
    const int ra = find(parent, a), rb = find(parent, b);
    if (ra != rb) parent[std::max(ra, rb)] = std::min(ra, rb);
  }
  // A road between two members of one cluster, not much longer than a road joined for its
  // length, lies inside the joined junction too: left out, it would be a loop through the
  // junction whose two ends the outline cannot hold apart.
  for (const Road& road : network.roads) {
    const int a = road.start_junction, b = road.end_junction;
    if (a < 0 || b < 0 || a == b || out.absorbed[road.id] || !has_height[road.id]) continue;
    if (find(parent, a) != find(parent, b)) continue;
    if (length[road.id] < radius[a] + radius[b] + min_kept_length_m + kInsideSlack) out.absorbed[road.id] = 1;
  }
  // The representative: the cluster's first intersection (a joined cluster has one).
  std::vector<int> first(n, -1);
  for (std::size_t j = 0; j < n; ++j) {
    int& f = first[find(parent, static_cast<int>(j))];
    if (f < 0 || (network.junctions[f].kind != JunctionKind::intersection &&
                  network.junctions[j].kind == JunctionKind::intersection))
      f = static_cast<int>(j);
  }
  out.representative.resize(n);
  out.members.assign(n, {});
  for (std::size_t j = 0; j < n; ++j) out.representative[j] = first[find(parent, static_cast<int>(j))];
  for (std::size_t j = 0; j < n; ++j) {
    const int r = out.representative[j];
    std::vector<int>& m = out.members[r];
    m.push_back(static_cast<int>(j));
    if (static_cast<int>(j) == r) std::swap(m.front(), m.back());  // the representative first
  }
  return out;
}

bool join_leaves_loop(const RoadNetwork& network, const JunctionClusters& clusters,
                      const std::vector<double>& radius, const std::vector<double>& length,
                      const std::vector<std::uint8_t>& has_height, double min_kept_length_m,
                      const Road& road) {
  if (road.start_junction < 0 || road.end_junction < 0) return false;
  const int ra = clusters.representative[road.start_junction];
  const int rb = clusters.representative[road.end_junction];
  for (const int m : clusters.members[ra]) {
    for (const RoadEnd& e : network.junctions[m].ends) {
      const Road& other = network.roads[e.road];
      if (other.id == road.id || clusters.absorbed[other.id] || !has_height[other.id]) continue;
      const int far = e.at_start ? other.end_junction : other.start_junction;
      if (far < 0 || clusters.representative[far] != rb) continue;
      const double inside = radius[other.start_junction] + radius[other.end_junction] + min_kept_length_m;
      if (length[other.id] >= inside + kInsideSlack) return true;
    }
  }
  return false;
}

bool JunctionClusters::reachable(const RoadNetwork& network, int from, int to) const {
  if (from == to) return true;
  const std::vector<int>& cluster = members[representative[from]];
  std::vector<int> reached{from};
  for (std::size_t k = 0; k < reached.size(); ++k) {
    for (const RoadEnd& e : network.junctions[reached[k]].ends) {
      if (!absorbed[e.road]) continue;
      const Road& road = network.roads[e.road];
      const WayAttributes& a = road.attributes;
      // Leaving from the road's start drives along it, from its end against it.
      const bool can = e.at_start ? a.lanes_forward > 0 : !a.oneway && a.lanes_backward > 0;
      const int next = e.at_start ? road.end_junction : road.start_junction;
      if (!can || std::find(reached.begin(), reached.end(), next) != reached.end()) continue;
      if (next == to) return true;
      if (std::find(cluster.begin(), cluster.end(), next) != cluster.end()) reached.push_back(next);
    }
  }
  return false;
}

}  // namespace relief::detail

#include "roads/junction_joining.h"

#include <cstddef>
#include <sstream>
#include <string>
#include <utility>

#include "relief/core/diagnostic_codes.h"
#include "relief/geometry/polygon.h"

namespace relief::detail {
namespace {

constexpr double kMaxJoinGap = 10.0;  // m beyond two radii a used-up road joins (netconvert's join-dist)

// One junction of a road seen from the road: the outlines of its other road ends and its area
// (the hull of all its road ends' end lines, the road's own end there included).
struct Side {
  std::vector<EndShape> others;
  Polyline2 area;
};

Side side(const JunctionEnds& ends, const Road& road, int junction) {
  Side out;
  Polyline2 corners;
  for (const RoadEnd* e : ends.ends_of(ends.network.junctions[ends.clusters.representative[junction]])) {
    if (!ends.usable(ends.network.roads[e->road])) continue;
    EndShape shape = ends.end_shape_at(*e);
    corners.push_back(shape.right);
    corners.push_back(shape.left);
    if (e->road != road.id) out.others.push_back(std::move(shape));
  }
  out.area = convex_hull(std::move(corners));
  return out;
}

// Whether a road end of `from` comes within the junction gap of `into`'s area.
bool reaches(const Side& from, const Side& into, double gap_m) {
  for (std::size_t i = 0; i < into.area.size(); ++i) {
    const Vec2& p = into.area[i];
    const Vec2& q = into.area[(i + 1) % into.area.size()];
    for (const EndShape& e : from.others) {
      if (segment_polygon_distance(p, q, e.strip) < gap_m) return true;
    }
  }
  return false;
}

// The two areas overlapping (each junction's surface would lie through the other's).
bool areas_overlap(const Side& x, const Side& y) {
  if (x.area.size() < 3 || y.area.size() < 3) return false;
  for (std::size_t i = 0; i < x.area.size(); ++i) {
    if (segment_polygon_distance(x.area[i], x.area[(i + 1) % x.area.size()], y.area) < 1e-9) return true;
  }
  return false;
}

// Whether the roads at one junction of a road reach into its other junction's area, or the two
// areas overlap: the trims at the first pushed them past the road between (roads meeting at a
// small angle), and the two junctions' surfaces would overlap. A far end that only carries the
// street on is covered by the end strips reaching to it.
bool junctions_meet(const JunctionEnds& ends, const Road& road) {
  const RoadNetwork& network = ends.network;
  const int ja = road.start_junction, jb = road.end_junction;
  if (ja < 0 || jb < 0 || network.junctions[ja].kind != JunctionKind::intersection ||
      network.junctions[jb].kind != JunctionKind::intersection)
    return false;
  const double gap = ends.options.junction_end_gap_m;
  const Side a = side(ends, road, ja), b = side(ends, road, jb);
  return reaches(a, b, gap) || reaches(b, a, gap) || areas_overlap(a, b) || areas_overlap(b, a);
}

}  // namespace

bool mark_used_up_roads(const JunctionEnds& ends, const std::vector<std::array<double, 2>>& radius_trim,
                        const std::vector<std::uint8_t>& stuck, std::vector<std::uint8_t>& used_up) {
  const RoadNetwork& network = ends.network;
  const double kept = ends.options.min_kept_length_m;
  // A road the trims left no more than min_kept_length_m: the two junctions' areas meet
  // across it (their kerb lines, their other roads' ends) and become one.
  bool joined_more = false;
  for (const Road& road : network.roads) {
    if (ends.loop(road) || used_up[road.id] || ends.clusters.absorbed[road.id] || !ends.has_height[road.id])
      continue;
    if (ends.road_length[road.id] - ends.trim[road.id][0] - ends.trim[road.id][1] > kept + 1e-6) continue;
    if (!stuck[road.id] &&
        ends.road_length[road.id] - radius_trim[road.id][0] - radius_trim[road.id][1] > kMaxJoinGap &&
        !(junctions_meet(ends, road) && !join_leaves_loop(network, ends.clusters, ends.radius,
                                                          ends.road_length, ends.has_height, kept, road)))
      continue;
    used_up[road.id] = 1;
    joined_more = true;
  }
  return joined_more;
}

void report_joined_junctions(const JunctionEnds& ends, Diagnostics& diagnostics, RoadModelStats& stats) {
  const RoadNetwork& network = ends.network;
  const JunctionClusters& clusters = ends.clusters;
  for (const Junction& j : network.junctions) {
    const std::vector<int>& members = clusters.members[j.id];
    if (members.size() < 2) continue;
    std::string nodes, roads;
    for (const int m : members)
      nodes += (nodes.empty() ? "" : ", ") + std::to_string(network.junctions[m].osm_node_id);
    for (const int m : members) {
      for (const RoadEnd& e : network.junctions[m].ends) {
        if (!clusters.absorbed[e.road] || !e.at_start) continue;
        std::ostringstream len;
        len.precision(1);
        len << std::fixed << ends.road_length[e.road];
        const Road& road = network.roads[e.road];
        const std::string way = road.osm_way_ids.empty() ? "?" : std::to_string(road.osm_way_ids.front());
        roads += (roads.empty() ? "" : ", ") + way + " (" + len.str() + " m)";
      }
    }
    Diagnostic d;
    d.severity = Severity::info;
    d.code = codes::kModelJunctionsJoined;
    d.message = "the junctions of OSM nodes " + nodes + " are one junction: the OSM way(s) " + roads +
                " between them are too short to hold both";
    d.osm_node_id = j.osm_node_id;
    diagnostics.report(std::move(d));
    for (const int m : members) {
      if (m != j.id && network.junctions[m].kind == JunctionKind::intersection) ++stats.junctions_joined;
    }
  }
  for (const std::uint8_t a : clusters.absorbed) stats.roads_absorbed += a;
}

}  // namespace relief::detail

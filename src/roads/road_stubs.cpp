#include "roads/road_stubs.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <sstream>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "relief/core/diagnostic_codes.h"
#include "relief/geometry/polyline.h"
#include "roads/lane_layout.h"

namespace relief::detail {
namespace {

constexpr double kStraight = 30.0 * std::numbers::pi / 180.0;  // from straight through
// A stub shorter than this cannot keep a piece of itself clear of the other pavement (the end
// trims keep 1 m of every road: stray_ends.h); it goes even where it leaves a corner.
constexpr double kUntrimmable = 1.0;

// One road end at a node: its road, half width and the unit direction it leaves the node in.
struct NodeEnd {
  std::size_t road = 0;
  double half = 0.0;
  Vec2 out = Vec2::Zero();
};

// Leaving the node along `line` (from its first point): the unit direction to the next
// distinct point.
Vec2 leaving(const Polyline2& line) {
  for (std::size_t i = 1; i < line.size(); ++i) {
    const Vec2 d = line[i] - line[0];
    if (d.norm() > 1e-9) return d.normalized();
  }
  return Vec2::Zero();
}

Polyline2 reversed_line(Polyline2 line) {
  std::reverse(line.begin(), line.end());
  return line;
}

}  // namespace

std::size_t drop_stubs(std::vector<Road>& roads, Diagnostics& diagnostics) {
  std::unordered_map<std::int64_t, std::vector<NodeEnd>> nodes;
  for (std::size_t r = 0; r < roads.size(); ++r) {
    const Road& road = roads[r];
    const double half = half_width(road);
    nodes[road.osm_node_ids.front()].push_back({r, half, leaving(road.points)});
    nodes[road.osm_node_ids.back()].push_back({r, half, leaving(reversed_line(road.points))});
  }
  // Candidates: one dead end, shorter than the pavement at its joined node reaches.
  std::vector<std::uint8_t> stub(roads.size(), 0);
  std::vector<double> reach(roads.size(), 0.0), length(roads.size(), 0.0);
  std::vector<std::int64_t> joined(roads.size(), 0);
  for (std::size_t r = 0; r < roads.size(); ++r) {
    const Road& road = roads[r];
    const bool dead_start = nodes[road.osm_node_ids.front()].size() == 1;
    const bool dead_end = nodes[road.osm_node_ids.back()].size() == 1;
    if (dead_start == dead_end) continue;
    joined[r] = dead_start ? road.osm_node_ids.back() : road.osm_node_ids.front();
    for (const NodeEnd& e : nodes[joined[r]])
      if (e.road != r) reach[r] = std::max(reach[r], e.half);
    reach[r] += half_width(road);
    length[r] = length_m(road.points);
    stub[r] = length[r] < reach[r] ? 1 : 0;
  }
  // Once the stubs are gone, their joined node must be a plain road end, a junction of three
  // roads or more, or a road straight through (within 30 degrees). Where the roads that stay
  // make a corner instead (a bend of wide roads, which a junction builds better), the longest
  // stub stays to keep the junction, unless it is under kUntrimmable; the others go. Stubs at
  // one node (a junction on a clip box's edge leaves several) are judged together.
  const auto no_corner_left = [&](std::int64_t node) {
    std::vector<Vec2> staying;
    for (const NodeEnd& e : nodes[node])
      if (!stub[e.road]) staying.push_back(e.out);
    return staying.size() != 2 || staying[0].dot(staying[1]) < -std::cos(kStraight);
  };
  std::unordered_map<std::int64_t, std::vector<std::size_t>> stubs_at;
  for (std::size_t r = 0; r < roads.size(); ++r)
    if (stub[r]) stubs_at[joined[r]].push_back(r);
  std::vector<std::uint8_t> drop = stub;
  for (const auto& [node, at] : stubs_at) {
    if (no_corner_left(node)) continue;
    const auto longest = std::max_element(at.begin(), at.end(), [&](std::size_t a, std::size_t b) {
      return length[a] < length[b] || (length[a] == length[b] && a > b);
    });
    if (length[*longest] >= kUntrimmable) drop[*longest] = 0;
  }

  std::vector<Road> kept;
  kept.reserve(roads.size());
  std::size_t dropped = 0;
  for (std::size_t r = 0; r < roads.size(); ++r) {
    Road& road = roads[r];
    if (!drop[r]) {
      road.id = static_cast<int>(kept.size());
      kept.push_back(std::move(road));
      continue;
    }
    ++dropped;
    std::ostringstream text;
    text.precision(3);
    text << "road of OSM way " << road.osm_way_ids.front()
         << (road.attributes.name.empty() ? "" : " (" + road.attributes.name + ")") << " is a dead end "
         << length[r] << " m long, lying on the roads it leaves (they reach " << reach[r]
         << " m): it is dropped";
    diagnostics.report({Severity::warning, std::string(codes::kNetworkStubDropped), text.str(),
                        road.osm_way_ids.front(), std::nullopt, std::nullopt});
  }
  roads = std::move(kept);
  return dropped;
}

}  // namespace relief::detail

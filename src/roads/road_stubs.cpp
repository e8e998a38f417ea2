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

// The road ends at one node: their half widths and the unit directions they leave it in.
struct NodeEnds {
  std::vector<std::pair<double, Vec2>> ends;
  void add(double half, const Vec2& out) { ends.emplace_back(half, out); }
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
  std::unordered_map<std::int64_t, NodeEnds> nodes;
  for (const Road& road : roads) {
    const double half = half_width(road);
    nodes[road.osm_node_ids.front()].add(half, leaving(road.points));
    nodes[road.osm_node_ids.back()].add(half, leaving(reversed_line(road.points)));
  }
  // Once the stub is gone its other node is a plain road end, a junction of three roads or
  // more, or a road straight through (within 30 degrees): not two roads at a corner, a bend of
  // wide roads the stub's junction builds better.
  const auto no_corner_left = [](const NodeEnds& node, const Vec2& stub_out) {
    std::vector<Vec2> others;
    bool skipped = false;
    for (const auto& [half, out] : node.ends) {
      if (!skipped && out == stub_out) {
        skipped = true;
        continue;
      }
      others.push_back(out);
    }
    return others.size() != 2 || others[0].dot(others[1]) < -std::cos(kStraight);
  };
  std::vector<Road> kept;
  kept.reserve(roads.size());
  std::size_t dropped = 0;
  for (Road& road : roads) {
    const NodeEnds& start = nodes[road.osm_node_ids.front()];
    const NodeEnds& end = nodes[road.osm_node_ids.back()];
    const bool dead_start = start.ends.size() == 1, dead_end = end.ends.size() == 1;
    const double half = half_width(road);
    double reach = 0.0;
    const NodeEnds& joined = dead_start ? end : start;
    const Vec2 out = dead_start ? leaving(reversed_line(road.points)) : leaving(road.points);
    for (const auto& [other_half, other_out] : joined.ends)
      if (other_out != out) reach = std::max(reach, other_half);
    reach += half;
    const double length = length_m(road.points);
    if (dead_start == dead_end || !(length < reach) || !no_corner_left(joined, out)) {
      road.id = static_cast<int>(kept.size());
      kept.push_back(std::move(road));
      continue;
    }
    ++dropped;
    std::ostringstream text;
    text.precision(3);
    text << "road of OSM way " << road.osm_way_ids.front()
         << (road.attributes.name.empty() ? "" : " (" + road.attributes.name + ")") << " is a dead end "
         << length << " m long, lying on the roads it leaves (they reach " << reach << " m): it is dropped";
    diagnostics.report({Severity::warning, std::string(codes::kNetworkStubDropped), text.str(),
                        road.osm_way_ids.front(), std::nullopt, std::nullopt});
  }
  roads = std::move(kept);
  return dropped;
}

}  // namespace relief::detail

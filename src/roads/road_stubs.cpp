#include "roads/road_stubs.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <sstream>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "relief/core/diagnostic_codes.h"
#include "relief/geometry/polyline.h"
#include "roads/lane_layout.h"
#include "roads/road_separation.h"

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

// How far along `stub` (from the node) its pavement runs before it is clear of `other`'s: both
// strips start at the node, the stub's edge on the other's side leaves the other's strip where
// its distance across the other's centre line reaches the other's half width, or, when the two
// leave more than 90 degrees apart, where it passes behind the other's start. Infinite for two
// roads leaving the node the same way (the stub lies on the other road).
double clear_reach(const NodeEnd& stub, const NodeEnd& other) {
  const double cos_phi = std::clamp(stub.out.dot(other.out), -1.0, 1.0);
  const double sin_phi = std::sqrt(1.0 - cos_phi * cos_phi);
  if (!(sin_phi > 0.0)) return cos_phi > 0.0 ? std::numeric_limits<double>::infinity() : 0.0;
  const double across = (other.half + stub.half * cos_phi) / sin_phi;
  if (cos_phi >= 0.0) return std::max(0.0, across);
  const double behind = stub.half * sin_phi / -cos_phi;
  return std::max(0.0, std::min(across, behind));
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
  const auto end_at = [&](std::size_t r, std::int64_t node) {
    for (const NodeEnd& e : nodes[node])
      if (e.road == r) return e;
    return NodeEnd{};
  };
  // Dead ends lying along another road at a junction (three ends or more: at two, a hairpin's
  // apex): a way that forks off at a few degrees and ends closer to the other than their half
  // widths, by more than road_separation moves a road (a link merging into Portland's Stadium
  // Freeway, cut by a clip box 32 m upstream: no trim or move could part them, the junction's
  // outline crossed itself and it was left open). Judged narrowest first against the roads
  // still there, so of two branches along each other only the narrower goes.
  const SeparationOptions separation;
  std::vector<std::size_t> dead_ends;
  for (std::size_t r = 0; r < roads.size(); ++r)
    if (joined[r] != 0 && !stub[r] && nodes[joined[r]].size() >= 3) dead_ends.push_back(r);
  std::sort(dead_ends.begin(), dead_ends.end(), [&](std::size_t a, std::size_t b) {
    const double ha = end_at(a, joined[a]).half, hb = end_at(b, joined[b]).half;
    return ha < hb || (ha == hb && (length[a] < length[b] || (length[a] == length[b] && a < b)));
  });
  std::vector<std::int64_t> along(roads.size(), 0);  // the OSM way a dead end lies along
  std::vector<double> too_close(roads.size(), 0.0);  // by this much at its far end
  for (const std::size_t r : dead_ends) {
    const NodeEnd me = end_at(r, joined[r]);
    for (const NodeEnd& e : nodes[joined[r]]) {
      if (e.road == r || stub[e.road]) continue;
      const double cos_phi = std::clamp(me.out.dot(e.out), -1.0, 1.0);
      if (cos_phi <= 0.0) continue;  // parting more than 90 degrees: apart beyond the junction
      const double apart = length[r] * std::sqrt(1.0 - cos_phi * cos_phi);  // centre lines, at its end
      const double shift = me.half + e.half + separation.margin_m - apart;
      if (shift > separation.max_shift_m) {
        stub[r] = 1;
        along[r] = roads[e.road].osm_way_ids.front();
        too_close[r] = shift;
        break;
      }
    }
  }
  // Once the stubs are gone, their joined node must be a plain road end, a junction of three
  // roads or more, or a road straight through (within 30 degrees). Where the roads that stay
  // make a corner instead (a bend of wide roads, which a junction builds better), the longest
  // stub stays to keep the junction, if its pavement reaches clear of theirs and by at least
  // kUntrimmable; the others go. (A stub leaving at an acute angle to a road that stays lies on
  // that road's pavement however the ends are trimmed: kept, its junction's outline crossed
  // itself and SUMO's lanes stepped, Liechtenstein clipped by --bbox.) Stubs at one node (a
  // junction on a clip box's edge leaves several) are judged together.
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
    double needed = kUntrimmable;
    NodeEnd stub_end;
    for (const NodeEnd& e : nodes[node])
      if (e.road == *longest) stub_end = e;
    for (const NodeEnd& e : nodes[node])
      if (!stub[e.road]) needed = std::max(needed, clear_reach(stub_end, e));
    if (length[*longest] >= needed) drop[*longest] = 0;
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
         << length[r] << " m long, lying on the roads it leaves (";
    if (along[r] != 0) {
      text << "along OSM way " << along[r] << ", " << too_close[r]
           << " m too close to it at its end, more than a road is moved";
    } else {
      text << "they reach " << reach[r] << " m";
    }
    text << "): it is dropped";
    diagnostics.report({Severity::warning, std::string(codes::kNetworkStubDropped), text.str(),
                        road.osm_way_ids.front(), std::nullopt, std::nullopt});
  }
  roads = std::move(kept);
  return dropped;
}

}  // namespace relief::detail

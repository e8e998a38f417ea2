#include "roads/way_crossings.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <tuple>
#include <unordered_map>
#include <utility>
#include <vector>

#include "relief/core/diagnostic_codes.h"
#include "relief/geometry/types.h"

namespace relief::detail {
namespace {

constexpr double kCell_m = 100.0;  // grid cell of the segment buckets
constexpr double kSnap_m = 0.01;   // a crossing this close to a segment's end node uses that node
constexpr double kEarthRadius_m = 6371008.8;

struct SegmentRef {
  std::uint32_t way = 0, index = 0;  // segment from node `index` to `index + 1`
};

// A node to insert into a way: after node `index`, at parameter t along that segment.
struct Insertion {
  std::uint32_t index = 0;
  double t = 0.0;
  std::int64_t id = 0;
  LonLat position;
};

bool on_one_level(const WayAttributes& a, const WayAttributes& b) {
  return !a.bridge && !a.tunnel && !b.bridge && !b.tunnel && a.layer == b.layer;
}

}  // namespace

std::size_t join_crossing_ways(OsmRoads& osm, Diagnostics& diagnostics) {
  std::vector<OsmWay>& ways = osm.ways;
  if (ways.size() < 2) return 0;
  // Local metres: an affine map of lon/lat, so crossings and their parameters are those of the
  // segments in degrees (the node positions written stay interpolated in lon/lat).
  const double lat0 = 0.5 * (osm.bounds.min_lat + osm.bounds.max_lat) * std::numbers::pi / 180.0;
  const double ky = kEarthRadius_m * std::numbers::pi / 180.0, kx = ky * std::cos(lat0);
  const auto metres = [&](const LonLat& p) { return Vec2(kx * p.lon_deg, ky * p.lat_deg); };

  std::int64_t next_id = -1;
  for (const OsmWay& way : ways) {
    for (const std::int64_t id : way.node_ids) next_id = std::min(next_id, id - 1);
  }

  std::unordered_map<std::uint64_t, std::vector<SegmentRef>> cells;
  const auto cell_key = [](std::int64_t cx, std::int64_t cy) {
    return (static_cast<std::uint64_t>(cx) << 32) ^ static_cast<std::uint64_t>(cy & 0xffffffff);
  };
  for (std::uint32_t w = 0; w < ways.size(); ++w) {
    const OsmWay& way = ways[w];
    if (way.attributes.bridge || way.attributes.tunnel) continue;
    for (std::uint32_t i = 0; i + 1 < way.nodes.size(); ++i) {
      const Vec2 a = metres(way.nodes[i]), b = metres(way.nodes[i + 1]);
      const auto lo_x = static_cast<std::int64_t>(std::floor(std::min(a.x(), b.x()) / kCell_m));
      const auto hi_x = static_cast<std::int64_t>(std::floor(std::max(a.x(), b.x()) / kCell_m));
      const auto lo_y = static_cast<std::int64_t>(std::floor(std::min(a.y(), b.y()) / kCell_m));
      const auto hi_y = static_cast<std::int64_t>(std::floor(std::max(a.y(), b.y()) / kCell_m));
      for (std::int64_t cx = lo_x; cx <= hi_x; ++cx) {
        for (std::int64_t cy = lo_y; cy <= hi_y; ++cy) cells[cell_key(cx, cy)].push_back({w, i});
      }
    }
  }

  // The crossings, each found in the cell that holds its point (segments lie in every cell
  // their box touches), then sorted so that node ids and reports do not depend on hashing.
  struct Crossing {
    SegmentRef s, t;
    double ts = 0.0, tt = 0.0;
  };
  const auto segment_key = [](const SegmentRef& r) {
    return (static_cast<std::uint64_t>(r.way) << 32) | r.index;
  };
  std::vector<Crossing> crossings;
  for (const auto& [key, segments] : cells) {
    for (std::size_t p = 0; p < segments.size(); ++p) {
      for (std::size_t q = p + 1; q < segments.size(); ++q) {
        SegmentRef s = segments[p], t = segments[q];
        if (s.way == t.way) continue;
        if (segment_key(t) < segment_key(s)) std::swap(s, t);
        const OsmWay& ws = ways[s.way];
        const OsmWay& wt = ways[t.way];
        if (!on_one_level(ws.attributes, wt.attributes)) continue;
        // Segments sharing a node meet there by design.
        const std::int64_t s0 = ws.node_ids[s.index], s1 = ws.node_ids[s.index + 1];
        const std::int64_t t0 = wt.node_ids[t.index], t1 = wt.node_ids[t.index + 1];
        if (s0 == t0 || s0 == t1 || s1 == t0 || s1 == t1) continue;
        const Vec2 a = metres(ws.nodes[s.index]), b = metres(ws.nodes[s.index + 1]);
        const Vec2 c = metres(wt.nodes[t.index]), d = metres(wt.nodes[t.index + 1]);
        const Vec2 r = b - a, u = d - c, ac = c - a;
        const double denom = r.x() * u.y() - r.y() * u.x();
        if (denom == 0.0) continue;  // parallel: no single crossing
        const double ts = (ac.x() * u.y() - ac.y() * u.x()) / denom;
        const double tt = (ac.x() * r.y() - ac.y() * r.x()) / denom;
        // Within the segments, or within kSnap_m past an end (a node on the other way, or two
        // nodes at one place).
        const double es = kSnap_m / r.norm(), et = kSnap_m / u.norm();
        if (!(ts > -es && ts < 1.0 + es && tt > -et && tt < 1.0 + et)) continue;
        const Vec2 x = a + ts * r;
        if (cell_key(static_cast<std::int64_t>(std::floor(x.x() / kCell_m)),
                     static_cast<std::int64_t>(std::floor(x.y() / kCell_m))) != key)
          continue;
        crossings.push_back({s, t, ts, tt});
      }
    }
  }
  std::sort(crossings.begin(), crossings.end(), [&](const Crossing& x, const Crossing& y) {
    return std::pair(segment_key(x.s), segment_key(x.t)) < std::pair(segment_key(y.s), segment_key(y.t));
  });

  std::size_t joined = 0;
  std::vector<std::vector<Insertion>> insertions(ways.size());
  std::unordered_map<std::int64_t, std::int64_t> alias;  // duplicate node -> the node kept
  // The node kept for `node` (three or more nodes at one place merge into the first).
  const auto kept = [&](std::int64_t node) {
    for (auto it = alias.find(node); it != alias.end(); it = alias.find(node)) node = it->second;
    return node;
  };
  std::set<std::tuple<std::int64_t, std::int64_t, std::int64_t>> reported;  // ways and node
  for (const Crossing& x : crossings) {
    const SegmentRef& s = x.s;
    const SegmentRef& t = x.t;
    const OsmWay& ws = ways[s.way];
    const OsmWay& wt = ways[t.way];
    // The node at the crossing: a segment's end node when the crossing lies on it; two such
    // nodes (one per way) are one node at one place, drawn twice.
    const double ls = (metres(ws.nodes[s.index + 1]) - metres(ws.nodes[s.index])).norm();
    const double lt = (metres(wt.nodes[t.index + 1]) - metres(wt.nodes[t.index])).norm();
    const auto end_node = [](double param, double length,
                             std::uint32_t index) -> std::optional<std::uint32_t> {
      if (param * length < kSnap_m) return index;
      if ((1.0 - param) * length < kSnap_m) return index + 1;
      return std::nullopt;
    };
    const std::optional<std::uint32_t> ks = end_node(x.ts, ls, s.index), kt = end_node(x.tt, lt, t.index);
    const LonLat& p0 = ws.nodes[s.index];
    const LonLat& p1 = ws.nodes[s.index + 1];
    LonLat at{p0.lon_deg + x.ts * (p1.lon_deg - p0.lon_deg), p0.lat_deg + x.ts * (p1.lat_deg - p0.lat_deg)};
    std::int64_t id = 0;
    std::string how;
    if (ks && kt) {
      id = ws.node_ids[*ks];
      at = ws.nodes[*ks];
      const std::int64_t twin = wt.node_ids[*kt];
      const std::int64_t a = kept(id), b = kept(twin);
      if (a == b) continue;
      alias.emplace(b, a);
      how = "two nodes at one place (" + std::to_string(id) + " and " + std::to_string(twin) + "): merged";
    } else if (ks) {
      id = ws.node_ids[*ks];
      at = ws.nodes[*ks];
      insertions[t.way].push_back({t.index, x.tt, id, at});
      how = "node " + std::to_string(id) + " of the first lies on the second: made a node of both";
    } else if (kt) {
      id = wt.node_ids[*kt];
      at = wt.nodes[*kt];
      insertions[s.way].push_back({s.index, x.ts, id, at});
      how = "node " + std::to_string(id) + " of the second lies on the first: made a node of both";
    } else {
      id = next_id--;
      insertions[s.way].push_back({s.index, x.ts, id, at});
      insertions[t.way].push_back({t.index, x.tt, id, at});
      how = "joined by a new node there";
    }
    if (!reported.emplace(ws.id, wt.id, id).second) continue;
    ++joined;
    std::ostringstream msg;
    msg.precision(7);
    msg << std::fixed << "OSM ways " << ws.id << " and " << wt.id
        << " cross on one level without a shared node (neither a bridge nor a tunnel, layer "
        << ws.attributes.layer << ") at lon " << at.lon_deg << ", lat " << at.lat_deg << ": " << how
        << ", a junction";
    Diagnostic diagnostic;
    diagnostic.severity = Severity::warning;
    diagnostic.code = codes::kOsmCrossingWithoutNode;
    diagnostic.message = msg.str();
    diagnostic.osm_way_id = ws.id;
    diagnostics.report(std::move(diagnostic));
  }
  for (std::size_t w = 0; w < ways.size(); ++w) {
    std::vector<Insertion>& list = insertions[w];
    std::sort(list.begin(), list.end(), [](const Insertion& x, const Insertion& y) {
      return std::pair(x.index, x.t) < std::pair(y.index, y.t);
    });
    OsmWay& way = ways[w];
    if (list.empty() && alias.empty()) continue;
    std::vector<std::int64_t> ids;
    std::vector<LonLat> nodes;
    std::size_t next = 0;
    for (std::uint32_t i = 0; i < way.node_ids.size(); ++i) {
      const std::int64_t node = kept(way.node_ids[i]);
      if (ids.empty() || ids.back() != node) {
        ids.push_back(node);
        nodes.push_back(way.nodes[i]);
      }
      for (; next < list.size() && list[next].index == i; ++next) {
        const std::int64_t inserted = kept(list[next].id);
        if (inserted == ids.back()) continue;  // two crossings at one node
        ids.push_back(inserted);
        nodes.push_back(list[next].position);
      }
    }
    way.node_ids = std::move(ids);
    way.nodes = std::move(nodes);
  }
  return joined;
}

}  // namespace relief::detail

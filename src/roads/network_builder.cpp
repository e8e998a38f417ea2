#include "relief/roads/network_builder.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <optional>
#include <span>
#include <sstream>
#include <unordered_map>

#include "relief/core/diagnostic_codes.h"
#include "relief/core/errors.h"
#include "relief/geometry/crs_transform.h"
#include "relief/geometry/polyline.h"
#include "roads/close_roads.h"
#include "roads/road_separation.h"
#include "roads/road_stubs.h"
#include "roads/way_crossings.h"
#include "roads/way_folds.h"

namespace relief {

namespace {

constexpr double kMinPieceLength_m = 0.01;

// Every OSM node of the input, indexed densely, with its local position.
struct NodeTable {
  std::unordered_map<std::int64_t, int> index;
  std::vector<std::int64_t> ids;
  std::vector<Vec2> positions;  // lon/lat first, local metres after projection
  std::vector<int> uses;        // occurrences in all ways, ends included
};

NodeTable collect_nodes(const OsmRoads& osm) {
  NodeTable t;
  for (const OsmWay& way : osm.ways) {
    for (std::size_t i = 0; i < way.node_ids.size(); ++i) {
      const auto [it, inserted] = t.index.emplace(way.node_ids[i], static_cast<int>(t.ids.size()));
      if (inserted) {
        t.ids.push_back(way.node_ids[i]);
        t.positions.emplace_back(way.nodes[i].lon_deg, way.nodes[i].lat_deg);
        t.uses.push_back(0);
      }
      ++t.uses[static_cast<std::size_t>(it->second)];
    }
  }
  return t;
}

// WGS84 -> frame CRS in one batch, then minus the frame origin.
void project_nodes(NodeTable& nodes, const OsmRoads& osm, const GeoFrame& frame) {
  const LonLatBox& b = osm.bounds;
  std::optional<LonLatBox> area;
  if (b.max_lon > b.min_lon && b.max_lat > b.min_lat) area = b;
  const CrsTransform to_frame("EPSG:4326", frame.crs(), area);
  std::vector<Vec2> lonlat = nodes.positions;
  to_frame.apply(std::span<Vec2>(nodes.positions));
  for (std::size_t i = 0; i < nodes.positions.size(); ++i) {
    Vec2& p = nodes.positions[i];
    if (!std::isfinite(p.x()) || !std::isfinite(p.y())) {
      std::ostringstream what;
      what.precision(10);
      what << "cannot project OSM node " << nodes.ids[i] << " (lon " << lonlat[i].x() << ", lat "
           << lonlat[i].y() << ") to " << frame.crs();
      throw ProjectionError(what.str());
    }
    p = frame.to_local(p);
  }
}

// A way between two split nodes: node indices into NodeTable, points deduplicated.
struct Piece {
  std::vector<int> nodes;
  std::int64_t way_id = 0;
  const WayAttributes* attributes = nullptr;
};

// Removes consecutive nodes at an identical position, always keeping both end nodes (they are
// the ones shared with other pieces).
void dedupe_points(std::vector<int>& nodes, const NodeTable& table) {
  const auto pos = [&](int n) -> const Vec2& { return table.positions[static_cast<std::size_t>(n)]; };
  std::vector<int> kept;
  kept.reserve(nodes.size());
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    if (!kept.empty() && pos(nodes[i]) == pos(kept.back())) {
      if (i + 1 == nodes.size() && kept.size() > 1) kept.back() = nodes[i];  // keep the end node
      continue;
    }
    kept.push_back(nodes[i]);
  }
  nodes = std::move(kept);
}

double piece_length_m(const Piece& piece, const NodeTable& table) {
  double length = 0.0;
  for (std::size_t i = 1; i < piece.nodes.size(); ++i) {
    length += (table.positions[static_cast<std::size_t>(piece.nodes[i])] -
               table.positions[static_cast<std::size_t>(piece.nodes[i - 1])])
                  .norm();
  }
  return length;
}

// Splits every way at nodes used more than once (by other ways or by itself) and drops the
// pieces shorter than kMinPieceLength_m.
std::vector<Piece> split_ways(const OsmRoads& osm, const NodeTable& table, Diagnostics& diagnostics) {
  std::vector<Piece> pieces;
  for (const OsmWay& way : osm.ways) {
    std::size_t start = 0;
    for (std::size_t i = 1; i < way.node_ids.size(); ++i) {
      const int node = table.index.at(way.node_ids[i]);
      const bool last = i + 1 == way.node_ids.size();
      if (!last && table.uses[static_cast<std::size_t>(node)] < 2) continue;
      Piece piece;
      piece.way_id = way.id;
      piece.attributes = &way.attributes;
      for (std::size_t k = start; k <= i; ++k) piece.nodes.push_back(table.index.at(way.node_ids[k]));
      dedupe_points(piece.nodes, table);
      if (piece.nodes.size() < 2 || piece_length_m(piece, table) < kMinPieceLength_m) {
        Diagnostic d;
        d.severity = Severity::warning;
        d.code = codes::kNetworkDegenerateWay;
        d.message = "way " + std::to_string(way.id) + ": the piece from node " +
                    std::to_string(way.node_ids[start]) + " to node " + std::to_string(way.node_ids[i]) +
                    " is shorter than 1 cm; dropped";
        d.osm_way_id = way.id;
        diagnostics.report(std::move(d));
      } else {
        pieces.push_back(std::move(piece));
      }
      start = i;
    }
  }
  return pieces;
}

// The attributes seen when travelling a two-way road against its direction.
WayAttributes reversed(WayAttributes a) {
  std::swap(a.lanes_forward, a.lanes_backward);
  return a;
}

// A piece end linked to the end of another piece it merges with.
struct Link {
  int piece = -1;
  bool at_start = true;
};

// links[piece][0] is the link at the piece's start, [1] at its end.
std::vector<std::array<std::optional<Link>, 2>> find_links(const std::vector<Piece>& pieces,
                                                           const NodeTable& table) {
  // The first two piece ends at every node, and how many there are.
  std::vector<std::array<RoadEnd, 2>> ends(table.ids.size());
  std::vector<int> end_count(table.ids.size(), 0);
  for (std::size_t p = 0; p < pieces.size(); ++p) {
    for (const bool at_start : {true, false}) {
      const auto node = static_cast<std::size_t>(at_start ? pieces[p].nodes.front() : pieces[p].nodes.back());
      if (end_count[node] < 2)
        ends[node][static_cast<std::size_t>(end_count[node])] = {static_cast<int>(p), at_start};
      ++end_count[node];
    }
  }

  std::vector<std::array<std::optional<Link>, 2>> links(pieces.size());
  for (std::size_t node = 0; node < ends.size(); ++node) {
    if (end_count[node] != 2) continue;
    const RoadEnd a = ends[node][0];
    const RoadEnd b = ends[node][1];
    if (a.road == b.road) continue;  // a closed loop stays a loop
    const WayAttributes& pa = *pieces[static_cast<std::size_t>(a.road)].attributes;
    const WayAttributes& pb = *pieces[static_cast<std::size_t>(b.road)].attributes;
    // Head to tail keeps both directions; head to head or tail to tail reverses one piece,
    // which a one-way must never be.
    const bool mergeable =
        a.at_start != b.at_start ? pa == pb : !pa.oneway && !pb.oneway && pa == reversed(pb);
    if (!mergeable) continue;
    links[static_cast<std::size_t>(a.road)][a.at_start ? 0 : 1] = Link{b.road, b.at_start};
    links[static_cast<std::size_t>(b.road)][b.at_start ? 0 : 1] = Link{a.road, a.at_start};
  }
  return links;
}

// A chain of pieces merged into one road, each with its direction of travel along the road.
struct ChainStep {
  int piece = -1;
  bool forward = true;
};

// Chains of linked pieces, ordered by their first piece in the input; the first piece of each
// chain keeps its direction. Linear: every piece is visited at most three times.
std::vector<std::vector<ChainStep>> merge_chains(
    const std::vector<Piece>& pieces, const std::vector<std::array<std::optional<Link>, 2>>& links) {
  const auto link_at = [&](int piece, bool at_start) -> const std::optional<Link>& {
    return links[static_cast<std::size_t>(piece)][at_start ? 0 : 1];
  };
  std::vector<char> visited(pieces.size(), 0);
  std::vector<std::vector<ChainStep>> chains;
  for (std::size_t first = 0; first < pieces.size(); ++first) {
    if (visited[first] != 0) continue;
    // Walk back from `first` (travelled forward) to the head of its chain; a ring of pieces
    // is cut at the start of `first`.
    ChainStep head{static_cast<int>(first), true};
    for (;;) {
      const auto& link = link_at(head.piece, head.forward);  // the end we enter through
      if (!link) break;
      if (link->piece == static_cast<int>(first)) {
        head = {static_cast<int>(first), true};
        break;
      }
      head = {link->piece, !link->at_start};  // we leave that piece through its linked end
    }
    // Walk forward from the head.
    std::vector<ChainStep> chain;
    for (ChainStep step = head;;) {
      visited[static_cast<std::size_t>(step.piece)] = 1;
      chain.push_back(step);
      const auto& link = link_at(step.piece, !step.forward);  // the end we leave through
      if (!link || visited[static_cast<std::size_t>(link->piece)] != 0) break;
      step = {link->piece, link->at_start};  // entered through its start: travelled forward
    }
    chains.push_back(std::move(chain));
  }
  return chains;
}

Road make_road(const std::vector<ChainStep>& chain, const std::vector<Piece>& pieces,
               const NodeTable& table) {
  Road road;
  const ChainStep& head = chain.front();
  const WayAttributes& a = *pieces[static_cast<std::size_t>(head.piece)].attributes;
  road.attributes = head.forward ? a : reversed(a);
  for (const ChainStep& step : chain) {
    const Piece& piece = pieces[static_cast<std::size_t>(step.piece)];
    std::vector<int> nodes = piece.nodes;
    if (!step.forward) std::reverse(nodes.begin(), nodes.end());
    // Consecutive pieces share their joining node.
    for (std::size_t k = road.points.empty() ? 0 : 1; k < nodes.size(); ++k) {
      road.points.push_back(table.positions[static_cast<std::size_t>(nodes[k])]);
      road.osm_node_ids.push_back(table.ids[static_cast<std::size_t>(nodes[k])]);
    }
    if (road.osm_way_ids.empty() || road.osm_way_ids.back() != piece.way_id) {
      road.osm_way_ids.push_back(piece.way_id);
    }
  }
  return road;
}

// Union-find root with path halving.
int find_root(std::vector<int>& parent, int i) {
  while (parent[static_cast<std::size_t>(i)] != i) {
    parent[static_cast<std::size_t>(i)] =
        parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(i)])];
    i = parent[static_cast<std::size_t>(i)];
  }
  return i;
}

void build_junctions(RoadNetwork& network, const OsmRoads& osm, const NodeTable& table) {
  std::vector<int> junction_at(table.ids.size(), -1);
  for (Road& road : network.roads) {
    for (const bool at_start : {true, false}) {
      const std::int64_t osm_id = at_start ? road.osm_node_ids.front() : road.osm_node_ids.back();
      int& j = junction_at[static_cast<std::size_t>(table.index.at(osm_id))];
      if (j < 0) {
        j = static_cast<int>(network.junctions.size());
        Junction junction;
        junction.id = j;
        junction.osm_node_id = osm_id;
        junction.position = at_start ? road.points.front() : road.points.back();
        junction.traffic_signal = osm.traffic_signals.contains(osm_id);
        network.junctions.push_back(std::move(junction));
      }
      Junction& junction = network.junctions[static_cast<std::size_t>(j)];
      junction.ends.push_back({road.id, at_start});
      junction.roundabout = junction.roundabout || road.attributes.roundabout;
      (at_start ? road.start_junction : road.end_junction) = j;
    }
  }

  // Kinds, and rings: roundabout roads joined at junctions form one roundabout.
  std::vector<int> parent(network.roads.size());
  std::iota(parent.begin(), parent.end(), 0);
  for (Junction& junction : network.junctions) {
    junction.kind = junction.ends.size() >= 3   ? JunctionKind::intersection
                    : junction.ends.size() == 2 ? JunctionKind::attribute_change
                                                : JunctionKind::dead_end;
    int ring = -1;
    for (const RoadEnd& end : junction.ends) {
      if (!network.roads[static_cast<std::size_t>(end.road)].attributes.roundabout) continue;
      if (ring < 0) {
        ring = end.road;
      } else {
        parent[static_cast<std::size_t>(find_root(parent, end.road))] = find_root(parent, ring);
      }
    }
  }
  for (const Road& road : network.roads) {
    if (road.attributes.roundabout && find_root(parent, road.id) == road.id) ++network.roundabouts;
  }
}

}  // namespace

RoadNetwork build_network(const OsmRoads& input, const GeoFrame& frame, Diagnostics& diagnostics) {
  OsmRoads osm = input;
  (void)detail::split_folds(osm, diagnostics);
  (void)detail::join_crossing_ways(osm, diagnostics);
  NodeTable table = collect_nodes(osm);
  project_nodes(table, osm, frame);
  const std::vector<Piece> pieces = split_ways(osm, table, diagnostics);
  const auto links = find_links(pieces, table);

  RoadNetwork network;
  network.frame = frame;
  for (const auto& chain : merge_chains(pieces, links)) {
    Road road = make_road(chain, pieces, table);
    road.id = static_cast<int>(network.roads.size());
    network.roads.push_back(std::move(road));
  }
  (void)detail::drop_stubs(network.roads, diagnostics);
  if (network.roads.empty()) {
    throw InvalidInput("no roads left to build a network from: all " + std::to_string(osm.ways.size()) +
                       " ways are empty or shorter than 1 cm");
  }
  build_junctions(network, osm, table);
  (void)detail::narrow_close_roads(network, diagnostics);
  (void)detail::separate_close_roads(network, diagnostics);
  return network;
}

}  // namespace relief

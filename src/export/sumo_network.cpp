#include "relief/export/sumo_network.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <unordered_map>

#include "export/sumo_shapes.h"
#include "geometry/outline_order.h"
#include "relief/core/diagnostic_codes.h"
#include "relief/core/errors.h"
#include "relief/roads/road_surface.h"

namespace relief {
namespace {

// SUMO priorities by road class (higher wins at uncontrolled junctions), after SUMO's own
// OSM type map.
int priority_of(HighwayClass c) {
  switch (c) {
    case HighwayClass::motorway:
      return 14;
    case HighwayClass::motorway_link:
      return 9;
    case HighwayClass::trunk:
      return 13;
    case HighwayClass::trunk_link:
      return 8;
    case HighwayClass::primary:
      return 12;
    case HighwayClass::primary_link:
      return 7;
    case HighwayClass::secondary:
      return 11;
    case HighwayClass::secondary_link:
      return 6;
    case HighwayClass::tertiary:
      return 10;
    case HighwayClass::tertiary_link:
    case HighwayClass::unclassified:
      return 5;
    case HighwayClass::residential:
      return 4;
    case HighwayClass::living_street:
      return 3;
    default:
      return 2;
  }
}

std::string edge_id(int road_id, bool along_s) {
  std::string id = along_s ? "" : "-";
  id += std::to_string(road_id);
  return id;
}

// A road whose ends meet at one node is two SUMO edges per direction (SUMO drops self-loops):
// "R" / "-R" up to the middle node, then "R#1" / "-R#1".
std::string second_half(const std::string& id) {
  return id + "#1";
}

// The driving lanes of one side of a section, innermost first.
std::vector<const LaneModel*> driving_lanes(const std::vector<LaneModel>& side) {
  std::vector<const LaneModel*> out;
  for (const LaneModel& lane : side) {
    if (lane.type == "driving") out.push_back(&lane);
  }
  return out;
}

// SUMO index of OpenDRIVE lane `odr_lane` on the edge of its side (0 = outermost), or -1.
int sumo_index(const ModelRoad& road, int odr_lane) {
  const LaneSection& sec = road.sections.front();
  const auto lanes = driving_lanes(odr_lane < 0 ? sec.right : sec.left);
  for (std::size_t k = 0; k < lanes.size(); ++k) {
    if (lanes[k]->id == odr_lane) return static_cast<int>(lanes.size() - 1 - k);
  }
  return -1;
}

// Largest |dz/ds| of the road's elevation, sampled every metre and at both ends.
double max_grade_percent(const ModelRoad& road) {
  const double length = road.length();
  double g = 0.0;
  const int n = std::max(1, static_cast<int>(std::ceil(length)));
  for (int i = 0; i <= n; ++i) {
    g = std::max(g, std::abs(road.elevation.derivative(length * i / n)));
  }
  return 100.0 * g;
}

// Outer corners of a road's cross-section at s: (left, right).
std::pair<Vec3, Vec3> cross_section(const ModelRoad& road, double s) {
  const LaneSection& sec = road.sections.front();
  const int left = sec.left.empty() ? 0 : sec.left.back().id;
  const int right = sec.right.empty() ? 0 : sec.right.back().id;
  return {surface_point(road, s, lane_border_t(road, s, left)),
          surface_point(road, s, lane_border_t(road, s, right))};
}

// A thin node outline across a cross-section: from `behind_m` behind it to `ahead_m` ahead of
// it along the unit direction `ahead` (plan). netconvert cuts edges where they enter a node's
// outline and gives the cut point the node's z; an outline this thin leaves the edges whole.
Polyline3 thin_outline(const std::pair<Vec3, Vec3>& lr, const Vec2& ahead, double behind_m, double ahead_m) {
  const auto shifted = [&](const Vec3& p, double d) {
    Vec3 q = p;
    q.head<2>() += d * ahead;
    return q;
  };
  return {shifted(lr.first, -behind_m), shifted(lr.second, -behind_m), shifted(lr.second, ahead_m),
          shifted(lr.first, ahead_m)};
}

// Unit plan direction out of the road at an end (0 = start, 1 = end).
Vec2 outward(const ModelRoad& road, int end) {
  const double h = heading_at(road, end == 0 ? 0.0 : road.length());
  const Vec2 d(std::cos(h), std::sin(h));
  return end == 0 ? Vec2(-d) : d;
}

// True when the lane bends about as tightly as its centre is far from the reference line
// (|curvature * t| >= 0.9). On the inside of the bend its centre line folds back (a cusp); on
// the outside such tight custom shapes come back from netconvert moved (measured on NE: taking
// only the inside raised the largest z error from 0.08 to 0.20 m and left a 0.19 m step between
// a lane and its internal lane), so both are left to netconvert's own curve and counted.
bool lane_centre_folds(const ModelRoad& road, int lane_id) {
  const double length = road.length();
  const int n = std::max(1, static_cast<int>(std::ceil(length / 0.5)));
  for (int i = 0; i <= n; ++i) {
    const double s = length * i / n;
    if (std::abs(road.plan.at(s).curvature * lane_centre_t(road, s, lane_id)) >= 0.9) return true;
  }
  return false;
}

class NodeTable {
 public:
  // Node id of (road index, end) with end 0 = start, 1 = end.
  std::string& at(int road, int end) { return ids_[key(road, end)]; }
  [[nodiscard]] bool has(int road, int end) const { return ids_.contains(key(road, end)); }

 private:
  static std::int64_t key(int road, int end) { return static_cast<std::int64_t>(road) * 2 + end; }
  std::unordered_map<std::int64_t, std::string> ids_;
};

}  // namespace

SumoPlainNetwork build_sumo_network(const RoadModel& model, const std::vector<SumoRoadInfo>& info,
                                    const SumoOptions& options, Diagnostics& diagnostics) {
  if (!(options.shape_tolerance_m > 0.0)) throw InvalidInput("SUMO shape tolerance must be > 0");
  if (!info.empty() && info.size() != model.roads.size()) {
    throw InvalidInput("SUMO road info: " + std::to_string(info.size()) + " entries for " +
                       std::to_string(model.roads.size()) + " roads");
  }
  SumoPlainNetwork net;
  net.frame = model.frame;

  // Nodes: one per junction, one per road-to-road link, one per dead end.
  NodeTable node_of;
  std::vector<std::uint8_t> at_dead_end(model.roads.size(), 0);  // a road with an end at no junction
  std::unordered_map<std::string, std::size_t> node_index;
  std::vector<int> node_points;  // how many road ends were averaged into each node
  const auto add_to_node = [&](const std::string& id, const Vec3& p, const std::string& type, int junction) {
    auto [it, inserted] = node_index.try_emplace(id, net.nodes.size());
    if (inserted) {
      net.nodes.push_back({id, Vec3::Zero(), type, junction, {}});
      node_points.push_back(0);
    }
    net.nodes[it->second].position += p;
    ++node_points[it->second];
  };
  for (std::size_t r = 0; r < model.roads.size(); ++r) {
    const ModelRoad& road = model.roads[r];
    if (road.junction >= 0 || road.sections.empty()) continue;
    for (int end = 0; end < 2; ++end) {
      const double s = end == 0 ? 0.0 : road.length();
      const Vec3 p = surface_point(road, s, lane_border_t(road, s, 0));
      const std::optional<RoadLink>& link = end == 0 ? road.predecessor : road.successor;
      std::string id;
      if (link && link->element == RoadLink::Element::junction) {
        id = "J" + std::to_string(link->id);
        const bool signalled = options.signalled_junctions.contains(link->id);
        add_to_node(id, p, signalled ? "traffic_light" : "priority", link->id);
      } else if (link && link->element == RoadLink::Element::road) {
        // Both roads name the node after the smaller (road id, end) so that they meet.
        const int other = model.road_index(link->id);
        const int other_end = link->contact == RoadLink::Contact::start ? 0 : 1;
        const bool mine = other < 0 || std::pair(road.id, end) < std::pair(link->id, other_end);
        id = mine ? "L" + std::to_string(road.id) + (end == 0 ? "s" : "e")
                  : "L" + std::to_string(link->id) + (other_end == 0 ? "s" : "e");
        add_to_node(id, p, "priority", -1);
        SumoNode& node = net.nodes[node_index.at(id)];
        if (node.shape.empty())
          node.shape = thin_outline(cross_section(road, s), outward(road, end), 0.01, 0.01);
      } else {
        id = "D" + std::to_string(road.id) + (end == 0 ? "s" : "e");
        at_dead_end[r] = 1;
        add_to_node(id, p, "dead_end", -1);
        net.nodes[node_index.at(id)].shape =
            thin_outline(cross_section(road, s), outward(road, end), 0.0, 0.1);
      }
      node_of.at(static_cast<int>(r), end) = id;
    }
  }
  for (std::size_t i = 0; i < net.nodes.size(); ++i) net.nodes[i].position /= node_points[i];
  // Junction outlines: the outer corners of every road end, each end's two corners from its
  // right to its left looking out of the junction along the road (counter-clockwise around the
  // junction whatever the end's position) and the ends in the order of junction_end_order, so the
  // ring is simple. A ring ordered by the angle of the ends' midpoints around the centre cut across
  // a road whose end lies beside the centre: netconvert cut that lane there, metres short of its
  // internal lanes.
  struct RingEnd {
    Vec3 right, left;
    Vec2 out;
  };
  std::unordered_map<std::string, std::vector<RingEnd>> road_ends;
  for (const ModelRoad& road : model.roads) {
    if (road.junction >= 0 || road.sections.empty()) continue;
    for (int end = 0; end < 2; ++end) {
      const std::optional<RoadLink>& link = end == 0 ? road.predecessor : road.successor;
      if (!link || link->element != RoadLink::Element::junction) continue;
      const auto [left, right] = cross_section(road, end == 0 ? 0.0 : road.length());
      // At the road's start "out of the junction" is along s, with the right border on the right.
      RingEnd ring_end = end == 0 ? RingEnd{right, left, {}} : RingEnd{left, right, {}};
      ring_end.out = -outward(road, end);
      road_ends["J" + std::to_string(link->id)].push_back(ring_end);
    }
  }
  for (SumoNode& node : net.nodes) {
    auto it = road_ends.find(node.id);
    if (it == road_ends.end() || it->second.size() < 2) continue;
    std::vector<detail::PlanEnd> plan_ends;
    for (const RingEnd& e : it->second) plan_ends.push_back({e.right.head<2>(), e.left.head<2>(), e.out});
    Polyline3 ring;
    for (const std::size_t k : detail::junction_end_order(plan_ends)) {
      ring.push_back(it->second[k].right);
      ring.push_back(it->second[k].left);
    }
    const Vec2 c = node.position.head<2>();
    for (Vec3& p : ring) {
      const Vec2 d = c - p.head<2>();
      const double len = d.norm();
      if (len > 2.0 * options.junction_inset_m) p.head<2>() += d * (options.junction_inset_m / len);
    }
    node.shape = ring;
  }
  std::vector<std::uint8_t> split(model.roads.size(), 0);
  for (std::size_t r = 0; r < model.roads.size(); ++r) {
    const ModelRoad& road = model.roads[r];
    if (road.junction >= 0 || road.sections.empty()) continue;
    if (at_dead_end[r] && road.length() < options.min_dead_end_length_m) {
      split[r] = 2;
      char length[32];
      std::snprintf(length, sizeof length, "%.2f", road.length());
      diagnostics.report({Severity::info, std::string(codes::kSumoDeadEndSkipped),
                          "road " + std::to_string(road.id) + osm_way_note(road) + " is a dead end of " +
                              length + " m beside its junction; SUMO gets no edge for it",
                          std::nullopt, std::nullopt, road.id});
      continue;
    }
    if (node_of.at(static_cast<int>(r), 0) != node_of.at(static_cast<int>(r), 1)) continue;
    if (road.length() < options.min_loop_length_m) {
      split[r] = 2;  // a turning loop too short to split into two edges that netconvert keeps whole
      diagnostics.report({Severity::info, std::string(codes::kSumoLoopSkipped),
                          "road " + std::to_string(road.id) + " (" + road.name + ") is a loop of " +
                              std::to_string(static_cast<int>(std::round(road.length()))) +
                              " m back to its own junction; SUMO gets no edge for it",
                          std::nullopt, std::nullopt, road.id});
      continue;
    }
    split[r] = 1;
    const double mid = 0.5 * road.length();
    const double h = heading_at(road, mid);
    net.nodes.push_back({"M" + std::to_string(road.id), surface_point(road, mid, lane_border_t(road, mid, 0)),
                         "priority", -1,
                         thin_outline(cross_section(road, mid), Vec2(std::cos(h), std::sin(h)), 0.01, 0.01)});
  }
  // Edge of a lane where vehicles enter the road (`entering`) or leave it.
  const auto edge_at = [&](const ModelRoad& road, int odr_lane, bool entering) {
    const bool along_s = odr_lane < 0;
    const std::string id = edge_id(road.id, along_s);
    return split[static_cast<std::size_t>(model.road_index(road.id))] && !entering ? second_half(id) : id;
  };

  // Edges: the right lanes along s, the left lanes against it. Every lane gets its own shape,
  // the OpenDRIVE lane centre, so that tapers and tight bends stay on the OpenDRIVE surface;
  // the edge shape (the centre lane line) only places the edge.
  for (std::size_t r = 0; r < model.roads.size(); ++r) {
    const ModelRoad& road = model.roads[r];
    if (road.junction >= 0 || road.sections.empty()) continue;
    const LaneSection& sec = road.sections.front();
    const HighwayClass cls = info.empty() ? HighwayClass::residential : info[r].highway;
    const double grade = max_grade_percent(road);
    const double length = road.length();
    // Stations of the edge pieces: the whole road, or both halves of a road split at its middle.
    std::vector<std::pair<double, double>> pieces = {{0.0, length}};
    if (split[r] == 2) continue;
    if (split[r]) pieces = {{0.0, 0.5 * length}, {0.5 * length, length}};
    for (const bool along_s : {true, false}) {
      const auto lanes = driving_lanes(along_s ? sec.right : sec.left);
      if (lanes.empty()) continue;
      for (std::size_t k = 0; k < pieces.size(); ++k) {
        // In travel direction: along s the pieces come in order, against s reversed.
        const auto [s0, s1] = along_s ? pieces[k] : pieces[pieces.size() - 1 - k];
        const auto sampled = [&](const std::function<double(double)>& t_of) {
          Polyline3 line = sample_road_curve(road, t_of, options.shape_tolerance_m, s0, s1);
          if (!along_s) std::reverse(line.begin(), line.end());
          return line;
        };
        SumoEdge e;
        e.id = k == 0 ? edge_id(road.id, along_s) : second_half(edge_id(road.id, along_s));
        e.odr_road = road.id;
        e.osm_way_ids = road.osm_way_ids;
        e.along_s = along_s;
        std::string middle = "M";  // not "M" + to_string(): GCC 12's false -Wrestrict (bug 105329)
        middle += std::to_string(road.id);
        e.from = k == 0 ? node_of.at(static_cast<int>(r), along_s ? 0 : 1) : middle;
        e.to = k + 1 < pieces.size() ? middle : node_of.at(static_cast<int>(r), along_s ? 1 : 0);
        e.shape = sampled([&](double s) { return lane_border_t(road, s, 0); });
        e.name = road.name;
        e.type = "highway." + std::string(to_string(cls));
        e.priority = priority_of(cls);
        e.speed_mps = road.speed_mps.value_or(default_speed_mps(cls));
        for (std::size_t i = 0; i < lanes.size(); ++i) {
          const int index = static_cast<int>(lanes.size() - 1 - i);
          const int id = lanes[i]->id;
          e.lanes.push_back({index, id, lanes[i]->width.value(0.5 * length),
                             sampled([&](double s) { return lane_centre_t(road, s, id); })});
        }
        std::sort(e.lanes.begin(), e.lanes.end(),
                  [](const SumoLane& x, const SumoLane& y) { return x.index < y.index; });
        e.max_grade_percent = grade;
        for (const auto& [vclass, limit] : options.max_grade_percent) {
          if (grade > limit) {
            e.disallow.push_back(vclass);
            ++net.stats.restricted_edges[vclass];
          }
        }
        if (k > 0) {
          for (const SumoLane& lane : e.lanes) {
            net.connections.push_back({net.edges.back().id, e.id, lane.index, lane.index, -1, 0, {}});
          }
        }
        net.edges.push_back(std::move(e));
      }
      net.stats.max_edge_grade_percent = std::max(net.stats.max_edge_grade_percent, grade);
    }
  }

  // Connections through junctions: one per lane link of every connecting road.
  for (const JunctionModel& junction : model.junctions) {
    for (const JunctionConnection& c : junction.connections) {
      const int ci = model.road_index(c.connecting_road);
      const int ii = model.road_index(c.incoming_road);
      if (ci < 0 || ii < 0) continue;
      const ModelRoad& conn = model.roads[static_cast<std::size_t>(ci)];
      const bool conn_along_s = c.contact == RoadLink::Contact::start;
      const std::optional<RoadLink>& exit = conn_along_s ? conn.successor : conn.predecessor;
      const int oi = exit ? model.road_index(exit->id) : -1;
      if (oi < 0 || exit->element != RoadLink::Element::road) continue;
      const ModelRoad& incoming = model.roads[static_cast<std::size_t>(ii)];
      const ModelRoad& outgoing = model.roads[static_cast<std::size_t>(oi)];
      for (const auto& [in_lane, conn_lane] : c.lane_links) {
        const LaneSection& csec = conn.sections.front();
        const auto& side = conn_lane < 0 ? csec.right : csec.left;
        const auto lane =
            std::find_if(side.begin(), side.end(), [&](const LaneModel& l) { return l.id == conn_lane; });
        if (lane == side.end()) continue;
        const std::optional<int> out_lane = conn_along_s ? lane->successor : lane->predecessor;
        if (!out_lane) continue;
        SumoConnection sc;
        sc.from = edge_at(incoming, in_lane, false);
        sc.to = edge_at(outgoing, *out_lane, true);
        sc.from_lane = sumo_index(incoming, in_lane);
        sc.to_lane = sumo_index(outgoing, *out_lane);
        if (sc.from_lane < 0 || sc.to_lane < 0) continue;
        sc.odr_road = conn.id;
        sc.odr_lane = conn_lane;
        if (lane_centre_folds(conn, conn_lane)) {
          ++net.stats.internal_lanes_by_netconvert;  // netconvert draws its own curve
        } else {
          // The internal lane's own centre line: no lanes are offset from it.
          sc.shape = sample_road_curve(
              conn, [&](double s) { return lane_centre_t(conn, s, conn_lane); }, options.shape_tolerance_m,
              0.0, -1.0, /*lanes_offset_from_it=*/false);
          if (!conn_along_s) std::reverse(sc.shape.begin(), sc.shape.end());
        }
        net.connections.push_back(std::move(sc));
      }
    }
  }

  // Connections at road-to-road links: every lane that arrives at a linked road end.
  for (const ModelRoad& road : model.roads) {
    if (road.junction >= 0 || road.sections.empty()) continue;
    const LaneSection& sec = road.sections.front();
    for (int end = 0; end < 2; ++end) {
      const std::optional<RoadLink>& link = end == 0 ? road.predecessor : road.successor;
      if (!link || link->element != RoadLink::Element::road) continue;
      const int oi = model.road_index(link->id);
      if (oi < 0) continue;
      const ModelRoad& other = model.roads[static_cast<std::size_t>(oi)];
      // Arriving at the end: right lanes (along s); at the start: left lanes (against s).
      for (const LaneModel* lane : driving_lanes(end == 1 ? sec.right : sec.left)) {
        const std::optional<int> next = end == 1 ? lane->successor : lane->predecessor;
        if (!next) continue;
        SumoConnection sc;
        sc.from = edge_at(road, lane->id, false);
        sc.to = edge_at(other, *next, true);
        sc.from_lane = sumo_index(road, lane->id);
        sc.to_lane = sumo_index(other, *next);
        if (sc.from_lane < 0 || sc.to_lane < 0) continue;
        net.connections.push_back(std::move(sc));
      }
    }
  }

  // Internal lanes start and end exactly where their lanes do (the lane shapes' end points).
  std::unordered_map<std::string, const SumoEdge*> edge_by_id;
  for (const SumoEdge& e : net.edges) edge_by_id[e.id] = &e;
  std::erase_if(net.connections, [&](const SumoConnection& c) {
    return !edge_by_id.contains(c.from) || !edge_by_id.contains(c.to);  // to or from a road left out
  });
  const auto lane_shape = [&](const std::string& edge, int index) -> const Polyline3* {
    const auto it = edge_by_id.find(edge);
    if (it == edge_by_id.end()) return nullptr;
    for (const SumoLane& lane : it->second->lanes) {
      if (lane.index == index && lane.shape.size() >= 2) return &lane.shape;
    }
    return nullptr;
  };
  for (SumoConnection& c : net.connections) {
    if (c.shape.size() < 2) continue;
    if (const Polyline3* from = lane_shape(c.from, c.from_lane)) c.shape.front() = from->back();
    if (const Polyline3* to = lane_shape(c.to, c.to_lane)) c.shape.back() = to->front();
  }

  net.stats.nodes = net.nodes.size();
  net.stats.edges = net.edges.size();
  net.stats.connections = net.connections.size();
  net.stats.traffic_lights = static_cast<std::size_t>(std::count_if(
      net.nodes.begin(), net.nodes.end(), [](const SumoNode& n) { return n.type == "traffic_light"; }));
  for (const int j : options.signalled_junctions) {
    if (!node_index.contains("J" + std::to_string(j))) {
      diagnostics.report(Severity::warning, codes::kSumoSignalWithoutNode,
                         "junction " + std::to_string(j) + " has a traffic signal but no SUMO node");
    }
  }
  return net;
}

}  // namespace relief

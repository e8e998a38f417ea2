#include "roads/connecting_roads.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <string>
#include <string_view>
#include <utility>

#include "relief/core/diagnostic_codes.h"
#include "relief/geometry/cubic_profile.h"
#include "relief/geometry/plane.h"
#include "relief/geometry/reference_line_fit.h"
#include "relief/roads/junction_height.h"
#include "relief/roads/way_attributes.h"
#include "roads/lane_layout.h"
#include "roads/turn_room.h"

namespace relief::detail {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kCapMargin = 0.005;  // a road on the junction's surface stays this far inside cap + 2 %
// Rounds of the junction's surface taking the departures of the roads that left it (the first on
// the surface alone).
constexpr int kSurfaceRounds = 3;

// The lane pairs (arriving lane, departing lane) that make `movement` ("through", "left",
// "right"; `slight`: a turn under 60 degrees, which a through lane may make too). With
// `turn:lanes` tagged (`turns`, one entry per arriving lane), the lanes that allow the movement
// make it: a left turn from the innermost of them into the innermost departing lanes, through
// and right from the outside in. Without, through pairs lanes from the outside in and a turn
// uses one lane, the outermost for a right turn, the innermost for a left turn.
std::vector<std::pair<int, int>> lane_pairs(const std::vector<std::string>& turns,
                                            const std::vector<int>& arriving,
                                            const std::vector<int>& departing, const char* movement,
                                            bool slight) {
  std::vector<std::pair<int, int>> pairs;
  if (turns.size() == arriving.size()) {
    std::vector<int> allowed;
    for (std::size_t k = 0; k < turns.size(); ++k)
      if (lane_allows(turns[k], movement)) allowed.push_back(arriving[k]);
    if (allowed.empty() && slight) {
      for (std::size_t k = 0; k < turns.size(); ++k)
        if (lane_allows(turns[k], "through")) allowed.push_back(arriving[k]);
    }
    const std::size_t k = std::min(allowed.size(), departing.size());
    for (std::size_t i = 0; i < k; ++i) {
      if (std::string_view(movement) == "left") {
        pairs.emplace_back(allowed[i], departing[i]);
      } else {
        pairs.emplace_back(allowed[allowed.size() - 1 - i], departing[departing.size() - 1 - i]);
      }
    }
  } else if (std::string_view(movement) == "through") {
    const std::size_t k = std::min(arriving.size(), departing.size());
    for (std::size_t i = 0; i < k; ++i)
      pairs.emplace_back(arriving[arriving.size() - 1 - i], departing[departing.size() - 1 - i]);
  } else if (std::string_view(movement) == "right") {
    pairs.emplace_back(arriving.back(), departing.back());
  } else {
    pairs.emplace_back(arriving.front(), departing.front());
  }
  return pairs;
}

// The connecting road `id` of junction `junction_id` from lane `la` of road a's end `in` to lane
// `lb` of road b's end `to`, on the junction's surface wherever that keeps its grade within
// `cap` (the larger fitted cap of the two roads + 2 %, less kCapMargin) or within the bound of
// slope_bounded_profile, whichever is larger; where the surface is steeper along it, its heights
// leave the surface there only (surface_profiles). `departure_m`: how far they leave it (from the
// surface without departures); `left`: where, if they left the surface given.
ModelRoad connecting_road(int id, int junction_id, const ModelRoad& a, const EndRef& in, int la,
                          const ModelRoad& b, const EndRef& to, int lb, const JunctionHeight& surface,
                          double cap, double& departure_m, std::vector<Vec3>& left) {
  ModelRoad c;
  c.id = id;
  c.junction = junction_id;
  c.name = "connection " + std::to_string(a.id) + ":" + std::to_string(la) + " -> " + std::to_string(b.id) +
           ":" + std::to_string(lb);
  c.type = a.type;
  c.speed_mps = std::min(a.speed_mps.value_or(10.0), b.speed_mps.value_or(10.0));
  // The reference line runs along the lane's centre (the lane kept right of it by a lane
  // offset of half its width), as the roundest arc the corner allows: then neither
  // border of a tight turn folds before the centre is tighter than half a lane.
  const double w0 = lane_width_at(a, in.at_start, la), w1 = lane_width_at(b, to.at_start, lb);
  const Pose2 from = to_lane_centre(lane_inner_pose(a, in.at_start, la), w0);
  const Pose2 dest = to_lane_centre(lane_inner_pose(b, to.at_start, lb), w1);
  c.plan = PlanView(corner_connector(from, dest));
  const double len = c.plan.length();
  const auto [z0, g0] = lane_end_height(a, in.at_start, la);
  const auto [z1, g1] = lane_end_height(b, to.at_start, lb);
  const double bound = slope_bound(len, z0, g0, z1, g1, kConnectionGradeAllowance);
  SurfaceProfiles on = surface_profiles(c.plan, surface, std::max(bound, cap - kCapMargin));
  departure_m = on.max_departure_m;
  left = std::move(on.left);
  c.elevation = std::move(on.elevation);
  c.superelevation = std::move(on.superelevation);
  c.lane_offset = CubicProfile({CubicPiece{0.0, Poly3{0.5 * w0, 0.5 * (w1 - w0) / len, 0.0, 0.0}}});
  LaneSection sec;
  LaneModel lane;
  lane.id = -1;
  lane.width = CubicProfile({CubicPiece{0.0, Poly3{w0, (w1 - w0) / len, 0.0, 0.0}}});
  lane.predecessor = la;
  lane.successor = lb;
  sec.right.push_back(lane);
  c.sections = {sec};
  c.predecessor = RoadLink{RoadLink::Element::road, a.id,
                           in.at_start ? RoadLink::Contact::start : RoadLink::Contact::end};
  c.successor = RoadLink{RoadLink::Element::road, b.id,
                         to.at_start ? RoadLink::Contact::start : RoadLink::Contact::end};
  return c;
}

}  // namespace

int junction_of(const RoadNetwork& network, const EndRef& e) {
  const Road& road = network.roads[e.network_road];
  return e.at_start ? road.start_junction : road.end_junction;
}

void add_junction(const RoadNetwork& network, const JunctionClusters& clusters, const Junction& j,
                  const std::vector<EndRef>& ends, const RoadModelOptions& options, RoadModelBuild& out,
                  Diagnostics& diagnostics) {
  RoadModel& model = out.model;
  const auto model_of = [&](const EndRef& e) -> ModelRoad& {
    return model.roads[out.model_road_of[e.network_road]];
  };
  JunctionModel jm;
  jm.id = static_cast<int>(model.junctions.size()) + 1;
  jm.source_junctions = clusters.members[j.id];
  jm.name = "junction " + std::to_string(j.osm_node_id);
  if (jm.source_junctions.size() > 1)
    jm.name += " (+" + std::to_string(jm.source_junctions.size() - 1) + " joined)";
  for (const EndRef& e : ends) {
    ModelRoad& m = model_of(e);
    (e.at_start ? m.predecessor : m.successor) =
        RoadLink{RoadLink::Element::junction, jm.id, RoadLink::Contact::start};
  }
  // The larger fitted cap of two roads (0 when none is known: the cubic's bound alone).
  const auto cap_of = [&](const EndRef& x, const EndRef& y) {
    if (options.grade_caps.empty()) return 0.0;
    return std::max(options.grade_caps[x.network_road], options.grade_caps[y.network_road]);
  };
  // The movements: (arriving end, departing end, their lanes).
  struct Movement {
    std::size_t in, to;
    int la, lb;
  };
  std::vector<Movement> movements;
  for (std::size_t ia = 0; ia < ends.size(); ++ia) {
    for (std::size_t ib = 0; ib < ends.size(); ++ib) {
      if (ia == ib) continue;
      const EndRef& in = ends[ia];
      const EndRef& to = ends[ib];
      // A movement between two member junctions follows the absorbed roads between them,
      // one-ways only forward.
      if (!clusters.reachable(network, junction_of(network, in), junction_of(network, to))) continue;
      const ModelRoad& a = model_of(in);
      const ModelRoad& b = model_of(to);
      const std::vector<int> arriving = arriving_lanes(a, in.at_start);
      const std::vector<int> departing = departing_lanes(b, to.at_start);
      if (arriving.empty() || departing.empty()) continue;
      const Pose2 from0 = lane_inner_pose(a, in.at_start, arriving.front());
      const Pose2 to0 = lane_inner_pose(b, to.at_start, departing.front());
      const double turn = wrap_angle(to0.heading - from0.heading);
      // A U-turn goes back into the arriving road, or turns back by more than 150 degrees into
      // another (the two carriageways where a divided street splits: their ends lie a metre
      // apart and the hairpin between them cannot carry a lane).
      const bool u_turn = in.network_road == to.network_road || std::abs(turn) > kUTurnAngle_rad;
      if (u_turn && !options.u_turns) continue;
      const char* movement = std::abs(turn) < kThroughAngle_rad ? "through" : turn > 0.0 ? "left" : "right";
      // A slight turn (under 60 degrees) may also be made from a through lane: streets bend.
      const bool slight = std::abs(turn) < kPi / 3.0;
      const WayAttributes& in_attr = network.roads[in.network_road].attributes;
      const std::vector<std::string>& turns = in.at_start ? in_attr.turn_backward : in_attr.turn_forward;
      for (const auto& [la, lb] : lane_pairs(turns, arriving, departing, movement, slight))
        movements.push_back({ia, ib, la, lb});
    }
  }

  // Every connecting road on the junction's surface; where some left it (too steep along them),
  // again on the surface with their departures, so that the roads crossing them meet them there.
  std::vector<EndPlane> end_planes;
  end_planes.reserve(ends.size());
  for (const EndRef& e : ends) end_planes.push_back(end_plane(model_of(e), e.at_start));
  const JunctionHeight base(std::move(end_planes));
  JunctionHeight surface = base;
  const int first_id = static_cast<int>(model.roads.size()) + 1;
  std::vector<ModelRoad> roads(movements.size());
  std::vector<double> departure(movements.size(), 0.0);
  std::vector<std::vector<Vec3>> left(movements.size());
  for (int round = 0; round < kSurfaceRounds; ++round) {
    bool any_left = false;
    for (std::size_t k = 0; k < movements.size(); ++k) {
      const Movement& m = movements[k];
      std::vector<Vec3> now_left;
      roads[k] =
          connecting_road(first_id + static_cast<int>(k), jm.id, model_of(ends[m.in]), ends[m.in], m.la,
                          model_of(ends[m.to]), ends[m.to], m.lb, surface,
                          cap_of(ends[m.in], ends[m.to]) + kConnectionGradeAllowance, departure[k], now_left);
      if (!now_left.empty()) {
        left[k] = std::move(now_left);
        any_left = true;
      }
    }
    if (!any_left || round + 1 == kSurfaceRounds) break;
    surface = base.with_departures(left);
  }
  for (std::size_t k = 0; k < movements.size(); ++k) {
    if (!left[k].empty()) ++out.stats.connecting_roads_off_surface;
    out.stats.connecting_road_departure_max_m =
        std::max(out.stats.connecting_road_departure_max_m, departure[k]);
    JunctionConnection conn;
    conn.id = static_cast<int>(jm.connections.size());
    conn.incoming_road = model_of(ends[movements[k].in]).id;
    conn.connecting_road = roads[k].id;
    conn.contact = RoadLink::Contact::start;
    conn.lane_links = {{movements[k].la, -1}};
    jm.connections.push_back(conn);
    ++out.stats.connecting_roads;
  }
  for (ModelRoad& c : roads) model.roads.push_back(std::move(c));
  if (jm.connections.empty()) {
    // No movement is possible here (every road leads away, or the turn lanes allow nothing):
    // the roads end at the junction's edge instead.
    for (const EndRef& e : ends) {
      ModelRoad& m = model_of(e);
      (e.at_start ? m.predecessor : m.successor).reset();
    }
    diagnostics.report(Severity::warning, codes::kOpendriveJunctionWithoutMovements,
                       "no movement is possible at the junction of OSM node " +
                           std::to_string(j.osm_node_id) +
                           " (one-ways all leading away, or turn lanes allowing none); its roads end there");
    ++out.stats.junctions_without_movements;
    return;
  }
  model.junctions.push_back(std::move(jm));
  ++out.stats.junctions;
}

}  // namespace relief::detail

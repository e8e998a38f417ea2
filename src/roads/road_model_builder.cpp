#include "relief/roads/road_model_builder.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <sstream>

#include "relief/core/errors.h"
#include "relief/geometry/polyline.h"
#include "relief/roads/road_surface.h"

namespace relief {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kMinRoadLength = 0.05;  // m left after trimming, else the road is skipped

double wrap_angle(double a) {
  while (a > kPi) a -= 2.0 * kPi;
  while (a <= -kPi) a += 2.0 * kPi;
  return a;
}

double half_width(const Road& road) {
  const WayAttributes& a = road.attributes;
  return 0.5 * a.lane_width_m * (a.lanes_forward + a.lanes_backward);
}

// Slope dz/ds of a profile at s, by central differences over +-h (one-sided at the ends).
double slope_at(const RoadProfile& p, double s, double h = 1.0) {
  const double lo = std::max(p.s.front(), s - h), hi = std::min(p.s.back(), s + h);
  if (hi - lo < 1e-9) return 0.0;
  return (height_at_station(p, hi) - height_at_station(p, lo)) / (hi - lo);
}

// The part [s0, s1] of a polyline; `kept_s` receives the polyline s of each returned point.
Polyline2 cut(const Polyline2& line, const std::vector<double>& cumulative, double s0, double s1,
              std::vector<double>& kept_s) {
  Polyline2 out{point_at(line, cumulative, s0)};
  kept_s = {s0};
  for (std::size_t i = 0; i < line.size(); ++i) {
    if (cumulative[i] > s0 + 1e-6 && cumulative[i] < s1 - 1e-6) {
      out.push_back(line[i]);
      kept_s.push_back(cumulative[i]);
    }
  }
  out.push_back(point_at(line, cumulative, s1));
  kept_s.push_back(s1);
  return out;
}

// Piecewise-linear map from polyline s to reference-line s through matching vertices.
double map_station(const std::vector<double>& from, const std::vector<double>& to, double s) {
  if (s <= from.front()) return to.front();
  if (s >= from.back()) return to.back();
  const auto it = std::upper_bound(from.begin(), from.end(), s);
  const auto i = static_cast<std::size_t>(it - from.begin());
  const double t = (s - from[i - 1]) / (from[i] - from[i - 1]);
  return to[i - 1] + t * (to[i] - to[i - 1]);
}

RoadMark mark(RoadMark::Type type, const char* color = "standard") {
  RoadMark m;
  m.type = type;
  m.color = color;
  return m;
}

bool is_major(HighwayClass c) {
  switch (c) {
    case HighwayClass::motorway:
    case HighwayClass::trunk:
    case HighwayClass::primary:
    case HighwayClass::secondary:
      return true;
    default:
      return false;
  }
}

std::string road_type(HighwayClass c) {
  switch (c) {
    case HighwayClass::motorway:
    case HighwayClass::motorway_link:
      return "motorway";
    case HighwayClass::trunk:
    case HighwayClass::trunk_link:
      return "rural";
    case HighwayClass::footway:
    case HighwayClass::path:
    case HighwayClass::steps:
    case HighwayClass::pedestrian:
      return "pedestrian";
    case HighwayClass::cycleway:
      return "bicycle";
    default:
      return "town";
  }
}

// One lane section over the whole road: right lanes along the reference line, left against it,
// road marks by position, the carriageway centred on the reference line by the lane offset.
void add_lanes(ModelRoad& m, const WayAttributes& a) {
  LaneSection section;
  const double w = a.lane_width_m;
  const int right = a.lanes_forward, left = a.oneway ? 0 : a.lanes_backward;
  for (int k = 1; k <= right; ++k) {
    LaneModel lane;
    lane.id = -k;
    lane.width = CubicProfile::constant(w);
    lane.mark = k == right ? mark(RoadMark::Type::solid) : mark(RoadMark::Type::broken);
    section.right.push_back(lane);
  }
  for (int k = 1; k <= left; ++k) {
    LaneModel lane;
    lane.id = k;
    lane.width = CubicProfile::constant(w);
    lane.mark = k == left ? mark(RoadMark::Type::solid) : mark(RoadMark::Type::broken);
    section.left.push_back(lane);
  }
  if (left == 0) {
    section.centre_mark = mark(RoadMark::Type::solid, "yellow");  // the left edge of a one-way
  } else {
    section.centre_mark = is_major(a.highway) ? mark(RoadMark::Type::solid_solid, "yellow")
                                              : mark(RoadMark::Type::broken, "yellow");
  }
  m.sections = {section};
  m.lane_offset = CubicProfile::constant(0.5 * w * (right - left));
}

// A road end at a junction, as the model sees it.
struct EndRef {
  int network_road = -1;
  bool at_start = true;
};

// Lanes that arrive at / depart from a road end, innermost first.
std::vector<int> arriving_lanes(const ModelRoad& m, bool at_start) {
  std::vector<int> ids;
  const LaneSection& sec = at_start ? m.sections.front() : m.sections.back();
  for (const LaneModel& l : at_start ? sec.left : sec.right) ids.push_back(l.id);
  return ids;
}
std::vector<int> departing_lanes(const ModelRoad& m, bool at_start) {
  std::vector<int> ids;
  const LaneSection& sec = at_start ? m.sections.front() : m.sections.back();
  for (const LaneModel& l : at_start ? sec.right : sec.left) ids.push_back(l.id);
  return ids;
}

// Pose of the inner border of `lane` at a road end, facing the lane's direction of travel.
Pose2 lane_inner_pose(const ModelRoad& m, bool at_start, int lane) {
  const double s = at_start ? 0.0 : m.length();
  const int inner = lane < 0 ? lane + 1 : lane - 1;
  const double t = lane_border_t(m, s, inner);
  const Pose2 ref = m.plan.at(s);
  Pose2 p;
  p.position = ref.position + t * Vec2(-std::sin(ref.heading), std::cos(ref.heading));
  p.heading = lane < 0 ? ref.heading : wrap_angle(ref.heading + kPi);
  return p;
}

double lane_width_at(const ModelRoad& m, bool at_start, int lane) {
  const double s = at_start ? 0.0 : m.length();
  return std::abs(lane_border_t(m, s, lane) - lane_border_t(m, s, lane < 0 ? lane + 1 : lane - 1));
}

// Height and slope along the direction of travel of a lane at a road end.
std::pair<double, double> end_height(const ModelRoad& m, bool at_start, bool along_reference) {
  const double s = at_start ? 0.0 : m.length();
  const double g = m.elevation.derivative(s);
  return {m.elevation.value(s), along_reference ? g : -g};
}

void set_lane_link(ModelRoad& m, bool at_start, int lane, int other) {
  LaneSection& sec = at_start ? m.sections.front() : m.sections.back();
  for (auto* side : {&sec.left, &sec.right}) {
    for (LaneModel& l : *side) {
      if (l.id != lane) continue;
      (at_start ? l.predecessor : l.successor) = other;
    }
  }
}

// Width of lane `k`-th (1 = innermost) of a list at a road end, 0 when there is no such lane.
double width_or_zero(const ModelRoad& m, bool at_start, const std::vector<int>& lanes, std::size_t k) {
  return k < lanes.size() ? lane_width_at(m, at_start, lanes[k]) : 0.0;
}

// A road from road `a`'s end at a junction to road `b`'s end there (no OpenDRIVE junction: two
// ends only). Its right lanes carry the traffic from a to b, its left lanes the traffic back;
// lanes missing on one side taper to width 0; the lane offset, heights and slopes blend from
// a's to b's with cubics, so every linked lane border meets exactly.
void add_transition_road(RoadModel& model, ModelRoad& a_ref, bool a_at_start, int b_id, bool b_at_start) {
  const ModelRoad a = a_ref;
  const ModelRoad b = model.roads[model.road_index(b_id)];
  ModelRoad t;
  t.id = static_cast<int>(model.roads.size()) + 1;
  t.name = a.name == b.name ? a.name : a.name + " / " + b.name;
  t.type = a.type;
  t.speed_mps = a.speed_mps;
  const double sa = a_at_start ? 0.0 : a.length(), sb = b_at_start ? 0.0 : b.length();
  Pose2 from = a.plan.at(sa), to = b.plan.at(sb);
  if (a_at_start) from.heading = wrap_angle(from.heading + kPi);  // leave a away from its body
  if (!b_at_start) to.heading = wrap_angle(to.heading + kPi);     // enter b along its body
  t.plan = PlanView({hermite_connector(from, to)});
  const double len = t.plan.length();
  const auto [z0, g0] = end_height(a, a_at_start, /*along_reference=*/!a_at_start);
  const auto [z1, g1] = end_height(b, b_at_start, /*along_reference=*/b_at_start);
  t.elevation = hermite_profile(len, z0, g0, z1, g1);
  t.superelevation = CubicProfile::constant(0.0);
  const double off0 = a_at_start ? -a.lane_offset.value(0.0) : a.lane_offset.value(sa);
  const double off1 = b_at_start ? b.lane_offset.value(0.0) : -b.lane_offset.value(sb);
  t.lane_offset = hermite_profile(len, off0, 0.0, off1, 0.0);

  const std::vector<int> a_in = arriving_lanes(a, a_at_start), a_out = departing_lanes(a, a_at_start);
  const std::vector<int> b_in = arriving_lanes(b, b_at_start), b_out = departing_lanes(b, b_at_start);
  LaneSection sec;
  sec.centre_mark = (a_at_start ? a.sections.front() : a.sections.back()).centre_mark;
  // Right lanes: a's arriving lanes continue as b's departing lanes; left lanes the reverse.
  const auto make_side = [&](const std::vector<int>& at_a, const std::vector<int>& at_b, int sign,
                             std::vector<LaneModel>& side) {
    const std::size_t n = std::max(at_a.size(), at_b.size());
    for (std::size_t k = 0; k < n; ++k) {
      LaneModel lane;
      lane.id = sign * static_cast<int>(k + 1);
      lane.width = hermite_profile(len, width_or_zero(a, a_at_start, at_a, k), 0.0,
                                   width_or_zero(b, b_at_start, at_b, k), 0.0);
      lane.mark = k + 1 == n ? mark(RoadMark::Type::solid) : mark(RoadMark::Type::broken);
      if (k < at_a.size()) {
        lane.predecessor = at_a[k];
        set_lane_link(a_ref, a_at_start, at_a[k], lane.id);
      }
      if (k < at_b.size()) {
        lane.successor = at_b[k];
        set_lane_link(model.roads[model.road_index(b_id)], b_at_start, at_b[k], lane.id);
      }
      side.push_back(lane);
    }
  };
  make_side(a_in, b_out, -1, sec.right);
  make_side(a_out, b_in, +1, sec.left);
  t.sections = {sec};
  t.predecessor =
      RoadLink{RoadLink::Element::road, a.id, a_at_start ? RoadLink::Contact::start : RoadLink::Contact::end};
  t.successor =
      RoadLink{RoadLink::Element::road, b.id, b_at_start ? RoadLink::Contact::start : RoadLink::Contact::end};
  (a_at_start ? a_ref.predecessor : a_ref.successor) =
      RoadLink{RoadLink::Element::road, t.id, RoadLink::Contact::start};
  ModelRoad& b_ref = model.roads[model.road_index(b_id)];
  (b_at_start ? b_ref.predecessor : b_ref.successor) =
      RoadLink{RoadLink::Element::road, t.id, RoadLink::Contact::end};
  model.roads.push_back(std::move(t));
}

// Direction in which a road leaves junction `at_start ? start : end` (unit vector).
Vec2 leaving_direction(const Road& road, bool at_start) {
  const Polyline2& p = road.points;
  const Vec2 d = at_start ? Vec2(p[1] - p[0]) : Vec2(p[p.size() - 2] - p.back());
  return d.normalized();
}

// Lanes arriving at / leaving a junction along a road end, from its attributes.
std::pair<int, int> arriving_departing(const WayAttributes& a, bool at_start) {
  const int forward = a.lanes_forward, backward = a.oneway ? 0 : a.lanes_backward;
  return at_start ? std::pair{backward, forward} : std::pair{forward, backward};
}

// Two roads meeting end to end link directly when one continues the other: straight enough that
// their outermost lane borders meet within 2 mm, with the same lanes each way and the same lane
// width. Otherwise a short transition road bends and widens from one to the other.
bool needs_transition(const RoadNetwork& network, const Junction& j) {
  if (j.kind != JunctionKind::attribute_change || j.ends.size() != 2) return false;
  const Road& a = network.roads[j.ends[0].road];
  const Road& b = network.roads[j.ends[1].road];
  const Vec2 da = leaving_direction(a, j.ends[0].at_start), db = leaving_direction(b, j.ends[1].at_start);
  const double sin_kink = std::abs(da.x() * db.y() - da.y() * db.x());
  const double reach = 2.0 * std::max(half_width(a), half_width(b));  // farthest border from the line
  if (da.dot(db) > 0.0 || reach * sin_kink > 0.002) return true;
  const auto [a_in, a_out] = arriving_departing(a.attributes, j.ends[0].at_start);
  const auto [b_in, b_out] = arriving_departing(b.attributes, j.ends[1].at_start);
  return a_in != b_out || a_out != b_in ||
         std::abs(a.attributes.lane_width_m - b.attributes.lane_width_m) > 1e-9;
}

}  // namespace

RoadModelBuild build_road_model(const RoadNetwork& network, const std::vector<RoadProfile>& profiles,
                                const RoadModelOptions& options, Diagnostics& diagnostics) {
  if (profiles.size() != network.roads.size())
    throw InvalidInput("build_road_model: one profile per road is required");
  RoadModelBuild out;
  RoadModel& model = out.model;
  model.frame = network.frame;
  out.model_road_of.assign(network.roads.size(), -1);

  // Junction radii: room for the junction at every intersection, and for a transition road
  // where two roads meet at an angle or with lanes that do not line up.
  std::vector<std::uint8_t> transition(network.junctions.size(), 0);
  for (const Junction& j : network.junctions) transition[j.id] = needs_transition(network, j) ? 1 : 0;
  std::vector<double> radius(network.junctions.size(), 0.0);
  for (const Junction& j : network.junctions) {
    if (j.kind != JunctionKind::intersection && !transition[j.id]) continue;
    double widest = 0.0;
    for (const RoadEnd& e : j.ends) widest = std::max(widest, half_width(network.roads[e.road]));
    radius[j.id] = widest + options.junction_margin_m;
  }

  // Slopes at the road ends, "leaving the junction" (downhill away from it is negative). Where
  // two roads meet head to tail (an attribute change), both take the mean so that the elevation
  // is C1 across the link: leaving slopes of a smooth pass-through are opposite.
  std::vector<std::array<double, 2>> leaving(network.roads.size(), {0.0, 0.0});
  for (const Road& road : network.roads) {
    const RoadProfile& p = profiles[road.id];
    if (!p.has_height) continue;
    leaving[road.id] = {slope_at(p, 0.0), -slope_at(p, p.s.back())};
  }
  for (const Junction& j : network.junctions) {
    if (j.kind != JunctionKind::attribute_change || j.ends.size() != 2) continue;
    const RoadEnd& e0 = j.ends[0];
    const RoadEnd& e1 = j.ends[1];
    if (!profiles[e0.road].has_height || !profiles[e1.road].has_height) continue;
    double& l0 = leaving[e0.road][e0.at_start ? 0 : 1];
    double& l1 = leaving[e1.road][e1.at_start ? 0 : 1];
    const double mean = 0.5 * (l0 - l1);
    l0 = mean;
    l1 = -mean;
  }

  // Roads: trimmed, fitted reference line, elevation records, lanes.
  for (const Road& road : network.roads) {
    const RoadProfile& p = profiles[road.id];
    if (!p.has_height) {
      ++out.stats.roads_skipped;
      continue;
    }
    const std::vector<double> cumulative = cumulative_length(road.points);
    const double length = cumulative.back();
    const double cap = options.max_trim_fraction * length;
    const double s0 = std::min(radius[road.start_junction], cap);
    const double s1 = length - std::min(radius[road.end_junction], cap);
    if (s1 - s0 < kMinRoadLength) {
      ++out.stats.roads_skipped;
      diagnostics.report(Severity::warning, "opendrive.road_too_short",
                         "road " + std::to_string(road.id) + " (" + std::to_string(length) +
                             " m) has no length left between its junctions; left out of the OpenDRIVE");
      continue;
    }
    std::vector<double> kept_s, ref_s;
    const Polyline2 part = cut(road.points, cumulative, s0, s1, kept_s);
    ModelRoad m;
    m.plan = fit_reference_line(part, {options.plan_tolerance_m, 1e-3}, &ref_s);
    m.id = static_cast<int>(model.roads.size()) + 1;
    m.name = road.attributes.name;
    m.source_road = road.id;
    m.osm_way_ids = road.osm_way_ids;
    m.type = road_type(road.attributes.highway);
    m.speed_mps = road.attributes.maxspeed_mps ? *road.attributes.maxspeed_mps
                                               : default_speed_mps(road.attributes.highway);

    // Elevation: the fitted profile's stations inside the trimmed part, on the reference line.
    std::vector<double> es{0.0}, ez{height_at_station(p, s0)};
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (p.s[i] <= s0 + 1e-6 || p.s[i] >= s1 - 1e-6) continue;
      const double rs = map_station(kept_s, ref_s, p.s[i]);
      if (rs - es.back() < 1e-6) continue;
      es.push_back(rs);
      ez.push_back(p.z[i]);
    }
    const double end_s = m.plan.length();
    if (end_s - es.back() < 1e-6) {
      es.pop_back();
      ez.pop_back();
    }
    es.push_back(end_s);
    ez.push_back(height_at_station(p, s1));
    // End slopes along the reference line; untrimmed ends take the junction's shared slope.
    const double g0 = s0 > 0.0 ? slope_at(p, s0) : leaving[road.id][0];
    const double g1 = s1 < length ? slope_at(p, s1) : -leaving[road.id][1];
    m.elevation = fit_cubic_profile(es, ez, options.elevation_tolerance_m, std::make_pair(g0, g1));
    for (std::size_t i = 0; i < es.size(); ++i) {
      out.stats.max_elevation_deviation_m =
          std::max(out.stats.max_elevation_deviation_m, std::abs(m.elevation.value(es[i]) - ez[i]));
    }
    m.superelevation = CubicProfile::constant(0.0);
    add_lanes(m, road.attributes);
    out.model_road_of[road.id] = static_cast<int>(model.roads.size());
    model.roads.push_back(std::move(m));
    ++out.stats.roads;
  }

  // Junctions.
  for (const Junction& j : network.junctions) {
    std::vector<EndRef> ends;
    for (const RoadEnd& e : j.ends) {
      if (out.model_road_of[e.road] >= 0) ends.push_back({e.road, e.at_start});
    }
    const auto model_of = [&](const EndRef& e) -> ModelRoad& {
      return model.roads[out.model_road_of[e.network_road]];
    };

    if (transition[j.id] && ends.size() == 2) {
      add_transition_road(model, model_of(ends[0]), ends[0].at_start, model_of(ends[1]).id, ends[1].at_start);
      ++out.stats.transition_roads;
      continue;
    }
    if (j.kind == JunctionKind::attribute_change && ends.size() == 2) {
      // Direct link, lane to lane: same direction (end meets start) pairs right with right.
      ModelRoad& a = model_of(ends[0]);
      ModelRoad& b = model_of(ends[1]);
      const auto contact = [](bool at_start) {
        return at_start ? RoadLink::Contact::start : RoadLink::Contact::end;
      };
      (ends[0].at_start ? a.predecessor : a.successor) =
          RoadLink{RoadLink::Element::road, b.id, contact(ends[1].at_start)};
      (ends[1].at_start ? b.predecessor : b.successor) =
          RoadLink{RoadLink::Element::road, a.id, contact(ends[0].at_start)};
      const bool same_direction = ends[0].at_start != ends[1].at_start;
      const LaneSection& sa = ends[0].at_start ? a.sections.front() : a.sections.back();
      const LaneSection& sb = ends[1].at_start ? b.sections.front() : b.sections.back();
      const auto link_side = [&](const std::vector<LaneModel>& la, const std::vector<LaneModel>& lb) {
        for (std::size_t k = 0; k < std::min(la.size(), lb.size()); ++k) {
          set_lane_link(a, ends[0].at_start, la[k].id, lb[k].id);
          set_lane_link(b, ends[1].at_start, lb[k].id, la[k].id);
        }
      };
      const std::vector<LaneModel> ar = sa.right, al = sa.left, br = sb.right, bl = sb.left;
      if (same_direction) {
        link_side(ar, br);
        link_side(al, bl);
      } else {
        link_side(ar, bl);
        link_side(al, br);
      }
      ++out.stats.direct_links;
      continue;
    }
    if (j.kind != JunctionKind::intersection || ends.size() < 2) continue;

    JunctionModel jm;
    jm.id = static_cast<int>(model.junctions.size()) + 1;
    jm.source_junction = j.id;
    jm.name = "junction " + std::to_string(j.osm_node_id);
    for (const EndRef& e : ends) {
      ModelRoad& m = model_of(e);
      (e.at_start ? m.predecessor : m.successor) =
          RoadLink{RoadLink::Element::junction, jm.id, RoadLink::Contact::start};
    }
    for (std::size_t ia = 0; ia < ends.size(); ++ia) {
      for (std::size_t ib = 0; ib < ends.size(); ++ib) {
        if (ia == ib) continue;
        const EndRef& in = ends[ia];
        const EndRef& to = ends[ib];
        if (!options.u_turns && in.network_road == to.network_road) continue;
        // Copies: adding connecting roads may reallocate model.roads.
        const ModelRoad a = model_of(in);
        const ModelRoad b = model_of(to);
        const std::vector<int> arriving = arriving_lanes(a, in.at_start);
        const std::vector<int> departing = departing_lanes(b, to.at_start);
        if (arriving.empty() || departing.empty()) continue;
        const Pose2 from0 = lane_inner_pose(a, in.at_start, arriving.front());
        const Pose2 to0 = lane_inner_pose(b, to.at_start, departing.front());
        const double turn = wrap_angle(to0.heading - from0.heading);
        const char* movement = std::abs(turn) < kPi / 6.0 ? "through" : turn > 0.0 ? "left" : "right";
        // A slight turn (under 60 degrees) may also be made from a through lane: streets bend.
        const bool slight = std::abs(turn) < kPi / 3.0;
        // With `turn:lanes` tagged, the lanes that allow the movement make it: a left turn from
        // the innermost of them into the innermost departing lanes, through and right from the
        // outside in. Without, through pairs lanes from the outside in and a turn uses one lane,
        // the outermost for a right turn, the innermost for a left turn.
        const WayAttributes& in_attr = network.roads[in.network_road].attributes;
        const std::vector<std::string>& turns = in.at_start ? in_attr.turn_backward : in_attr.turn_forward;
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
        for (const auto& [la, lb] : pairs) {
          ModelRoad c;
          c.id = static_cast<int>(model.roads.size()) + 1;
          c.junction = jm.id;
          c.name = "connection " + std::to_string(a.id) + ":" + std::to_string(la) + " -> " +
                   std::to_string(b.id) + ":" + std::to_string(lb);
          c.type = a.type;
          c.speed_mps = std::min(a.speed_mps.value_or(10.0), b.speed_mps.value_or(10.0));
          const Pose2 from = lane_inner_pose(a, in.at_start, la);
          const Pose2 dest = lane_inner_pose(b, to.at_start, lb);
          c.plan = PlanView({hermite_connector(from, dest)});
          const double len = c.plan.length();
          const auto [z0, g0] = end_height(a, in.at_start, /*along_reference=*/la < 0);
          const auto [z1, g1] = end_height(b, to.at_start, /*along_reference=*/lb < 0);
          c.elevation = hermite_profile(len, z0, g0, z1, g1);
          c.superelevation = CubicProfile::constant(0.0);
          c.lane_offset = CubicProfile::constant(0.0);
          const double w0 = lane_width_at(a, in.at_start, la), w1 = lane_width_at(b, to.at_start, lb);
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
          JunctionConnection conn;
          conn.id = static_cast<int>(jm.connections.size());
          conn.incoming_road = a.id;
          conn.connecting_road = c.id;
          conn.contact = RoadLink::Contact::start;
          conn.lane_links = {{la, -1}};
          jm.connections.push_back(conn);
          model.roads.push_back(std::move(c));
          ++out.stats.connecting_roads;
        }
      }
    }
    if (jm.connections.empty()) {
      // No movement is possible here (every road leads away, or the turn lanes allow nothing):
      // the roads end at the junction's edge instead.
      for (const EndRef& e : ends) {
        ModelRoad& m = model_of(e);
        (e.at_start ? m.predecessor : m.successor).reset();
      }
      diagnostics.report(
          Severity::warning, "opendrive.junction_without_movements",
          "no movement is possible at the junction of OSM node " + std::to_string(j.osm_node_id) +
              " (one-ways all leading away, or turn lanes allowing none); its roads end there");
      ++out.stats.junctions_without_movements;
      continue;
    }
    model.junctions.push_back(std::move(jm));
    ++out.stats.junctions;
  }
  return out;
}

}  // namespace relief

#include "roads/transition_roads.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <utility>

#include "relief/core/diagnostic_codes.h"
#include "relief/core/number_format.h"
#include "relief/geometry/cubic_profile.h"
#include "relief/geometry/plane.h"
#include "relief/geometry/polyline.h"
#include "relief/geometry/reference_line_fit.h"
#include "relief/roads/road_surface.h"
#include "roads/junction_planes.h"
#include "roads/lane_layout.h"
#include "roads/road_records.h"

namespace relief::detail {
namespace {

constexpr double kFoldStep_m = 0.25;     // stations along a transition road checked for folding
constexpr double kLaneGradeRun_m = 0.2;  // a lane centre's grade is taken over this much of its length

// Direction in which a road leaves junction `at_start ? start : end`, `along` metres into it:
// that of the polyline segment there (unit vector).
Vec2 leaving_direction(const Road& road, bool at_start, double along = 0.0) {
  const Polyline2& p = road.points;
  const std::size_t n = p.size();
  double walked = 0.0;
  for (std::size_t k = 0; k + 1 < n; ++k) {
    const Vec2 a = at_start ? p[k] : p[n - 1 - k], b = at_start ? p[k + 1] : p[n - 2 - k];
    walked += (b - a).norm();
    if (walked >= along || k + 2 == n) return (b - a).normalized();
  }
  return Vec2::UnitX();  // not reached: a road has two distinct points
}

// Lanes arriving at / leaving a junction along a road end, from its attributes.
std::pair<int, int> arriving_departing(const WayAttributes& a, bool at_start) {
  const int forward = a.lanes_forward, backward = a.oneway ? 0 : a.lanes_backward;
  return at_start ? std::pair{backward, forward} : std::pair{forward, backward};
}

// Whether a border of the road's lanes comes within `margin_m` of the centre of its reference
// line's curvature, or beyond it (where the lofted border folds back on itself): sampled every
// 0.25 m, and at every geometry record's ends.
bool folds(const ModelRoad& road, double margin_m) {
  const double len = road.length();
  std::vector<double> stations;
  for (double s = 0.0; s < len; s += kFoldStep_m) stations.push_back(s);
  for (const PlanGeometry& g : road.plan.records()) stations.push_back(std::min(g.s + g.length, len));
  for (const double s : stations) {
    const double k = road.plan.at(s).curvature;
    if (k == 0.0) continue;
    const LaneSection& sec = section_at(road, s);
    const double ds = s - sec.s;
    double t = road.lane_offset.value(s);  // the border on the inside of the bend
    for (const LaneModel& lane : k > 0.0 ? sec.left : sec.right)
      t += (k > 0.0 ? 1.0 : -1.0) * lane.width.value(ds);
    if (std::abs(t) + margin_m >= 1.0 / std::abs(k) && t * k > 0.0) return true;
  }
  return false;
}

// The steepest grade of any lane centre of the road over runs of kLaneGradeRun_m of the lane's
// own plan length (the stations every kFoldStep_m; a last run shorter than half of it joins
// the one before).
double steepest_lane_grade(const ModelRoad& road) {
  const double len = road.length();
  double steepest = 0.0;
  const LaneSection& sec = road.sections.front();
  for (const std::vector<LaneModel>* side : {&sec.left, &sec.right}) {
    for (const LaneModel& lane : *side) {
      Vec3 last = surface_point(road, 0.0, lane_centre_t(road, 0.0, lane.id));
      Vec3 before = last;
      for (double s = kFoldStep_m;; s += kFoldStep_m) {
        s = std::min(s, len);
        const Vec3 p = surface_point(road, s, lane_centre_t(road, s, lane.id));
        const double run = (p - last).head<2>().norm();
        if (s == len && run < 0.5 * kLaneGradeRun_m) {
          steepest = std::max(steepest,
                              std::abs(p.z() - before.z()) / std::max((p - before).head<2>().norm(), 1e-9));
          break;
        }
        if (run >= kLaneGradeRun_m || s == len) {
          steepest = std::max(steepest, std::abs(p.z() - last.z()) / std::max(run, 1e-9));
          before = last;
          last = p;
        }
        if (s == len) break;
      }
    }
  }
  return steepest;
}

}  // namespace

double transition_reach(const RoadNetwork& network, const std::vector<RoadProfile>& profiles,
                        const Junction& j, double reach, const RoadModelOptions& options) {
  const RoadEnd ends[2] = {j.ends[0], j.ends[1]};
  const Road* roads[2] = {&network.roads[ends[0].road], &network.roads[ends[1].road]};
  const std::vector<double> cumulative[2] = {cumulative_length(roads[0]->points),
                                             cumulative_length(roads[1]->points)};
  const double r = std::max(minimum_radius(*roads[0], options), minimum_radius(*roads[1], options));
  const double limit = options.max_trim_fraction * std::min(cumulative[0].back(), cumulative[1].back());
  double best = reach, widest = -1.0;
  double allowed = std::numeric_limits<double>::infinity();  // the steepest the transition may get
  for (double d = reach; d <= limit; d *= 1.25) {
    Vec2 p[2], dir[2];
    double s_at[2];
    for (int k = 0; k < 2; ++k) {
      s_at[k] = ends[k].at_start ? d : cumulative[k].back() - d;
      p[k] = point_at(roads[k]->points, cumulative[k], s_at[k]);
      dir[k] = leaving_direction(*roads[k], ends[k].at_start, d);
    }
    const double turn = std::acos(std::clamp(-dir[0].dot(dir[1]), -1.0, 1.0));
    const double chord = (p[0] - p[1]).norm();
    const double radius =
        turn < 1e-9 ? std::numeric_limits<double>::infinity() : chord / (2.0 * std::sin(0.5 * turn));
    const RoadProfile& pa = profiles[roads[0]->id];
    const RoadProfile& pb = profiles[roads[1]->id];
    if (pa.has_height && pb.has_height) {
      const double length = turn < 1e-9 ? chord : radius * turn;
      const double grade = std::abs(height_at_station(pa, s_at[0]) - height_at_station(pb, s_at[1])) / length;
      const double roads_grade = std::max(std::abs(slope_at(pa, s_at[0])), std::abs(slope_at(pb, s_at[1])));
      if (d == reach) {
        allowed = std::max(grade, roads_grade + kConnectionGradeAllowance);
      } else if (grade > allowed) {
        break;
      }
    }
    if (radius >= r) return d;
    if (radius > widest) {
      widest = radius;
      best = d;
    }
  }
  return best;
}

std::vector<std::uint8_t> transition_junctions(const RoadNetwork& network) {
  std::vector<std::uint8_t> transition(network.junctions.size(), 0);
  for (const Junction& j : network.junctions) transition[j.id] = needs_transition(network, j) ? 1 : 0;
  return transition;
}

bool has_passage(const RoadNetwork& network, const Junction& j) {
  const auto [a_in, a_out] = arriving_departing(network.roads[j.ends[0].road].attributes, j.ends[0].at_start);
  const auto [b_in, b_out] = arriving_departing(network.roads[j.ends[1].road].attributes, j.ends[1].at_start);
  return (a_in > 0 && b_out > 0) || (b_in > 0 && a_out > 0);
}

bool needs_transition(const RoadNetwork& network, const Junction& j) {
  if (j.kind != JunctionKind::attribute_change || j.ends.size() != 2 || !has_passage(network, j))
    return false;
  const Road& a = network.roads[j.ends[0].road];
  const Road& b = network.roads[j.ends[1].road];
  const Vec2 da = leaving_direction(a, j.ends[0].at_start), db = leaving_direction(b, j.ends[1].at_start);
  const double sin_kink = std::abs(cross(da, db));
  const double reach = 2.0 * std::max(half_width(a), half_width(b));  // farthest border from the line
  if (da.dot(db) > 0.0 || reach * sin_kink > 0.002) return true;
  const auto [a_in, a_out] = arriving_departing(a.attributes, j.ends[0].at_start);
  const auto [b_in, b_out] = arriving_departing(b.attributes, j.ends[1].at_start);
  return a_in != b_out || a_out != b_in ||
         std::abs(a.attributes.lane_width_m - b.attributes.lane_width_m) > 1e-9;
}

TransitionOutcome add_transition_road(RoadModel& model, ModelRoad& a_ref, bool a_at_start, int b_id,
                                      bool b_at_start, const Vec2& gradient, double margin_m,
                                      double max_lane_grade) {
  const ModelRoad& a = a_ref;
  const ModelRoad& b = model.roads[model.road_index(b_id)];
  ModelRoad t;
  t.id = static_cast<int>(model.roads.size()) + 1;
  t.name = a.name == b.name ? a.name : a.name + " / " + b.name;
  t.type = a.type;
  t.speed_mps = a.speed_mps;
  const double sa = a_at_start ? 0.0 : a.length(), sb = b_at_start ? 0.0 : b.length();
  Pose2 from = a.plan.at(sa), to = b.plan.at(sb);
  if (a_at_start) from.heading = wrap_angle(from.heading + std::numbers::pi);  // leave a away from its body
  if (!b_at_start) to.heading = wrap_angle(to.heading + std::numbers::pi);     // enter b along its body
  // The roundest circular arc the corner allows (and a line): a cubic between the same poses
  // pinches the bend into a radius smaller than the lanes are wide, and the lanes fold.
  t.plan = PlanView(corner_connector(from, to));
  const double len = t.plan.length();
  const auto [z0, g0] = end_height(a, a_at_start, /*along_reference=*/!a_at_start);
  const auto [z1, g1] = end_height(b, b_at_start, /*along_reference=*/b_at_start);
  t.elevation = slope_bounded_profile(len, z0, g0, z1, g1, kConnectionGradeAllowance);
  t.superelevation = plane_rolls(t.plan, gradient, gradient);
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
      if (k < at_a.size()) lane.predecessor = at_a[k];
      if (k < at_b.size()) lane.successor = at_b[k];
      side.push_back(lane);
    }
  };
  make_side(a_in, b_out, -1, sec.right);
  make_side(a_out, b_in, +1, sec.left);
  t.sections = {sec};
  if (folds(t, margin_m)) return TransitionOutcome::folds;
  if (steepest_lane_grade(t) > max_lane_grade) return TransitionOutcome::too_steep;

  for (const std::vector<LaneModel>* side : {&t.sections.front().right, &t.sections.front().left}) {
    for (const LaneModel& lane : *side) {
      if (lane.predecessor) set_lane_link(a_ref, a_at_start, *lane.predecessor, lane.id);
      if (lane.successor)
        set_lane_link(model.roads[model.road_index(b_id)], b_at_start, *lane.successor, lane.id);
    }
  }
  t.predecessor = RoadLink{RoadLink::Element::road, a_ref.id,
                           a_at_start ? RoadLink::Contact::start : RoadLink::Contact::end};
  t.successor =
      RoadLink{RoadLink::Element::road, b_id, b_at_start ? RoadLink::Contact::start : RoadLink::Contact::end};
  (a_at_start ? a_ref.predecessor : a_ref.successor) =
      RoadLink{RoadLink::Element::road, t.id, RoadLink::Contact::start};
  ModelRoad& b_ref = model.roads[model.road_index(b_id)];
  (b_at_start ? b_ref.predecessor : b_ref.successor) =
      RoadLink{RoadLink::Element::road, t.id, RoadLink::Contact::end};
  model.roads.push_back(std::move(t));
  return TransitionOutcome::added;
}

void link_directly(ModelRoad& a, bool a_at_start, ModelRoad& b, bool b_at_start) {
  const auto contact = [](bool at_start) {
    return at_start ? RoadLink::Contact::start : RoadLink::Contact::end;
  };
  (a_at_start ? a.predecessor : a.successor) = RoadLink{RoadLink::Element::road, b.id, contact(b_at_start)};
  (b_at_start ? b.predecessor : b.successor) = RoadLink{RoadLink::Element::road, a.id, contact(a_at_start)};
  const bool same_direction = a_at_start != b_at_start;
  const LaneSection& sa = a_at_start ? a.sections.front() : a.sections.back();
  const LaneSection& sb = b_at_start ? b.sections.front() : b.sections.back();
  const auto link_side = [&](const std::vector<LaneModel>& la, const std::vector<LaneModel>& lb) {
    for (std::size_t k = 0; k < std::min(la.size(), lb.size()); ++k) {
      set_lane_link(a, a_at_start, la[k].id, lb[k].id);
      set_lane_link(b, b_at_start, lb[k].id, la[k].id);
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
}

void report_transition_as_junction(const Junction& j, const ModelRoad& a, const ModelRoad& b,
                                   TransitionOutcome why, double radius_m, double max_lane_grade,
                                   Diagnostics& diagnostics) {
  Diagnostic d;
  d.severity = Severity::info;
  d.code = codes::kModelTransitionAsJunction;
  std::string reason;
  if (why == TransitionOutcome::too_steep) {
    reason = "a transition road's inner lane would climb steeper than ";
    append_shortest(reason, 100.0 * max_lane_grade);
    reason += " % over its shortened length";
  } else {
    reason = "a transition road's inner lane border would pass within ";
    append_shortest(reason, radius_m);
    reason += " m of the bend's centre, or beyond it";
  }
  d.message = "roads " + std::to_string(a.id) + " and " + std::to_string(b.id) + " meet at OSM node " +
              std::to_string(j.osm_node_id) + " in a bend too tight for their lanes (" + reason +
              "); the node is a junction, one connecting road per movement";
  d.osm_node_id = j.osm_node_id;
  diagnostics.report(std::move(d));
}

void report_no_passage(const Junction& j, const ModelRoad& a, const ModelRoad& b, Diagnostics& diagnostics) {
  Diagnostic d;
  d.severity = Severity::warning;
  d.code = codes::kModelNoPassage;
  d.message = "roads " + std::to_string(a.id) + " and " + std::to_string(b.id) + " meet at OSM node " +
              std::to_string(j.osm_node_id) +
              " but no lane leads from one into the other (one-ways both arriving or both leaving); "
              "both end there";
  d.osm_node_id = j.osm_node_id;
  diagnostics.report(std::move(d));
}

}  // namespace relief::detail

#include "relief/roads/road_model_builder.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <sstream>

#include <Eigen/Eigenvalues>

#include "relief/core/diagnostic_codes.h"
#include "relief/core/errors.h"
#include "relief/geometry/polygon.h"
#include "relief/geometry/polyline.h"
#include "relief/roads/road_surface.h"
#include "roads/junction_clusters.h"
#include "roads/stray_ends.h"

namespace relief {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kUTurn_rad = 5.0 * kPi / 6.0;
constexpr double kMinRoadLength = 0.05;  // m left after trimming, else the road is skipped
constexpr double kTrimStep = 0.5;        // m added to an overlapping road end's trim per pass
constexpr int kMaxTrimPasses = 400;      // bounds the trims' growth at one junction
constexpr int kMaxJoinRounds = 8;        // bounds the rounds of junctions joined by their trims
// A road inside a junction is no steeper than its steeper end or than its mean grade plus this.
constexpr double kConnectionGradeAllowance = 0.02;
constexpr double kMaxJoinGap = 10.0;  // m beyond two radii a used-up road joins (netconvert's join-dist)

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

// The centre of a lane of width w whose inner border runs along `inner` (lanes lie right of
// their direction of travel).
Pose2 to_lane_centre(Pose2 inner, double w) {
  inner.position += 0.5 * w * Vec2(std::sin(inner.heading), -std::cos(inner.heading));
  return inner;
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

// Height and slope along the direction of travel of the centre of `lane` at a road end (the
// roll eases to its end value with zero slope, so the slope is the reference line's).
std::pair<double, double> lane_end_height(const ModelRoad& m, bool at_start, int lane) {
  const double s = at_start ? 0.0 : m.length();
  const double g = end_height(m, at_start, /*along_reference=*/lane < 0).second;
  return {surface_z(m, s, lane_centre_t(m, s, lane)), g};
}

// Superelevation (roll, radians) that lays a cross-section of the given heading on a plane of
// gradient g: the surface rises by tan(roll) per metre to the left (road_surface.h).
double plane_roll(const Vec2& g, double heading) {
  return std::atan(g.dot(Vec2(-std::sin(heading), std::cos(heading))));
}

// A road's roll eases from its junction's to level over this length: a lane t metres from the
// reference line climbs at most 1.5 t tan(roll) / kRollEase_m more than the road (0.45 % for a
// 1.5 m lane centre at a 10 % cross-slope).
constexpr double kRollEase_m = 50.0;
constexpr double kRollStep_m = 0.5;  // roll samples along a road inside a junction
// A direction of a junction's plane counts as determined by its roads when lambda, the sum of
// the squared cosines of the roads' directions with it, is at least kPlaneDetermined (a T
// junction: 2 along the through road, 1 across; a fork at 45 degrees: 0.5 across), and not at
// all under kPlaneUndetermined (a road straight through: 0; a fork at 13 degrees: 0.05), a
// smoothstep between.
constexpr double kPlaneDetermined = 0.5;
constexpr double kPlaneUndetermined = 0.05;
constexpr double kRollTolerance_rad = 1e-5;  // 0.02 mm at 2 m from the reference line

// The part of a junction's plane gradient its roads determine. The fit's plane is pinned only
// along the roads' directions: across a road that runs straight through, or across the two
// roads of a fork at a shallow angle, it is set by a few centimetres of height over a lateral
// offset of a metre or by nothing at all, and tilting the lanes by it would twist a wide road
// for no reason. With M = sum of u u^T over the roads' unit directions u leaving the junction,
// each eigen-direction e of M (eigenvalue lambda) keeps the share of G . e that lambda says.
Vec2 determined_gradient(const RoadNetwork& network, const Junction& j, const Vec2& g) {
  Eigen::Matrix2d m = Eigen::Matrix2d::Zero();
  for (const RoadEnd& e : j.ends) {
    const Polyline2& pts = network.roads[e.road].points;
    if (pts.size() < 2) continue;
    const Vec2 d = e.at_start ? Vec2(pts[1] - pts[0]) : Vec2(pts[pts.size() - 2] - pts.back());
    if (!(d.norm() > 0.0)) continue;
    const Vec2 u = d.normalized();
    m += u * u.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(m);
  Vec2 out = Vec2::Zero();
  for (int k = 0; k < 2; ++k) {
    const double x = std::clamp(
        (eig.eigenvalues()[k] - kPlaneUndetermined) / (kPlaneDetermined - kPlaneUndetermined), 0.0, 1.0);
    const Vec2 e = eig.eigenvectors().col(k);
    out += x * x * (3.0 - 2.0 * x) * g.dot(e) * e;
  }
  return out;
}

// A road's roll: at each end the roll r0, r1 of its junction's plane, eased to level with zero
// slope at both ends of the ease within kRollEase_m; a road shorter than two eases turns from
// r0 to r1 in one.
CubicProfile end_rolls(double length, double r0, double r1) {
  if (r0 == 0.0 && r1 == 0.0) return CubicProfile::constant(0.0);
  if (length < 2.0 * kRollEase_m) return hermite_profile(length, r0, 0.0, r1, 0.0);
  const double e = kRollEase_m;
  const double e2 = e * e, e3 = e2 * e;
  std::vector<CubicPiece> pieces{{0.0, Poly3{r0, 0.0, -3.0 * r0 / e2, 2.0 * r0 / e3}}};
  if (length > 2.0 * e) pieces.push_back({e, Poly3{0.0, 0.0, 0.0, 0.0}});
  pieces.push_back({length - e, Poly3{0.0, 0.0, 3.0 * r1 / e2, -2.0 * r1 / e3}});
  return CubicProfile(std::move(pieces));
}

// Roll along a road inside a junction: at every station the roll that lays its cross-section
// on the junction's plane, the gradient blended from g0 at its start to g1 at its end (they
// differ where the ends belong to different intersections joined into one junction). Its ends
// take exactly the rolls of the roads they join.
CubicProfile plane_rolls(const PlanView& plan, const Vec2& g0, const Vec2& g1) {
  if (g0.isZero(0.0) && g1.isZero(0.0)) return CubicProfile::constant(0.0);
  const double len = plan.length();
  const auto n = static_cast<std::size_t>(std::max(8.0, std::ceil(len / kRollStep_m)));
  std::vector<double> s(n + 1), r(n + 1);
  for (std::size_t i = 0; i <= n; ++i) {
    s[i] = len * static_cast<double>(i) / static_cast<double>(n);
    const double u = s[i] / len;
    r[i] = plane_roll((1.0 - u) * g0 + u * g1, plan.at(s[i]).heading);
  }
  return fit_cubic_profile(s, r, kRollTolerance_rad);
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
void add_transition_road(RoadModel& model, ModelRoad& a_ref, bool a_at_start, int b_id, bool b_at_start,
                         const Vec2& gradient) {
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

// Whether traffic can pass between the two roads of an attribute change: not where two one-ways
// both arrive or both leave (an extract's edge cutting through a merge leaves such nodes).
bool has_passage(const RoadNetwork& network, const Junction& j) {
  const auto [a_in, a_out] = arriving_departing(network.roads[j.ends[0].road].attributes, j.ends[0].at_start);
  const auto [b_in, b_out] = arriving_departing(network.roads[j.ends[1].road].attributes, j.ends[1].at_start);
  return (a_in > 0 && b_out > 0) || (b_in > 0 && a_out > 0);
}

// Two roads meeting end to end link directly when one continues the other: straight enough that
// their outermost lane borders meet within 2 mm, with the same lanes each way and the same lane
// width. Otherwise a short transition road bends and widens from one to the other.
bool needs_transition(const RoadNetwork& network, const Junction& j) {
  if (j.kind != JunctionKind::attribute_change || j.ends.size() != 2 || !has_passage(network, j))
    return false;
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

// Distance of the outermost lane borders from the reference line: add_lanes centres the
// carriageway, so both sides reach half the total width.
double outer_border_t(const WayAttributes& a) {
  return 0.5 * a.lane_width_m * (a.lanes_forward + (a.oneway ? 0 : a.lanes_backward));
}

// The smallest radius the reference line rounds a vertex by: the road's outer border plus a
// margin, so that no lane border folds.
double minimum_radius(const Road& road, const RoadModelOptions& options) {
  return outer_border_t(road.attributes) + options.min_radius_margin_m;
}

// Direction in which a road leaves junction `at_start ? start : end`, `along` metres into it:
// that of the polyline segment there (unit vector).
Vec2 leaving_direction_at(const Road& road, bool at_start, double along) {
  const Polyline2& p = road.points;
  const std::size_t n = p.size();
  double walked = 0.0;
  for (std::size_t k = 0; k + 1 < n; ++k) {
    const Vec2 a = at_start ? p[k] : p[n - 1 - k], b = at_start ? p[k + 1] : p[n - 2 - k];
    walked += (b - a).norm();
    if (walked >= along || k + 2 == n) return (b - a).normalized();
  }
  return leaving_direction(road, at_start);
}

// How far a transition road reaches into both roads: from `reach` on, the least (in steps of
// 25 %, at most max_trim_fraction of either road) at which the bend between the two ends is
// no tighter than either road's minimum radius (what the reference line keeps at an OSM
// vertex; the bend's radius is chord / (2 sin(turn / 2))), or else the one with the widest
// bend. Reaching further stops where the transition would climb steeper than both roads there
// (plus the connection allowance) and than it does at `reach`: the legs of a hairpin drawn to
// one node can part in height faster than in plan.
double transition_reach(const RoadNetwork& network, const std::vector<RoadProfile>& profiles,
                        const Junction& j, double reach, const RoadModelOptions& options) {
  const RoadEnd ends[2] = {j.ends[0], j.ends[1]};
  const Road* roads[2] = {&network.roads[ends[0].road], &network.roads[ends[1].road]};
  std::vector<double> cumulative[2] = {cumulative_length(roads[0]->points),
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
      dir[k] = leaving_direction_at(*roads[k], ends[k].at_start, d);
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

double cross2(const Vec2& a, const Vec2& b) {
  return a.x() * b.y() - a.y() * b.x();
}

double point_segment_distance(const Vec2& q, const Vec2& a, const Vec2& b) {
  const Vec2 d = b - a;
  const double len2 = d.squaredNorm();
  const double t = len2 > 0.0 ? std::clamp((q - a).dot(d) / len2, 0.0, 1.0) : 0.0;
  return (a + t * d - q).norm();
}

// Distance between two segments, 0 when they cross or touch.
double segment_distance(const Vec2& a0, const Vec2& a1, const Vec2& b0, const Vec2& b1) {
  const double d1 = cross2(a1 - a0, b0 - a0), d2 = cross2(a1 - a0, b1 - a0);
  const double d3 = cross2(b1 - b0, a0 - b0), d4 = cross2(b1 - b0, a1 - b0);
  if (((d1 > 0.0) != (d2 > 0.0)) && ((d3 > 0.0) != (d4 > 0.0))) return 0.0;
  return std::min({point_segment_distance(a0, b0, b1), point_segment_distance(a1, b0, b1),
                   point_segment_distance(b0, a0, a1), point_segment_distance(b1, a0, a1)});
}

// A road end at a junction in plan: its end cross-section (outermost right to outermost left
// lane border) and the outline of its lanes over the first metres from that end (at most
// `max_reach` of them).
struct EndShape {
  Vec2 left = Vec2::Zero(), right = Vec2::Zero();
  Polyline2 strip;  ///< closed implicitly
};

constexpr double kStripLength = 50.0;  // m of lanes next to a junction that other ends must clear
constexpr double kStripStep = 1.0;     // m between outline samples

EndShape end_shape(const PlanView& plan, double outer_t, bool at_start, double max_reach) {
  const double length = plan.length();
  const double reach = std::min({length, kStripLength, max_reach});
  const int steps = std::max(1, static_cast<int>(std::ceil(reach / kStripStep)));
  Polyline2 left, right;
  for (int k = 0; k <= steps; ++k) {
    const double d = reach * k / steps;
    const Pose2 pose = plan.at(at_start ? d : length - d);
    const Vec2 n(-std::sin(pose.heading), std::cos(pose.heading));
    left.push_back(pose.position + outer_t * n);
    right.push_back(pose.position - outer_t * n);
  }
  EndShape e;
  e.left = left.front();
  e.right = right.front();
  e.strip = right;
  e.strip.insert(e.strip.end(), left.rbegin(), left.rend());
  return e;
}

// Distance from a segment to a polygon's area (0 when it enters it).
double segment_polygon_distance(const Vec2& a, const Vec2& b, const Polyline2& polygon) {
  bool inside = false;
  for (std::size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++) {
    const Vec2& p = polygon[i];
    const Vec2& q = polygon[j];
    if ((p.y() > a.y()) != (q.y() > a.y()) &&
        a.x() < p.x() + (a.y() - p.y()) / (q.y() - p.y()) * (q.x() - p.x())) {
      inside = !inside;
    }
  }
  if (inside) return 0.0;
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++) {
    best = std::min(best, segment_distance(a, b, polygon[j], polygon[i]));
  }
  return best;
}

}  // namespace

std::vector<double> driven_stations(const Road& road, const RoadProfile& profile,
                                    const RoadModelOptions& options) {
  std::vector<double> ref_s;
  const PlanView plan = fit_reference_line(
      road.points, {options.plan_tolerance_m, 1e-3, minimum_radius(road, options)}, &ref_s, nullptr);
  const std::vector<double> cumulative = cumulative_length(road.points);
  // The outermost lane's centre on the inside of each bend: d(driven) = (1 - |curvature| t) ds,
  // each step between stations at its tightest curvature, so that a grade limit on the step
  // holds where the lane is shortest (the elevation records climb no steeper than the step).
  // The minimum radius (outer border plus margin) keeps the factor above zero.
  const double t = std::max(0.0, outer_border_t(road.attributes) - 0.5 * road.attributes.lane_width_m);
  const std::vector<PlanGeometry>& records = plan.records();
  std::vector<double> out(profile.size());
  double previous = 0.0;
  for (std::size_t i = 0; i < profile.size(); ++i) {
    const double s = map_station(cumulative, ref_s, profile.s[i]);
    double tightest = 0.0;  // |curvature| (the reference line has lines and arcs only)
    if (i > 0) {
      for (std::size_t k = plan.record_at(previous); k < records.size() && records[k].s < s; ++k) {
        if (records[k].s + records[k].length > previous)
          tightest = std::max(tightest, std::abs(records[k].curvature));
      }
    }
    out[i] = i == 0 ? s : out[i - 1] + (s - previous) * (1.0 - t * tightest);
    previous = s;
  }
  return out;
}

namespace {

// build_road_model; with `trims_only` it returns once the road ends are trimmed for their
// junctions (end_trims), before any road, lane or connecting road is built.
RoadModelBuild build_model(const RoadNetwork& network, const std::vector<RoadProfile>& profiles,
                           const RoadModelOptions& options, Diagnostics& diagnostics,
                           const std::vector<Vec2>& junction_gradient, bool trims_only) {
  if (profiles.size() != network.roads.size())
    throw InvalidInput("build_road_model: one profile per road is required");
  if (!junction_gradient.empty() && junction_gradient.size() != network.junctions.size())
    throw InvalidInput("build_road_model: one junction gradient per junction is required");
  std::vector<Vec2> planes(network.junctions.size(), Vec2::Zero());
  if (!junction_gradient.empty()) {
    for (const Junction& j : network.junctions)
      planes[j.id] = determined_gradient(network, j, junction_gradient[j.id]);
  }
  const auto gradient_of = [&](int junction) -> Vec2 { return planes[junction]; };

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
    // Two one-ways without passage between them end apart, clear of each other as at a fork.
    const bool apart =
        j.kind == JunctionKind::attribute_change && j.ends.size() == 2 && !has_passage(network, j);
    if (j.kind != JunctionKind::intersection && !transition[j.id] && !apart) continue;
    double widest = 0.0;
    for (const RoadEnd& e : j.ends) widest = std::max(widest, half_width(network.roads[e.road]));
    radius[j.id] = widest + options.junction_margin_m;
    if (transition[j.id]) radius[j.id] = transition_reach(network, profiles, j, radius[j.id], options);
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

  // Trims at both ends of every road: the junction radius, then grown where road ends at a
  // junction overlap.
  std::vector<std::array<double, 2>> trim(network.roads.size(), {0.0, 0.0});
  std::vector<std::vector<double>> cumulative_of(network.roads.size());
  std::vector<double> road_length(network.roads.size());
  std::vector<std::uint8_t> has_height(network.roads.size());
  for (const Road& road : network.roads) {
    cumulative_of[road.id] = cumulative_length(road.points);
    road_length[road.id] = cumulative_of[road.id].back();
    has_height[road.id] = profiles[road.id].has_height ? 1 : 0;
    const double cap = options.max_trim_fraction * cumulative_of[road.id].back();
    trim[road.id] = {std::min(radius[road.start_junction], cap), std::min(radius[road.end_junction], cap)};
  }
  const auto min_radius = [&](const Road& road) { return minimum_radius(road, options); };
  const auto fit_part = [&](const Road& road, std::vector<double>& kept_s, std::vector<double>& ref_s,
                            ReferenceLineReport* report, std::array<bool, 2> untrimmed = {false, false}) {
    const std::vector<double>& cumulative = cumulative_of[road.id];
    const double s0 = untrimmed[0] ? 0.0 : trim[road.id][0];
    const double s1 = cumulative.back() - (untrimmed[1] ? 0.0 : trim[road.id][1]);
    const Polyline2 part = cut(road.points, cumulative, s0, s1, kept_s);
    return fit_reference_line(part, {options.plan_tolerance_m, 1e-3, min_radius(road)}, &ref_s, report);
  };
  const auto usable = [&](const Road& road) {
    return profiles[road.id].has_height &&
           cumulative_of[road.id].back() - trim[road.id][0] - trim[road.id][1] >= kMinRoadLength;
  };
  // Intersections too close for the road between them to hold both become one junction (more
  // are joined below where the trims use a road up).
  detail::JunctionClusters clusters =
      detail::join_junctions(network, radius, road_length, has_height, options.min_kept_length_m, {});
  // The road ends at a junction; for a joined one, at any of its members but the absorbed roads'.
  const auto ends_of = [&](const Junction& j) {
    std::vector<const RoadEnd*> ends;
    for (const int m : clusters.members[j.id]) {
      for (const RoadEnd& e : network.junctions[m].ends) {
        if (!clusters.absorbed[e.road]) ends.push_back(&e);
      }
    }
    return ends;
  };
  // Trims grown where road ends at a junction overlap. A road whose trims leave it only
  // min_kept_length_m while its ends still overlap others is used up: its two junctions are
  // joined and the trims run again from the radii (a stub between two junctions cannot hold both).
  std::vector<std::pair<int, std::vector<int>>> overlaps;  // junction, network roads
  const std::vector<std::array<double, 2>> radius_trim = trim;
  const std::vector<Vec2> given_planes = planes;
  std::vector<std::uint8_t> used_up(network.roads.size(), 0);
  // Both ends at one junction, or at two joined into one.
  const auto loop = [&](const Road& road) {
    return road.start_junction == road.end_junction ||
           (road.start_junction >= 0 && road.end_junction >= 0 &&
            clusters.representative[road.start_junction] == clusters.representative[road.end_junction]);
  };
  // The outline of a road end's first metres (its kerb lines and the line across its end) with
  // the current trims.
  const auto end_shape_at = [&](const RoadEnd& end) {
    const Road& road = network.roads[end.road];
    std::vector<double> kept_s, ref_s;
    // Where the street only carries on at the far end (a lane or tag change, a bend), the
    // road's area runs on to that node: its trimmed-off part is a transition road's or
    // the next road's, which this junction's ends must clear as well.
    const int far = end.at_start ? road.end_junction : road.start_junction;
    const bool carries_on = far >= 0 && !loop(road) &&
                            network.junctions[far].kind != JunctionKind::intersection &&
                            clusters.members[far].size() == 1;
    std::array<bool, 2> untrimmed{false, false};
    untrimmed[end.at_start ? 1 : 0] = carries_on;
    const PlanView plan = fit_part(road, kept_s, ref_s, nullptr, untrimmed);
    // A loop's strip stops at its middle: the far half holds its other end, which would
    // otherwise always overlap this one however far both are trimmed.
    const double max_reach = loop(road) ? 0.5 * plan.length() : kStripLength;
    return end_shape(plan, outer_border_t(road.attributes), end.at_start, max_reach);
  };
  // Whether two road ends come closer than the junction gap (either's end line on the other's
  // outline).
  const auto ends_overlap = [&](const EndShape& a, const EndShape& b) {
    return std::min(segment_polygon_distance(a.right, a.left, b.strip),
                    segment_polygon_distance(b.right, b.left, a.strip)) < options.junction_end_gap_m;
  };
  for (int round = 0;; ++round) {
    trim = radius_trim;
    planes = given_planes;
    overlaps.clear();
    std::size_t ends_trimmed = 0;
    std::vector<std::uint8_t> stuck(network.roads.size(), 0);
    for (const Junction& j : network.junctions) {
      if (!(radius[j.id] > 0.0) || clusters.members[j.id].empty()) continue;
      std::vector<const RoadEnd*> ends;
      for (const RoadEnd* e : ends_of(j)) {
        if (usable(network.roads[e->road])) ends.push_back(e);
      }
      if (ends.size() < 2) continue;
      std::vector<std::optional<EndShape>> shape(ends.size());
      const auto shape_of = [&](std::size_t k) -> const EndShape& {
        if (!shape[k]) shape[k] = end_shape_at(*ends[k]);
        return *shape[k];
      };
      std::vector<std::uint8_t> grown(ends.size(), 0), capped(ends.size(), 0);
      bool clear = false;
      for (int pass = 0; pass < kMaxTrimPasses && !clear; ++pass) {
        std::vector<std::uint8_t> grow(ends.size(), 0);
        for (std::size_t a = 0; a < ends.size(); ++a) {
          for (std::size_t b = a + 1; b < ends.size(); ++b) {
            if (!ends_overlap(shape_of(a), shape_of(b))) continue;
            grow[a] = grow[b] = 1;
          }
        }
        clear = std::find(grow.begin(), grow.end(), 1) == grow.end();
        bool any = false;
        for (std::size_t k = 0; k < ends.size(); ++k) {
          if (!grow[k]) continue;
          const Road& road = network.roads[ends[k]->road];
          const double length = cumulative_of[road.id].back();
          double& t = trim[road.id][ends[k]->at_start ? 0 : 1];
          // Both ends of a road draw on its length, leaving it min_kept_length_m; a loop's two
          // ends overlap each other whatever is cut, so it keeps the per-end share.
          const double cap =
              loop(road) ? options.max_trim_fraction * length
                         : length - trim[road.id][ends[k]->at_start ? 1 : 0] - options.min_kept_length_m;
          const double next = std::min(t + kTrimStep, cap);
          if (next - t < 1e-9) {
            capped[k] = loop(road) ? 0 : 1;
            continue;
          }
          t = next;
          shape[k].reset();
          grown[k] = 1;
          any = true;
        }
        if (!any) break;
      }
      for (const std::uint8_t g : grown) ends_trimmed += g;
      if (!clear) {
        for (std::size_t k = 0; k < ends.size(); ++k) {
          if (capped[k]) stuck[ends[k]->road] = 1;
        }
        std::vector<int> roads;
        roads.reserve(ends.size());
        for (const RoadEnd* e : ends) roads.push_back(e->road);
        overlaps.emplace_back(static_cast<int>(j.id), roads);
        // Road ends that still overlap would cross each other once tilted differently: the
        // junction stays level.
        for (const int m : clusters.members[j.id]) planes[m] = Vec2::Zero();
        planes[j.id] = Vec2::Zero();
      }
    }
    out.stats.junction_ends_trimmed = ends_trimmed;
    // Whether the roads at one junction of a road reach into its other junction's area (the
    // hull of its road ends' end lines, this road's own end there included), or the two areas
    // overlap: the trims at the first pushed them past the road between (roads meeting at a
    // small angle), and the two junctions' surfaces would overlap. A far end that only carries
    // the street on is covered by the end strips reaching to it.
    const auto junctions_meet = [&](const Road& road) {
      const int ja = road.start_junction, jb = road.end_junction;
      if (ja < 0 || jb < 0 || network.junctions[ja].kind != JunctionKind::intersection ||
          network.junctions[jb].kind != JunctionKind::intersection)
        return false;
      struct Side {
        std::vector<EndShape> others;
        Polyline2 area;
      };
      const auto side = [&](int junction) {
        Side out;
        Polyline2 corners;
        for (const RoadEnd* e : ends_of(network.junctions[clusters.representative[junction]])) {
          if (!usable(network.roads[e->road])) continue;
          EndShape shape = end_shape_at(*e);
          corners.push_back(shape.right);
          corners.push_back(shape.left);
          if (e->road != road.id) out.others.push_back(std::move(shape));
        }
        out.area = convex_hull(std::move(corners));
        return out;
      };
      const auto reaches = [&](const Side& from, const Side& into) {
        for (std::size_t i = 0; i < into.area.size(); ++i) {
          const Vec2& p = into.area[i];
          const Vec2& q = into.area[(i + 1) % into.area.size()];
          for (const EndShape& e : from.others) {
            if (segment_polygon_distance(p, q, e.strip) < options.junction_end_gap_m) return true;
          }
        }
        return false;
      };
      // The two areas overlapping (each junction's surface would lie through the other's).
      const auto areas_overlap = [&](const Side& x, const Side& y) {
        if (x.area.size() < 3 || y.area.size() < 3) return false;
        for (std::size_t i = 0; i < x.area.size(); ++i) {
          if (segment_polygon_distance(x.area[i], x.area[(i + 1) % x.area.size()], y.area) < 1e-9)
            return true;
        }
        return false;
      };
      const Side a = side(ja), b = side(jb);
      return reaches(a, b) || reaches(b, a) || areas_overlap(a, b) || areas_overlap(b, a);
    };
    // A road the trims left no more than min_kept_length_m: the two junctions' areas meet
    // across it (their kerb lines, their other roads' ends) and become one.
    bool joined_more = false;
    for (const Road& road : network.roads) {
      if (loop(road) || used_up[road.id] || clusters.absorbed[road.id] || !has_height[road.id]) continue;
      if (road_length[road.id] - trim[road.id][0] - trim[road.id][1] > options.min_kept_length_m + 1e-6)
        continue;
      if (!stuck[road.id] &&
          road_length[road.id] - radius_trim[road.id][0] - radius_trim[road.id][1] > kMaxJoinGap &&
          !(junctions_meet(road) && !detail::join_leaves_loop(network, clusters, radius, road_length,
                                                              has_height, options.min_kept_length_m, road)))
        continue;
      used_up[road.id] = 1;
      joined_more = true;
    }
    if (!joined_more || round + 1 == kMaxJoinRounds) break;
    clusters =
        detail::join_junctions(network, radius, road_length, has_height, options.min_kept_length_m, used_up);
  }
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
        len << std::fixed << road_length[e.road];
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
      if (m != j.id && network.junctions[m].kind == JunctionKind::intersection) ++out.stats.junctions_joined;
    }
  }
  for (const std::uint8_t a : clusters.absorbed) out.stats.roads_absorbed += a;

  // Dead ends that stop on another road (ways closer than their widths, "almost junctions").
  {
    std::vector<double> widths(network.roads.size());
    for (const Road& road : network.roads) widths[road.id] = half_width(road);
    detail::StrayEndOptions stray;
    stray.gap_m = options.junction_end_gap_m;
    stray.min_kept_length_m = options.min_kept_length_m;
    const std::vector<detail::StrayEnd> strays =
        detail::clear_stray_ends(network, profiles, widths, trim, stray);
    for (const detail::StrayEnd& e : trims_only ? std::vector<detail::StrayEnd>{} : strays) {
      const Road& road = network.roads[static_cast<std::size_t>(e.road)];
      const Road& other = network.roads[static_cast<std::size_t>(e.other_road)];
      const auto way = [](const Road& r) {
        return r.osm_way_ids.empty() ? std::string("?") : std::to_string(r.osm_way_ids.front());
      };
      std::ostringstream msg;
      msg.precision(1);
      msg << std::fixed << "the dead end of OSM way " << way(road) << " lies on OSM way " << way(other)
          << " (no shared node; ways closer than their widths): "
          << (e.cleared ? "trimmed back " : "still there after trimming back ") << e.trimmed_m << " m";
      Diagnostic d;
      d.severity = e.cleared ? Severity::info : Severity::warning;
      d.code = e.cleared ? codes::kModelStrayEndTrimmed : codes::kModelStrayEndOverlap;
      d.message = msg.str();
      if (!road.osm_way_ids.empty()) d.osm_way_id = road.osm_way_ids.front();
      diagnostics.report(std::move(d));
      ++(e.cleared ? out.stats.stray_ends_trimmed : out.stats.stray_ends_left);
    }
  }

  out.end_trims = trim;
  if (trims_only) return out;

  // Roads: trimmed, fitted reference line, elevation records, lanes.
  for (const Road& road : network.roads) {
    const RoadProfile& p = profiles[road.id];
    if (!p.has_height) {
      ++out.stats.roads_skipped;
      continue;
    }
    if (clusters.absorbed[road.id]) continue;  // inside a joined junction
    const std::vector<double>& cumulative = cumulative_of[road.id];
    const double length = cumulative.back();
    const double s0 = trim[road.id][0];
    const double s1 = length - trim[road.id][1];
    if (s1 - s0 < kMinRoadLength) {
      ++out.stats.roads_skipped;
      diagnostics.report(Severity::warning, codes::kOpendriveRoadTooShort,
                         "road " + std::to_string(road.id) + " (" + std::to_string(length) +
                             " m) has no length left between its junctions; left out of the OpenDRIVE");
      continue;
    }
    std::vector<double> kept_s, ref_s;
    ReferenceLineReport fit_report;
    ModelRoad m;
    m.plan = fit_part(road, kept_s, ref_s, &fit_report);
    m.id = static_cast<int>(model.roads.size()) + 1;
    if (fit_report.corners_widened > 0 || fit_report.vertices_merged > 0) {
      ++out.stats.corners_rounded;
      out.stats.max_corner_departure_m =
          std::max(out.stats.max_corner_departure_m, fit_report.max_departure_m);
      if (fit_report.max_departure_m > options.plan_tolerance_m) {
        std::ostringstream msg;
        msg.precision(2);
        msg << std::fixed << "road " << m.id << ": "
            << fit_report.corners_widened + fit_report.vertices_merged
            << " sharp corner(s) rounded to the minimum radius " << min_radius(road)
            << " m; the reference line departs from the OSM way by up to " << fit_report.max_departure_m
            << " m";
        Diagnostic d;
        d.severity = Severity::info;
        d.code = codes::kModelCornerRounded;
        d.message = msg.str();
        d.road_id = m.id;
        if (!road.osm_way_ids.empty()) d.osm_way_id = road.osm_way_ids.front();
        diagnostics.report(std::move(d));
      }
    }
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
    m.elevation = fit_grade_bounded_profile(es, ez, options.elevation_tolerance_m, std::make_pair(g0, g1));
    for (std::size_t i = 0; i < es.size(); ++i) {
      out.stats.max_elevation_deviation_m =
          std::max(out.stats.max_elevation_deviation_m, std::abs(m.elevation.value(es[i]) - ez[i]));
    }
    m.superelevation =
        end_rolls(m.plan.length(), plane_roll(gradient_of(road.start_junction), m.plan.at(0.0).heading),
                  plane_roll(gradient_of(road.end_junction), m.plan.at(m.plan.length()).heading));
    add_lanes(m, road.attributes);
    out.model_road_of[road.id] = static_cast<int>(model.roads.size());
    model.roads.push_back(std::move(m));
    ++out.stats.roads;
  }

  for (const auto& [junction, roads] : overlaps) {
    std::string ids;
    for (const int r : roads) {
      if (out.model_road_of[r] < 0) continue;
      ids += (ids.empty() ? "" : ", ") + std::to_string(model.roads[out.model_road_of[r]].id);
    }
    Diagnostic d;
    d.code = codes::kModelJunctionEndsOverlap;
    d.message = "the ends of roads " + ids + " at the junction of OSM node " +
                std::to_string(network.junctions[junction].osm_node_id) +
                " still overlap after trimming them by the largest share allowed";
    d.osm_node_id = network.junctions[junction].osm_node_id;
    diagnostics.report(std::move(d));
    ++out.stats.junction_ends_overlap;
  }

  // Junctions.
  for (const Junction& j : network.junctions) {
    if (clusters.members[j.id].empty()) continue;  // joined into another
    std::vector<EndRef> ends;
    for (const RoadEnd* e : ends_of(j)) {
      if (out.model_road_of[e->road] >= 0) ends.push_back({e->road, e->at_start});
    }
    const auto model_of = [&](const EndRef& e) -> ModelRoad& {
      return model.roads[out.model_road_of[e.network_road]];
    };
    // The network junction an end belongs to (a joined junction holds several).
    const auto junction_of = [&](const EndRef& e) {
      const Road& road = network.roads[e.network_road];
      return e.at_start ? road.start_junction : road.end_junction;
    };

    if (j.kind == JunctionKind::attribute_change && ends.size() == 2 && !has_passage(network, j)) {
      Diagnostic d;
      d.severity = Severity::warning;
      d.code = codes::kModelNoPassage;
      d.message = "roads " + std::to_string(model_of(ends[0]).id) + " and " +
                  std::to_string(model_of(ends[1]).id) + " meet at OSM node " +
                  std::to_string(j.osm_node_id) +
                  " but no lane leads from one into the other (one-ways both arriving or both leaving); "
                  "both end there";
      d.osm_node_id = j.osm_node_id;
      diagnostics.report(std::move(d));
      ++out.stats.ends_without_passage;
      continue;
    }
    if (transition[j.id] && ends.size() == 2) {
      add_transition_road(model, model_of(ends[0]), ends[0].at_start, model_of(ends[1]).id, ends[1].at_start,
                          gradient_of(j.id));
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
    jm.source_junctions = clusters.members[j.id];
    jm.name = "junction " + std::to_string(j.osm_node_id);
    if (jm.source_junctions.size() > 1)
      jm.name += " (+" + std::to_string(jm.source_junctions.size() - 1) + " joined)";
    // The member junction a road end touches: a movement between two members follows the
    // absorbed roads between them, one-ways only forward.
    const auto member_of = [&](const EndRef& e) {
      const Road& road = network.roads[e.network_road];
      return e.at_start ? road.start_junction : road.end_junction;
    };
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
        if (!clusters.reachable(network, member_of(in), member_of(to))) continue;
        // Copies: adding connecting roads may reallocate model.roads.
        const ModelRoad a = model_of(in);
        const ModelRoad b = model_of(to);
        const std::vector<int> arriving = arriving_lanes(a, in.at_start);
        const std::vector<int> departing = departing_lanes(b, to.at_start);
        if (arriving.empty() || departing.empty()) continue;
        const Pose2 from0 = lane_inner_pose(a, in.at_start, arriving.front());
        const Pose2 to0 = lane_inner_pose(b, to.at_start, departing.front());
        const double turn = wrap_angle(to0.heading - from0.heading);
        // A U-turn goes back into the arriving road, or turns back by more than 150 degrees into
        // another (the two carriageways where a divided street splits: their ends lie a metre
        // apart and the hairpin between them cannot carry a lane).
        const bool u_turn = in.network_road == to.network_road || std::abs(turn) > kUTurn_rad;
        if (u_turn && !options.u_turns) continue;
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
          c.elevation = slope_bounded_profile(len, z0, g0, z1, g1, kConnectionGradeAllowance);
          c.superelevation = plane_rolls(c.plan, gradient_of(junction_of(in)), gradient_of(junction_of(to)));
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
          Severity::warning, codes::kOpendriveJunctionWithoutMovements,
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

}  // namespace

RoadModelBuild build_road_model(const RoadNetwork& network, const std::vector<RoadProfile>& profiles,
                                const RoadModelOptions& options, Diagnostics& diagnostics,
                                const std::vector<Vec2>& junction_gradient) {
  return build_model(network, profiles, options, diagnostics, junction_gradient, false);
}

std::vector<std::array<double, 2>> junction_end_trims(const RoadNetwork& network,
                                                      const std::vector<RoadProfile>& profiles,
                                                      const RoadModelOptions& options) {
  Diagnostics ignored;  // build_road_model reports the same findings
  return build_model(network, profiles, options, ignored, {}, true).end_trims;
}

}  // namespace relief

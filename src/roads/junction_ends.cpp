#include "roads/junction_ends.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "relief/geometry/plane.h"
#include "relief/geometry/polyline.h"
#include "roads/lane_layout.h"

namespace relief::detail {
namespace {

constexpr double kStripStep = 1.0;  // m between outline samples

// Distance between two segments, 0 when they cross or touch.
double segment_distance(const Vec2& a0, const Vec2& a1, const Vec2& b0, const Vec2& b1) {
  const double d1 = cross(a1 - a0, b0 - a0), d2 = cross(a1 - a0, b1 - a0);
  const double d3 = cross(b1 - b0, a0 - b0), d4 = cross(b1 - b0, a1 - b0);
  if (((d1 > 0.0) != (d2 > 0.0)) && ((d3 > 0.0) != (d4 > 0.0))) return 0.0;
  return std::min({point_segment_distance(a0, b0, b1), point_segment_distance(a1, b0, b1),
                   point_segment_distance(b0, a0, a1), point_segment_distance(b1, a0, a1)});
}

}  // namespace

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
  const double heading = plan.at(at_start ? 0.0 : length).heading;
  e.out = (at_start ? -1.0 : 1.0) * Vec2(std::cos(heading), std::sin(heading));
  e.left = left.front();
  e.right = right.front();
  e.strip = right;
  e.strip.insert(e.strip.end(), left.rbegin(), left.rend());
  return e;
}

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

JunctionEnds::JunctionEnds(const RoadNetwork& network_, const std::vector<RoadProfile>& profiles_,
                           const RoadModelOptions& options_, std::vector<double> radius_)
    : network(network_), profiles(profiles_), options(options_), radius(std::move(radius_)) {
  trim.assign(network.roads.size(), {0.0, 0.0});
  cumulative.resize(network.roads.size());
  road_length.resize(network.roads.size());
  has_height.resize(network.roads.size());
  for (const Road& road : network.roads) {
    cumulative[road.id] = cumulative_length(road.points);
    road_length[road.id] = cumulative[road.id].back();
    has_height[road.id] = profiles[road.id].has_height ? 1 : 0;
    const double cap = options.max_trim_fraction * cumulative[road.id].back();
    trim[road.id] = {std::min(radius[road.start_junction], cap), std::min(radius[road.end_junction], cap)};
  }
  // Intersections too close for the road between them to hold both become one junction (more
  // are joined where the trims use a road up).
  clusters = join_junctions(network, radius, road_length, has_height, options.min_kept_length_m, {});
}

bool JunctionEnds::loop(const Road& road) const {
  return road.start_junction == road.end_junction ||
         (road.start_junction >= 0 && road.end_junction >= 0 &&
          clusters.representative[road.start_junction] == clusters.representative[road.end_junction]);
}

bool JunctionEnds::usable(const Road& road) const {
  return profiles[road.id].has_height &&
         cumulative[road.id].back() - trim[road.id][0] - trim[road.id][1] >= kMinRoadLength;
}

std::vector<const RoadEnd*> JunctionEnds::ends_of(const Junction& j) const {
  std::vector<const RoadEnd*> ends;
  for (const int m : clusters.members[j.id]) {
    for (const RoadEnd& e : network.junctions[m].ends) {
      if (!clusters.absorbed[e.road]) ends.push_back(&e);
    }
  }
  return ends;
}

PlanView JunctionEnds::fit_part(const Road& road, std::vector<double>& kept_s, std::vector<double>& ref_s,
                                ReferenceLineReport* report, std::array<bool, 2> untrimmed) const {
  const std::vector<double>& c = cumulative[road.id];
  const double s0 = untrimmed[0] ? 0.0 : trim[road.id][0];
  const double s1 = c.back() - (untrimmed[1] ? 0.0 : trim[road.id][1]);
  const Polyline2 part = cut(road.points, c, s0, s1, kept_s);
  return fit_reference_line(part, {options.plan_tolerance_m, 1e-3, minimum_radius(road, options)}, &ref_s,
                            report);
}

EndShape JunctionEnds::end_shape_at(const RoadEnd& end) const {
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
}

bool JunctionEnds::ends_overlap(const EndShape& a, const EndShape& b) const {
  return std::min(segment_polygon_distance(a.right, a.left, b.strip),
                  segment_polygon_distance(b.right, b.left, a.strip)) < options.junction_end_gap_m;
}

}  // namespace relief::detail

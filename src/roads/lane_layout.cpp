#include "roads/lane_layout.h"

#include <cmath>
#include <numbers>

#include "relief/geometry/plane.h"
#include "relief/roads/road_surface.h"

namespace relief::detail {
namespace {

// Major roads (motorway to secondary) part their directions with a double solid line.
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

}  // namespace

double half_width(const Road& road) {
  const WayAttributes& a = road.attributes;
  return 0.5 * a.lane_width_m * (a.lanes_forward + a.lanes_backward);
}

RoadMark mark(RoadMark::Type type, const char* color) {
  RoadMark m;
  m.type = type;
  m.color = color;
  return m;
}

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

Pose2 lane_inner_pose(const ModelRoad& m, bool at_start, int lane) {
  const double s = at_start ? 0.0 : m.length();
  const int inner = lane < 0 ? lane + 1 : lane - 1;
  const double t = lane_border_t(m, s, inner);
  const Pose2 ref = m.plan.at(s);
  Pose2 p;
  p.position = ref.position + t * Vec2(-std::sin(ref.heading), std::cos(ref.heading));
  p.heading = lane < 0 ? ref.heading : wrap_angle(ref.heading + std::numbers::pi);
  return p;
}

Pose2 to_lane_centre(Pose2 inner, double w) {
  inner.position += 0.5 * w * Vec2(std::sin(inner.heading), -std::cos(inner.heading));
  return inner;
}

double lane_width_at(const ModelRoad& m, bool at_start, int lane) {
  const double s = at_start ? 0.0 : m.length();
  return std::abs(lane_border_t(m, s, lane) - lane_border_t(m, s, lane < 0 ? lane + 1 : lane - 1));
}

std::pair<double, double> end_height(const ModelRoad& m, bool at_start, bool along_reference) {
  const double s = at_start ? 0.0 : m.length();
  const double g = m.elevation.derivative(s);
  return {m.elevation.value(s), along_reference ? g : -g};
}

std::pair<double, double> lane_end_height(const ModelRoad& m, bool at_start, int lane) {
  const double s = at_start ? 0.0 : m.length();
  const double g = end_height(m, at_start, /*along_reference=*/lane < 0).second;
  return {surface_z(m, s, lane_centre_t(m, s, lane)), g};
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

double width_or_zero(const ModelRoad& m, bool at_start, const std::vector<int>& lanes, std::size_t k) {
  return k < lanes.size() ? lane_width_at(m, at_start, lanes[k]) : 0.0;
}

double outer_border_t(const WayAttributes& a) {
  return 0.5 * a.lane_width_m * (a.lanes_forward + (a.oneway ? 0 : a.lanes_backward));
}

double minimum_radius(const Road& road, const RoadModelOptions& options) {
  return outer_border_t(road.attributes) + options.min_radius_margin_m;
}

}  // namespace relief::detail

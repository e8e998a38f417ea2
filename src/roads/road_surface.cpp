#include "relief/roads/road_surface.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>

#include "relief/core/errors.h"

namespace relief {

namespace {

const LaneModel* find_lane(const std::vector<LaneModel>& lanes, int id) {
  for (const LaneModel& lane : lanes) {
    if (lane.id == id) return &lane;
  }
  return nullptr;
}

[[noreturn]] void unknown_lane(const ModelRoad& road, double s, int lane_id) {
  throw InvalidInput("road " + std::to_string(road.id) + ": no lane " + std::to_string(lane_id) +
                     " in the lane section at s=" + std::to_string(s));
}

}  // namespace

const LaneSection& section_at(const ModelRoad& road, double s) {
  if (road.sections.empty()) {
    throw InvalidInput("road " + std::to_string(road.id) + " has no lane sections");
  }
  // Last section starting at or before s; s before the first section uses the first.
  const auto it =
      std::upper_bound(road.sections.begin(), road.sections.end(), s,
                       [](double value, const LaneSection& section) { return value < section.s; });
  return it == road.sections.begin() ? road.sections.front() : *(it - 1);
}

double lane_border_t(const ModelRoad& road, double s, int lane_id) {
  const LaneSection& section = section_at(road, s);
  const double ds = s - section.s;
  double t = road.lane_offset.value(s);
  if (lane_id == 0) return t;
  // Widths of lanes 1..lane_id (left, +t) or -1..lane_id (right, -t), centre lane outwards.
  const int side = lane_id > 0 ? 1 : -1;
  const std::vector<LaneModel>& lanes = lane_id > 0 ? section.left : section.right;
  for (int id = side; id != lane_id + side; id += side) {
    const LaneModel* lane = find_lane(lanes, id);
    if (lane == nullptr) unknown_lane(road, s, lane_id);
    t += side * lane->width.value(ds);
  }
  return t;
}

double lane_centre_t(const ModelRoad& road, double s, int lane_id) {
  if (lane_id == 0) {
    throw InvalidInput("road " + std::to_string(road.id) + ": the centre lane (0) has no middle");
  }
  const int inner = lane_id > 0 ? lane_id - 1 : lane_id + 1;
  return 0.5 * (lane_border_t(road, s, lane_id) + lane_border_t(road, s, inner));
}

Vec3 surface_point(const ModelRoad& road, double s, double t) {
  return surface_point(road, road.plan.at(s), s, t);
}

double surface_z(const ModelRoad& road, double s, double t) {
  const double clamped = std::clamp(s, 0.0, road.plan.length());
  return road.elevation.value(clamped) + t * std::tan(road.superelevation.value(clamped));
}

Vec3 surface_point(const ModelRoad& road, const Pose2& pose, double s, double t) {
  const Vec2 normal(-std::sin(pose.heading), std::cos(pose.heading));
  const Vec2 xy = pose.position + t * normal;
  return {xy.x(), xy.y(), surface_z(road, s, t)};
}

double heading_at(const ModelRoad& road, double s) {
  return road.plan.at(s).heading;
}

}  // namespace relief

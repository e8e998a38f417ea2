#include "roads/turn_room.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "relief/geometry/plane.h"

namespace relief::detail {
namespace {

// Unit normal on the right of direction u.
Vec2 right_of(const Vec2& u) {
  return {u.y(), -u.x()};
}

}  // namespace

EndLanes end_lanes(const Road& road, bool at_start) {
  const WayAttributes& a = road.attributes;
  const int forward = a.lanes_forward, backward = a.oneway ? 0 : a.lanes_backward;
  EndLanes lanes;
  lanes.arriving = at_start ? backward : forward;
  lanes.departing = at_start ? forward : backward;
  lanes.lane_width = a.lane_width_m;
  lanes.width = a.lane_width_m * (forward + backward);
  return lanes;
}

TurnRoom turn_room(const EndShape& a, const EndLanes& la, const EndShape& b, const EndLanes& lb) {
  constexpr double kNone = std::numeric_limits<double>::infinity();
  if (la.arriving == 0 || lb.departing == 0) return {kNone, 0};
  const Vec2 d0 = a.out;   // driving into the junction from a
  const Vec2 d1 = -b.out;  // and out of it into b
  const double turn = std::atan2(cross(d0, d1), d0.dot(d1));
  if (std::abs(turn) < kThroughAngle_rad || std::abs(turn) > kUTurnAngle_rad) return {kNone, 0};
  // Lane centres to the right of the direction of travel: the outermost lane for a right turn,
  // the innermost for a left turn.
  const auto offset = [&](const EndLanes& l, int lanes) {
    const double outermost = 0.5 * (l.width - l.lane_width);
    return turn < 0.0 ? outermost : outermost - (lanes - 1) * l.lane_width;
  };
  const Vec2 p0 = 0.5 * (a.left + a.right) + offset(la, la.arriving) * right_of(d0);
  const Vec2 p1 = 0.5 * (b.left + b.right) + offset(lb, lb.departing) * right_of(d1);
  // p0 + s d0 = p1 - t d1: the tangents from either lane centre to the lines' crossing.
  const Vec2 delta = p1 - p0;
  const double det = cross(d0, d1);
  const double s = cross(delta, d1) / det;
  const double t = cross(d0, delta) / det;
  const int shorter = s <= t ? 0 : 1;
  return {std::max(0.0, std::min(s, t)) / std::tan(0.5 * std::abs(turn)), shorter};
}

}  // namespace relief::detail

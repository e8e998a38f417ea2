#pragma once
// Private to the sight module: a lane's centre line in its direction of travel, sampled on the
// surface, and its continuation ahead through the lane's links (the next road, or through a
// junction on the straightest connecting road that the lane links into).

#include <vector>

#include "relief/geometry/types.h"
#include "relief/roads/road_model.h"

namespace relief::detail {

/// A lane in its direction of travel: right lanes (id < 0) along the reference line.
struct LaneRef {
  int road = -1;  ///< index into RoadModel::roads
  int lane = 0;
  [[nodiscard]] bool forward() const { return lane < 0; }
};

/// Points of a lane's centre on the surface, in the direction of travel, with the plan distance
/// travelled to each.
struct LanePoints {
  std::vector<Vec3> points;
  std::vector<double> distance;  ///< from points.front(), along the polyline in plan
  std::vector<double> s;         ///< station on the lane's own road; NaN on the roads ahead
  [[nodiscard]] std::size_t size() const { return points.size(); }
};

/// The lane's own centre every `step` m of its road's reference line (and at its last station),
/// in the direction of travel. Where a lane section does not have the lane, the outermost lane
/// on its side stands in. Empty where the road has no lane on that side.
[[nodiscard]] LanePoints lane_points(const RoadModel& model, const LaneRef& lane, double step);

/// Where the lane goes at its end in the direction of travel: the next road's lane, or through a
/// junction the connecting road's lane whose heading at its far end turns least from the lane's.
/// Nullopt at a dead end (no link, or nothing in the junction from this lane).
[[nodiscard]] std::optional<LaneRef> next_lane(const RoadModel& model, const LaneRef& lane);

/// `lane`'s points followed by those of the lanes after it (next_lane) until `length` m of plan
/// distance are covered or the lanes end (`ended`: they ended first). At most 64 lanes ahead.
[[nodiscard]] LanePoints lane_ahead(const RoadModel& model, const LaneRef& lane, double step, double length,
                                    bool& ended);

}  // namespace relief::detail

#pragma once
// Private to the roads module: the lanes of a model road, laid out from its way's attributes
// (one lane section, right lanes along the reference line, the carriageway centred on it), and
// what the roads that continue a road need of its lanes at either end: which lanes arrive and
// depart, their borders' poses, widths and heights, and their links.

#include <cstddef>
#include <utility>
#include <vector>

#include "relief/geometry/plan_view.h"
#include "relief/roads/road_model.h"
#include "relief/roads/road_model_builder.h"
#include "relief/roads/road_network.h"

namespace relief::detail {

/// Half the paved width of a road from its attributes: lane_width_m x (lanes_forward +
/// lanes_backward) / 2, what a junction makes room for.
[[nodiscard]] double half_width(const Road& road);

/// Distance of the outermost lane borders from the reference line: add_lanes centres the
/// carriageway, so both sides reach half the total width (a one-way has no backward lanes).
[[nodiscard]] double outer_border_t(const WayAttributes& a);

/// The smallest radius the reference line rounds a vertex by: the road's outer border plus a
/// margin, so that no lane border folds.
[[nodiscard]] double minimum_radius(const Road& road, const RoadModelOptions& options);

/// A road mark of the given type and colour.
[[nodiscard]] RoadMark mark(RoadMark::Type type, const char* color = "standard");

/// One lane section over the whole road: right lanes along the reference line, left against it,
/// road marks by position, the carriageway centred on the reference line by the lane offset.
void add_lanes(ModelRoad& m, const WayAttributes& a);

/// Lanes that arrive at / depart from a road end, innermost first.
[[nodiscard]] std::vector<int> arriving_lanes(const ModelRoad& m, bool at_start);
[[nodiscard]] std::vector<int> departing_lanes(const ModelRoad& m, bool at_start);

/// Pose of the inner border of `lane` at a road end, facing the lane's direction of travel.
[[nodiscard]] Pose2 lane_inner_pose(const ModelRoad& m, bool at_start, int lane);

/// The centre of a lane of width w whose inner border runs along `inner` (lanes lie right of
/// their direction of travel).
[[nodiscard]] Pose2 to_lane_centre(Pose2 inner, double w);

/// Width of `lane` at a road end (m).
[[nodiscard]] double lane_width_at(const ModelRoad& m, bool at_start, int lane);

/// Width of the `k`-th lane (0 = innermost) of a list at a road end, 0 when there is no such lane.
[[nodiscard]] double width_or_zero(const ModelRoad& m, bool at_start, const std::vector<int>& lanes,
                                   std::size_t k);

/// Height and slope along the direction of travel of a lane at a road end.
[[nodiscard]] std::pair<double, double> end_height(const ModelRoad& m, bool at_start, bool along_reference);

/// Height and slope along the direction of travel of the centre of `lane` at a road end (the
/// roll eases to its end value with zero slope, so the slope is the reference line's).
[[nodiscard]] std::pair<double, double> lane_end_height(const ModelRoad& m, bool at_start, int lane);

/// A road inside a junction (connecting or transition road) is no steeper than its steeper end
/// or than its mean grade plus this.
inline constexpr double kConnectionGradeAllowance = 0.02;

/// Links `lane` of a road end to lane `other` of the road beyond (its predecessor at the start,
/// its successor at the end).
void set_lane_link(ModelRoad& m, bool at_start, int lane, int other);

}  // namespace relief::detail

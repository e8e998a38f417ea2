#pragma once
// Checks of a RoadModel: lane borders meet at every link, a model read back from a file matches
// the one written. (The elevation records' distance from the fitted profiles is measured where
// they are fitted: RoadModelStats::max_elevation_deviation_m.)

#include <vector>

#include "relief/roads/road_model.h"

namespace relief {

struct LinkContinuity {
  double max_horizontal_m = 0.0;  ///< largest horizontal gap between matching lane borders
  double max_vertical_m = 0.0;    ///< largest height step there
  std::size_t borders_checked = 0;
  std::size_t over_tolerance = 0;  ///< border pairs with a gap above the tolerance
  int worst_road = -1;             ///< road id where the largest gap is
  int worst_other_road = -1;       ///< the road it links to there
  Vec3 worst_at = Vec3::Zero();    ///< the border point of worst_road there
};

/// At every road-to-road link and at both ends of every connecting road, the inner and outer
/// borders of each linked lane pair (lane.predecessor / lane.successor) must meet.
[[nodiscard]] LinkContinuity check_link_continuity(const RoadModel& model, double tolerance_m = 0.01);

/// Where the lane centres of two connecting roads of one junction cross or run together (within
/// `near_m` in plan), the vehicles on them are at one place: their heights should agree. The
/// largest difference found, and where.
struct ConnectingRoadCrossings {
  double max_step_m = 0.0;         ///< largest height difference at a crossing
  std::size_t junctions_over = 0;  ///< junctions with a difference above the tolerance
  std::size_t crossings = 0;       ///< sample points of one lane centre on another
  int worst_junction = -1;
  Vec2 worst_xy = Vec2::Zero();
};

/// Samples every connecting road's lane centres every `step_m`, and measures each sample against
/// the lane centres of the junction's other connecting roads it lies on (within `near_m` in plan;
/// the other's height interpolated along its sampled centre line).
[[nodiscard]] ConnectingRoadCrossings check_connecting_road_crossings(const RoadModel& model,
                                                                      double tolerance_m = 0.02,
                                                                      double step_m = 0.25,
                                                                      double near_m = 0.05);

/// Where a connecting road's lane centre runs over the pavement of one of its junction's roads
/// (a road end lying inside the junction, in the path of the connections between other ends),
/// the .xodr has two surfaces at one place: a vehicle there is at either height. The largest
/// difference found, and where.
struct ConnectingRoadsOverRoads {
  double max_step_m = 0.0;         ///< largest height difference between the two surfaces
  std::size_t junctions_over = 0;  ///< junctions with a difference above the tolerance
  std::size_t samples = 0;         ///< lane-centre samples lying on a road's pavement
  int worst_junction = -1;
  int worst_road = -1;  ///< OpenDRIVE id of the road under (or over) the worst sample
  Vec2 worst_xy = Vec2::Zero();
};

/// Samples every connecting road's driving lane centres every `step_m` and measures each sample
/// lying on the pavement (between the outermost lane borders) of a road that ends at the same
/// junction, within `reach_m` of that end and at least `inset_m` behind its end line (the
/// connecting roads leave from the end lines) against that road's surface.
[[nodiscard]] ConnectingRoadsOverRoads check_connecting_roads_over_roads(const RoadModel& model,
                                                                         double tolerance_m = 0.02,
                                                                         double step_m = 0.25,
                                                                         double reach_m = 30.0,
                                                                         double inset_m = 0.25);

/// Grades of the elevation records against the caps (fraction, 0.35 for 35 %), roads and
/// connecting roads apart (a connecting road runs along its lane's centre, so its record's grade
/// is the grade a vehicle drives there).
struct GradeCheck {
  double max_grade_percent = 0.0;
  double max_excess_percent = 0.0;  ///< largest grade minus the road's cap (0 when none over)
  std::size_t roads_over = 0;       ///< roads with a grade over their cap + the tolerance
  int worst_road = -1;              ///< OpenDRIVE id of the largest excess
  double worst_s = 0.0;
  Vec2 worst_xy = Vec2::Zero();
};
/// Cross slopes (tan of the roll, the superelevation) of the roads, connecting roads left out
/// (they lie on their junction's surface). Measured, not gated: a road's ends take the roll of
/// their junction's plane (junction_planes.h), which on a hillside or where a steep street
/// crosses can be the steep grade itself; vehicles on it lean by as much.
struct CrossSlopeCheck {
  double max_percent = 0.0;
  int worst_road = -1;  ///< OpenDRIVE id of the largest
  double worst_s = 0.0;
  Vec2 worst_xy = Vec2::Zero();
  double length_m = 0.0;       ///< road length sampled
  double length_over_m = 0.0;  ///< of it, with a cross slope over `over` (check_grades)
  std::size_t roads_over = 0;  ///< roads with some of their length over it
};
struct ModelGrades {
  GradeCheck roads;
  GradeCheck connecting_roads;
  CrossSlopeCheck cross_slopes;  ///< over 8 % (`over` of check_grades)
};

/// The grade cap of the road at `index` from per-road caps (fractions; `cap` may be shorter than
/// the roads): cap[index] where given and >= 0, else (a connecting road) the larger cap of the
/// roads it links to, 0 when none has one.
[[nodiscard]] double linked_grade_cap(const RoadModel& model, const std::vector<double>& cap,
                                      std::size_t index);

/// Samples every road's elevation record every `step_m` metres (the grade of each chord) and
/// compares it with `cap[i]` for the road at index i (a connecting road: the largest cap of the
/// two roads it joins, when given as a negative number the cap is taken from its links). Roads
/// over cap + `tolerance` (fraction) are counted. The roads' cross slopes are sampled at the
/// middle of the same chords; length over `cross_slope_over` (fraction, 0.08: 8 %, the usual
/// upper end of a road's superelevation) is summed.
[[nodiscard]] ModelGrades check_grades(const RoadModel& model, const std::vector<double>& cap,
                                       double tolerance = 0.0, double step_m = 0.5,
                                       double cross_slope_over = 0.08);

struct ModelDeviation {
  double max_xy_m = 0.0;
  double max_z_m = 0.0;
  std::size_t points = 0;
  int worst_road = -1;
};

/// Evaluates both models along the reference line of every road of `a` (matched by id in `b`)
/// every `step_m` metres, at t = 0 and at the outer border of every lane.
[[nodiscard]] ModelDeviation compare_models(const RoadModel& a, const RoadModel& b, double step_m = 1.0);

}  // namespace relief

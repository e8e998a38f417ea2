#pragma once
// Private to the roads module: the road ends at each junction, trimmed back from its node to
// leave room for it, and their outlines in plan. The trims start at the junction's radius and
// grow (end_trims.h) until the ends at a junction lie apart; junctions whose areas meet are
// joined (junction_clusters.h, junction_joining.h). JunctionEnds holds the trims and the
// queries both ask of them.

#include <array>
#include <cstdint>
#include <vector>

#include "relief/geometry/plan_view.h"
#include "relief/geometry/reference_line_fit.h"
#include "relief/geometry/types.h"
#include "relief/roads/elevation_sampling.h"
#include "relief/roads/road_model_builder.h"
#include "relief/roads/road_network.h"
#include "roads/junction_clusters.h"

namespace relief::detail {

inline constexpr double kMinRoadLength = 0.05;  ///< m left after trimming, else the road is skipped
inline constexpr double kStripLength = 50.0;    ///< m of lanes next to a junction that other ends must clear

/// A road end at a junction in plan: its end cross-section (outermost right to outermost left
/// lane border) and the outline of its lanes over the first metres from that end.
struct EndShape {
  Vec2 left = Vec2::Zero(), right = Vec2::Zero();
  Vec2 out = Vec2::UnitX();  ///< unit direction from the end into its junction
  Polyline2 strip;           ///< closed implicitly
};

/// The EndShape of the end of `plan` (at its start or its end) whose outermost lane borders lie
/// `outer_t` either side of it, its strip reaching min(length, kStripLength, max_reach) metres
/// in, sampled every metre.
[[nodiscard]] EndShape end_shape(const PlanView& plan, double outer_t, bool at_start, double max_reach);

/// Distance from segment ab to a polygon's area (0 when it enters it).
[[nodiscard]] double segment_polygon_distance(const Vec2& a, const Vec2& b, const Polyline2& polygon);

/// The part [s0, s1] of a polyline (`cumulative` its cumulative length); `kept_s` receives the
/// polyline s of each returned point.
[[nodiscard]] Polyline2 cut(const Polyline2& line, const std::vector<double>& cumulative, double s0,
                            double s1, std::vector<double>& kept_s);

/// The network's road ends with their current trims, and the junctions they belong to.
struct JunctionEnds {
  /// Trims from `radius` (per network junction: the room it takes, 0 for none), capped at
  /// max_trim_fraction of each road's length; every junction on its own.
  JunctionEnds(const RoadNetwork& network, const std::vector<RoadProfile>& profiles,
               const RoadModelOptions& options, std::vector<double> radius);

  const RoadNetwork& network;
  const std::vector<RoadProfile>& profiles;
  const RoadModelOptions& options;
  std::vector<double> radius;                   ///< per network junction
  std::vector<std::vector<double>> cumulative;  ///< per network road: cumulative length of its points
  std::vector<double> road_length;              ///< per network road (m)
  std::vector<std::uint8_t> has_height;         ///< per network road
  std::vector<std::array<double, 2>> trim;      ///< per network road: cut off at its start, its end (m)
  JunctionClusters clusters;                    ///< the junctions joined so far

  /// Both ends at one junction, or at two joined into one.
  [[nodiscard]] bool loop(const Road& road) const;
  /// With a height and at least kMinRoadLength left between its trims.
  [[nodiscard]] bool usable(const Road& road) const;
  /// The road ends at a junction; for a joined one, at any of its members but the absorbed roads'.
  [[nodiscard]] std::vector<const RoadEnd*> ends_of(const Junction& j) const;
  /// The reference line of a road between its trims (an end flagged `untrimmed` runs on to its
  /// node); `kept_s` and `ref_s` as for cut and fit_reference_line's station map.
  [[nodiscard]] PlanView fit_part(const Road& road, std::vector<double>& kept_s, std::vector<double>& ref_s,
                                  ReferenceLineReport* report,
                                  std::array<bool, 2> untrimmed = {false, false}) const;
  /// The outline of a road end's first metres (its kerb lines and the line across its end) with
  /// the current trims.
  [[nodiscard]] EndShape end_shape_at(const RoadEnd& end) const;
  /// Whether two road ends come closer than the junction gap (either's end line on the other's
  /// outline).
  [[nodiscard]] bool ends_overlap(const EndShape& a, const EndShape& b) const;
};

}  // namespace relief::detail

#pragma once
// Private to the roads module: the model road of each network road between its trims: its
// reference line (the OSM centreline rounded within plan_tolerance_m, no tighter than its lanes
// allow), its elevation records (the fitted profile's stations within elevation_tolerance_m, the
// end slopes shared across an attribute change), its superelevation from the junction planes at
// its ends, its type, speed and lanes.

#include <array>
#include <vector>

#include "relief/core/diagnostics.h"
#include "relief/geometry/types.h"
#include "relief/roads/elevation_sampling.h"
#include "relief/roads/road_model_builder.h"
#include "relief/roads/road_network.h"
#include "roads/junction_ends.h"

namespace relief::detail {

/// Slope dz/ds of a profile at s, by central differences over +-h (one-sided at the ends).
[[nodiscard]] double slope_at(const RoadProfile& p, double s, double h = 1.0);

/// Piecewise-linear map from polyline s to reference-line s through matching vertices (`from`
/// and `to` parallel and increasing).
[[nodiscard]] double map_station(const std::vector<double>& from, const std::vector<double>& to, double s);

/// Per network road, the slopes dz/ds at its start and its end "leaving the junction" (downhill
/// away from it is negative). Where two roads meet head to tail (an attribute change), both take
/// the mean, so that the elevation is C1 across the link: leaving slopes of a smooth pass-through
/// are opposite.
[[nodiscard]] std::vector<std::array<double, 2>> leaving_slopes(const RoadNetwork& network,
                                                                const std::vector<RoadProfile>& profiles);

/// Adds a model road to `out.model` for every network road with height that is not inside a
/// joined junction and keeps at least 5 cm between its trims (`ends`), in network order, and
/// sets out.model_road_of. `leaving` as leaving_slopes gives; `planes` per network junction
/// (junction_planes.h). Roads left out are counted (stats.roads_skipped) and those too short
/// reported (codes::kOpendriveRoadTooShort); corners rounded beyond the tolerance are reported
/// (codes::kModelCornerRounded).
void add_model_roads(const JunctionEnds& ends, const std::vector<std::array<double, 2>>& leaving,
                     const std::vector<Vec2>& planes, RoadModelBuild& out, Diagnostics& diagnostics);

}  // namespace relief::detail

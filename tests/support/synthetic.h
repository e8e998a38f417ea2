#pragma once
// Tiny synthetic worlds for tests: a frame near San Francisco, analytic DEMs written as GeoTIFF,
// and roads built directly in the local frame.

#include <functional>
#include <string>

#include "relief/roads/elevation_sampling.h"
#include "relief/roads/road_network.h"
#include "relief/terrain/dem_writer.h"

namespace relief::test {

/// UTM 10N frame with origin (550000, 4180000).
[[nodiscard]] GeoFrame synthetic_frame();

/// Writes a DEM over local x, y in [-extent_m, extent_m] with `cell_m` pixels whose value at
/// each cell centre is f(x, y) in LOCAL coordinates; returns its path (in a scratch dir).
[[nodiscard]] std::string write_local_dem(const std::string& name, double extent_m, double cell_m,
                                          const std::function<double(double, double)>& f,
                                          std::optional<double> nodata = std::nullopt);

/// A network of straight roads given as polylines; junctions are made where road ends coincide
/// (within 1 mm). Attributes default to residential two-way.
[[nodiscard]] RoadNetwork make_network(const std::vector<Polyline2>& roads,
                                       const std::vector<WayAttributes>& attributes = {});

/// Stations of every road every `spacing_m`, with z = ground(x, y) (local frame).
[[nodiscard]] std::vector<RoadProfile> drape(const RoadNetwork& network,
                                             const std::function<double(const Vec2&)>& ground,
                                             double spacing_m = 1.0);

}  // namespace relief::test

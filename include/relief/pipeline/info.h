#pragma once
// `relief info`: what an OSM file and DEMs hold and how well they fit together, without
// building or writing anything.

#include <optional>
#include <string>
#include <vector>

#include "relief/pipeline/build.h"

namespace relief {

struct InfoResult {
  std::string osm_path;
  std::optional<LonLatBox> osm_header_bounds;
  LonLatBox roads_bounds;  ///< of the road nodes (after --bbox)
  GeoFrame frame;
  std::size_t ways_read = 0;
  std::size_t highway_ways = 0;
  std::size_t road_ways = 0;
  NetworkStats network;
  std::vector<DemInfo> dems;
  std::size_t samples = 0;         ///< road samples at the chosen spacing
  double covered_percent = 0.0;    ///< samples with a DEM height
  double void_percent = 0.0;       ///< samples in a void inside the DEM extent
  double uncovered_percent = 0.0;  ///< samples outside every DEM
};

/// Reads and inspects; throws like build() for unreadable inputs, but not for partial coverage.
[[nodiscard]] InfoResult inspect(const BuildOptions& options, Diagnostics& diagnostics);

}  // namespace relief

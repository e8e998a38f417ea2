#pragma once
// Streaming passes over a region's OSM file that never hold the region: the road nodes' positions
// (for the plan) and one tile's window of complete road ways (for its build).

#include <cstdint>
#include <filesystem>
#include <vector>

#include "relief/geometry/types.h"
#include "relief/roads/osm_reader.h"

namespace relief::detail {

/// Positions of every node of every way read_osm builds under `options` (builds_way), in two
/// passes (the ways' node ids, then those nodes). 24 bytes per road node.
[[nodiscard]] std::vector<LonLat> road_node_positions(const std::filesystem::path& osm_path,
                                                      const OsmReadOptions& options);

struct WindowCounts {
  std::size_t ways = 0;
  std::size_t nodes = 0;
};

/// Writes to `out` (.osm.pbf) every way read_osm builds under `options` that has a node inside
/// `window`, whole, with all its nodes (and their tags): three passes (the window's node ids; the
/// ways; the nodes they need). Memory grows with the window's nodes and ways, not the region's.
WindowCounts extract_window(const std::filesystem::path& osm_path, const LonLatBox& window,
                            const OsmReadOptions& options, const std::filesystem::path& out);

}  // namespace relief::detail

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
  std::size_t chain_ways = 0;  ///< of `ways`: taken for structure chains, without a node in the window
};

/// Writes to `out` (.osm.pbf) every way read_osm builds under `options` that has a node inside
/// `window`, whole, with all its nodes (and their tags); and for every structure chain those ways
/// touch (the bridge and tunnel ways connected by shared nodes, which the profile fit spans
/// between their abutments instead of anchoring them to the DEM), the whole chain and every way
/// with a node within `halo_m` of one of its nodes (its approaches with the context the window
/// gives its own roads). Streaming passes: the region's structure ways; the nodes (the window's,
/// the structures' positions); the ways; for the chains, the nodes near them and the ways again;
/// the nodes the ways need. Memory grows with the window, its chains' surroundings and the
/// region's structure nodes, not with the region's roads.
WindowCounts extract_window(const std::filesystem::path& osm_path, const LonLatBox& window, double halo_m,
                            const OsmReadOptions& options, const std::filesystem::path& out);

}  // namespace relief::detail

#pragma once
// Streaming passes over a region's OSM file that never hold the region: the road nodes' positions
// (for the plan) and one tile's window of complete road ways (for its build).

#include <cstdint>
#include <filesystem>
#include <vector>

#include "relief/geometry/types.h"
#include "relief/roads/osm_reader.h"

namespace relief::detail {

/// Every way read_osm builds under `options` (builds_way) with its nodes' positions in order, and
/// the road nodes once each.
struct RoadWays {
  std::vector<std::int64_t> way_ids;
  std::vector<std::size_t> offsets;  ///< way i's points: points[offsets[i], offsets[i + 1])
  std::vector<LonLat> points;        ///< per node reference (NaN where the node is missing)
  std::vector<LonLat> nodes;         ///< each road node once
};

/// Two passes (the ways' node references, then those nodes). About 40 bytes per road node.
[[nodiscard]] RoadWays read_road_ways(const std::filesystem::path& osm_path, const OsmReadOptions& options);

struct WindowCounts {
  std::size_t ways = 0;
  std::size_t nodes = 0;
  std::size_t chain_ways = 0;      ///< of `ways`: taken for structure chains, without a node in the window
  std::size_t neighbour_ways = 0;  ///< of `ways`: taken because they join a taken way (two rings)
};

/// Writes to `out` (.osm.pbf) every way read_osm builds under `options` that has a node inside
/// `window` or crosses it, whole, with all its nodes (and their tags); and for every structure chain those
/// ways touch (the bridge and tunnel ways connected by shared nodes, which the profile fit spans between
/// their abutments instead of anchoring them to the DEM), the whole chain and every way with a node within
/// `halo_m` of one of its nodes (its approaches with the context the window gives its own roads); and, in two
/// rings, every way that shares a node with a way taken (so the taken ways split into the roads and junctions
/// a whole build makes). Streaming passes: the region's structure ways; the nodes (the window's, the
/// structures' positions); the ways; for the chains, the nodes near them and the ways again; the ways twice
/// more (the rings); the nodes the ways need. Memory grows with the window, its chains' surroundings and the
/// region's structure nodes, not with the region's roads. `crossing_ways`: ways taken although no node of
/// theirs lies in the window (sorted ids: the plan's TileSpec::crossing_ways, whose segments cross it).
WindowCounts extract_window(const std::filesystem::path& osm_path, const LonLatBox& window, double halo_m,
                            const std::vector<std::int64_t>& crossing_ways, const OsmReadOptions& options,
                            const std::filesystem::path& out);

}  // namespace relief::detail

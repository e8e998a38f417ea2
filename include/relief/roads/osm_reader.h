#pragma once
// Reads the road ways of an OSM file (.osm, .osm.gz, .osm.bz2, .osm.pbf) with libosmium.

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "relief/core/diagnostics.h"
#include "relief/geometry/types.h"
#include "relief/roads/way_attributes.h"

namespace relief {

struct OsmReadOptions {
  /// Also build footways, paths, cycleways, steps, pedestrian streets, tracks, bridleways.
  bool include_non_motor = false;
  /// Clip to this box (WGS84): ways are cut where they cross its edge, with a new node at the
  /// crossing; the parts outside are dropped and each inside run becomes its own OsmWay with
  /// the way's id. A crossing node gets a negative synthetic id (below every node id of the
  /// file), the same for every way through the same segment, so clipped ways stay connected.
  std::optional<LonLatBox> bbox;
};

/// One road way with its nodes resolved. Oneway=-1 ways are already reversed.
struct OsmWay {
  std::int64_t id = 0;
  std::vector<std::int64_t> node_ids;  ///< clip crossings get negative synthetic ids
  std::vector<LonLat> nodes;           ///< WGS84 positions, parallel to node_ids
  WayAttributes attributes;
};

struct OsmRoads {
  std::vector<OsmWay> ways;
  std::unordered_set<std::int64_t> traffic_signals;  ///< nodes tagged highway=traffic_signals
  LonLatBox bounds;                                  ///< of the nodes of `ways` (after clipping)
  std::optional<LonLatBox> header_bounds;            ///< <bounds> of the file, when present
  std::size_t ways_read = 0;                         ///< every way in the file
  std::size_t highway_ways = 0;                      ///< ways with a highway tag
  std::size_t ways_skipped_class = 0;                ///< highway classes not built (footway by default, ...)
  std::size_t ways_with_missing_nodes = 0;
  std::size_t missing_node_refs = 0;
};

/// Reads `path`. Ways whose nodes are missing from the file are split at the missing nodes and
/// the parts with two or more nodes kept, each missing node reported to `diagnostics`
/// ("osm.missing_node"). Ways with fewer than two distinct nodes are skipped
/// ("osm.degenerate_way"); tag values that fall back to defaults are reported once per way
/// ("osm.tag_value"). Consecutive repeats of a node in a way are collapsed.
/// The format follows the extension (.osm, .osm.gz, .osm.bz2, .osm.pbf).
/// Throws IoError (missing/unreadable file) and InvalidInput (unknown extension, malformed or
/// truncated file, no road ways at all); messages name the file.
[[nodiscard]] OsmRoads read_osm(const std::filesystem::path& path, const OsmReadOptions& options,
                                Diagnostics& diagnostics);

/// Whether read_osm builds a way with these tags under `options`: a highway of a class it builds
/// (footways, paths and the like only with include_non_motor). The region tiles plan with it.
[[nodiscard]] bool builds_way(const std::map<std::string, std::string, std::less<>>& tags,
                              const OsmReadOptions& options);

}  // namespace relief

#pragma once
// DIR/tiles/X_Y/tile.json: what a tile's build left (its key, status, figures and gates). Written
// last, so a tile with a record is complete.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "relief/export/report_writer.h"

namespace relief::detail {

inline constexpr const char* kTileRecordFile = "tile.json";

struct TileRecord {
  std::string key;
  int x = 0, y = 0;
  std::string status;  ///< "built" or "gates_failed"
  double seconds = 0.0;
  /// The building process's peak resident memory, MB (with `tiles build --all` each tile has a
  /// process of its own: the tile's peak).
  double peak_rss_mb = 0.0;
  std::size_t window_ways = 0, window_nodes = 0;
  std::size_t window_chain_ways = 0;      ///< of window_ways: taken for structure chains beyond the window
  std::size_t window_neighbour_ways = 0;  ///< of window_ways: taken because they join a taken way
  std::vector<std::string> failed_gates;  ///< failed in the core (or at no known place)
  /// Failed at a place in the halo only: reported, not the tile's (its owner checks the place).
  std::vector<std::string> halo_gates;
};

/// nullopt when the folder has no (readable) record.
[[nodiscard]] std::optional<TileRecord> read_tile_record(const std::filesystem::path& tile_dir);
/// The record plus the build's gates and network figures (for the region's report).
void write_tile_record(const std::filesystem::path& tile_dir, const TileRecord& record,
                       const RunReport& report);

}  // namespace relief::detail

#pragma once
// DIR/tiles/X_Y/tile.json: what a tile's build left (its key, status, figures and gates). Written
// last, so a tile with a record is complete.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "relief/export/report_writer.h"
#include "relief/tiles/tiles.h"

namespace relief::detail {

inline constexpr const char* kTileRecordFile = "tile.json";
/// The heights a built tile's neighbours of later phases hold (tile_holds.h).
inline constexpr const char* kHoldsFile = "holds.bin";

struct TileRecord {
  std::string key;
  int x = 0, y = 0;
  std::string status;  ///< "built" or "gates_failed"
  double seconds = 0.0;
  /// The building process's peak resident memory, MB (with `tiles build --all` each tile has a
  /// process of its own: the tile's peak).
  double peak_rss_mb = 0.0;
  std::size_t window_ways = 0, window_nodes = 0;
  std::size_t window_chain_ways = 0;       ///< of window_ways: taken for structure chains beyond the window
  std::size_t window_neighbour_ways = 0;   ///< of window_ways: taken because they join a taken way
  std::vector<std::string> holds_from;     ///< "X,Y" of the dependencies whose holds the fit took
  std::vector<std::string> holds_missing;  ///< "X,Y" of the dependencies not built yet
  std::size_t held_variables = 0;          ///< fit variables held at the dependencies' values
  std::size_t holds_mismatched = 0;        ///< held roads with another number of samples here (free)
  std::vector<std::string> failed_gates;   ///< failed in the core (or at no known place)
  /// Failed at a place in the halo only: reported, not the tile's (its owner checks the place).
  std::vector<std::string> halo_gates;
};

/// nullopt when the folder has no (readable) record.
[[nodiscard]] std::optional<TileRecord> read_tile_record(const std::filesystem::path& tile_dir);
/// The record plus the build's gates and network figures (for the region's report).
void write_tile_record(const std::filesystem::path& tile_dir, const TileRecord& record,
                       const RunReport& report);

/// A tile's dependencies (tile_dependencies) as they stand: the key of its build (tile_key and
/// every dependency's own key, or that it is missing), and the dependencies built (with their
/// holds file) and not, in the order of their phases.
struct DependencyState {
  std::string key;
  std::vector<const TileSpec*> built;
  std::vector<std::string> built_names, missing_names;  ///< "X,Y"
};
[[nodiscard]] DependencyState dependency_state(const std::filesystem::path& dir, const TileManifest& manifest,
                                               const TileSpec& tile);

}  // namespace relief::detail

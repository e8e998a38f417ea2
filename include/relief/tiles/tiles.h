#pragma once
// Region-scale conversion: a region too large for one build is planned as a grid of square
// tiles, each built from its own window of the OSM (the tile plus a halo, ways complete) and the
// DEMs, then merged. Each tile owns what lies in its core: a road whose midpoint and a junction
// whose centre lie there, the scene's triangles whose centroid lies there. Every build step reads
// only its window, so memory is bounded by the largest window, not the region.
//
//   plan_tiles   region OSM (streamed twice) -> DIR/manifest.json (frame, grid, halo, inputs'
//                SHA-256, the build's options)
//   build_tile   one tile -> DIR/tiles/X_Y/ (window.osm.pbf, out/, tile.json); skipped when its
//                key (inputs, options, grid) did not change
//   merge_tiles  every built tile -> DIR/merged/ (one NAME.xodr, its SUMO network, the scene
//                tiles, tileset.json, report.json)

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "relief/core/diagnostics.h"
#include "relief/geometry/geo_frame.h"
#include "relief/geometry/types.h"
#include "relief/pipeline/build.h"

namespace relief {

struct TileInput {
  std::string path;    ///< as given (GDAL virtual paths allowed for DEMs)
  std::string sha256;  ///< of the content (file_hash.h)
  std::string role;    ///< "osm" or "dem"
};

struct TileSpec {
  int x = 0, y = 0;            ///< column (east) and row (north), from 0 at the south-west tile
  Aabb2 core;                  ///< local frame, [min, max) (what the tile owns)
  LonLatBox window;            ///< core plus halo, in WGS84 (what the tile reads)
  std::size_t road_nodes = 0;  ///< OSM road nodes in the core (the plan's count)
  /// Road ways that cross the window without a node in it (sorted OSM ids): a segment longer
  /// than the halo. The window takes them too.
  std::vector<std::int64_t> crossing_ways;
};

struct TileManifest {
  std::string name;
  GeoFrame frame;
  LonLat frame_centre;  ///< the builds' BuildOptions::frame_centre
  double tile_size_m = 0.0;
  double halo_m = 0.0;
  /// Whether a tile holds what its neighbours of earlier phases fitted (tile_dependencies).
  bool hold_neighbours = true;
  Vec2 grid_origin = Vec2::Zero();  ///< south-west corner of tile (0, 0), local frame
  std::vector<TileSpec> tiles;      ///< only tiles whose core holds road nodes, row-major
  std::vector<TileInput> inputs;
  /// The `relief build` options every tile is built with, as command-line arguments
  /// (without --osm, --out, --name, --origin, --crs, which the tiles set).
  std::vector<std::string> build_args;

  [[nodiscard]] const TileSpec* find(int x, int y) const;
  [[nodiscard]] std::string to_json() const;
  /// Throws InvalidInput when `text` is not a manifest.
  [[nodiscard]] static TileManifest from_json(std::string_view text, std::string_view source);
};

struct TilePlanOptions {
  std::filesystem::path osm_path;
  std::vector<std::string> dem_paths;
  std::string name;                ///< default: the OSM file's stem
  std::optional<std::string> crs;  ///< default: the WGS84 UTM zone of the region's centre
  /// Centre of the local frame (--origin): default, the centre of the road nodes' box. Give a
  /// whole build's --origin to plan tiles in its frame, or another plan's to share its grid.
  std::optional<LonLat> frame_centre;
  double tile_size_m = 2000.0;
  /// Context read around each tile. A road's profile feels the network for a few hundred
  /// metres; 500 m keeps heights within millimetres of a whole build (README, tiles).
  double halo_m = 500.0;
  /// A tile holds what its neighbours of earlier phases fitted where their elements meet its
  /// own, so that their links meet exactly where both are neighbours (README, tiles: without
  /// them a mountain region's merge fails, its links up to centimetres apart).
  bool hold_neighbours = true;
  /// Which ways are roads (include_non_motor), as the tiles' builds will read them: a tile is
  /// planned only where such a road has a node.
  OsmReadOptions osm;
  std::vector<std::string> build_args;
};

/// Plans the tiles of a region: streams the OSM twice (road ways' node ids, then their
/// locations; memory 24 bytes per road node), hashes the inputs. Throws InvalidInput when the
/// OSM holds no roads, OptionError for a tile size or halo that is not finite and > 0.
[[nodiscard]] TileManifest plan_tiles(const TilePlanOptions& options);

/// Reads DIR/manifest.json. Throws IoError or InvalidInput.
[[nodiscard]] TileManifest read_manifest(const std::filesystem::path& dir);
void write_manifest(const std::filesystem::path& dir, const TileManifest& manifest);

/// Folder of tile (x, y): DIR/tiles/X_Y.
[[nodiscard]] std::filesystem::path tile_dir(const std::filesystem::path& dir, int x, int y);

/// The key of a tile's build: SHA-256 over the inputs' hashes, the options, the grid, the
/// halo and the tile. A tile whose tile.json carries the same key and status "built" is done.
[[nodiscard]] std::string tile_key(const TileManifest& manifest, const TileSpec& tile);

/// The tile's phase, (x mod 2) + 2 (y mod 2): 0 to 3. No two of a tile's eight neighbours share
/// its phase; `--all` builds the phases in order, the tiles of one phase at once.
[[nodiscard]] int tile_phase(const TileSpec& tile);

/// With manifest.hold_neighbours, the tiles of the plan among `tile`'s eight neighbours with an
/// earlier phase: the tiles whose fitted heights it holds where their elements meet its own
/// (tile_holds.h), so that the two build the same surface there, exactly. Otherwise none.
[[nodiscard]] std::vector<const TileSpec*> tile_dependencies(const TileManifest& manifest,
                                                             const TileSpec& tile);

/// The plan's tiles phase after phase (stable within a phase): the order every tile finds its
/// dependencies built in.
[[nodiscard]] std::vector<const TileSpec*> build_order(const TileManifest& manifest);

struct TileBuildResult {
  std::string status;  ///< "built", "gates_failed" (built, a gate failed), "skipped" (up to date)
  double seconds = 0.0;
  std::vector<std::string> failed_gates;  ///< failed at a place in the core (or at none known)
  /// Failed only at places in the halo, where the window cuts the network short: not this
  /// tile's (the tile owning the place checks it with its whole context).
  std::vector<std::string> halo_gates;
};

/// Builds tile (x, y) of the plan in DIR: extracts its window of the OSM (complete road ways
/// with a node in the window, and the structure chains they touch with the ways within the halo
/// of them: osm_window.h) to DIR/tiles/X_Y/window.osm.pbf in streaming passes, runs
/// build() on it in the manifest's frame (`options` as parsed from manifest.build_args; its
/// osm_path, out_dir, name, crs, frame_centre and the scene's core are set here) and writes
/// tile.json. Its fit holds what its dependencies (tile_dependencies) fitted where their
/// elements meet its own, from their DIR/tiles/X_Y/holds.bin, and it writes its own for the
/// tiles after it; a dependency not built yet is recorded in tile.json (`holds.missing`) and
/// its key, so the tile is built again once it is. Throws what build() throws; a tile that throws
/// keeps no tile.json.
[[nodiscard]] TileBuildResult build_tile(const std::filesystem::path& dir, const TileManifest& manifest,
                                         int x, int y, BuildOptions options, Diagnostics& diagnostics,
                                         bool force = false);

struct TileMergeOptions {
  /// The .xodr of a whole build of the region in the same frame (relief build --origin at the
  /// manifest's centre), to measure the merge against (report.json "whole_build").
  std::optional<std::filesystem::path> whole_xodr;
  /// The coarse level's clustering cell (metres; 0: the tile size / 32, 7.8 m for 250 m tiles).
  double lod_cell_m = 0.0;
  /// The region's SUMO network from the merged model (netconvert over its plain XML), checked by
  /// the build's SUMO gates with `gates`' thresholds. `sumo` and `gates` are the tiles' options
  /// (the plan's build options); so is `fit`, whose grade caps (by each road's highway class)
  /// the net's height steps are judged against, as in a build (SumoOptions::grade_caps).
  bool sumo_net = true;
  SumoOptions sumo;
  GateThresholds gates;
  ProfileFitOptions fit;
};

struct TileMergeResult {
  std::size_t tiles = 0;
  std::size_t roads = 0;
  std::size_t junctions = 0;
  std::size_t scene_tiles = 0;
  std::size_t road_self_intersections = 0;  ///< of the tiles' Road_Road joined into one
  std::vector<std::string> failed_gates;    ///< "X_Y: gate" of every tile
  std::vector<std::filesystem::path> written;
  /// Against TileMergeOptions::whole_xodr: roads matched by their ends, then their surfaces.
  std::size_t whole_roads = 0, whole_unmatched = 0;
  double whole_max_xy_m = 0.0, whole_max_z_m = 0.0;
  std::size_t whole_roads_over_1mm = 0;  ///< matched roads whose heights differ by more than 1 mm
  /// The paved vertices of the scene tiles given their owners' heights (report.json
  /// seams.owner_heights): how many there are, moved, with no owner's vertex (of them
  /// interpolated from their neighbours), and the largest change.
  std::size_t paved_vertices = 0, paved_moved = 0, paved_unmatched = 0, paved_interpolated = 0;
  double paved_max_dz_m = 0.0;
  /// Terrain vertices on tile lines beside roads whose tiles' copies stood apart, joined at one
  /// tile's (seams.owner_heights.terrain_seams), and the largest change.
  std::size_t terrain_seams = 0;
  double terrain_seams_max_dz_m = 0.0;
  /// The coarse level of the scene tiles (NAME_Tile_X_Y_lod1.glb), summed over the tiles, and
  /// the largest measured error of one (its geometricError in tileset.json).
  std::size_t lod_full_triangles = 0, lod_coarse_triangles = 0;
  double lod_max_error_m = 0.0;
};

/// Merges every built tile of DIR into DIR/merged/: NAME.xodr (each tile's own roads and
/// junctions, ids renumbered, links across tiles joined), NAME.net.xml with its plain XML and
/// NAME.sumo_mapping.json (from the merged model, as a build makes them), the scene tiles NAME_Tile_X_Y.glb
/// (each tile's core) and their coarse level NAME_Tile_X_Y_lod1.glb, tileset.json (OGC 3D Tiles
/// 1.1, the coarse tiles refined by replacement with the full ones) and report.json. Throws InvalidInput when
/// a planned tile is not built or out of date (and writes nothing then); reports
/// "tiles.link_unresolved" for each link no tile answers.
[[nodiscard]] TileMergeResult merge_tiles(const std::filesystem::path& dir, const TileMergeOptions& options,
                                          Diagnostics& diagnostics);

}  // namespace relief

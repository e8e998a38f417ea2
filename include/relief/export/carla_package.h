#pragma once
// CARLA's import package: the folder and JSON that CARLA 0.9.x's `make import`
// (Util/BuildTools/Import.py) ingests from carla/Import/, packed as one gzip-compressed tar
// archive. Extracted into carla/Import/ it gives the layout of CARLA's documentation:
//
//   standard map (tuto_M_manual_map_package.md)     large map (content_authoring_large_maps.md)
//   NAME/NAME.json                                  NAME/NAME.json
//   NAME/NAME/NAME.fbx                              NAME/NAME.xodr
//   NAME/NAME/NAME.xodr                             NAME/NAME_Tile_X_Y.fbx ...
//
// NAME.json (the file's stem is the package's name in CARLA):
//   {"maps": [{"name": NAME, "source": "./NAME/NAME.fbx", "use_carla_materials": true,
//              "xodr": "./NAME/NAME.xodr"}], "props": []}
//   {"maps": [{"name": NAME, "xodr": "./NAME.xodr", "use_carla_materials": true,
//              "tile_size": S, "tiles": ["./NAME_Tile_0_0.fbx", ...]}], "props": []}
// Import.py imports "source" as one map, or, when the first map has "tiles", every tile with
// bForceVerticesRelativeToTile and that map's "tile_size" (m; its default 2000, the most CARLA
// supports). The cook then looks the tiles up from NAME_Tile_0_0 row by row (X = 0, 1, ... while
// a tile is found, then the next Y) and places tile (X, Y) at the first tile's centre plus
// tile_size * (X, -Y) in Unreal's frame, whose y is OpenDRIVE's -y: Y grows northward, as
// relief's tiles do (mesh_tiles.h). Mesh names tell CARLA the semantic tag and, with
// use_carla_materials, the material (MoveAssetsCommandlet.cpp, PrepareAssetsForCooking
// Commandlet.cpp): Road_Road, Road_Marking, Road_Sidewalk, Terrain are relief's mesh names.
//
// The archive is POSIX ustar (every entry mode 0644, directories 0755, owner 0, times
// `mtime_s`), written and gzip-compressed (libdeflate) by relief: equal inputs give equal bytes.

#include <cstdint>
#include <set>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "relief/export/mesh_writer.h"

namespace relief {

/// Largest tile edge CARLA's large maps support, m (content_authoring_large_maps.md: "The
/// maximum tile size supported by the CARLA engine is 2 km").
inline constexpr int kCarlaMaxTileSizeM = 2000;

/// What goes into the package.
struct CarlaPackageInput {
  /// The map's name in CARLA and the stem of its files; also the package's name. Letters,
  /// digits, '_' and '-' only (Unreal's package paths refuse '.', spaces and most punctuation).
  std::string map_name;
  std::string xodr;  ///< the OpenDRIVE text, packed as NAME.xodr
  /// The scene as FBX: one file NAME.fbx (a standard map), or the tiles NAME_Tile_X_Y.fbx of a
  /// large map (tile_size_m > 0), in any order.
  std::vector<EncodedFile> fbx_files;
  /// 0: a standard map; else a large map of tiles of this edge, 1..kCarlaMaxTileSizeM m.
  int tile_size_m = 0;
  bool use_carla_materials = true;  ///< CARLA's road, marking, sidewalk and grass materials
  std::int64_t mtime_s = 0;         ///< the entries' modification time, s since 1970 (>= 0)
};

/// True when `name` can be a CARLA map and package name (see CarlaPackageInput::map_name).
[[nodiscard]] bool is_valid_carla_map_name(std::string_view name);

/// The package's JSON (NAME.json above), as written into the archive.
/// Throws InvalidInput as encode_carla_package.
[[nodiscard]] std::string carla_package_json(const CarlaPackageInput& input);

/// The paths of the archive's entries in the order written (directories end with '/').
/// Throws InvalidInput as encode_carla_package.
[[nodiscard]] std::vector<std::string> carla_package_entries(const CarlaPackageInput& input);

/// The tiles a large map's grid lacks: "X Y" of every tile in the rectangle from (0, 0) to the
/// largest X and Y given that has no file. CARLA's cook stops a row at its first missing tile
/// and stops at the first row without tile X = 0, so the tiles beyond a gap are not imported.
/// Empty for a standard map. Throws InvalidInput as encode_carla_package.
[[nodiscard]] std::vector<std::string> carla_tile_grid_gaps(const CarlaPackageInput& input);

/// Placeholders for the tiles of a large map's grid rectangle (0, 0)..(max X, max Y) of
/// `present` that it lacks (CARLA's cook stops a row at its first missing tile): for each, the FBX
/// NAME_Tile_X_Y.fbx of one triangle named "Placeholder", 10 cm wide, at the tile's centre
/// `grid_origin` + size * (X + 0.5, Y + 0.5) (`grid_origin`: the south-west corner of tile
/// (0, 0)) at height `z`, in `like`'s frame with its metadata. Appends "X Y" of each to `placed`.
[[nodiscard]] std::vector<EncodedFile> carla_placeholder_tiles(const std::set<std::pair<int, int>>& present,
                                                               const Vec2& grid_origin, double size_m,
                                                               double z, const MeshScene& like,
                                                               const std::string& name,
                                                               std::vector<std::string>& placed);

/// The warning for `placed` placeholder tiles ("X Y" each) of a grid of `tile_size_m`.
[[nodiscard]] std::string carla_placeholder_message(const std::vector<std::string>& placed, int tile_size_m);

/// The package as a .tar.gz. Throws InvalidInput for a map name that is not valid, no FBX, an
/// FBX not named NAME.fbx (standard map: exactly one) or NAME_Tile_X_Y.fbx (large map), the same
/// tile twice, a tile size out of range, mtime_s < 0, or a path too long for ustar.
[[nodiscard]] std::string encode_carla_package(const CarlaPackageInput& input);

}  // namespace relief

#pragma once
// A merged region as CARLA's large map: NAME.carla.tar.gz with the region's NAME.xodr and its
// scene tiles NAME_Tile_X_Y.fbx on the plan's grid (export/carla_package.h), placeholders filling
// the grid's rectangle where a tile holds no triangles.

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "relief/core/atomic_file.h"
#include "relief/core/diagnostics.h"
#include "relief/export/mesh_writer.h"
#include "relief/tiles/tiles.h"

namespace relief::detail {

/// Why the region cannot be a CARLA large map ("" when it can): a tile larger than CARLA's 2 km
/// or not whole metres, a name CARLA refuses, or no FBX tiles.
[[nodiscard]] std::string carla_large_map_refusal(const TileManifest& manifest, std::size_t fbx_tiles);

/// Writes DIR/NAME.carla.tar.gz of `xodr` and the tiles' `fbx` (NAME_Tile_X_Y.fbx, X and Y the
/// plan's) into `files`, `lowest_z` the scene's lowest point (placeholders go 50 m under it, in
/// `like`'s frame and with its metadata).
/// Reports the placeholder tiles (carla.tile_grid_gap). Returns report.json's "carla" object.
nlohmann::json write_carla_large_map(const TileManifest& manifest, std::string xodr,
                                     std::vector<EncodedFile> fbx,
                                     const std::vector<std::pair<int, int>>& tiles, double lowest_z,
                                     const MeshScene& like, const std::filesystem::path& dir,
                                     OutputSet& files, std::vector<std::filesystem::path>& written,
                                     Diagnostics& diagnostics);

}  // namespace relief::detail

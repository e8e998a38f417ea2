#include "tiles/carla_merge.h"

#include <cmath>
#include <ctime>
#include <set>

#include "relief/core/diagnostic_codes.h"
#include "relief/export/carla_package.h"

namespace relief::detail {

std::string carla_large_map_refusal(const TileManifest& manifest, std::size_t fbx_tiles) {
  const double size = manifest.tile_size_m;
  if (size > kCarlaMaxTileSizeM || size != std::round(size)) {
    return "the tile size " + std::to_string(size) + " m is not whole metres up to CARLA's " +
           std::to_string(kCarlaMaxTileSizeM) + " m";
  }
  if (!is_valid_carla_map_name(manifest.name))
    return "the name '" + manifest.name + "' is not a CARLA map name (letters, digits, '_' and '-')";
  if (fbx_tiles == 0) return "no tile has an FBX scene (the plan's --mesh-formats lacks fbx)";
  return {};
}

nlohmann::json write_carla_large_map(const TileManifest& manifest, std::string xodr,
                                     std::vector<EncodedFile> fbx,
                                     const std::vector<std::pair<int, int>>& tiles, double lowest_z,
                                     const MeshScene& like, const std::filesystem::path& dir,
                                     OutputSet& files, std::vector<std::filesystem::path>& written,
                                     Diagnostics& diagnostics) {
  CarlaPackageInput package;
  package.map_name = manifest.name;
  package.xodr = std::move(xodr);
  package.tile_size_m = static_cast<int>(manifest.tile_size_m);
  package.mtime_s = static_cast<std::int64_t>(std::time(nullptr));
  const std::set<std::pair<int, int>> present(tiles.begin(), tiles.end());
  std::vector<std::string> placed;
  package.fbx_files = carla_placeholder_tiles(present, manifest.grid_origin, manifest.tile_size_m,
                                              lowest_z - 50.0, like, manifest.name, placed);
  for (EncodedFile& f : fbx) package.fbx_files.push_back(std::move(f));
  if (!placed.empty()) {
    diagnostics.report(Severity::warning, codes::kCarlaTileGridGap,
                       carla_placeholder_message(placed, package.tile_size_m));
  }
  const std::string bytes = encode_carla_package(package);
  const std::filesystem::path path = dir / (manifest.name + ".carla.tar.gz");
  files.add(path, [&bytes](std::ostream& o) { o << bytes; });
  written.push_back(path);
  return {{"package", path.filename().string()},
          {"tile_size_m", package.tile_size_m},
          {"tiles", tiles.size()},
          {"placeholder_tiles", placed},
          {"entries", carla_package_entries(package)}};
}

}  // namespace relief::detail

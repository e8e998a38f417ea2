#include <algorithm>

#include "relief/export/carla_package.h"

namespace relief {

std::vector<EncodedFile> carla_placeholder_tiles(const std::set<std::pair<int, int>>& present,
                                                 const Vec2& grid_origin, double size_m, double z,
                                                 const MeshScene& like, const std::string& name,
                                                 std::vector<std::string>& placed) {
  std::vector<EncodedFile> out;
  if (present.empty()) return out;
  int max_x = 0, max_y = 0;
  for (const auto& [x, y] : present) {
    max_x = std::max(max_x, x);
    max_y = std::max(max_y, y);
  }
  constexpr double kHalfM = 0.05;
  for (int y = 0; y <= max_y; ++y) {
    for (int x = 0; x <= max_x; ++x) {
      if (present.contains({x, y})) continue;
      const Vec2 c = grid_origin + size_m * Vec2(x + 0.5, y + 0.5);
      MeshScene tile;
      tile.frame = like.frame;
      tile.metadata = like.metadata;
      tile.metadata["relief:tile"] = std::to_string(x) + " " + std::to_string(y);
      tile.metadata["relief:placeholder"] = "a tile without triangles, for CARLA's cook";
      TriangleMesh m;
      m.name = "Placeholder";
      m.kind = SurfaceKind::terrain;
      m.vertices = {{c.x() - kHalfM, c.y() - kHalfM, z},
                    {c.x() + kHalfM, c.y() - kHalfM, z},
                    {c.x(), c.y() + kHalfM, z}};
      m.triangles = {{0, 1, 2}};
      m.normals.assign(3, Vec3::UnitZ());
      tile.meshes.push_back(std::move(m));
      const std::string base = name + "_Tile_" + std::to_string(x) + "_" + std::to_string(y);
      for (EncodedFile& f : encode_mesh_scene(tile, MeshFormat::fbx, base)) out.push_back(std::move(f));
      placed.push_back(std::to_string(x) + " " + std::to_string(y));
    }
  }
  return out;
}

std::string carla_placeholder_message(const std::vector<std::string>& placed, int tile_size_m) {
  std::string listed;
  for (std::size_t i = 0; i < placed.size() && i < 10; ++i) listed += (i == 0 ? "" : ", ") + placed[i];
  return std::to_string(placed.size()) + " tile(s) of the " + std::to_string(tile_size_m) +
         " m grid hold no triangles (X Y: " + listed + (placed.size() > 10 ? ", ..." : "") +
         "): the CARLA package gives each a placeholder triangle 50 m under the scene, since CARLA's cook "
         "stops a row at its first missing tile";
}

}  // namespace relief

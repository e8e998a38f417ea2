#include "relief/geometry/mesh_tiles.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <string>
#include <utility>

#include "relief/core/errors.h"
#include "relief/core/number_format.h"

namespace relief {
namespace {

constexpr std::uint32_t kUnused = ~std::uint32_t{0};

// The triangles `ids` of `mesh` as a mesh of their own; `index` (one entry per vertex of
// `mesh`, all kUnused) is left as it was found.
TriangleMesh extract(const TriangleMesh& mesh, const std::vector<std::uint32_t>& ids,
                     std::vector<std::uint32_t>& index) {
  TriangleMesh out;
  out.name = mesh.name;
  out.kind = mesh.kind;
  const bool normals = mesh.normals.size() == mesh.vertices.size();
  const bool uvs = mesh.uvs.size() == mesh.vertices.size();
  out.triangles.reserve(ids.size());
  for (const std::uint32_t id : ids) {
    std::array<std::uint32_t, 3> t{};
    for (std::size_t k = 0; k < 3; ++k) {
      const std::uint32_t v = mesh.triangles[id][k];
      if (index[v] == kUnused) {
        index[v] = static_cast<std::uint32_t>(out.vertices.size());
        out.vertices.push_back(mesh.vertices[v]);
        if (normals) out.normals.push_back(mesh.normals[v]);
        if (uvs) out.uvs.push_back(mesh.uvs[v]);
      }
      t[k] = index[v];
    }
    out.triangles.push_back(t);
  }
  for (const std::uint32_t id : ids) {
    for (const std::uint32_t v : mesh.triangles[id]) index[v] = kUnused;
  }
  return out;
}

using Cell = std::pair<long long, long long>;  // (row, column): sorts row-major

// The grid cell holding triangle `i`'s centroid.
Cell cell_of(const TriangleMesh& mesh, std::size_t i, double size_m) {
  Vec3 c = Vec3::Zero();
  for (const std::uint32_t v : mesh.triangles[i]) {
    if (v >= mesh.vertices.size()) {
      throw InvalidInput("tiles: mesh '" + mesh.name + "' has a vertex index out of range");
    }
    c += mesh.vertices[v];
  }
  c /= 3.0;
  return {static_cast<long long>(std::floor(c.y() / size_m)),
          static_cast<long long>(std::floor(c.x() / size_m))};
}

void check_size(double size_m) {
  if (!(size_m > 0.0) || !std::isfinite(size_m)) {
    throw InvalidInput("tiles: the tile size must be positive and finite (got " + std::to_string(size_m) +
                       ")");
  }
}

}  // namespace

FileOrigin cell_file_origin(double size_m, long long column, long long row) {
  check_size(size_m);
  FileOrigin o;
  o.at = Vec2(std::round((static_cast<double>(column) + 0.5) * size_m),
              std::round((static_cast<double>(row) + 0.5) * size_m));
  // A float holds every multiple k q with |k| <= 2^24 exactly: 2^24 q >= 2 size_m.
  o.quantum_m = std::exp2(std::ceil(std::log2(size_m / 8388608.0)));
  return o;
}

MeshScene scene_in_cell(const MeshScene& scene, double size_m, long long column, long long row) {
  check_size(size_m);
  MeshScene out;
  out.frame = scene.frame;
  out.metadata = scene.metadata;
  out.file_origin = cell_file_origin(size_m, column, row);
  for (const TriangleMesh& mesh : scene.meshes) {
    std::vector<std::uint32_t> ids;
    for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
      if (cell_of(mesh, i, size_m) == Cell{row, column}) ids.push_back(static_cast<std::uint32_t>(i));
    }
    if (ids.empty()) continue;
    std::vector<std::uint32_t> index(mesh.vertices.size(), kUnused);
    out.meshes.push_back(extract(mesh, ids, index));
  }
  return out;
}

std::vector<SceneTile> split_into_tiles(const MeshScene& scene, double size_m) {
  check_size(size_m);
  // Grid cell of every triangle, per mesh; the cells used, in row-major order.
  std::map<Cell, std::vector<std::vector<std::uint32_t>>> cells;
  for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
    const TriangleMesh& mesh = scene.meshes[m];
    for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
      auto& per_mesh = cells[cell_of(mesh, i, size_m)];
      if (per_mesh.empty()) per_mesh.resize(scene.meshes.size());
      per_mesh[m].push_back(static_cast<std::uint32_t>(i));
    }
  }
  if (cells.empty()) return {};
  long long min_row = cells.begin()->first.first, min_col = cells.begin()->first.second;
  for (const auto& [cell, per_mesh] : cells) min_col = std::min(min_col, cell.second);

  std::vector<std::vector<std::uint32_t>> index(scene.meshes.size());
  for (std::size_t m = 0; m < scene.meshes.size(); ++m)
    index[m].assign(scene.meshes[m].vertices.size(), kUnused);
  std::vector<SceneTile> tiles;
  tiles.reserve(cells.size());
  for (const auto& [cell, per_mesh] : cells) {
    SceneTile tile;
    tile.x = static_cast<int>(cell.second - min_col);
    tile.y = static_cast<int>(cell.first - min_row);
    tile.bounds.extend(
        Vec2(static_cast<double>(cell.second) * size_m, static_cast<double>(cell.first) * size_m));
    tile.bounds.extend(
        Vec2(static_cast<double>(cell.second + 1) * size_m, static_cast<double>(cell.first + 1) * size_m));
    tile.scene.frame = scene.frame;
    tile.scene.metadata = scene.metadata;
    tile.scene.file_origin = cell_file_origin(size_m, cell.second, cell.first);
    tile.scene.metadata["relief:tile"] = std::to_string(tile.x) + " " + std::to_string(tile.y);
    std::string bounds;
    for (const double v :
         {tile.bounds.min.x(), tile.bounds.min.y(), tile.bounds.max.x(), tile.bounds.max.y()}) {
      if (!bounds.empty()) bounds += ' ';
      append_fixed(bounds, v, 3);
    }
    tile.scene.metadata["relief:tile_bounds"] = bounds;
    for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
      if (per_mesh[m].empty()) continue;
      tile.scene.meshes.push_back(extract(scene.meshes[m], per_mesh[m], index[m]));
    }
    tiles.push_back(std::move(tile));
  }
  return tiles;
}

}  // namespace relief

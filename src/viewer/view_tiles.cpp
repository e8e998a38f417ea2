// The scene cut into the view's plan tiles, each encoded as a <script> file of typed arrays.
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <map>
#include <numeric>
#include <set>
#include <string_view>
#include <unordered_map>

#include <Eigen/Geometry>

#include "core/base64.h"
#include "relief/core/errors.h"
#include "relief/viewer/view_writer.h"

namespace relief {
namespace {

static_assert(std::endian::native == std::endian::little, "the view's typed arrays are little-endian");

/// The view's layer of a scene mesh ("Road_Marking" -> "marking"); Road_Road is split later.
std::string layer_of(const std::string& mesh_name) {
  if (mesh_name == "Terrain") return "terrain";
  std::string layer = mesh_name.rfind("Road_", 0) == 0 ? mesh_name.substr(5) : mesh_name;
  std::transform(layer.begin(), layer.end(), layer.begin(), [](unsigned char c) { return std::tolower(c); });
  return layer;
}

/// Steepest slope of a triangle in percent (capped at 1000 % for walls).
double slope_percent(const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 n = (b - a).cross(c - a);
  const double horizontal = std::hypot(n.x(), n.y());
  if (std::abs(n.z()) * 10.0 <= horizontal) return 1000.0;
  return 100.0 * horizontal / std::abs(n.z());
}

template <class T>
void append_array(std::string& out, std::string_view key, const std::vector<T>& values) {
  out += ",\"";
  out += key;
  out += "\":\"";
  detail::append_base64(out, {reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T)});
  out += '"';
}

/// The triangles of one mesh that fall in one tile, and how to encode them.
struct LayerPart {
  std::string layer;
  const TriangleMesh* mesh = nullptr;
  std::vector<std::uint32_t> triangles;
};

struct TileBuild {
  int x = 0, y = 0;
  std::vector<LayerPart> parts;
};

/// Encodes one layer part: vertices renumbered in order of first use (split where two owners
/// share a position, so that a road's colour and pick stay its own), and per vertex the
/// owner, grade and height over the DEM for paved layers.
void encode_part(const LayerPart& part, const std::vector<int>* owner_of_triangle, const DemSampler& dem,
                 bool attributes, ViewTile& tile, std::string& script) {
  const TriangleMesh& mesh = *part.mesh;
  std::unordered_map<std::uint64_t, std::uint32_t> index_of;
  index_of.reserve(part.triangles.size() * 2);
  std::vector<float> positions;
  std::vector<std::uint32_t> indices;
  std::vector<std::int32_t> owners;
  std::vector<double> slope_area, area;
  std::vector<std::uint32_t> source;
  indices.reserve(part.triangles.size() * 3);
  for (const std::uint32_t t : part.triangles) {
    const auto& tri = mesh.triangles[t];
    const std::int32_t owner = owner_of_triangle ? (*owner_of_triangle)[t] : -1;
    const Vec3& a = mesh.vertices[tri[0]];
    const Vec3& b = mesh.vertices[tri[1]];
    const Vec3& c = mesh.vertices[tri[2]];
    const double tri_area = attributes ? 0.5 * (b - a).cross(c - a).norm() : 0.0;
    const double slope = attributes ? slope_percent(a, b, c) : 0.0;
    for (const std::uint32_t v : tri) {
      const std::uint64_t key = static_cast<std::uint64_t>(v) |
                                static_cast<std::uint64_t>(static_cast<std::uint32_t>(owner + 1)) << 32;
      auto [it, inserted] = index_of.try_emplace(key, static_cast<std::uint32_t>(source.size()));
      if (inserted) {
        source.push_back(v);
        const Vec3& p = mesh.vertices[v];
        // three.js axes, as the glTF files: (x, z, -y).
        positions.insert(positions.end(),
                         {static_cast<float>(p.x()), static_cast<float>(p.z()), static_cast<float>(-p.y())});
        tile.bounds.extend(Vec2(p.x(), p.y()));
        tile.z_min = std::min(tile.z_min, p.z());
        tile.z_max = std::max(tile.z_max, p.z());
        if (attributes) {
          owners.push_back(owner);
          slope_area.push_back(0.0);
          area.push_back(0.0);
        }
      }
      indices.push_back(it->second);
      if (attributes) {
        slope_area[it->second] += slope * tri_area;
        area[it->second] += tri_area;
      }
    }
  }
  script += "{\"layer\":\"" + part.layer + "\",\"vertices\":" + std::to_string(source.size()) +
            ",\"triangles\":" + std::to_string(part.triangles.size());
  append_array(script, "positions", positions);
  append_array(script, "indices", indices);
  if (attributes) {
    std::vector<float> grade(source.size()), dz(source.size());
    for (std::size_t i = 0; i < source.size(); ++i) {
      grade[i] = static_cast<float>(area[i] > 0.0 ? slope_area[i] / area[i] : 0.0);
      const Vec3& p = mesh.vertices[source[i]];
      const auto ground = dem.height_at(Vec2(p.x(), p.y()));
      dz[i] = ground ? static_cast<float>(p.z() - *ground) : std::numeric_limits<float>::quiet_NaN();
    }
    append_array(script, "owner", owners);
    append_array(script, "grade", grade);
    append_array(script, "dz", dz);
  }
  script += '}';
}

/// A coarse copy of a layer part for distant views (vertex clustering, Rossignac and Borrel
/// 1993): corners in one plan cell of `cell_m` with the same owner become one vertex at their
/// mean, triangles that collapse are dropped, and so are repeats. Linear in the triangles.
struct Clustered {
  TriangleMesh mesh;
  std::vector<int> owner;  ///< per triangle, parallel to mesh.triangles (when owners are given)
};
Clustered cluster_part(const LayerPart& part, const std::vector<int>* owner_of_triangle, double cell_m) {
  struct Cell {
    Vec3 sum = Vec3::Zero();
    int count = 0;
  };
  Clustered out;
  out.mesh.name = part.mesh->name;
  out.mesh.kind = part.mesh->kind;
  std::unordered_map<std::uint64_t, std::uint32_t> index_of;
  std::vector<Cell> cells;
  std::set<std::array<std::uint32_t, 3>> seen;  // a triangle's three cells, to drop repeats
  std::vector<std::uint32_t> corner_cell;
  for (const std::uint32_t t : part.triangles) {
    const auto& tri = part.mesh->triangles[t];
    const int owner = owner_of_triangle ? (*owner_of_triangle)[t] : -1;
    std::array<std::uint32_t, 3> c{};
    for (int k = 0; k < 3; ++k) {
      const Vec3& p = part.mesh->vertices[tri[k]];
      // 20 bits of cell per axis (wrapping after 1M cells: 2 500 km at the smallest cell) and
      // 24 of the owner's index: one key.
      const auto ix =
          static_cast<std::uint64_t>(static_cast<std::int64_t>(std::floor(p.x() / cell_m)) & 0xfffff);
      const auto iy =
          static_cast<std::uint64_t>(static_cast<std::int64_t>(std::floor(p.y() / cell_m)) & 0xfffff);
      const std::uint64_t key =
          ix | iy << 20 | static_cast<std::uint64_t>(static_cast<std::uint32_t>(owner + 1)) << 40;
      auto [it, inserted] = index_of.try_emplace(key, static_cast<std::uint32_t>(cells.size()));
      if (inserted) cells.emplace_back();
      cells[it->second].sum += p;
      ++cells[it->second].count;
      c[k] = it->second;
    }
    if (c[0] == c[1] || c[1] == c[2] || c[0] == c[2]) continue;
    // The same three cells in either winding are one triangle.
    std::array<std::uint32_t, 3> sorted = c;
    std::sort(sorted.begin(), sorted.end());
    if (!seen.insert(sorted).second) continue;
    out.mesh.triangles.push_back(c);
    if (owner_of_triangle) out.owner.push_back(owner);
  }
  out.mesh.vertices.reserve(cells.size());
  for (const Cell& cell : cells) out.mesh.vertices.push_back(cell.sum / cell.count);
  return out;
}

}  // namespace

ViewTiles view_tiles(const Scene& scene, const DemSampler& dem, const ViewTileSink& write,
                     const ViewOptions& options) {
  if (!(options.tile_size_m >= 0.0) || !std::isfinite(options.tile_size_m) || options.tile_triangles == 0 ||
      !(options.lod_cells_per_tile >= 1.0) || std::isnan(options.lod_min_tile_m))
    throw InvalidInput(
        "view: tile size must be finite and >= 0 (0: automatic), tile_triangles > 0, lod_cells_per_tile >= "
        "1");
  ViewTiles out;
  Aabb2 extent;
  for (const TriangleMesh& mesh : scene.meshes.meshes) {
    out.triangles += mesh.triangles.size();
    for (const Vec3& v : mesh.vertices) extent.extend(Vec2(v.x(), v.y()));
  }
  if (out.triangles == 0) return out;
  double size = options.tile_size_m;
  if (size == 0.0) {
    // About tile_triangles per tile if the triangles were spread evenly over the extent.
    const double area_m2 = std::max(1.0, (extent.max - extent.min).prod());
    const double per_tile =
        area_m2 * static_cast<double>(options.tile_triangles) / static_cast<double>(out.triangles);
    size = std::clamp(std::ceil(std::sqrt(per_tile) / 250.0) * 250.0, 250.0, 4000.0);
  }
  out.tile_size_m = size;
  // A coarse copy of each tile for distant views, on tiles big enough to be seen from afar.
  const double lod_cell_m = size >= options.lod_min_tile_m ? size / options.lod_cells_per_tile : 0.0;
  const int x0 = static_cast<int>(std::floor(extent.min.x() / size));
  const int y0 = static_cast<int>(std::floor(extent.min.y() / size));

  // Owners of Road_Road's triangles, as indices into out.owners.
  const std::vector<int>& owner_ids = scene.roads.road_triangle_owner;
  std::vector<int> owner_index(owner_ids.size());
  std::map<int, int> index_of_owner;
  for (std::size_t t = 0; t < owner_ids.size(); ++t) {
    auto [it, inserted] = index_of_owner.try_emplace(owner_ids[t], static_cast<int>(out.owners.size()));
    if (inserted) out.owners.push_back(owner_ids[t]);
    owner_index[t] = it->second;
  }

  // Every triangle to the tile of its centroid, per layer.
  std::map<std::pair<int, int>, TileBuild> builds;  // (row, column): row-major order
  const auto part_of = [&](int ix, int iy, const std::string& layer, const TriangleMesh& mesh) -> LayerPart& {
    TileBuild& b = builds[{iy, ix}];
    b.x = ix;
    b.y = iy;
    for (LayerPart& p : b.parts)
      if (p.layer == layer) return p;
    b.parts.push_back({layer, &mesh, {}});
    return b.parts.back();
  };
  for (const TriangleMesh& mesh : scene.meshes.meshes) {
    const bool road = mesh.name == "Road_Road";
    const bool split_ground = road && scene.ground.size() == mesh.triangles.size();
    const std::string layer = layer_of(mesh.name);
    for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t) {
      const auto& tri = mesh.triangles[t];
      const Vec3 c = (mesh.vertices[tri[0]] + mesh.vertices[tri[1]] + mesh.vertices[tri[2]]) / 3.0;
      const int ix = static_cast<int>(std::floor(c.x() / size)) - x0;
      const int iy = static_cast<int>(std::floor(c.y() / size)) - y0;
      const std::string name = split_ground && scene.ground[t] == 0 ? std::string("structure") : layer;
      part_of(ix, iy, name, mesh).triangles.push_back(t);
    }
  }

  out.tiles.reserve(builds.size());
  for (auto& entry : builds) {
    const TileBuild& b = entry.second;
    ViewTile tile;
    tile.x = b.x;
    tile.y = b.y;
    tile.filename = "tile_" + std::to_string(b.x) + "_" + std::to_string(b.y) + ".js";
    tile.z_min = std::numeric_limits<double>::infinity();
    tile.z_max = -std::numeric_limits<double>::infinity();
    // The marks in a file of their own, loaded only near: afar they are under a pixel wide.
    const auto encode_file = [&](bool marks, std::size_t& triangles) {
      std::string s = "RELIEF_TILE({\"x\":" + std::to_string(b.x) + ",\"y\":" + std::to_string(b.y) +
                      ",\"part\":\"" + (marks ? "marks" : "base") + "\",\"layers\":[";
      bool first = true;
      for (const LayerPart& part : b.parts) {
        if ((part.layer == "marking") != marks) continue;
        const bool paved = part.mesh->name == "Road_Road";
        const bool attributes = paved || part.layer == "sidewalk";
        if (!first) s += ',';
        first = false;
        encode_part(part, paved && owner_index.size() == part.mesh->triangles.size() ? &owner_index : nullptr,
                    dem, attributes, tile, s);
        triangles += part.triangles.size();
      }
      return s + "]});\n";
    };
    const std::string base = encode_file(false, tile.triangles);
    write(tile.filename, base);
    // The distant view's copy of every layer but the marks.
    if (lod_cell_m > 0.0) {
      std::string lod = "RELIEF_TILE({\"x\":" + std::to_string(b.x) + ",\"y\":" + std::to_string(b.y) +
                        ",\"part\":\"lod\",\"layers\":[";
      bool first = true;
      ViewTile ignored;  // the bounds are the full tile's
      for (const LayerPart& part : b.parts) {
        if (part.layer == "marking") continue;
        const bool paved = part.mesh->name == "Road_Road";
        const std::vector<int>* owners =
            paved && owner_index.size() == part.mesh->triangles.size() ? &owner_index : nullptr;
        const Clustered coarse = cluster_part(part, owners, lod_cell_m);
        if (coarse.mesh.triangles.empty()) continue;
        LayerPart whole{part.layer, &coarse.mesh, {}};
        whole.triangles.resize(coarse.mesh.triangles.size());
        std::iota(whole.triangles.begin(), whole.triangles.end(), 0u);
        if (!first) lod += ',';
        first = false;
        encode_part(whole, owners ? &coarse.owner : nullptr, dem, paved || part.layer == "sidewalk", ignored,
                    lod);
        tile.lod_triangles += coarse.mesh.triangles.size();
      }
      tile.lod_filename = "tile_" + std::to_string(b.x) + "_" + std::to_string(b.y) + "_lod.js";
      write(tile.lod_filename, lod + "]});\n");
    }
    const std::string marks = encode_file(true, tile.marks_triangles);
    if (tile.marks_triangles > 0) {
      tile.marks_filename = "tile_" + std::to_string(b.x) + "_" + std::to_string(b.y) + "_marks.js";
      write(tile.marks_filename, marks);
    }
    out.tiles.push_back(std::move(tile));
  }
  return out;
}

}  // namespace relief

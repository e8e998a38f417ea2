#include "tiles/owner_surface.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <optional>
#include <unordered_map>
#include <utility>

#include "relief/core/atomic_file.h"
#include "relief/geometry/mesh_quality.h"
#include "tiles/binary_file.h"
#include "tiles/scene_seams.h"
#include "tiles/xodr_merge.h"

namespace relief::detail {
namespace {

constexpr char kMagic[] = "relief-owned-surface 1\n";
constexpr double kOwnersApartM = 1e-3;  // two owners' heights at one place further apart are reported
// A terrain vertex at a road vertex's place this close to its height is the road's edge (an
// opening's top stands the portal's height, 5 m by default, over it).
constexpr double kTerrainOnRoadM = 1.0;

// The owners' vertices of one mesh, by grid cells of the tolerance: a lookup searches the 3 x 3
// cells around its point. Cells are ranges of one array sorted by cell (no allocation per cell).
class OwnerIndex {
 public:
  struct Entry {
    Vec3 p;
    std::size_t tile;
  };

  OwnerIndex(std::vector<Entry> entries, double cell) : cell_(cell), entries_(std::move(entries)) {
    std::vector<std::uint64_t> keys(entries_.size());
    for (std::size_t i = 0; i < entries_.size(); ++i)
      keys[i] = key(cell_of(entries_[i].p.x()), cell_of(entries_[i].p.y()));
    order_.resize(entries_.size());
    std::iota(order_.begin(), order_.end(), std::uint32_t{0});
    // Stable: within a cell, the entries stay in the owners' order (the first owner first).
    std::stable_sort(order_.begin(), order_.end(),
                     [&](std::uint32_t a, std::uint32_t b) { return keys[a] < keys[b]; });
    for (std::size_t i = 0; i < order_.size();) {
      std::size_t j = i;
      while (j < order_.size() && keys[order_[j]] == keys[order_[i]]) ++j;
      ranges_.emplace(keys[order_[i]],
                      std::make_pair(static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(j)));
      i = j;
    }
  }

  [[nodiscard]] const std::vector<Entry>& entries() const { return entries_; }

  /// The index of the entry nearest `p` in plan within `tolerance` (of equally near ones, the
  /// first owner's), skipping `skip`.
  [[nodiscard]] std::optional<std::size_t> nearest(const Vec2& p, double tolerance,
                                                   std::size_t skip = ~std::size_t{0}) const {
    std::optional<std::size_t> best;
    double best_d = 0.0;
    const long long cx = cell_of(p.x()), cy = cell_of(p.y());
    for (long long dx = -1; dx <= 1; ++dx) {
      for (long long dy = -1; dy <= 1; ++dy) {
        const auto it = ranges_.find(key(cx + dx, cy + dy));
        if (it == ranges_.end()) continue;
        for (std::uint32_t k = it->second.first; k < it->second.second; ++k) {
          const std::size_t i = order_[k];
          if (i == skip) continue;
          const double d = (entries_[i].p.head<2>() - p).norm();
          if (d > tolerance) continue;
          if (!best || d < best_d || (d == best_d && i < *best)) {
            best_d = d;
            best = i;
          }
        }
      }
    }
    return best;
  }

 private:
  [[nodiscard]] long long cell_of(double v) const { return static_cast<long long>(std::floor(v / cell_)); }
  static std::uint64_t key(long long x, long long y) {
    return (static_cast<std::uint64_t>(x) * 0x9E3779B97F4A7C15ull) ^ static_cast<std::uint64_t>(y);
  }
  double cell_;
  std::vector<Entry> entries_;
  std::vector<std::uint32_t> order_;
  std::unordered_map<std::uint64_t, std::pair<std::uint32_t, std::uint32_t>> ranges_;
};

// Per paved mesh of the scene, the owner (road id or -1 - junction id) of each triangle.
const std::vector<int>* owners_of(const Scene& scene, const std::string& name) {
  if (name == "Road_Road") return &scene.roads.road_triangle_owner;
  if (name == "Road_Sidewalk") return &scene.roads.sidewalk_triangle_owner;
  if (name == "Road_Marking") return &scene.roads.marking_triangle_owner;
  return nullptr;
}

// Each vertex's neighbours along a mesh's triangle edges (an edge of two triangles listed twice).
struct VertexNeighbours {
  std::vector<std::size_t> start;  // vertex v's neighbours: at[start[v] .. start[v + 1])
  std::vector<std::uint32_t> at;

  explicit VertexNeighbours(const TriangleMesh& mesh) : start(mesh.vertices.size() + 1, 0) {
    for (const auto& t : mesh.triangles)
      for (const std::uint32_t v : t) start[v + 1] += 2;
    std::partial_sum(start.begin(), start.end(), start.begin());
    at.resize(start.back());
    std::vector<std::size_t> fill(start.begin(), start.end() - 1);
    for (const auto& t : mesh.triangles) {
      for (std::size_t k = 0; k < 3; ++k) {
        at[fill[t[k]]++] = t[(k + 1) % 3];
        at[fill[t[k]]++] = t[(k + 2) % 3];
      }
    }
  }
};

// `dz` with each vertex that has no height change of its own (NaN) given the mean of its mesh
// neighbours' changes weighted by their inverse plan distance, ring by ring out from the vertices
// that have one (NaN where no path leads): a run of stations the owner's loft did not make (its
// refinement went otherwise) follows the stations around it instead of standing out of the moved
// surface by the two fits' difference. Linear.
std::vector<double> interpolate_unmatched(const TriangleMesh& mesh, const std::vector<double>& dz) {
  if (std::none_of(dz.begin(), dz.end(), [](double d) { return std::isnan(d); })) return dz;
  const VertexNeighbours near(mesh);
  std::vector<double> out = dz;
  std::vector<std::uint8_t> queued(dz.size(), 0);
  std::vector<std::uint32_t> ring;
  const auto enqueue_around = [&](std::uint32_t v, std::vector<std::uint32_t>& into) {
    for (std::size_t k = near.start[v]; k < near.start[v + 1]; ++k) {
      const std::uint32_t w = near.at[k];
      if (!std::isnan(out[w]) || queued[w]) continue;
      queued[w] = 1;
      into.push_back(w);
    }
  };
  for (std::uint32_t v = 0; v < dz.size(); ++v)
    if (!std::isnan(dz[v])) enqueue_around(v, ring);
  while (!ring.empty()) {
    std::vector<double> value(ring.size());
    for (std::size_t i = 0; i < ring.size(); ++i) {
      const std::uint32_t v = ring[i];
      double sum = 0.0, weight = 0.0;
      for (std::size_t k = near.start[v]; k < near.start[v + 1]; ++k) {
        const std::uint32_t w = near.at[k];
        if (std::isnan(out[w])) continue;
        const double d = std::max((mesh.vertices[v].head<2>() - mesh.vertices[w].head<2>()).norm(), 1e-3);
        sum += out[w] / d;
        weight += 1.0 / d;
      }
      value[i] = sum / weight;
    }
    for (std::size_t i = 0; i < ring.size(); ++i) out[ring[i]] = value[i];
    std::vector<std::uint32_t> next;
    for (const std::uint32_t v : ring) enqueue_around(v, next);
    ring = std::move(next);
  }
  return out;
}

// The vertices on a mesh's boundary (edges of one triangle) within `band` of the border of
// `core`: where another tile's file may hold the same vertex (the tiles' terrains are disjoint
// pieces of one surface, cut at the tile lines but for triangles beside a road that cross one).
std::vector<std::uint32_t> border_vertices(const TriangleMesh& mesh, const Aabb2& core, double band) {
  const Aabb2 outer = core.inflated(band), inner = core.inflated(-band);
  std::vector<std::uint8_t> on(mesh.vertices.size(), 0);
  for (const auto& [a, b] : boundary_edges(mesh)) {
    for (const std::uint32_t v : {a, b}) {
      const Vec2 p = mesh.vertices[v].head<2>();
      if (outer.contains(p) && !inner.contains(p)) on[v] = 1;
    }
  }
  std::vector<std::uint32_t> out;
  for (std::uint32_t v = 0; v < on.size(); ++v)
    if (on[v]) out.push_back(v);
  return out;
}

// How far each paved vertex of each tile's files moved onto its owner's height: moved[tile][mesh]
// per vertex, empty for a mesh that is not paved.
using PavedMoves = std::vector<std::vector<std::vector<float>>>;

// The terrain's copies of a place on a tile line beside a road came from each tile's batter on
// its own fit of the road; the road now has its owner's heights. Every copy takes the one of the
// tile whose paved vertex nearest the place (within kBatterReachM) moved least: the owner's own
// file where it is one of them, else the fit nearest the owner's.
void join_terrain_borders(std::vector<MeshScene>& tiles, const std::vector<Aabb2>& cores,
                          const PavedMoves& moved, OwnerHeights& out) {
  struct Copy {
    std::size_t tile, mesh;
    std::uint32_t vertex;
  };
  std::unordered_map<PlanKey, std::vector<Copy>, PlanKeyHash> places;
  for (std::size_t t = 0; t < tiles.size() && t < cores.size(); ++t) {
    for (std::size_t m = 0; m < tiles[t].meshes.size(); ++m) {
      const TriangleMesh& mesh = tiles[t].meshes[m];
      if (mesh.name != "Terrain") continue;
      for (const std::uint32_t v : border_vertices(mesh, cores[t], kBatterReachM))
        places[plan_key(mesh.vertices[v])].push_back({t, m, v});
    }
  }
  const auto point_of = [&](const Copy& c) -> const Vec3& {
    return tiles[c.tile].meshes[c.mesh].vertices[c.vertex];
  };
  const auto z_of = [&](const Copy& c) { return point_of(c).z(); };
  // The copies of one place, by height, in runs no more than kTerrainOnRoadM apart (an opening's
  // top over a road's edge at the same place is another vertex): a run of two tiles' copies at
  // different heights is a seam apart.
  std::vector<std::vector<Copy>> apart;
  for (auto& place : places) {
    std::vector<Copy>& copies = place.second;
    if (copies.size() < 2) continue;
    std::stable_sort(copies.begin(), copies.end(),
                     [&](const Copy& a, const Copy& b) { return z_of(a) < z_of(b); });
    for (std::size_t i = 0; i < copies.size();) {
      std::size_t j = i + 1;
      while (j < copies.size() && z_of(copies[j]) - z_of(copies[j - 1]) <= kTerrainOnRoadM) ++j;
      const bool two_tiles = std::any_of(copies.begin() + static_cast<std::ptrdiff_t>(i) + 1,
                                         copies.begin() + static_cast<std::ptrdiff_t>(j),
                                         [&](const Copy& c) { return c.tile != copies[i].tile; });
      if (two_tiles && z_of(copies[i]) != z_of(copies[j - 1]))
        apart.emplace_back(copies.begin() + static_cast<std::ptrdiff_t>(i),
                           copies.begin() + static_cast<std::ptrdiff_t>(j));
      i = j;
    }
  }
  if (apart.empty()) return;
  // Each tile's paved vertices near those places, as (x, y, how far it moved), in the order of
  // the move: of two as near, the one that moved less is found.
  std::vector<OwnerIndex::Entry> place_points;
  place_points.reserve(apart.size());
  for (const auto& copies : apart) place_points.push_back({point_of(copies[0]), 0});
  const OwnerIndex near_place(std::move(place_points), kBatterReachM);
  std::vector<OwnerIndex> paved;
  paved.reserve(tiles.size());
  for (std::size_t t = 0; t < tiles.size(); ++t) {
    std::vector<OwnerIndex::Entry> entries;
    for (std::size_t m = 0; m < tiles[t].meshes.size(); ++m) {
      if (moved[t][m].empty()) continue;
      const TriangleMesh& mesh = tiles[t].meshes[m];
      for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
        const Vec3& v = mesh.vertices[i];
        if (near_place.nearest(v.head<2>(), kBatterReachM))
          entries.push_back({Vec3(v.x(), v.y(), moved[t][m][i]), t});
      }
    }
    std::stable_sort(
        entries.begin(), entries.end(),
        [](const OwnerIndex::Entry& a, const OwnerIndex::Entry& b) { return a.p.z() < b.p.z(); });
    paved.emplace_back(std::move(entries), kBatterReachM);
  }
  // The move of tile t's paved vertex nearest p within the reach; infinity where it has none.
  const auto nearest_move = [&](std::size_t t, const Vec2& p) {
    const std::optional<std::size_t> i = paved[t].nearest(p, kBatterReachM);
    return i ? paved[t].entries()[*i].p.z() : std::numeric_limits<double>::infinity();
  };
  for (const auto& copies : apart) {
    const Vec2 p = point_of(copies[0]).head<2>();
    const Copy* best = nullptr;
    double best_move = std::numeric_limits<double>::infinity();
    for (const Copy& c : copies) {
      const double move = nearest_move(c.tile, p);
      if (move < best_move || (move == best_move && best != nullptr && c.tile < best->tile)) {
        best_move = move;
        best = &c;
      }
    }
    if (best == nullptr) continue;  // no road near: the weld takes it, or leaves it apart and counts it
    const double z = z_of(*best);
    ++out.terrain_seams;
    for (const Copy& c : copies) {
      Vec3& v = tiles[c.tile].meshes[c.mesh].vertices[c.vertex];
      if (std::abs(z - v.z()) > out.terrain_seams_max_dz_m) {
        out.terrain_seams_max_dz_m = std::abs(z - v.z());
        out.terrain_seams_at = v;
      }
      v.z() = z;
    }
  }
}

}  // namespace

OwnedSurface owned_surface(const RoadModel& model, const Scene& scene, const Aabb2& core) {
  std::unordered_map<int, bool> junction_owned;
  for (const JunctionModel& j : model.junctions) junction_owned[j.id] = owns(core, junction_anchor(model, j));
  const auto owned = [&](int owner) {
    if (owner < 0) {
      const auto it = junction_owned.find(-1 - owner);
      return it != junction_owned.end() && it->second;
    }
    const int index = model.road_index(owner);
    if (index < 0) return false;
    const ModelRoad& road = model.roads[static_cast<std::size_t>(index)];
    if (road.junction == -1) return owns(core, road_anchor(road));
    const auto it = junction_owned.find(road.junction);
    return it != junction_owned.end() && it->second;
  };
  std::unordered_map<int, bool> owned_by_id;
  OwnedSurface out;
  for (const TriangleMesh& mesh : scene.meshes.meshes) {
    const std::vector<int>* owners = owners_of(scene, mesh.name);
    if (owners == nullptr || owners->size() != mesh.triangles.size()) continue;
    std::vector<std::uint8_t> keep(mesh.vertices.size(), 0);
    for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
      const int owner = (*owners)[i];
      auto [it, inserted] = owned_by_id.try_emplace(owner, false);
      if (inserted) it->second = owned(owner);
      if (!it->second) continue;
      for (const std::uint32_t v : mesh.triangles[i]) keep[v] = 1;
    }
    std::vector<Vec3>& vertices = out.vertices[mesh.name];
    // Heights as the tile's files hold them (a float), so that a tile's own vertices keep theirs.
    for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
      if (!keep[v]) continue;
      const Vec3& p = mesh.vertices[v];
      vertices.emplace_back(p.x(), p.y(), static_cast<double>(static_cast<float>(p.z())));
    }
  }
  return out;
}

void write_owned_surface(const std::filesystem::path& path, const OwnedSurface& surface) {
  std::string out(kMagic);
  put<std::uint64_t>(out, surface.vertices.size());
  for (const auto& [name, vertices] : surface.vertices) {
    put<std::uint64_t>(out, name.size());
    out += name;
    put<std::uint64_t>(out, vertices.size());
    for (const Vec3& v : vertices)
      for (const double c : {v.x(), v.y(), v.z()}) put(out, c);
  }
  write_file_atomically(path, out);
}

OwnedSurface read_owned_surface(const std::filesystem::path& path) {
  BinaryReader r(path, "owned surface");
  r.expect(kMagic);
  OwnedSurface surface;
  const auto meshes = r.get<std::uint64_t>();
  for (std::uint64_t m = 0; m < meshes; ++m) {
    std::string name(r.get<std::uint64_t>(), '\0');
    for (char& c : name) c = r.get<char>();
    std::vector<Vec3>& vertices = surface.vertices[name];
    vertices.resize(r.get<std::uint64_t>());
    for (Vec3& v : vertices) {
      const auto x = r.get<double>();
      const auto y = r.get<double>();
      v = Vec3(x, y, r.get<double>());
    }
  }
  r.finish();
  return surface;
}

OwnerHeights take_owner_heights(std::vector<MeshScene>& tiles, const std::vector<Aabb2>& cores,
                                const std::vector<OwnedSurface>& owned, double tolerance_m) {
  OwnerHeights out;
  std::map<std::string, OwnerIndex> indexes;
  {
    std::map<std::string, std::vector<OwnerIndex::Entry>> entries;
    for (std::size_t t = 0; t < owned.size(); ++t)
      for (const auto& [name, vertices] : owned[t].vertices)
        for (const Vec3& v : vertices) entries[name].push_back({v, t});
    for (auto& [name, list] : entries) indexes.emplace(name, OwnerIndex(std::move(list), tolerance_m));
  }
  // Where two owners meet: each place once, from the later owner's side.
  for (const auto& [name, index] : indexes) {
    const std::vector<OwnerIndex::Entry>& e = index.entries();
    for (std::size_t i = 0; i < e.size(); ++i) {
      const std::optional<std::size_t> other = index.nearest(e[i].p.head<2>(), tolerance_m, i);
      if (!other || *other > i || e[*other].tile == e[i].tile) continue;
      const double dz = std::abs(e[*other].p.z() - e[i].p.z());
      if (!(dz > kOwnersApartM)) continue;
      ++out.owners_apart;
      if (dz > out.owners_apart_max_m) {
        out.owners_apart_max_m = dz;
        out.owners_apart_at = e[i].p;
      }
    }
  }
  // Every tile's Road_Road vertices by plan position (exact bits): their height now (the first
  // tile's where two tiles' files hold one).
  std::unordered_map<PlanKey, double, PlanKeyHash> road_heights;
  PavedMoves moved(tiles.size());
  for (std::size_t t = 0; t < tiles.size(); ++t) {
    moved[t].resize(tiles[t].meshes.size());
    for (std::size_t m = 0; m < tiles[t].meshes.size(); ++m) {
      TriangleMesh& mesh = tiles[t].meshes[m];
      const auto index = indexes.find(mesh.name);
      if (index == indexes.end()) continue;
      moved[t][m].assign(mesh.vertices.size(), 0.0F);
      // Per vertex, the owner's height and that less its own; NaN where no owner has it.
      std::vector<double> owner_z(mesh.vertices.size(), std::numeric_limits<double>::quiet_NaN());
      std::vector<double> dz = owner_z;
      for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
        const std::optional<std::size_t> owner =
            index->second.nearest(mesh.vertices[i].head<2>(), tolerance_m);
        if (!owner) continue;
        owner_z[i] = index->second.entries()[*owner].p.z();
        dz[i] = owner_z[i] - mesh.vertices[i].z();
      }
      const std::vector<double> interpolated = interpolate_unmatched(mesh, dz);
      for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
        Vec3& v = mesh.vertices[i];
        ++out.vertices;
        double z = owner_z[i];
        if (std::isnan(z)) {
          if (out.unmatched++ == 0) out.unmatched_at = v;
          if (std::isnan(interpolated[i])) continue;
          ++out.interpolated;
          z = v.z() + interpolated[i];
        }
        if (mesh.name == "Road_Road") road_heights.emplace(plan_key(v), z);
        if (z == v.z()) continue;
        ++out.moved;
        moved[t][m][i] = static_cast<float>(std::abs(z - v.z()));
        if (std::abs(z - v.z()) > out.max_dz_m) {
          out.max_dz_m = std::abs(z - v.z());
          out.at = v;
        }
        v.z() = z;  // the owner's bits: every tile's copy of a shared vertex comes out the same
      }
    }
  }
  // The terrain meets the road's edge with vertices of its own at the road's (a tile's terrain
  // may hold a road edge vertex that only the neighbour's file holds, where its triangles cross
  // the tile line beside a road): those take the road's height now. An opening's top stands the
  // portal's height over the road and stays.
  for (MeshScene& tile : tiles) {
    for (TriangleMesh& mesh : tile.meshes) {
      if (mesh.name != "Terrain") continue;
      for (Vec3& v : mesh.vertices) {
        const auto it = road_heights.find(plan_key(v));
        if (it == road_heights.end() || !(std::abs(it->second - v.z()) <= kTerrainOnRoadM)) continue;
        if (it->second == v.z()) continue;
        v.z() = it->second;
        ++out.terrain_moved;
      }
    }
  }
  join_terrain_borders(tiles, cores, moved, out);
  return out;
}

}  // namespace relief::detail

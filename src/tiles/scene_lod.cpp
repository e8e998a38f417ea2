#include "tiles/scene_lod.h"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <Eigen/Geometry>
#include <Eigen/SVD>
#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <optional>
#include <unordered_map>
#include <unordered_set>

#include "relief/core/errors.h"

namespace relief::detail {
namespace {

// A cell (i, j, k, 0), a pinned vertex (bits of x, y, z, 1), a cell of the finer road grid
// (i, j, k, 2).
using Key = std::array<std::int64_t, 4>;
constexpr double kRoadCellMaxM = 8.0;

Key bits(const Vec3& v) {
  return {std::bit_cast<std::int64_t>(v.x()), std::bit_cast<std::int64_t>(v.y()),
          std::bit_cast<std::int64_t>(v.z()), 1};
}
struct KeyHash {
  std::size_t operator()(const Key& k) const {
    std::size_t h = 0x9e3779b97f4a7c15ULL;
    for (const std::int64_t v : k) h = (h ^ std::hash<std::int64_t>()(v)) * 0x100000001b3ULL;
    return h;
  }
};

struct Cluster {
  Eigen::Matrix3d a = Eigen::Matrix3d::Zero();  // sum of area * n n^T
  Vec3 b = Vec3::Zero();                        // sum of area * d n
  Vec3 sum = Vec3::Zero();                      // of the positions
  std::size_t count = 0;
  Vec3 cell_min = Vec3::Zero();
  double cell_m = 0.0;
  bool pinned = false;
  Vec3 at = Vec3::Zero();  // the representative
};

// The point of the cluster where its quadric is least, near the mean of its vertices where the
// quadric is flat in some direction (singular values below 1e-3 of the largest are dropped),
// clamped to the cell.
Vec3 representative(const Cluster& c) {
  Vec3 mean = c.sum / static_cast<double>(c.count);
  if (c.pinned) return mean;
  Vec3 x = mean;
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(c.a, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Vec3& s = svd.singularValues();
  if (s(0) > 0.0) {
    const Vec3 r = -(c.a * mean + c.b);  // the gradient's negative half at the mean
    Vec3 y = svd.matrixU().transpose() * r;
    for (int i = 0; i < 3; ++i) y(i) = s(i) > 1e-3 * s(0) ? y(i) / s(i) : 0.0;
    x = mean + svd.matrixV() * y;
  }
  return x.cwiseMax(c.cell_min).cwiseMin(c.cell_min + Vec3::Constant(c.cell_m));
}

bool on_border(const Vec3& v, const Aabb2& border) {
  constexpr double kTol = 1e-3;
  if (border.empty()) return false;
  return std::abs(v.x() - border.min.x()) <= kTol || std::abs(v.x() - border.max.x()) <= kTol ||
         std::abs(v.y() - border.min.y()) <= kTol || std::abs(v.y() - border.max.y()) <= kTol;
}

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Triangles = std::vector<K::Triangle_3>;
using Tree =
    CGAL::AABB_tree<CGAL::AABB_traits<K, CGAL::AABB_triangle_primitive<K, Triangles::const_iterator>>>;

K::Point_3 point(const Vec3& v) {
  return {v.x(), v.y(), v.z()};
}

// Squared distances to a tree's triangles, each query starting from the previous answer (the
// queries come in order along the surface).
struct Nearest {
  const Tree& tree;
  std::optional<K::Point_3> hint;
  double operator()(const K::Point_3& p) {
    const K::Point_3 q = hint ? tree.closest_point(p, *hint) : tree.closest_point(p);
    hint = q;
    return CGAL::squared_distance(p, q);
  }
};

Triangles triangles_of(const MeshScene& scene) {
  Triangles triangles;
  for (const TriangleMesh& m : scene.meshes) {
    for (const auto& t : m.triangles) {
      triangles.emplace_back(point(m.vertices[t[0]]), point(m.vertices[t[1]]), point(m.vertices[t[2]]));
    }
  }
  return triangles;
}

// The largest distance from a corner or centroid of a triangle of `full` to the triangles of
// `coarse` (vertices no triangle uses are no part of the surface).
double full_to_coarse(const MeshScene& full, const Triangles& coarse) {
  if (coarse.empty()) return std::numeric_limits<double>::infinity();
  Tree tree(coarse.begin(), coarse.end());
  tree.accelerate_distance_queries();
  double worst2 = 0.0;
  Nearest nearest{tree, std::nullopt};
  for (const TriangleMesh& m : full.meshes) {
    std::vector<std::uint8_t> used(m.vertices.size(), 0);
    for (const auto& t : m.triangles) {
      const Vec3 c = (m.vertices[t[0]] + m.vertices[t[1]] + m.vertices[t[2]]) / 3.0;
      worst2 = std::max(worst2, nearest(point(c)));
      for (const std::uint32_t i : t) used[i] = 1;
    }
    for (std::size_t i = 0; i < used.size(); ++i) {
      if (used[i] != 0) worst2 = std::max(worst2, nearest(point(m.vertices[i])));
    }
  }
  return std::sqrt(worst2);
}

// A bound on the distance from any point of `coarse` to the triangles of `full`: each coarse
// triangle split into k x k similar ones, their edges at most `spacing` long; the distance at
// their corners, plus the farthest any point of a small triangle is from its nearest corner
// (longest edge / sqrt 3: the circumradius of an acute triangle, half the longest edge of
// another). The distance to a surface is 1-Lipschitz.
double coarse_to_full(const Triangles& coarse, const Triangles& full, double spacing) {
  if (full.empty()) return std::numeric_limits<double>::infinity();
  Tree tree(full.begin(), full.end());
  tree.accelerate_distance_queries();
  double worst = 0.0;
  Nearest nearest{tree, std::nullopt};
  for (const K::Triangle_3& t : coarse) {
    const Vec3 a(t[0].x(), t[0].y(), t[0].z()), b(t[1].x(), t[1].y(), t[1].z()),
        c(t[2].x(), t[2].y(), t[2].z());
    const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
    const int k = std::max(1, static_cast<int>(std::ceil(longest / spacing)));
    double worst2 = 0.0;
    for (int i = 0; i <= k; ++i) {
      for (int j = 0; i + j <= k; ++j) {
        const Vec3 p = a + (b - a) * (static_cast<double>(i) / k) + (c - a) * (static_cast<double>(j) / k);
        worst2 = std::max(worst2, nearest(point(p)));
      }
    }
    worst = std::max(worst, std::sqrt(worst2) + longest / k / std::sqrt(3.0));
  }
  return worst;
}

}  // namespace

void scene_bounds(const MeshScene& scene, Vec3& min, Vec3& max) {
  min = Vec3::Constant(std::numeric_limits<double>::infinity());
  max = -min;
  for (const TriangleMesh& m : scene.meshes) {
    for (const Vec3& v : m.vertices) {
      min = min.cwiseMin(v);
      max = max.cwiseMax(v);
    }
  }
}

SceneLod coarsen_scene(const MeshScene& full, double cell_m, const Aabb2& border) {
  if (!(cell_m > 0.0) || !std::isfinite(cell_m)) throw InvalidInput("coarsen_scene: cell size must be > 0");
  const Vec3 origin = border.empty() ? Vec3::Zero() : Vec3(border.min.x(), border.min.y(), 0.0);
  std::unordered_map<Key, std::uint32_t, KeyHash> ids;
  std::vector<Cluster> clusters;
  // The road surfaces' grid: the cell halved until it is at most kRoadCellMaxM, so that a road
  // is not narrower than its cells (they still divide the terrain's cells and the tile). The
  // terrain's vertices on a road's edge (the border of its hole there, the same bits) take the
  // road's grid too, so that road and terrain still meet.
  double road_cell_m = cell_m;
  while (road_cell_m > kRoadCellMaxM) road_cell_m /= 2.0;
  std::unordered_set<Key, KeyHash> road_points;
  if (road_cell_m < cell_m) {
    for (const TriangleMesh& m : full.meshes) {
      if (m.kind == SurfaceKind::marking || m.kind == SurfaceKind::terrain) continue;
      for (const Vec3& v : m.vertices) road_points.insert(bits(v));
    }
  }
  // The cluster of every vertex, per mesh (markings have none).
  std::vector<std::vector<std::uint32_t>> of(full.meshes.size());
  SceneLod lod;
  lod.scene.frame = full.frame;
  lod.scene.metadata = full.metadata;
  for (std::size_t mi = 0; mi < full.meshes.size(); ++mi) {
    const TriangleMesh& m = full.meshes[mi];
    lod.full_triangles += m.triangles.size();
    if (m.kind == SurfaceKind::marking) continue;
    of[mi].resize(m.vertices.size());
    for (std::size_t vi = 0; vi < m.vertices.size(); ++vi) {
      const Vec3& v = m.vertices[vi];
      const bool pinned = on_border(v, border);
      const bool road_grid =
          road_cell_m < cell_m && (m.kind != SurfaceKind::terrain || road_points.contains(bits(v)));
      const double size = road_grid ? road_cell_m : cell_m;
      const Vec3 cell = ((v - origin) / size).array().floor();
      const Key key = pinned ? bits(v)
                             : Key{static_cast<std::int64_t>(cell.x()), static_cast<std::int64_t>(cell.y()),
                                   static_cast<std::int64_t>(cell.z()), road_grid ? 2 : 0};
      const auto [it, added] = ids.try_emplace(key, static_cast<std::uint32_t>(clusters.size()));
      if (added) {
        clusters.emplace_back();
        clusters.back().pinned = pinned;
        clusters.back().cell_min = origin + cell * size;
        clusters.back().cell_m = size;
      }
      Cluster& c = clusters[it->second];
      c.sum += v;
      ++c.count;
      of[mi][vi] = it->second;
    }
    for (const auto& t : m.triangles) {
      const Vec3& p = m.vertices[t[0]];
      const Vec3 cross = (m.vertices[t[1]] - p).cross(m.vertices[t[2]] - p);
      const double twice_area = cross.norm();
      if (!(twice_area > 0.0)) continue;
      const Vec3 n = cross / twice_area;
      const double d = -n.dot(p);
      const double w = 0.5 * twice_area;
      for (const std::uint32_t corner : t) {
        Cluster& c = clusters[of[mi][corner]];
        c.a += w * n * n.transpose();
        c.b += w * d * n;
      }
    }
  }
  for (Cluster& c : clusters) c.at = representative(c);

  for (std::size_t mi = 0; mi < full.meshes.size(); ++mi) {
    const TriangleMesh& m = full.meshes[mi];
    if (m.kind == SurfaceKind::marking) continue;
    TriangleMesh out;
    out.name = m.name;
    out.kind = m.kind;
    std::unordered_map<std::uint32_t, std::uint32_t> index;  // cluster -> vertex of `out`
    std::unordered_set<Key, KeyHash> seen;                   // sorted cluster triples
    for (std::size_t vi = 0; vi < m.vertices.size(); ++vi) {
      lod.max_vertex_shift_m =
          std::max(lod.max_vertex_shift_m, (m.vertices[vi] - clusters[of[mi][vi]].at).norm());
    }
    for (const auto& t : m.triangles) {
      std::array<std::uint32_t, 3> c{of[mi][t[0]], of[mi][t[1]], of[mi][t[2]]};
      if (c[0] == c[1] || c[1] == c[2] || c[0] == c[2]) continue;
      std::array<std::uint32_t, 3> sorted = c;
      std::sort(sorted.begin(), sorted.end());
      if (!seen.insert(Key{sorted[0], sorted[1], sorted[2], 0}).second) continue;
      const Vec3& a = clusters[c[0]].at;
      if ((clusters[c[1]].at - a).cross(clusters[c[2]].at - a).norm() < 2e-6) continue;  // < 1 mm^2
      std::array<std::uint32_t, 3> tri{};
      for (int k = 0; k < 3; ++k) {
        const auto [it, added] = index.try_emplace(c[k], static_cast<std::uint32_t>(out.vertices.size()));
        if (added) out.vertices.push_back(clusters[c[k]].at);
        tri[k] = it->second;
      }
      out.triangles.push_back(tri);
    }
    if (out.empty()) continue;
    lod.coarse_triangles += out.triangles.size();
    lod.scene.meshes.push_back(std::move(out));
  }
  if (lod.scene.meshes.empty()) {
    // Nothing survived (a tile of a few triangles): the full scene, markings left out when
    // something else remains.
    lod.max_vertex_shift_m = 0.0;
    lod.coarse_triangles = 0;
    for (const TriangleMesh& m : full.meshes) {
      if (m.kind != SurfaceKind::marking && !m.empty()) lod.scene.meshes.push_back(m);
    }
    if (lod.scene.meshes.empty()) lod.scene.meshes = full.meshes;
    for (TriangleMesh& m : lod.scene.meshes) {
      m.normals.clear();
      m.uvs.clear();
      lod.coarse_triangles += m.triangles.size();
    }
  }
  const Triangles coarse = triangles_of(lod.scene), whole = triangles_of(full);
  if (!whole.empty()) {
    lod.max_full_to_coarse_m = full_to_coarse(full, coarse);
    lod.coarse_to_full_m = coarse_to_full(coarse, whole, cell_m / 4.0);
  }
  return lod;
}

}  // namespace relief::detail

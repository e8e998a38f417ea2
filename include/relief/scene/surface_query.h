#pragma once
// "Which surface is under (x, y)?": the height of the road surface or the ground at a plan
// point, for placing vehicles (the co-simulation) and for sensors. A uniform 2-D grid over the
// plan lists each triangle in every cell its plan bounding box touches; a query tests the
// triangles of one cell. Heights are the triangle's plane at (x, y) (barycentric), so a scene
// whose meshes lie on a plane answers that plane's height to rounding.
//
// Where surfaces lie over each other (a bridge deck over a road, a road over a tunnel), the
// rule is the caller's choice, and stated in the name:
// - highest(x, y): the top surface seen from above (the deck);
// - nearest(x, y, z_m): the surface whose height is closest to z_m, the higher on a tie (a
//   vehicle passes its current height: under the bridge it gets the road, on the deck the deck);
// - all(x, y): every surface, highest first.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "relief/geometry/triangle_mesh.h"
#include "relief/geometry/types.h"

namespace relief {

struct SurfaceQueryOptions {
  double cell_size_m = 4.0;  ///< side of a grid cell (> 0; grown so the grid holds at most 2^24 cells)
  /// Index Road_Marking too (SurfaceKind::marking). Off by default: markings float a few
  /// millimetres over the road and would be the highest surface on every painted line.
  bool markings = false;
};

/// One surface at a plan point.
struct SurfaceHit {
  double z_m = 0.0;          ///< height of the surface at the point (local frame)
  std::size_t mesh = 0;      ///< index into MeshScene::meshes
  std::size_t triangle = 0;  ///< index into that mesh's triangles
  SurfaceKind kind = SurfaceKind::road;
};

/// The surfaces of a MeshScene (e.g. Scene::meshes) under plan points. Keeps a reference to
/// `scene`: it must outlive the query and not change. A point on an edge or a vertex counts as
/// inside (within 1e-9 of the triangle's barycentric range); triangles vertical in plan are
/// left out. Queries only read: safe from several threads.
class SurfaceQuery {
 public:
  /// Throws InvalidInput when options.cell_size_m is not > 0.
  explicit SurfaceQuery(const MeshScene& scene, const SurfaceQueryOptions& options = {});

  /// Every surface at (x, y), highest first; a triangle's neighbour in the same mesh at the same
  /// height (within 1 mm: the point on their shared edge) is listed once. Empty: no surface.
  [[nodiscard]] std::vector<SurfaceHit> all(double x, double y) const;
  /// The top surface at (x, y), nothing where there is none.
  [[nodiscard]] std::optional<SurfaceHit> highest(double x, double y) const;
  /// The surface at (x, y) whose height is closest to z_m (the higher of two as close).
  [[nodiscard]] std::optional<SurfaceHit> nearest(double x, double y, double z_m) const;

  [[nodiscard]] std::size_t triangles_indexed() const { return indexed_; }

 private:
  struct Entry {
    std::uint32_t mesh, triangle;
  };
  [[nodiscard]] std::optional<double> height_in(const Entry& e, double x, double y) const;

  const MeshScene& scene_;
  Aabb2 bounds_;
  double cell_m_ = 1.0;
  std::size_t nx_ = 0, ny_ = 0, indexed_ = 0;
  std::vector<std::uint32_t> cell_start_;  ///< nx_ * ny_ + 1 offsets into entries_
  std::vector<Entry> entries_;
};

}  // namespace relief

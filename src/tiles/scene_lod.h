#pragma once
// A coarse level of detail of a scene tile, for the 3D Tiles hierarchy (tileset_writer.h): the
// tile's meshes decimated by vertex clustering with quadric representatives (Lindstrom 2000,
// "Out-of-core simplification of large polygonal models"): every vertex falls in a cell of a
// cubic grid, the cell's vertices become one, placed where the sum of its triangles' plane
// quadrics is least (clamped to the cell), and triangles whose corners fall in fewer than three
// cells disappear. Linear in the input (hash maps), indifferent to non-manifold input. One grid
// for all meshes of the scene, so that a road's edge and the terrain beside it meet in the same
// cells at the same points. Markings are left out (they lie on the road, a centimetre above it).
// Vertices on the tile's core border keep their exact position (their own cell), so that two
// neighbouring coarse tiles still share their seam's vertices.
//
// The error is measured, both ways:
//   coarse to full: every coarse triangle is the image of a full triangle whose corners moved
//     by at most max_vertex_shift_m; a point of it at given barycentric coordinates is that far
//     at most from the full triangle's point at the same coordinates (a bound, not a sample);
//   full to coarse: the largest distance from a full vertex or triangle centroid (markings'
//     included) to the coarse surface (CGAL AABB tree; a sample, as Hausdorff-distance tools do).
// error_m() is the larger: the tile's geometricError in tileset.json.

#include "relief/geometry/triangle_mesh.h"
#include "relief/geometry/types.h"

namespace relief::detail {

struct SceneLod {
  MeshScene scene;  ///< the coarse meshes (no normals or UVs), same frame and metadata
  std::size_t full_triangles = 0, coarse_triangles = 0;
  double max_vertex_shift_m = 0.0;    ///< bound on the distance coarse -> full
  double max_full_to_coarse_m = 0.0;  ///< sampled distance full -> coarse
  [[nodiscard]] double error_m() const {
    return max_vertex_shift_m > max_full_to_coarse_m ? max_vertex_shift_m : max_full_to_coarse_m;
  }
};

/// The coarse scene of `full`, clustered in cubes of `cell_m` (> 0, else InvalidInput) anchored
/// at border.min (so that cell faces fall on the border when cell_m divides the tile's size).
/// Vertices within 1 mm of an edge of `border` (when it is not empty) are not moved. When no
/// triangle survives, the coarse scene is the full one without markings (else all of it).
[[nodiscard]] SceneLod coarsen_scene(const MeshScene& full, double cell_m, const Aabb2& border);

/// The box of every vertex of `scene` (min > max when it has none).
void scene_bounds(const MeshScene& scene, Vec3& min, Vec3& max);

}  // namespace relief::detail

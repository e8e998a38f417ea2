#pragma once
// A coarse level of detail of a scene tile, for the 3D Tiles hierarchy (tileset_writer.h): the
// tile's meshes decimated by vertex clustering with quadric representatives (Lindstrom 2000,
// "Out-of-core simplification of large polygonal models"): every vertex falls in a cell of a
// cubic grid, the cell's vertices become one, placed where the sum of its triangles' plane
// quadrics is least (clamped to the cell), and triangles whose corners fall in fewer than three
// cells disappear. Linear in the input (hash maps), indifferent to non-manifold input. The road
// surfaces (every mesh but the terrain) take a finer grid when the cell is over 8 m (the cell
// halved until it is at most 8 m), so that a road is not narrower than its cells and stays; the
// terrain's vertices on a road's edge (the border of the terrain's hole there, the same bits)
// take the road's grid too, so that road and terrain meet at the same points. Markings are left
// out (they lie on the road, a centimetre above it).
// Vertices on the tile's core border keep their exact position (their own cell), so that two
// neighbouring coarse tiles still share their seam's vertices.
//
// The error is measured both ways (CGAL AABB trees over each surface), as Hausdorff-distance
// tools do:
//   coarse to full: the distance to the full surface of points on every coarse triangle, a
//     triangular grid of them at most cell/4 apart, plus the largest distance of a point of a
//     coarse triangle from its grid's nearest point (at most a grid edge / sqrt 3); the distance
//     to a surface moving by at most as much as the point, this is a bound;
//   full to coarse: the largest distance from a full triangle's corner or centroid (markings'
//     included) to the coarse surface (a sample: the full triangles are the small ones).
// error_m() is the larger: the tile's geometricError in tileset.json. How far vertices moved to
// their cell's point (max_vertex_shift_m) is larger still (most of it along the surface) and
// bounds the coarse-to-full distance too (a coarse triangle's point at given barycentric
// coordinates is at most that far from the full triangle's point at the same coordinates).

#include "relief/geometry/triangle_mesh.h"
#include "relief/geometry/types.h"

namespace relief::detail {

struct SceneLod {
  MeshScene scene;  ///< the coarse meshes (no normals or UVs), same frame and metadata
  std::size_t full_triangles = 0, coarse_triangles = 0;
  double max_vertex_shift_m = 0.0;    ///< vertex to its cell's point (a loose bound coarse -> full)
  double coarse_to_full_m = 0.0;      ///< bound on the distance coarse -> full (see above)
  double max_full_to_coarse_m = 0.0;  ///< sampled distance full -> coarse
  [[nodiscard]] double error_m() const {
    return coarse_to_full_m > max_full_to_coarse_m ? coarse_to_full_m : max_full_to_coarse_m;
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

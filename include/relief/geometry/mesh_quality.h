#pragma once
// Mesh-quality figures of a TriangleMesh: topology (components, boundary edges and holes,
// non-manifold edges and vertices, orientation consistency), self-intersections (CGAL Polygon
// Mesh Processing, exact predicates), degenerate and sliver triangles, and the gap along the
// seam between two meshes. CGAL stays in src/geometry/.

#include <cstddef>
#include <string>
#include <vector>

#include "relief/geometry/triangle_mesh.h"

namespace relief {

struct MeshQualityOptions {
  double sliver_min_angle_deg = 5.0;    ///< a triangle with a smaller angle is a sliver
  double sliver_max_aspect_ratio = 20;  ///< ... or with a larger longest-edge / shortest-altitude
  double degenerate_area_m2 = 1e-8;     ///< a triangle with area <= this is degenerate
  bool self_intersections = true;       ///< the costly test; off for a quick look
};

struct MeshQuality {
  std::string name;
  std::size_t vertices = 0;
  std::size_t triangles = 0;
  std::size_t unused_vertices = 0;
  std::size_t components = 0;      ///< edge-connected triangle sets
  std::size_t boundary_edges = 0;  ///< edges with exactly one triangle
  std::size_t boundary_loops = 0;
  std::size_t holes = 0;  ///< boundary loops that are not the outer loop of their component
  std::size_t non_manifold_edges = 0;     ///< edges with three or more triangles
  std::size_t non_manifold_vertices = 0;  ///< vertices whose triangle fan is not one disc/half-disc
  std::size_t inconsistent_orientation_edges = 0;  ///< interior edges both triangles use the same way
  std::size_t upside_down_triangles = 0;           ///< normal with z < 0 (for 2.5-D surfaces)
  std::size_t self_intersecting_pairs = 0;         ///< triangle pairs that intersect other than at shared vertices/edges
  std::size_t degenerate_triangles = 0;
  std::size_t sliver_triangles = 0;
  double min_angle_deg = 0.0;
  double max_aspect_ratio = 0.0;
  double area_m2 = 0.0;
  Aabb2 bounds;
  double min_z = 0.0, max_z = 0.0;
};

/// Figures of one mesh. Vertices are taken by index (no welding of coincident vertices: a mesh
/// whose pieces merely touch counts as separate components with boundaries).
[[nodiscard]] MeshQuality analyse_mesh(const TriangleMesh& mesh, const MeshQualityOptions& options = {});

struct SeamGap {
  std::size_t vertices_checked = 0;  ///< boundary vertices of `a` that have a boundary of `b` within reach
  double max_gap_m = 0.0;            ///< largest 3D distance from such a vertex to b's boundary
};

/// Gap along the seam between two meshes: for every boundary vertex of `a` whose horizontal
/// distance to a boundary edge of `b` is at most `reach_m`, the 3D distance to the nearest
/// boundary edge of `b`. Shared positions give 0.
[[nodiscard]] SeamGap seam_gap(const TriangleMesh& a, const TriangleMesh& b, double reach_m = 0.5);

}  // namespace relief

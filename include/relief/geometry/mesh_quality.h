#pragma once
// Mesh-quality figures of a TriangleMesh: topology (components, boundary edges and holes,
// non-manifold edges and vertices, orientation consistency), self-intersections (CGAL Polygon
// Mesh Processing, exact predicates), degenerate and sliver triangles, and the gap along the
// seam between two meshes. CGAL stays in src/geometry/.

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "relief/geometry/triangle_mesh.h"

namespace relief {

inline constexpr std::size_t kMaxSelfIntersectionSites = 20;

struct MeshQualityOptions {
  double sliver_min_angle_deg = 5.0;    ///< a triangle with a smaller angle is a sliver
  double sliver_max_aspect_ratio = 20;  ///< ... or with a larger longest-edge / shortest-altitude
  double degenerate_area_m2 = 1e-8;     ///< a triangle with area <= this is degenerate
  bool self_intersections = true;       ///< the costly test; off for a quick look
  /// When not empty (one flag per triangle): only pairs of a flagged and an unflagged triangle
  /// are tested, for a mesh joined from two whose own pairs are known (roads + terrain).
  std::vector<std::uint8_t> intersections_across;
};

/// Figures of one mesh. Edges and vertices are identified by index. Degenerate triangles
/// (area <= MeshQualityOptions::degenerate_area_m2, or a vertex index repeated) are counted
/// once, as degenerate: they are neither slivers nor upside down, and they do not enter
/// min_angle_deg / max_aspect_ratio.
struct MeshQuality {
  std::string name;
  std::size_t vertices = 0;
  std::size_t triangles = 0;
  std::size_t unused_vertices = 0;
  std::size_t components = 0;      ///< edge-connected triangle sets
  std::size_t boundary_edges = 0;  ///< edges with exactly one triangle
  std::size_t boundary_loops = 0;  ///< closed loops of boundary edges (see boundary_loops())
  /// Boundary loops that are not the outer loop of their component. The outer loop of a
  /// component is its loop of largest vector area |sum p_i x p_i+1| / 2 (the projected area
  /// for a 2.5-D surface), ties broken by length.
  std::size_t holes = 0;
  /// Where the first kMaxSelfIntersectionSites holes are (the mean of a loop's vertices) and
  /// how long their loops are, in the order the loops are found.
  std::vector<Vec3> hole_sites;
  std::vector<double> hole_lengths_m;
  std::size_t non_manifold_edges = 0;  ///< edges with three or more triangles
  /// Vertices whose triangles, joined through the edges with exactly two triangles, form more
  /// than one fan (a vertex where two sheets touch, and both ends of a non-manifold edge).
  std::size_t non_manifold_vertices = 0;
  std::size_t inconsistent_orientation_edges = 0;  ///< interior edges both triangles use the same way
  std::size_t upside_down_triangles = 0;           ///< normal with z < 0 (for 2.5-D surfaces)
  /// Triangle pairs that intersect other than at shared vertices/edges (exact predicates).
  /// Vertices are compared by index: two triangles that touch at distinct vertices with equal
  /// positions intersect. Triangles with collinear corners are left out (they are degenerate).
  /// With MeshQualityOptions::intersections_across, only pairs across the two sets.
  std::size_t self_intersecting_pairs = 0;
  /// Where the first kMaxSelfIntersectionSites pairs are (the midpoint of the two triangles'
  /// centroids), to find them in a viewer.
  std::vector<Vec3> self_intersection_sites;
  /// The triangles of the same pairs (indices into the mesh's triangles, smaller first).
  std::vector<std::array<std::size_t, 2>> self_intersection_triangles;
  bool self_intersections_checked = false;  ///< false when MeshQualityOptions::self_intersections is off
  std::size_t degenerate_triangles = 0;
  std::size_t sliver_triangles = 0;
  double min_angle_deg = 0.0;     ///< smallest angle of the non-degenerate triangles (0 if none)
  double max_aspect_ratio = 0.0;  ///< largest longest-edge / shortest-altitude of the same
  double area_m2 = 0.0;
  Aabb2 bounds;                     ///< of the vertices the triangles use (empty if none)
  double min_z = 0.0, max_z = 0.0;  ///< of the same vertices (0 if none)
};

/// Figures of one mesh. Vertices are taken by index (no welding of coincident vertices: a mesh
/// whose pieces merely touch counts as separate components with boundaries). Indices must be
/// below mesh.vertices.size() (else InvalidInput). The self-intersection test takes about
/// a few seconds per million triangles.
[[nodiscard]] MeshQuality analyse_mesh(const TriangleMesh& mesh, const MeshQualityOptions& options = {});

/// The edges used by exactly one triangle, each in its triangle's direction. Indices must be
/// valid (not checked).
[[nodiscard]] std::vector<std::pair<std::uint32_t, std::uint32_t>> boundary_edges(const TriangleMesh& mesh);

struct SeamGap {
  std::size_t vertices_checked = 0;  ///< boundary vertices of `a` that have a boundary of `b` within reach
  double max_gap_m = 0.0;            ///< largest 3D distance from such a vertex to b's boundary
};

/// Gap along the seam between two meshes: for every boundary vertex of `a` whose 3D distance to
/// a boundary edge of `b` is at most `reach_m`, that distance (to the nearest such edge). A
/// reach in 3D keeps a bridge deck above another surface's edge from counting as a seam; a gap
/// wider than the reach is not a seam either and shows as a hole instead. Shared positions give 0. reach_m <
/// 0 or not finite: InvalidInput.
[[nodiscard]] SeamGap seam_gap(const TriangleMesh& a, const TriangleMesh& b, double reach_m = 0.5);

}  // namespace relief

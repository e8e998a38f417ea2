#pragma once
// Private to the roads module: the paved area of one junction as a CGAL constrained Delaunay
// triangulation of its outline (road end cross-sections joined by the turns' kerb lines).

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "relief/roads/junction_height.h"
#include "relief/scene/road_mesh.h"
#include "scene/mesh_builder.h"

namespace relief::detail {

/// One road end at a junction: the road-mesh vertices of its end cross-section ordered from the
/// right corner to the left corner looking out of the junction along the road.
struct JunctionEnd {
  int road_index = -1;
  bool at_start = false;                ///< the road's start (s = 0) touches the junction
  std::vector<std::uint32_t> vertices;  ///< the end's edge, right to left looking out of the junction
  /// The road mesh's outer edges looking out of the junction, each from its corner outward.
  std::vector<std::uint32_t> left_edge, right_edge;
};

/// A polyline closing the outline between two consecutive road ends (a kerb line), from
/// the left corner of `from` to the right corner of `to` (indices into the ends).
struct OutlineGap {
  std::vector<Vec3> points;  ///< interior points only; empty for a straight segment
  /// Per point, the mesh vertex it is (a road's edge vertex), or kNoVertex for a new one; empty:
  /// every point is new.
  std::vector<std::uint32_t> vertices;
};

/// What build_junction_surface made of a junction.
struct JunctionSurfaceResult {
  std::string problem;  ///< empty: the surface is built; else what is wrong (nothing is added then)
  /// Road ends (road index, at its start) the surface leaves out: each lay on another end's
  /// road, or across the others where no outline joining all the ends was simple.
  std::vector<std::pair<int, bool>> left_out;
};

/// Orders the ends counter-clockwise (junction_end_order: by a point ahead along each road, the
/// order netconvert's node outlines take too), closes the gap
/// between consecutive ends with the outermost lane border of a connecting road (of
/// `connecting_roads`, indices into model.roads) that joins those two road ends, else a straight
/// segment, and triangulates the outline (triangulate_junction). An end lying on another end's
/// road (its edge's midpoint behind that end's edge, by at most the edge's width or 5 m) is left
/// out first, where the others make a simple outline. When the outline is not simple (a kerb
/// line cutting across a neighbouring road end at a sharp fork), one gap straight; then all
/// straight; then the ends in another order (simple_outline_order); and last, where one end lies
/// across the others, the outline of all the ends but one: first one whose edge lies behind
/// another end's, then the narrowest.
[[nodiscard]] JunctionSurfaceResult build_junction_surface(const RoadModel& model,
                                                           const JunctionModel& junction,
                                                           std::vector<JunctionEnd> ends,
                                                           const std::vector<int>& connecting_roads,
                                                           const RoadMeshOptions& options, MeshBuilder& mesh);

/// The straight side of an outline from a's left corner P to b's right corner Q, where a road
/// leaving at a or b runs along it at a few degrees (a joined junction's long side, or one with
/// no connecting road between those ends): that road's edge can bow across the side, and a patch
/// up to the side would lie over its pavement at another height. The road mesh's own edge
/// vertices (a.left_edge, b.right_edge) that lie inside the junction across PQ, in order along
/// it; each edge is followed from its corner until it leaves PQ's extent or turns away from it
/// by more than 1 m. Empty where no edge comes inside (the usual case).
[[nodiscard]] OutlineGap along_road_edges(const JunctionEnd& a, const JunctionEnd& b,
                                          const std::vector<Vec3>& vertices);

/// Triangulates the polygon made of the ends (in counter-clockwise order around the junction)
/// and the gaps (gaps[k] between ends[k] and ends[k + 1], cyclically) with the ends' edges as
/// constraints, and appends the triangles (owner -1 - junction_id) and the gap points to `mesh`.
/// The `interior` points that lie inside the outline, at least 0.3 m from it, are vertices of
/// the triangulation too (Steiner points carrying the surface's height inside the junction).
/// With a `surface`, the outline's straight sides and the pieces of a gap that end at a new
/// point get points on it every 2 m (a side 13 m long across a junction on a grade change
/// otherwise cut 0.2 m under the connecting road along it).
/// Returns an empty string on success, else what is wrong (nothing is added then).
[[nodiscard]] std::string triangulate_junction(const std::vector<JunctionEnd>& ends,
                                               const std::vector<OutlineGap>& gaps, int junction_id,
                                               MeshBuilder& mesh, const std::vector<Vec3>& interior = {},
                                               const JunctionHeight* surface = nullptr);

/// Points of the junction's height surface on a square grid over the outline's bounding box
/// (`outline`: the ends' vertices and the gaps' points), every 2 m (farther apart where that
/// would give over 4000), except those within 1 m of a `lane_points` point: between its
/// connecting roads the patch follows the surface, not a plane across tens of metres. Where a
/// lane point lies off the surface (its connecting road left it where it was too steep along the
/// road), the grid points within 4 m take its departure, fading with distance (an inverse-square
/// blend with the surface's own weight at 4 m): the patch does not stand a step off the road.
[[nodiscard]] std::vector<Vec3> surface_grid(const std::vector<Vec2>& outline,
                                             const std::vector<Vec3>& lane_points,
                                             const JunctionHeight& surface);

/// Points of the junction's surface inside it: every lane centre of its connecting roads
/// (`connecting_roads`, indices into model.roads) every 2 m, their first and last metre left
/// out; points of different lanes within 1 m of each other are merged into their mean (where
/// two turns cross, the surface takes the mean of their heights).
[[nodiscard]] std::vector<Vec3> junction_interior(const RoadModel& model,
                                                  const std::vector<int>& connecting_roads);

}  // namespace relief::detail

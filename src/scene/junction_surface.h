#pragma once
// Private to the roads module: the paved area of one junction as a CGAL constrained Delaunay
// triangulation of its outline (road end cross-sections joined by the turns' kerb lines).

#include <cstdint>
#include <string>
#include <vector>

#include "relief/scene/road_mesh.h"
#include "scene/mesh_builder.h"

namespace relief::detail {

/// One road end at a junction: the road-mesh vertices of its end cross-section ordered from the
/// right corner to the left corner looking out of the junction along the road.
struct JunctionEnd {
  int road_index = -1;
  bool at_start = false;  ///< the road's start (s = 0) touches the junction
  std::vector<std::uint32_t> vertices;
};

/// A polyline closing the outline between two consecutive road ends (a kerb line), from
/// the left corner of `from` to the right corner of `to` (indices into the ends).
struct OutlineGap {
  std::vector<Vec3> points;  ///< interior points only; empty for a straight segment
};

/// Orders the ends counter-clockwise (junction_end_order: by a point ahead along each road, the
/// order netconvert's node outlines take too), closes the gap
/// between consecutive ends with the outermost lane border of a connecting road (of
/// `connecting_roads`, indices into model.roads) that joins those two road ends, else a straight
/// segment, and triangulates the outline (triangulate_junction); when that outline is not simple
/// (a kerb line cutting across a neighbouring road end at a sharp fork), straight gaps instead.
/// Returns an empty string on success, else what is wrong (with the kerb lines).
[[nodiscard]] std::string build_junction_surface(const RoadModel& model, const JunctionModel& junction,
                                                 std::vector<JunctionEnd> ends,
                                                 const std::vector<int>& connecting_roads,
                                                 const RoadMeshOptions& options, MeshBuilder& mesh);

/// Triangulates the polygon made of the ends (in counter-clockwise order around the junction)
/// and the gaps (gaps[k] between ends[k] and ends[k + 1], cyclically) with the ends' edges as
/// constraints, and appends the triangles (owner -1 - junction_id) and the gap points to `mesh`.
/// Returns an empty string on success, else what is wrong (nothing is added then).
[[nodiscard]] std::string triangulate_junction(const std::vector<JunctionEnd>& ends,
                                               const std::vector<OutlineGap>& gaps, int junction_id,
                                               MeshBuilder& mesh);

}  // namespace relief::detail

#pragma once
// Private to the roads module: lofting of one road's lanes along its 3D reference line, and the
// adaptive sampling along s that it shares with the junction kerbs (road_mesh.cpp).

#include <cstdint>
#include <vector>

#include "relief/scene/road_mesh.h"
#include "scene/mesh_builder.h"

namespace relief::detail {

/// Vertices of one end cross-section of a lofted road, by decreasing t (left to right looking
/// along +s), restricted to the contiguous range of lanes that go to that mesh.
struct RoadEnd {
  std::vector<std::uint32_t> road_vertices;      ///< in the road mesh
  std::vector<std::uint32_t> sidewalk_vertices;  ///< in the sidewalk mesh
  std::vector<std::uint32_t> marking_vertices;   ///< in the marking mesh: the marks' end edges
};

struct LoftedRoad {
  RoadEnd start, end;
  /// The road mesh's two outer edges, one vertex per station in +s order: the +t edge (left
  /// looking along +s) and the -t edge. A junction patch whose straight side runs along a road
  /// follows them (build_junction_surface).
  std::vector<std::uint32_t> left_edge, right_edge;
  std::size_t stations = 0;
  /// Largest distance between the mesh and S(road, s, t) at the middle of the steps: the
  /// midpoints of the border edges against S at the mid-station, and the twist of each quad
  /// (its diagonals' midpoints off the quad's plane).
  double max_deviation_m = 0.0;
};

/// Lofts every lane of `road` (sidewalk lanes into `sidewalk`, all others into `road_mesh`, marks
/// into `marking` when not null). Stations: the section starts, the plan-view record boundaries,
/// at most options.max_spacing_m apart, bisected until the chord error of every border and
/// the twist of every quad are within options.tolerance_m. Throws InvalidInput for a road without
/// plan view or lanes.
[[nodiscard]] LoftedRoad loft_road(const ModelRoad& road, const RoadMeshOptions& options,
                                   MeshBuilder& road_mesh, MeshBuilder& sidewalk, MeshBuilder* marking);

/// Points of the outer border of lane `lane_id` of `road` (0: the centre lane) from s = 0 to the
/// end, sampled like the lanes. Throws InvalidInput when a lane section lacks that lane.
[[nodiscard]] std::vector<Vec3> sample_lane_border(const ModelRoad& road, int lane_id,
                                                   const RoadMeshOptions& options);

}  // namespace relief::detail

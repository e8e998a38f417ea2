#pragma once
// The paved surface of a RoadModel as triangle meshes: every road's lanes lofted along its 3D
// reference line (sampled to an explicit tolerance), every junction's area triangulated with a
// CGAL constrained Delaunay triangulation whose constraints are the incoming road ends, so
// roads and junctions share their seam vertices and the paved area is one surface.

#include <cstdint>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "relief/core/diagnostics.h"
#include "relief/geometry/triangle_mesh.h"
#include "relief/roads/road_model.h"

namespace relief {

struct RoadMeshOptions {
  /// Largest distance between the mesh and the OpenDRIVE surface S(road, s, t) (chord error
  /// of the sampling along s, in plan and in height).
  double tolerance_m = 0.02;
  double max_spacing_m = 10.0;    ///< longest step along a road even where it is flat and straight
  bool markings = true;           ///< Road_Marking strips from the lanes' road marks
  double marking_lift_m = 0.005;  ///< markings float this far above the road (no z-fighting)
};

struct RoadMeshes {
  TriangleMesh road;      ///< "Road_Road": lanes of every road + junction areas, one welded surface
  TriangleMesh marking;   ///< "Road_Marking"
  TriangleMesh sidewalk;  ///< "Road_Sidewalk" (lanes of type sidewalk; empty if none)
  /// Per triangle of `road`: the OpenDRIVE road id it belongs to, or -1 - junction id.
  std::vector<int> road_triangle_owner;
  std::vector<int> marking_triangle_owner;   ///< the same per triangle of `marking`
  std::vector<int> sidewalk_triangle_owner;  ///< the same per triangle of `sidewalk`
  std::size_t junctions_meshed = 0;
  std::size_t junctions_failed = 0;   ///< reported as "mesh.junction_failed"; their area is left open
  std::string first_failed_junction;  ///< "junction J at (x, y, z)" of the first failed; empty if none
  /// Every failed junction with a place: its id and the mean of its road ends' edge vertices.
  std::vector<std::pair<int, Vec3>> failed_junctions;
  double max_surface_deviation_m = 0.0;  ///< largest measured mesh-to-S(road, s, t) distance on roads
};

/// Builds the meshes. Data problems (a junction whose outline cannot be triangulated, a road
/// too short to loft) go to `diagnostics`; throws InvalidInput only for options out of range.
[[nodiscard]] RoadMeshes build_road_meshes(const RoadModel& model, const RoadMeshOptions& options,
                                           Diagnostics& diagnostics);

}  // namespace relief

#pragma once
// OpenDRIVE-like roads built in code for the scene tests: straight lines with constant-width
// lanes and a linear elevation, whose meshes have analytic areas and vertex positions.

#include "relief/geometry/triangle_mesh.h"
#include "relief/roads/road_model.h"
#include "support/plan_records.h"

namespace relief::test {

/// Lane `id` of constant `width_m` with road mark `mark` on its outer border.
[[nodiscard]] LaneModel constant_lane(int id, double width_m, RoadMark::Type mark = RoadMark::Type::none);

/// A straight road along `heading` from `start`, z = z0 + grade * s, no lane offset, one lane
/// section with lane 1 of 3 m and lane -1 of 3.5 m.
[[nodiscard]] ModelRoad straight_road(int id, const Vec2& start, double heading, double length_m, double z0,
                                      double grade);

/// Sum of the triangles' 3D areas (m2).
[[nodiscard]] double mesh_area(const TriangleMesh& mesh);

/// Whether every triangle is counter-clockwise seen from above (its normal has z > 0).
[[nodiscard]] bool all_facing_up(const TriangleMesh& mesh);

}  // namespace relief::test

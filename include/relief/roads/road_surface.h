#pragma once
// Evaluation of the road surface of a RoadModel: S(road, s, t) -> (x, y, z), lane borders,
// lane centres. One implementation for every consumer (OpenDRIVE checks, SUMO lanes, meshes).

#include "relief/roads/road_model.h"

namespace relief {

/// Lane section of `road` that contains s (the last one starting at or before s; the first
/// for s before it). Throws InvalidInput when the road has no lane sections.
[[nodiscard]] const LaneSection& section_at(const ModelRoad& road, double s);

/// t of the outer border of lane `lane_id` at s (t of the centre lane for lane 0), including
/// the lane offset. Throws InvalidInput for a lane id the section does not have.
[[nodiscard]] double lane_border_t(const ModelRoad& road, double s, int lane_id);

/// t of the middle of lane `lane_id`. Throws InvalidInput for lane 0 or an unknown lane.
[[nodiscard]] double lane_centre_t(const ModelRoad& road, double s, int lane_id);

/// Point of the road surface at (s, t): the reference line's pose at s, shifted by t along its
/// normal, z = elevation(s) + t * tan(superelevation(s)); s is clamped to the road.
/// Throws InvalidInput when the road has no plan view records (as does heading_at).
[[nodiscard]] Vec3 surface_point(const ModelRoad& road, double s, double t);
/// Height of the road surface at (s, t), the z of surface_point() without its plan position.
[[nodiscard]] double surface_z(const ModelRoad& road, double s, double t);
/// The same with the reference line's pose at s already evaluated (road.plan.at(s)).
[[nodiscard]] Vec3 surface_point(const ModelRoad& road, const Pose2& pose, double s, double t);

/// Heading of the reference line at s.
[[nodiscard]] double heading_at(const ModelRoad& road, double s);

}  // namespace relief

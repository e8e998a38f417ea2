#include "support/road_models.h"

#include <Eigen/Geometry>

namespace relief::test {

LaneModel constant_lane(int id, double width_m, RoadMark::Type mark) {
  LaneModel l;
  l.id = id;
  l.width = CubicProfile::constant(width_m);
  l.mark.type = mark;
  return l;
}

ModelRoad straight_road(int id, const Vec2& start, double heading, double length_m, double z0, double grade) {
  ModelRoad road;
  road.id = id;
  road.plan = PlanView({line_record(0.0, start, heading, length_m)});
  road.elevation = CubicProfile({CubicPiece{0.0, {z0, grade, 0.0, 0.0}}});
  road.lane_offset = CubicProfile::constant(0.0);
  LaneSection section;
  section.left = {constant_lane(1, 3.0)};
  section.right = {constant_lane(-1, 3.5)};
  road.sections = {section};
  return road;
}

double mesh_area(const TriangleMesh& mesh) {
  double sum = 0.0;
  for (const auto& t : mesh.triangles) {
    const Vec3& a = mesh.vertices[t[0]];
    sum += 0.5 * (mesh.vertices[t[1]] - a).cross(mesh.vertices[t[2]] - a).norm();
  }
  return sum;
}

bool all_facing_up(const TriangleMesh& mesh) {
  for (const auto& t : mesh.triangles) {
    const Vec3& a = mesh.vertices[t[0]];
    if (!((mesh.vertices[t[1]] - a).cross(mesh.vertices[t[2]] - a).z() > 0.0)) return false;
  }
  return true;
}

}  // namespace relief::test

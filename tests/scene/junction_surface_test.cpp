#include "scene/junction_surface.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <numbers>

#include "support/road_models.h"

namespace relief::detail {
namespace {

using test::all_facing_up;
using test::mesh_area;

// An end whose vertices are new mesh vertices at `points` (right corner to left corner).
JunctionEnd add_end(MeshBuilder& mesh, int road_index, const std::vector<Vec3>& points) {
  JunctionEnd end;
  end.road_index = road_index;
  end.at_start = true;
  for (const Vec3& p : points) end.vertices.push_back(mesh.add_vertex(p, p.head<2>()));
  return end;
}

// Four roads 6 m wide (3 m each side of the reference line) start 5 m from the centre, east,
// north, west and south: the outline is the 10 m square less four corner triangles of legs 2 m,
// 92 m2 in 12 vertices, so 10 triangles, with the ends given in any order.
TEST(JunctionSurface, CrossingOfFourRoadEndsIsItsOctagon) {
  RoadModel model;
  for (int k = 0; k < 4; ++k) {
    const double heading = k * std::numbers::pi / 2.0;
    const Vec2 dir(std::cos(heading), std::sin(heading));
    model.roads.push_back(test::straight_road(k + 1, 5.0 * dir, heading, 50.0, 2.0, 0.0));
  }
  MeshBuilder mesh;
  std::vector<JunctionEnd> ends;
  for (const int k : {2, 0, 3, 1}) {
    // Looking out along the road, its right is the road's own right: t = -3, 0, +3.
    const double heading = k * std::numbers::pi / 2.0;
    const Vec2 dir(std::cos(heading), std::sin(heading));
    const Vec2 left(-dir.y(), dir.x());
    std::vector<Vec3> points;
    for (const double t : {-3.0, 0.0, 3.0}) {
      const Vec2 xy = 5.0 * dir + t * left;
      points.emplace_back(xy.x(), xy.y(), 2.0);
    }
    ends.push_back(add_end(mesh, k, points));
  }
  JunctionModel junction;
  junction.id = 7;
  const std::string failed = build_junction_surface(model, junction, ends, {}, {}, mesh);
  EXPECT_EQ(failed, "");
  EXPECT_EQ(mesh.mesh.vertices.size(), 12u);  // straight gaps: no vertex added
  EXPECT_EQ(mesh.mesh.triangles.size(), 10u);
  EXPECT_NEAR(mesh_area(mesh.mesh), 100.0 - 4.0 * 2.0, 1e-9);
  EXPECT_EQ(mesh.owner, std::vector<int>(10, -8));
  EXPECT_TRUE(all_facing_up(mesh.mesh));
}

TEST(JunctionSurface, EndsWithoutAnEdgeAreNoSurface) {
  MeshBuilder mesh;
  const std::vector<JunctionEnd> ends{add_end(mesh, 0, {Vec3(0.0, 0.0, 0.0)})};
  EXPECT_EQ(build_junction_surface(RoadModel{}, JunctionModel{}, ends, {}, {}, mesh), "no road ends");
  EXPECT_TRUE(mesh.mesh.triangles.empty());
}

// An L-shaped outline: two ends and a kerb of two points around the inner corner. The notch
// (inside the convex hull, outside the outline) stays open: 6 vertices, 4 triangles, 64 m2.
TEST(JunctionSurface, ConcaveOutlineWithKerbPointsLeavesItsNotchOpen) {
  MeshBuilder mesh;
  const std::vector<JunctionEnd> ends{add_end(mesh, 0, {Vec3(0.0, 0.0, 1.0), Vec3(10.0, 0.0, 1.0)}),
                                      add_end(mesh, 1, {Vec3(4.0, 10.0, 1.0), Vec3(0.0, 10.0, 1.0)})};
  const std::vector<OutlineGap> gaps{{{Vec3(10.0, 4.0, 1.5), Vec3(4.0, 4.0, 1.5)}}, {}};
  EXPECT_EQ(triangulate_junction(ends, gaps, 3, mesh), "");
  ASSERT_EQ(mesh.mesh.vertices.size(), 6u);  // the kerb points were added, uv = (x, y)
  EXPECT_EQ(mesh.mesh.vertices[4], Vec3(10.0, 4.0, 1.5));
  EXPECT_EQ(mesh.mesh.uvs[5], Vec2(4.0, 4.0));
  EXPECT_EQ(mesh.mesh.triangles.size(), 4u);
  EXPECT_EQ(mesh.owner, std::vector<int>(4, -4));
  EXPECT_TRUE(all_facing_up(mesh.mesh));
  double plan_area = 0.0;
  for (const auto& t : mesh.mesh.triangles) {
    const auto& v = mesh.mesh.vertices;
    const Vec2 a = (v[t[1]] - v[t[0]]).head<2>(), b = (v[t[2]] - v[t[0]]).head<2>();
    plan_area += 0.5 * (a.x() * b.y() - a.y() * b.x());
  }
  EXPECT_NEAR(plan_area, 100.0 - 36.0, 1e-9);
  // No triangle in the notch x > 4, y > 4.
  for (const auto& t : mesh.mesh.triangles) {
    const Vec3 c = (mesh.mesh.vertices[t[0]] + mesh.mesh.vertices[t[1]] + mesh.mesh.vertices[t[2]]) / 3.0;
    EXPECT_FALSE(c.x() > 4.0 && c.y() > 4.0) << c.transpose();
  }
}

// Outlines that cannot be a surface are reported, and nothing is added to the mesh.
TEST(JunctionSurface, BadOutlinesAreReportedAndAddNothing) {
  MeshBuilder mesh;
  const JunctionEnd bottom = add_end(mesh, 0, {Vec3(0.0, 0.0, 0.0), Vec3(10.0, 0.0, 0.0)});
  const JunctionEnd top = add_end(mesh, 1, {Vec3(10.0, 10.0, 0.0), Vec3(0.0, 10.0, 0.0)});
  const JunctionEnd crossed = add_end(mesh, 1, {Vec3(0.0, 10.0, 0.0), Vec3(10.0, 10.0, 0.0)});
  const std::size_t vertices = mesh.mesh.vertices.size();
  const auto expect_failure = [&](const std::vector<JunctionEnd>& ends, const std::vector<OutlineGap>& gaps,
                                  const std::string& reason) {
    const std::string failed = triangulate_junction(ends, gaps, 0, mesh);
    EXPECT_NE(failed.find(reason), std::string::npos) << failed;
    EXPECT_TRUE(mesh.mesh.triangles.empty());
    EXPECT_EQ(mesh.mesh.vertices.size(), vertices);
  };
  expect_failure({bottom, top, bottom}, {}, "passes twice");
  expect_failure({bottom}, {}, "fewer than three");
  // The square walked clockwise.
  JunctionEnd reversed_bottom = bottom;
  JunctionEnd reversed_top = top;
  std::reverse(reversed_bottom.vertices.begin(), reversed_bottom.vertices.end());
  std::reverse(reversed_top.vertices.begin(), reversed_top.vertices.end());
  expect_failure({reversed_top, reversed_bottom}, {}, "not counter-clockwise");
  // A bow tie with a kerb point that keeps its signed area positive: its edges cross.
  expect_failure({bottom, crossed}, {{{Vec3(20.0, 5.0, 0.0)}}, {}}, "not simple");
  // The square itself is fine: 2 triangles of 100 m2 together.
  EXPECT_EQ(triangulate_junction({bottom, top}, {}, 0, mesh), "");
  EXPECT_NEAR(mesh_area(mesh.mesh), 100.0, 1e-9);
}

}  // namespace
}  // namespace relief::detail

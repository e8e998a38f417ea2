#include "relief/scene/surface_query.h"

#include <gtest/gtest.h>

#include "relief/core/errors.h"
#include "support/mesh_grid.h"

namespace relief {
namespace {

using test::add_grid;

TriangleMesh named(TriangleMesh mesh, const char* name, SurfaceKind kind) {
  mesh.name = name;
  mesh.kind = kind;
  return mesh;
}

// A 10 m x 10 m ground from (0, 0), flat at 3 m.
MeshScene flat_scene() {
  TriangleMesh m;
  add_grid(m, 0, 0, 10, 10, 3.0);
  MeshScene s;
  s.meshes.push_back(named(std::move(m), "Terrain", SurfaceKind::terrain));
  return s;
}

TEST(SurfaceQuery, FlatGroundGivesItsHeightExactly) {
  const MeshScene scene = flat_scene();
  const SurfaceQuery query(scene);
  EXPECT_EQ(query.triangles_indexed(), 200u);
  for (const Vec2& p : {Vec2(2.3, 4.7), Vec2(0.01, 0.01), Vec2(9.99, 5.5), Vec2(7.5, 9.2)}) {
    const auto hit = query.highest(p.x(), p.y());
    ASSERT_TRUE(hit) << p.transpose();
    EXPECT_EQ(hit->z_m, 3.0);
    EXPECT_EQ(hit->kind, SurfaceKind::terrain);
    EXPECT_EQ(hit->mesh, 0u);
  }
}

TEST(SurfaceQuery, SlopedGroundIsItsPlane) {
  MeshScene scene = flat_scene();
  const auto plane = [](double x, double y) { return 1.0 + 0.1 * x + 0.05 * y; };
  for (Vec3& v : scene.meshes[0].vertices) v.z() = plane(v.x(), v.y());
  const SurfaceQuery query(scene, {.cell_size_m = 1.5});
  for (const Vec2& p : {Vec2(2.3, 4.7), Vec2(0.2, 9.9), Vec2(9.5, 0.5), Vec2(5.0, 5.0), Vec2(6.25, 3.75)}) {
    const auto hit = query.highest(p.x(), p.y());
    ASSERT_TRUE(hit) << p.transpose();
    EXPECT_NEAR(hit->z_m, plane(p.x(), p.y()), 1e-12) << p.transpose();
  }
}

TEST(SurfaceQuery, NothingOutsideEveryTriangle) {
  const MeshScene scene = flat_scene();
  const SurfaceQuery query(scene);
  for (const Vec2& p : {Vec2(-0.5, 5.0), Vec2(10.5, 5.0), Vec2(5.0, 20.0), Vec2(1e6, -1e6)}) {
    EXPECT_FALSE(query.highest(p.x(), p.y())) << p.transpose();
    EXPECT_FALSE(query.nearest(p.x(), p.y(), 3.0)) << p.transpose();
    EXPECT_TRUE(query.all(p.x(), p.y()).empty()) << p.transpose();
  }
  // Inside the index's grid but outside the only triangle: the bounding box does not count.
  TriangleMesh m;
  m.vertices = {Vec3(0, 0, 1), Vec3(100, 0, 1), Vec3(0, 100, 1)};
  m.triangles = {{0, 1, 2}};
  MeshScene big;
  big.meshes.push_back(named(std::move(m), "Road_Road", SurfaceKind::road));
  const SurfaceQuery fine(big, {.cell_size_m = 1.0});
  EXPECT_FALSE(fine.highest(70, 40));  // x + y > 100
  ASSERT_TRUE(fine.highest(60, 20));   // listed in cells far from its corners
  EXPECT_EQ(fine.highest(60, 20)->z_m, 1.0);
  EXPECT_TRUE(SurfaceQuery(MeshScene{}).all(0, 0).empty());
}

TEST(SurfaceQuery, PointOnASharedEdgeIsOneSurface) {
  const MeshScene scene = flat_scene();
  const SurfaceQuery query(scene);
  EXPECT_EQ(query.all(1.0, 0.5).size(), 1u);    // the edge between two squares
  EXPECT_EQ(query.all(4.0, 4.0).size(), 1u);    // a vertex of several triangles
  EXPECT_EQ(query.all(10.0, 10.0).size(), 1u);  // the far corner: on the border, inside
}

// A street along x at 0 m under a bridge deck along y at 6 m, both in Road_Road, over the
// crossing square |x|, |y| <= 2.
MeshScene bridge_over_street() {
  TriangleMesh road;
  add_grid(road, -10, -2, 20, 4, 0.0);
  add_grid(road, -2, -10, 4, 20, 6.0);
  MeshScene s;
  s.meshes.push_back(named(std::move(road), "Road_Road", SurfaceKind::road));
  return s;
}

TEST(SurfaceQuery, BridgeOverAStreetByTheDocumentedRule) {
  const MeshScene scene = bridge_over_street();
  const SurfaceQuery query(scene);
  // Both levels, highest first.
  const std::vector<SurfaceHit> both = query.all(0.3, 0.4);
  ASSERT_EQ(both.size(), 2u);
  EXPECT_EQ(both[0].z_m, 6.0);
  EXPECT_EQ(both[1].z_m, 0.0);
  // highest: the deck, seen from above.
  EXPECT_EQ(query.highest(0.3, 0.4)->z_m, 6.0);
  // nearest: the level closest to the height given (a vehicle under the bridge, on the deck);
  // the higher where both are as close.
  EXPECT_EQ(query.nearest(0.3, 0.4, 0.5)->z_m, 0.0);
  EXPECT_EQ(query.nearest(0.3, 0.4, -3.0)->z_m, 0.0);
  EXPECT_EQ(query.nearest(0.3, 0.4, 5.0)->z_m, 6.0);
  EXPECT_EQ(query.nearest(0.3, 0.4, 3.0)->z_m, 6.0);
  // Off the crossing only one level, whatever the height given.
  EXPECT_EQ(query.nearest(5.3, 0.4, 6.0)->z_m, 0.0);
  EXPECT_EQ(query.nearest(0.3, 7.0, 0.0)->z_m, 6.0);
  EXPECT_EQ(query.all(5.3, 0.4).size(), 1u);
}

TEST(SurfaceQuery, MarkingsOnlyWhenAsked) {
  MeshScene scene = flat_scene();
  TriangleMesh paint;
  add_grid(paint, 2, 2, 1, 1, 3.005);
  scene.meshes.push_back(named(std::move(paint), "Road_Marking", SurfaceKind::marking));
  EXPECT_EQ(SurfaceQuery(scene).highest(2.5, 2.5)->z_m, 3.0);
  const SurfaceQuery with(scene, {.markings = true});
  const auto hit = with.highest(2.5, 2.5);
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->z_m, 3.005);
  EXPECT_EQ(hit->kind, SurfaceKind::marking);
  EXPECT_EQ(hit->mesh, 1u);
  EXPECT_EQ(with.all(2.5, 2.5).size(), 2u);
}

TEST(SurfaceQuery, CellSizeMustBePositive) {
  const MeshScene scene = flat_scene();
  EXPECT_THROW(SurfaceQuery(scene, {.cell_size_m = 0.0}), InvalidInput);
  EXPECT_THROW(SurfaceQuery(scene, {.cell_size_m = -1.0}), InvalidInput);
}

}  // namespace
}  // namespace relief

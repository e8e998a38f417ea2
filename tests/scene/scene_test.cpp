#include "relief/scene/scene.h"

#include <gtest/gtest.h>

#include <optional>
#include <string>

#include "relief/scene/surface_query.h"
#include "scene/bridge_world.h"

namespace relief {
namespace {

const MeshQuality* quality_of(const SceneChecks& checks, const std::string& name) {
  for (const MeshQuality& q : checks.quality)
    if (q.name == name) return &q;
  return nullptr;
}

const TriangleMesh* mesh_of(const Scene& scene, const std::string& name) {
  for (const TriangleMesh& m : scene.meshes.meshes)
    if (m.name == name) return &m;
  return nullptr;
}

// The bridge world's scene checks are the figures the pipeline's mesh stage reported for the
// same model and DEM before the scene had a module of its own (measured with the mesh stage
// of commit 79a62e0 on this world).
TEST(Scene, BridgeWorldChecksAsThePipelineReportedThem) {
  Diagnostics d;
  const test::BridgeWorld w = test::make_bridge_world(d);
  Diagnostics diagnostics;
  const Scene scene = build_scene(w.built.model, w.network, w.dem, {}, diagnostics);
  ASSERT_TRUE(scene.checks);
  ASSERT_TRUE(scene.terrain);
  const SceneChecks& c = *scene.checks;
  // Printed by the mesh stage then: junctions 1 0, xodr 0.019090072462152108, seams 0 / 0;
  // Road_Road 369 triangles, 2 components (the street with its T, the bridge), 0 holes, 0
  // self-intersections, 4486.9900452878483 m2; Terrain 275 triangles, 1 component, 3 holes;
  // ground 0 holes, 1 component, 0 portals; 68 deck triangles on the ground; 0 structure x
  // terrain pairs; 0 triangles under roads; 14 TIN vertices; no diagnostic.
  EXPECT_EQ(scene.stats.junctions_meshed, 1u);
  EXPECT_EQ(scene.stats.junctions_failed, 0u);
  // Since the elevation became the grade-bounded fit (vertical curves at the samples' kinks),
  // the xodr distance was 0.019147615215334923 and the area 4486.9897244227286 m2; since the
  // elevation records keep within 0.4 mm of the fit (34d9206), 0.019962396955513384 and
  // 4486.9981196350018 m2.
  EXPECT_DOUBLE_EQ(scene.stats.xodr_surface_max_distance_m, 0.019962396955513384);
  EXPECT_EQ(scene.stats.seam_road_junction_m, 0.0);
  EXPECT_EQ(c.seam_road_terrain_m, std::optional<double>(0.0));
  const MeshQuality* road = quality_of(c, "Road_Road");
  ASSERT_NE(road, nullptr);
  // 369 before the junction's interior points, 387 with those a lane's, 417 with all of them
  // and the surface's points on the straight sides and inside, 413 with the 0.4 mm elevation
  // records.
  EXPECT_EQ(road->triangles, 413u);
  EXPECT_EQ(road->components, 2u);
  EXPECT_EQ(road->holes, 0u);
  EXPECT_EQ(road->self_intersecting_pairs, 0u);
  EXPECT_EQ(road->upside_down_triangles, 0u);
  EXPECT_DOUBLE_EQ(road->area_m2, 4486.9981196350018);
  const MeshQuality* terrain = quality_of(c, "Terrain");
  ASSERT_NE(terrain, nullptr);
  // 275 before the straight sides had the surface's points, 279 until the 0.4 mm elevation
  // records.
  EXPECT_EQ(terrain->triangles, 275u);
  EXPECT_EQ(terrain->components, 1u);
  EXPECT_EQ(terrain->holes, 3u);
  EXPECT_EQ(c.ground_holes, 0u);
  EXPECT_EQ(c.ground_components, 1u);
  EXPECT_EQ(c.ground_portals, 0u);
  EXPECT_EQ(scene.stats.deck_triangles_on_ground, 68u);
  EXPECT_EQ(scene.stats.tunnel_triangles_open, 0u);
  EXPECT_EQ(c.structure_terrain_pairs, 0u);
  EXPECT_EQ(scene.stats.ground_triangles_under_roads, 0u);
  EXPECT_EQ(scene.terrain->tin_vertices, 14u);
  EXPECT_EQ(diagnostics.total(), 0u);
  // The meshes in CARLA's naming, with normals; the ground flags per Road_Road triangle.
  ASSERT_EQ(scene.meshes.meshes.size(), 3u);  // no sidewalk
  EXPECT_EQ(scene.meshes.meshes[0].name, "Road_Road");
  EXPECT_EQ(scene.meshes.meshes[1].name, "Road_Marking");
  EXPECT_EQ(scene.meshes.meshes[2].name, "Terrain");
  for (const TriangleMesh& m : scene.meshes.meshes) EXPECT_EQ(m.normals.size(), m.vertices.size()) << m.name;
  EXPECT_EQ(scene.ground.size(), road->triangles);
  EXPECT_EQ(c.quality.back().name, "Ground (Road_Road on the ground + Terrain, welded)");
}

// The checks run inside build_scene or by the caller beside other work are the same checks,
// and report the same diagnostics.
TEST(Scene, ChecksBesideAreTheChecksInside) {
  Diagnostics d;
  const test::BridgeWorld w = test::make_bridge_world(d);
  Diagnostics inside_d, beside_d;
  const Scene inside = build_scene(w.built.model, w.network, w.dem, {}, inside_d);
  SceneOptions o;
  o.checks = false;
  const Scene beside = build_scene(w.built.model, w.network, w.dem, o, beside_d);
  EXPECT_FALSE(beside.checks);
  const SceneChecks checks = check_scene(beside);
  report_scene_checks(beside, checks, w.built.model, beside_d);
  ASSERT_TRUE(inside.checks);
  ASSERT_EQ(checks.quality.size(), inside.checks->quality.size());
  for (std::size_t i = 0; i < checks.quality.size(); ++i) {
    EXPECT_EQ(checks.quality[i].name, inside.checks->quality[i].name);
    EXPECT_EQ(checks.quality[i].triangles, inside.checks->quality[i].triangles);
    EXPECT_EQ(checks.quality[i].holes, inside.checks->quality[i].holes);
    EXPECT_EQ(checks.quality[i].self_intersecting_pairs, inside.checks->quality[i].self_intersecting_pairs);
  }
  EXPECT_EQ(checks.ground_holes, inside.checks->ground_holes);
  EXPECT_EQ(checks.ground_portals, inside.checks->ground_portals);
  EXPECT_EQ(checks.structure_terrain_pairs, inside.checks->structure_terrain_pairs);
  EXPECT_EQ(checks.seam_road_terrain_m, inside.checks->seam_road_terrain_m);
  EXPECT_EQ(beside_d.counts(), inside_d.counts());
}

TEST(Scene, WithoutTerrainOnlyThePavedSurface) {
  Diagnostics d;
  const test::BridgeWorld w = test::make_bridge_world(d);
  SceneOptions o;
  o.terrain = false;
  const Scene scene = build_scene(w.built.model, w.network, w.dem, o, d);
  EXPECT_FALSE(scene.terrain);
  EXPECT_EQ(mesh_of(scene, "Terrain"), nullptr);
  ASSERT_NE(mesh_of(scene, "Road_Road"), nullptr);
  ASSERT_TRUE(scene.checks);
  EXPECT_EQ(scene.checks->quality.size(), scene.meshes.meshes.size());  // no welded ground
  EXPECT_FALSE(scene.checks->seam_road_terrain_m);
}

// The query on a built scene: the street lies at the plane's 20 m, the deck 7 m over it at the
// crossing, the terrain at 20 m away from the roads.
TEST(Scene, SurfaceUnderTheBridgeWorld) {
  Diagnostics d;
  const test::BridgeWorld w = test::make_bridge_world(d);
  const Scene scene = build_scene(w.built.model, w.network, w.dem, {}, d);
  const SurfaceQuery query(scene.meshes);
  const auto deck = query.highest(0.0, 0.5);
  ASSERT_TRUE(deck);
  EXPECT_NEAR(deck->z_m, test::kWorldGroundM + test::kWorldDeckRiseM, 0.05);
  EXPECT_EQ(scene.meshes.meshes[deck->mesh].name, "Road_Road");
  const auto street = query.nearest(0.0, 0.5, test::kWorldGroundM);
  ASSERT_TRUE(street);
  EXPECT_NEAR(street->z_m, test::kWorldGroundM, 1e-9);
  EXPECT_EQ(scene.meshes.meshes[street->mesh].name, "Road_Road");
  const auto field = query.highest(50.0, 50.0);
  ASSERT_TRUE(field);
  EXPECT_EQ(scene.meshes.meshes[field->mesh].name, "Terrain");
  EXPECT_NEAR(field->z_m, test::kWorldGroundM, 1e-9);
  EXPECT_FALSE(query.highest(1000.0, 0.0));
}

}  // namespace
}  // namespace relief

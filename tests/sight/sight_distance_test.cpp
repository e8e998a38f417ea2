// Sight distance (relief/sight/sight_distance.h) on exact cases: AASHTO's stopping distance,
// a flat straight road, the textbook crest vertical curve, a cutting on a horizontal curve.

#include "relief/sight/sight_distance.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "relief/core/errors.h"
#include "relief/roads/road_surface.h"
#include "support/plan_records.h"
#include "support/road_models.h"

namespace relief {
namespace {

// The road's surface from t0 to t1 as a strip of triangles every ds along it.
TriangleMesh strip(const ModelRoad& road, double t0, double t1, double ds) {
  TriangleMesh mesh;
  mesh.name = "Road_Road";
  mesh.kind = SurfaceKind::road;
  const auto n = static_cast<std::uint32_t>(std::ceil(road.length() / ds));
  for (std::uint32_t i = 0; i <= n; ++i) {
    const double s = std::min(road.length(), i * ds);
    mesh.vertices.push_back(surface_point(road, s, t0));
    mesh.vertices.push_back(surface_point(road, s, t1));
    if (i == 0) continue;
    const std::uint32_t a = 2 * (i - 1), b = a + 1, c = a + 2, d = a + 3;
    mesh.triangles.push_back({a, c, b});
    mesh.triangles.push_back({b, c, d});
  }
  return mesh;
}

std::vector<SightStation> stations_of(const SightResult& r, int lane) {
  std::vector<SightStation> out;
  for (const SightStation& s : r.stations)
    if (s.lane == lane) out.push_back(s);
  return out;
}

TEST(StoppingSightDistance, IsAashtosFormulaWithItsGradeCorrection) {
  // AASHTO 2018 Table 3-1 (metric): 50 km/h, 34.8 m of reaction + 28.7 m of braking = 63.5 m
  // (its 0.039 V^2 / a rounds 1 / (2 x 3.6^2)).
  const double v = 50.0 / 3.6;
  EXPECT_NEAR(stopping_sight_distance(v, 0.0), 63.5, 0.01 * 63.5);
  EXPECT_DOUBLE_EQ(stopping_sight_distance(v, 0.0), v * 2.5 + v * v / (2.0 * 3.4));
  // On grade: a + g G. A 6 % downgrade needs more, a 6 % upgrade less.
  EXPECT_DOUBLE_EQ(stopping_sight_distance(v, -0.06), v * 2.5 + v * v / (2.0 * (3.4 - 9.80665 * 0.06)));
  EXPECT_GT(stopping_sight_distance(v, -0.06), stopping_sight_distance(v, 0.0));
  EXPECT_LT(stopping_sight_distance(v, 0.06), stopping_sight_distance(v, 0.0));
  EXPECT_THROW((void)stopping_sight_distance(v, -0.4), InvalidInput);
  EXPECT_THROW((void)stopping_sight_distance(-1.0, 0.0), InvalidInput);
}

// A flat straight road 200 m long: nothing hides the lane, and each direction sees to the road's
// end (the path ends there: not short).
TEST(SightDistance, AFlatStraightRoadIsSeenToItsEnd) {
  RoadModel model;
  model.roads.push_back(test::straight_road(1, Vec2(0.0, 0.0), 0.3, 200.0, 5.0, 0.0));
  MeshScene scene;
  scene.meshes.push_back(strip(model.roads[0], -3.5, 3.0, 1.0));
  SightOptions o;
  o.measure_beyond_required = true;
  o.keep_stations = true;
  const SightResult r = sight_distances(model, scene, o);
  const std::vector<SightStation> ahead = stations_of(r, -1), back = stations_of(r, 1);
  ASSERT_EQ(ahead.size(), 101u);  // every 2 m, both ends
  ASSERT_EQ(back.size(), 101u);
  for (const SightStation& st : ahead) {
    EXPECT_NEAR(st.available_m, 200.0 - st.s, 1e-6) << st.s;
    EXPECT_EQ(st.obstacle, SightObstacle::none);
  }
  for (const SightStation& st : back) EXPECT_NEAR(st.available_m, st.s, 1e-6) << st.s;
  EXPECT_TRUE(r.stretches.empty());
  EXPECT_DOUBLE_EQ(r.km_short, 0.0);
  EXPECT_NEAR(r.km_checked, 0.4, 1e-9);  // two lanes of 200 m
}

// A crest vertical curve from +4 % to -4 % over L = 200 m (A = 8 %): with eye and object on the
// curve, S < L and L = A S^2 / (200 (sqrt h1 + sqrt h2)^2), so S = 128.3 m wherever it is
// measured; the road itself hides the object.
TEST(SightDistance, ACrestVerticalCurveGivesTheTextbookDistance) {
  ModelRoad road = test::straight_road(1, Vec2(0.0, 0.0), 0.0, 600.0, 0.0, 0.0);
  road.elevation = CubicProfile({CubicPiece{0.0, {0.0, 0.04, 0.0, 0.0}},
                                 CubicPiece{200.0, {8.0, 0.04, -0.08 / 400.0, 0.0}},
                                 CubicPiece{400.0, {8.0, -0.04, 0.0, 0.0}}});
  road.speed_mps = 100.0 / 3.6;
  RoadModel model;
  model.roads.push_back(road);
  MeshScene scene;
  scene.meshes.push_back(strip(road, -3.5, 3.0, 0.5));
  SightOptions o;
  o.measure_beyond_required = true;
  o.keep_stations = true;
  const SightResult r = sight_distances(model, scene, o);
  const double h = std::sqrt(o.eye_height_m) + std::sqrt(o.object_height_m);
  const double expected = std::sqrt(200.0 * 200.0 * h * h / 8.0);
  ASSERT_NEAR(expected, 128.3, 0.05);
  int checked = 0;
  for (const SightStation& st : stations_of(r, -1)) {
    if (st.s < 200.0 || st.s + expected > 400.0) continue;
    EXPECT_NEAR(st.available_m, expected, 0.01 * expected) << st.s;
    EXPECT_EQ(st.obstacle, SightObstacle::road);
    EXPECT_TRUE(st.short_of_required());  // 100 km/h needs about 183 m
    ++checked;
  }
  EXPECT_GE(checked, 35);
  ASSERT_FALSE(r.stretches.empty());
  EXPECT_NEAR(r.stretches.front().available_m, expected, 0.01 * expected);
  EXPECT_EQ(r.stretches.front().obstacle, SightObstacle::road);
}

// A left curve of radius 100 m; the right lane's centre runs at 101.75 m; a cutting's face (a
// wall 10 m high) stands on the inside at 95.75 m, 6 m from it. The line of sight touches the
// face: the object is hidden beyond the arc 2 R acos(R_face / R) = 70.23 m along the lane.
TEST(SightDistance, ACuttingOnAHorizontalCurveLimitsItAsTheGeometrySays) {
  ModelRoad road = test::straight_road(1, Vec2(0.0, 0.0), 0.0, 300.0, 0.0, 0.0);
  road.plan = PlanView({test::arc_record(0.0, Vec2(0.0, 0.0), 0.0, 300.0, 0.01)});
  RoadModel model;
  model.roads.push_back(road);
  MeshScene scene;
  scene.meshes.push_back(strip(road, -3.5, 3.0, 0.5));
  TriangleMesh wall;
  wall.name = "Terrain";
  wall.kind = SurfaceKind::terrain;
  const double face = 95.75;
  const int segments = 1440;
  for (int i = 0; i < segments; ++i) {
    const double a = 2.0 * std::numbers::pi * i / segments;
    const Vec2 p = Vec2(0.0, 100.0) + face * Vec2(std::cos(a), std::sin(a));
    wall.vertices.emplace_back(p.x(), p.y(), -1.0);
    wall.vertices.emplace_back(p.x(), p.y(), 10.0);
  }
  for (std::uint32_t i = 0; i < static_cast<std::uint32_t>(segments); ++i) {
    const std::uint32_t a = 2 * i, b = a + 1, c = 2 * ((i + 1) % segments), d = c + 1;
    wall.triangles.push_back({a, c, b});
    wall.triangles.push_back({b, c, d});
  }
  scene.meshes.push_back(wall);
  SightOptions o;
  o.measure_beyond_required = true;
  o.keep_stations = true;
  const SightResult r = sight_distances(model, scene, o);
  const double lane = 101.75;
  const double expected = 2.0 * lane * std::acos(face / lane);
  ASSERT_NEAR(expected, 70.23, 0.01);
  int checked = 0;
  for (const SightStation& st : stations_of(r, -1)) {
    if (st.s + 1.1 * expected > 300.0) continue;
    EXPECT_NEAR(st.available_m, expected, 0.01 * expected) << st.s;
    EXPECT_EQ(st.obstacle, SightObstacle::terrain);
    EXPECT_NEAR((st.obstacle_point.head<2>() - Vec2(0.0, 100.0)).norm(), face, 0.01);
    ++checked;
  }
  EXPECT_GE(checked, 100);
}

TEST(SightDistance, BadOptionsAndClassesAreRefused) {
  RoadModel model;
  model.roads.push_back(test::straight_road(1, Vec2(0.0, 0.0), 0.0, 50.0, 0.0, 0.0));
  const MeshScene scene;
  SightOptions o;
  o.step_m = 0.0;
  EXPECT_THROW((void)sight_distances(model, scene, o), InvalidInput);
  o = {};
  o.eye_height_m = std::nan("");
  EXPECT_THROW((void)sight_distances(model, scene, o), InvalidInput);
  EXPECT_THROW((void)sight_distances(model, scene, {}, {"a", "b"}), InvalidInput);
  // No obstacles at all: the lanes are seen to their ends.
  const SightResult r = sight_distances(model, scene);
  EXPECT_TRUE(r.stretches.empty());
}

}  // namespace
}  // namespace relief

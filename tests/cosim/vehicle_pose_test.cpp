#include "relief/cosim/vehicle_pose.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>

#include "relief/core/errors.h"

namespace relief {
namespace {

// A surface z = f(x, y) on a grid of `cell` squares over [x0, x0 + n cell] x [y0, y0 + n cell].
TriangleMesh surface(const std::function<double(double, double)>& f, double x0, double y0, int n, double cell,
                     SurfaceKind kind = SurfaceKind::road) {
  TriangleMesh mesh;
  mesh.kind = kind;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const double x = x0 + i * cell, y = y0 + j * cell;
      mesh.vertices.emplace_back(x, y, f(x, y));
    }
  const auto at = [&](int i, int j) { return static_cast<std::uint32_t>(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      mesh.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      mesh.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  return mesh;
}

// Removes the triangles whose centroid lies within `radius` of `at` in plan.
void punch_hole(TriangleMesh& mesh, const Vec2& at, double radius) {
  std::erase_if(mesh.triangles, [&](const std::array<std::uint32_t, 3>& t) {
    Vec2 c = Vec2::Zero();
    for (const std::uint32_t v : t) c += mesh.vertices[v].head<2>() / 3.0;
    return (c - at).norm() < radius;
  });
}

MeshScene scene_of(std::vector<TriangleMesh> meshes) {
  MeshScene scene;
  scene.meshes = std::move(meshes);
  return scene;
}

constexpr double kPi = std::numbers::pi;

TEST(WheelBase, FollowsTheVehicleSizeAndRejectsNonsense) {
  const WheelBase car = wheel_base_of(5.0, 1.8);
  EXPECT_DOUBLE_EQ(car.wheelbase_m, 3.0);
  EXPECT_DOUBLE_EQ(car.track_m, 1.4);
  EXPECT_DOUBLE_EQ(wheel_base_of(2.0, 0.8).track_m, 0.48);  // narrow: 60 % of the width
  EXPECT_THROW((void)wheel_base_of(0.0, 1.8), InvalidInput);
  EXPECT_THROW((void)wheel_base_of(5.0, std::nan("")), InvalidInput);
}

// On a 10 % plane the body lies on the plane: z within 1e-9, pitch atan(0.1) uphill, roll
// atan(0.1) with the right side down when the slope falls to the right.
TEST(PlaceOnSurface, OnATenPercentPlaneThePoseIsThePlanes) {
  const MeshScene scene = scene_of({surface([](double x, double) { return 0.1 * x; }, -20, -20, 40, 1.0)});
  const SurfaceQuery query(scene);
  const WheelBase wheels = wheel_base_of(4.5, 1.8);
  const auto up = place_on_surface(query, Vec2(3.3, 1.7), 0.0, wheels, 0.0);  // heading east, uphill
  ASSERT_TRUE(up);
  EXPECT_NEAR(up->z_m, 0.33, 1e-9);
  EXPECT_NEAR(up->pitch_rad, std::atan(0.1), 1e-9);
  EXPECT_NEAR(up->roll_rad, 0.0, 1e-9);
  for (const double under : up->wheel_under_m) EXPECT_NEAR(under, 0.0, 1e-9);
  const auto down = place_on_surface(query, Vec2(3.3, 1.7), kPi, wheels, 0.0);  // west, downhill
  ASSERT_TRUE(down);
  EXPECT_NEAR(down->pitch_rad, -std::atan(0.1), 1e-9);
  const auto north = place_on_surface(query, Vec2(3.3, 1.7), kPi / 2, wheels, 0.0);
  ASSERT_TRUE(north);
  EXPECT_NEAR(north->pitch_rad, 0.0, 1e-9);
  EXPECT_NEAR(north->roll_rad, -std::atan(0.1), 1e-9);  // heading north the right side is east: up
  const auto south = place_on_surface(query, Vec2(3.3, 1.7), -kPi / 2, wheels, 0.0);
  ASSERT_TRUE(south);
  EXPECT_NEAR(south->roll_rad, std::atan(0.1), 1e-9);  // heading south the right side is west: down
  // Heading north-east at 45 degrees: the slope along the heading is 0.1 cos 45.
  const auto diagonal = place_on_surface(query, Vec2(0.0, 0.0), kPi / 4, wheels, 0.0);
  ASSERT_TRUE(diagonal);
  EXPECT_NEAR(diagonal->pitch_rad, std::atan(0.1 * std::cos(kPi / 4)), 1e-9);
}

// Over a parabolic crest z = -k x^2 / 2 the chord between the axles has the tangent's slope at
// their midpoint, so the pitch follows the tangent at the centre; the centre sits k a^2 / 2
// below the crest's surface (a: half the wheelbase). A fine grid keeps the chord error small.
TEST(PlaceOnSurface, OverAParabolicCrestPitchFollowsTheTangent) {
  const double k = 0.02;
  const MeshScene scene =
      scene_of({surface([&](double x, double) { return -0.5 * k * x * x; }, -30, -30, 600, 0.1)});
  const SurfaceQuery query(scene);
  const WheelBase wheels = wheel_base_of(5.0, 1.8);
  const double a = 0.5 * wheels.wheelbase_m;
  for (const double x : {-20.0, -7.5, 0.0, 4.0, 15.0}) {
    const auto pose = place_on_surface(query, Vec2(x, 0.3), 0.0, wheels, -0.5 * k * x * x, std::atan(-k * x));
    ASSERT_TRUE(pose) << x;
    EXPECT_NEAR(pose->pitch_rad, std::atan(-k * x), 1e-4) << x;  // the grid's chords: < 0.006 degrees
    EXPECT_NEAR(pose->z_m, -0.5 * k * x * x - 0.5 * k * a * a, 2e-4) << x;
    EXPECT_NEAR(pose->roll_rad, 0.0, 1e-9) << x;
  }
}

// A twisted surface z = c x y: no plane holds all four wheels; the two wheels of one diagonal
// are c a b above the body plane (they would sink in), the other two as far below.
TEST(PlaceOnSurface, OnATwistedSurfaceTheWheelsOffTheBodyPlaneAreMeasured) {
  const double c = 0.05;
  const MeshScene scene =
      scene_of({surface([&](double x, double y) { return c * x * y; }, -10, -10, 200, 0.1)});
  const SurfaceQuery query(scene);
  const WheelBase wheels = wheel_base_of(5.0, 1.8);
  const auto pose = place_on_surface(query, Vec2(0.0, 0.0), 0.0, wheels, 0.0);
  ASSERT_TRUE(pose);
  const double twist = c * 0.5 * wheels.wheelbase_m * 0.5 * wheels.track_m;
  EXPECT_NEAR(pose->wheel_under_m[0], twist, 1e-9);   // front left (+a, +b)
  EXPECT_NEAR(pose->wheel_under_m[1], -twist, 1e-9);  // front right
  EXPECT_NEAR(pose->wheel_under_m[2], -twist, 1e-9);  // rear left
  EXPECT_NEAR(pose->wheel_under_m[3], twist, 1e-9);   // rear right
  EXPECT_NEAR(pose->pitch_rad, 0.0, 1e-9);
  EXPECT_NEAR(pose->z_m, 0.0, 1e-9);
}

// Under a deck the vehicle takes the surface nearest its height: the road below or the deck;
// a wheel off every surface leaves the vehicle unplaced; each contact says what it stands on.
TEST(PlaceOnSurface, TakesTheSurfaceNearestItsHeightAndSaysWhatEachWheelIsOn) {
  const MeshScene scene =
      scene_of({surface([](double, double) { return 0.0; }, -10, -10, 20, 1.0),
                surface([](double, double) { return 7.0; }, -10, -3, 40, 0.3, SurfaceKind::road),
                surface([](double, double) { return -0.2; }, 10, -10, 20, 1.0, SurfaceKind::terrain)});
  const SurfaceQuery query(scene);
  const WheelBase wheels = wheel_base_of(4.0, 1.8);
  const auto below = place_on_surface(query, Vec2(0.0, 0.0), 0.0, wheels, 0.3);
  const auto above = place_on_surface(query, Vec2(0.0, 0.0), 0.0, wheels, 6.8);
  ASSERT_TRUE(below && above);
  EXPECT_NEAR(below->z_m, 0.0, 1e-12);
  EXPECT_NEAR(above->z_m, 7.0, 1e-12);
  // Straddling the road's edge at x = 10: the front wheels on the terrain 0.2 m lower.
  const auto edge = place_on_surface(query, Vec2(9.5, 0.0), 0.0, wheels, 0.0);
  ASSERT_TRUE(edge);
  EXPECT_EQ(edge->wheel_kind[0], SurfaceKind::terrain);
  EXPECT_EQ(edge->wheel_kind[3], SurfaceKind::road);
  EXPECT_NEAR(edge->pitch_rad, std::atan(-0.2 / wheels.wheelbase_m), 1e-9);
  EXPECT_FALSE(place_on_surface(query, Vec2(29.5, 0.0), 0.0, wheels, 0.0));  // front wheels off the world
}

// In a tunnel a wheel past the pavement's edge finds only the hill above: that contact takes the
// plane of the other three; two such contacts leave the vehicle unplaced. The expected height
// follows the hint's pitch along the body.
TEST(PlaceOnSurface, AContactWithNoSurfaceNearItsHeightTakesThePlaneOfTheOtherThree) {
  TriangleMesh road = surface([](double x, double) { return 0.1 * x; }, -10, -10, 40, 0.5);
  // A hole in the road under the front left contact of a car at the origin heading east.
  const WheelBase wheels = wheel_base_of(5.0, 1.8);
  const Vec2 front_left(0.5 * wheels.wheelbase_m, 0.5 * wheels.track_m);
  punch_hole(road, front_left, 0.6);
  const MeshScene scene =
      scene_of({road, surface([](double, double) { return 6.0; }, -10, -10, 20, 1.0, SurfaceKind::terrain)});
  const SurfaceQuery query(scene);
  const auto pose = place_on_surface(query, Vec2::Zero(), 0.0, wheels, 0.0, std::atan(0.1));
  ASSERT_TRUE(pose);
  EXPECT_EQ(pose->contacts_missing, 1);
  EXPECT_NEAR(pose->z_m, 0.0, 1e-9);
  EXPECT_NEAR(pose->pitch_rad, std::atan(0.1), 1e-9);
  EXPECT_NEAR(pose->roll_rad, 0.0, 1e-9);
  for (const double under : pose->wheel_under_m) EXPECT_NEAR(under, 0.0, 1e-9);
  // Without the pitch hint the front contacts expect 0.15 m lower: still within the 1 m gap.
  EXPECT_TRUE(place_on_surface(query, Vec2::Zero(), 0.0, wheels, 0.0));
  // A hint 5.5 m up takes the hill for every contact.
  const auto hill = place_on_surface(query, Vec2::Zero(), 0.0, wheels, 5.5);
  ASSERT_TRUE(hill);
  EXPECT_NEAR(hill->z_m, 6.0, 1e-9);
  // Two holes: unplaced.
  const Vec2 front_right(0.5 * wheels.wheelbase_m, -0.5 * wheels.track_m);
  punch_hole(road, front_right, 0.6);
  const MeshScene holed =
      scene_of({road, surface([](double, double) { return 6.0; }, -10, -10, 20, 1.0, SurfaceKind::terrain)});
  const SurfaceQuery holed_query(holed);
  EXPECT_FALSE(place_on_surface(holed_query, Vec2::Zero(), 0.0, wheels, 0.0, std::atan(0.1)));
}

}  // namespace
}  // namespace relief

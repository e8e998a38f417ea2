#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "relief/core/errors.h"
#include "relief/cosim/ego_controller.h"
#include "relief/cosim/ego_world.h"

namespace relief {
namespace {

// A plane z = grade x over [-half, half]^2 as two triangles, in a scene of its own.
MeshScene plane_scene(double grade, double half = 2000.0) {
  TriangleMesh m;
  m.name = "Road_Road";
  for (const auto& [x, y] : {std::pair{-half, -half}, {half, -half}, {half, half}, {-half, half}})
    m.vertices.emplace_back(x, y, grade * x);
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  MeshScene scene;
  scene.meshes.push_back(m);
  return scene;
}

std::vector<Vec2> straight_path(double from_x, double to_x, double y = 0.0) {
  return {Vec2(from_x, y), Vec2(to_x, y)};
}

TEST(EgoSpec, TheTableGivesEachClassItsDynamicsAndRejectsNonsense) {
  const EgoSpec car = ego_spec_for("passenger", 5.0, 1.8, 0.0);
  EXPECT_EQ(car.vclass, "passenger");
  EXPECT_DOUBLE_EQ(car.mass_kg, 1500.0);
  EXPECT_DOUBLE_EQ(car.height_m, 1.5);      // the class's when SUMO's type has none
  EXPECT_NEAR(car.wheelbase_m, 3.0, 1e-9);  // 60 % of the length (vehicle_pose.h)
  const EgoSpec truck = ego_spec_for("truck", 7.1, 2.4, 3.4);
  EXPECT_DOUBLE_EQ(truck.mass_kg, 20000.0);
  EXPECT_DOUBLE_EQ(truck.engine_power_w, 240e3);
  EXPECT_DOUBLE_EQ(truck.height_m, 3.4);
  EXPECT_EQ(ego_spec_for("evehicle", 4.0, 1.7, 1.5).vclass, "passenger");  // not in the table
  EXPECT_THROW((void)ego_spec_for("truck", 0.0, 2.4, 3.0), InvalidInput);
  EXPECT_THROW((void)ego_spec_for("truck", 7.0, 2.4, std::nan("")), InvalidInput);
  // The climbing speed the power allows: on the level it is the drag limit (hundreds of
  // km/h for a car), on 15 % a loaded truck crawls.
  EXPECT_GT(power_limited_speed(car, 0.0), 50.0);
  EXPECT_NEAR(power_limited_speed(truck, 0.15), 7.8, 0.1);
}

// At rest with the brakes on, on a 10 % plane, facing up it: the footing on the plane, the
// body's pitch the plane's plus what the weight on the rear springs adds (under 0.5 degree),
// all four wheels down, no creep.
TEST(EgoWorld, AnEgoAtRestOnATenPercentPlaneStandsOnItWithItsSlope) {
  EgoWorld world(plane_scene(0.1));
  const EgoSpec spec = ego_spec_for("passenger", 4.5, 1.8, 1.5);
  world.place("car", spec, Vec2(10.0, 5.0), 0.0, 1.0, 0.0, std::atan(0.1));
  world.set_controls("car", {0.0, 0.0, spec.max_brake_force_n});
  for (int i = 0; i < 60; ++i) world.step(0.05);
  const EgoState s = world.state("car");
  EXPECT_EQ(s.wheels_on_ground, 4);
  EXPECT_NEAR(s.ground_z_m, 0.1 * s.centre.x(), 0.002);
  EXPECT_NEAR(s.pitch_rad, std::atan(0.1), 0.5 * std::numbers::pi / 180.0);
  EXPECT_NEAR(s.roll_rad, 0.0, 0.1 * std::numbers::pi / 180.0);
  EXPECT_NEAR(s.centre.x(), 10.0, 0.05);
  EXPECT_NEAR(s.centre.y(), 5.0, 0.01);
  EXPECT_NEAR(std::abs(s.speed_mps), 0.0, 0.01);
  for (const Vec3& c : s.contacts) EXPECT_NEAR(c.z(), 0.1 * c.x(), 0.002);
  EXPECT_THROW((void)world.state("nobody"), Error);
  world.remove("car");
  EXPECT_FALSE(world.has("car"));
}

// A loaded truck on a long 15 % climb, the driver asking for 25 m/s: it settles where its power
// carries the climb, P = m g v (sin a + c_rr cos a) + rho/2 c_d A v^3 (within 3 %), and keeps
// its lane.
TEST(EgoWorld, AHeavyEgoOnALongFifteenPercentClimbSettlesAtItsPowerLimitedSpeed) {
  constexpr double kGrade = 0.15;
  EgoWorld world(plane_scene(kGrade, 1500.0));
  const EgoSpec truck = ego_spec_for("truck", 7.1, 2.4, 3.4);
  world.place("truck", truck, Vec2(-1200.0, 0.0), 0.0, -180.0, 5.0, std::atan(kGrade));
  const std::vector<Vec2> lane = straight_path(-1500.0, 1500.0);
  for (int i = 0; i < 1200; ++i) {  // 60 s
    world.set_controls("truck", drive_along(truck, world.state("truck"), lane, 25.0));
    world.step(0.05);
  }
  const EgoState s = world.state("truck");
  const double expected = power_limited_speed(truck, kGrade);
  EXPECT_NEAR(s.speed_mps, expected, 0.03 * expected);
  EXPECT_NEAR(s.centre.y(), 0.0, 0.1);
  EXPECT_NEAR(s.pitch_rad, std::atan(kGrade), 0.5 * std::numbers::pi / 180.0);
}

// Stanley's law: left of the lane it steers right, right of it left, on it straight; a sharp
// curve ahead takes the speed down before it.
TEST(EgoDriver, SteersBackOntoTheLaneAndSlowsForACurveAhead) {
  const EgoSpec car = ego_spec_for("passenger", 4.5, 1.8, 1.5);
  const std::vector<Vec2> lane = straight_path(-100.0, 100.0);
  EgoState s;
  s.speed_mps = 10.0;
  s.centre = Vec2(0.0, 0.5);
  EXPECT_LT(drive_along(car, s, lane, 10.0).steer_rad, -0.01);
  s.centre = Vec2(0.0, -0.5);
  EXPECT_GT(drive_along(car, s, lane, 10.0).steer_rad, 0.01);
  s.centre = Vec2(0.0, 0.0);
  const EgoControls straight = drive_along(car, s, lane, 10.0);
  EXPECT_NEAR(straight.steer_rad, 0.0, 1e-9);
  EXPECT_GT(straight.drive_force_n, 0.0);  // rolling and drag at 10 m/s
  EXPECT_EQ(straight.brake_force_n, 0.0);
  // A right-angle turn of radius 8 m, 15 m ahead, approached at 14 m/s: brake.
  std::vector<Vec2> turn = {Vec2(-50.0, 0.0), Vec2(15.0, 0.0)};
  for (int k = 1; k <= 16; ++k) {
    const double a = 0.5 * std::numbers::pi * k / 16.0;
    turn.emplace_back(15.0 + 8.0 * std::sin(a), -8.0 + 8.0 * std::cos(a));
  }
  turn.emplace_back(23.0, -60.0);
  s.speed_mps = 14.0;
  const EgoControls approach = drive_along(car, s, turn, 14.0);
  EXPECT_GT(approach.brake_force_n, 0.0);
  EXPECT_EQ(approach.drive_force_n, 0.0);
  // Stopped with nowhere to go: held on the brakes.
  s.speed_mps = 0.0;
  EXPECT_DOUBLE_EQ(drive_along(car, s, lane, 0.0).brake_force_n, car.max_brake_force_n);
}

}  // namespace
}  // namespace relief

#include "cosim/placement_measures.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "relief/core/diagnostics.h"
#include "support/sumo_ramp.h"
#include "support/test_data.h"

namespace relief {
namespace {

// The ramp (support/sumo_ramp.h: road 1 east along y = 0, z = 0.1 x, lanes 1 and -1 of 3 m, its
// pavement from y = -3 to 3) rolled 10 % to the left: z = 0.1 x + 0.1 y on it.
RoadModel rolled_ramp() {
  RoadModel model = test::ramp_model();
  model.roads[0].superelevation = CubicProfile::constant(std::atan(0.1));
  return model;
}

// A car (5 x 1.8 m: wheels 3 m by 1.4 m apart) on lane 1_0 centred at (50, y) facing north,
// across the road, set on a surface that is level across the road's edges (z = 5 under every
// wheel), measured once: placed on the surface, or an ego (the physics' body) with
// `wheels_in_air` wheels off the ground and its z `lift` above that.
CosimResult measure_across(double y, bool ego = false, int wheels_in_air = 0, double lift = 0.0) {
  const RoadModel model = rolled_ramp();
  const std::filesystem::path net = test::scratch_dir("net") / "ramp.net.xml";
  std::ofstream(net) << test::ramp_net_xml();
  SumoSurface odr(net, model);
  CosimOptions options;
  detail::PlacementMeasures measures(odr, options);
  SumoVehicleState v;
  v.id = "car";
  v.lane = "1_0";
  v.angle_deg = 0.0;  // north
  v.length_m = 5.0;
  v.width_m = 1.8;
  v.front = Vec3(50.0, y + 2.5, 5.0);
  SurfacePose pose;
  pose.z_m = 5.0 + lift;
  pose.wheel_z_m = {5.0, 5.0, 5.0, 5.0};
  pose.wheels_in_air = wheels_in_air;
  CosimResult result;
  measures.track_lane(v);
  measures.add(v, pose, 0.0, result, /*sumo_placed=*/!ego);
  Diagnostics diagnostics;
  measures.finish(result, diagnostics);
  return result;
}

TEST(PlacementMeasures, ACarAcrossTheRoadWithinItsEdgesIsMeasuredOnIt) {
  // Centred at y = 0: its wheels at y = +-1.5, on the pavement, where the road's surface is
  // 0.1 x + 0.1 y: the body's mean 5.0, as placed.
  const CosimResult r = measure_across(0.0);
  ASSERT_EQ(r.z_error_body_m.count, 1u);
  EXPECT_NEAR(r.z_error_body_m.max, 0.0, 1e-6);
}

TEST(PlacementMeasures, AWheelOutsideTheRoadsEdgesIsNotMeasuredOnTheRoadsRollCarriedPastThem) {
  // Centred at y = -3.5: the rear wheels at y = -5, 2 m outside the road's edge, where the road
  // has no surface; its roll carried out there would put them 0.5 m under the car, and the
  // body's mean 0.35 m. The body is not measured; the centre (its own measure, on the road it
  // projects onto) still is.
  const CosimResult r = measure_across(-3.5);
  EXPECT_EQ(r.z_error_body_m.count, 0u);
  EXPECT_EQ(r.z_error_m.count, 1u);
}

// An ego's body is the physics' (its suspension, a crest taken fast), not a placement: it is
// measured apart from the vehicles set on the surface, and with a wheel off the ground only
// counted, with its height over the surface.
TEST(PlacementMeasures, AnEgoIsMeasuredApartAndAWheelInTheAirOnlyCounted) {
  // The centre at (50, 0) on the rolled ramp: the surface 5.0 there.
  const CosimResult on_ground = measure_across(0.0, /*ego=*/true, 0, 0.03);
  EXPECT_EQ(on_ground.z_error_m.count, 0u);
  EXPECT_EQ(on_ground.z_error_body_m.count, 0u);
  ASSERT_EQ(on_ground.ego_z_error_m.count, 1u);
  EXPECT_NEAR(on_ground.ego_z_error_m.max, 0.03, 1e-6);
  EXPECT_EQ(on_ground.ego_steps_wheels_in_air, 0u);
  EXPECT_NE(on_ground.worst_ego_z_place.find("vehicle 'car'"), std::string::npos);

  const CosimResult flying = measure_across(0.0, /*ego=*/true, 2, 0.4);
  EXPECT_EQ(flying.z_error_m.count, 0u);
  EXPECT_EQ(flying.ego_z_error_m.count, 0u);
  EXPECT_EQ(flying.ego_steps_wheels_in_air, 1u);
  EXPECT_NEAR(flying.wheels_in_air_z_max_m, 0.4, 1e-6);
  EXPECT_NE(flying.worst_in_air_place.find("vehicle 'car'"), std::string::npos);

  // The same body placed on the surface by relief is a placement, 0.4 m off.
  const CosimResult placed = measure_across(0.0, /*ego=*/false, 0, 0.4);
  ASSERT_EQ(placed.z_error_m.count, 1u);
  EXPECT_NEAR(placed.z_error_m.max, 0.4, 1e-6);
  EXPECT_EQ(placed.ego_z_error_m.count, 0u);
}

}  // namespace
}  // namespace relief

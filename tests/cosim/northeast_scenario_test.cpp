// Issue 16's real scenario: San Francisco's NE quadrant (1 500 random trips over 300 s, 20 of
// them egos driven by the physics), SUMO in this process and every vehicle set on relief's
// scene at 20 Hz for 300 s, measured against the OpenDRIVE surface (README, "Co-simulation
// checks"). 219 s in the Release suite of CI; not run under the sanitizers (.ci/run).

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>

#include "relief/cosim/cosim.h"
#include "relief/pipeline/build.h"
#include "support/test_data.h"

namespace relief {
namespace {

namespace fs = std::filesystem;

TEST(CosimRealData, NortheastFor300sAt20HzSitsOnTheOpenDriveSurface) {
  RELIEF_REQUIRE_SHARED_DATA();
  const fs::path dir = test::scratch_dir("cosim_northeast");
  BuildOptions o;
  o.osm_path = test::shared_data("sf-ne/sf_ne_drive_2017.osm.gz");
  o.dem_paths = {test::shared_data("sf-ne/sf_ne_usgs24k_30m_nad27utm10_m.tif").string()};
  o.out_dir = dir / "out";
  o.outputs = {Output::report, Output::xodr, Output::sumo, Output::mesh};
  o.mesh_formats = {MeshFormat::glb};
  o.demand.trips = 1500;
  o.demand.end_s = 300.0;
  Diagnostics build_diagnostics;
  (void)build(o, build_diagnostics);

  CosimOptions options;
  options.end_s = 300.0;
  options.ego_count = 20;
  options.replay_period_s = 0.0;
  Diagnostics d;
  const CosimResult r =
      run_cosim(find_cosim_inputs(dir / "out" / "sf_ne_drive_2017.sumocfg"), options, dir / "cosim", d);
  std::cout << std::setprecision(3) << "  NE 300 s: " << r.vehicles << " vehicles (" << r.max_vehicles
            << " at once), body z vs the "
            << "OpenDRIVE surface p99 " << r.z_error_body_m.p99 << " m, max " << r.z_error_body_m.max
            << " m; SUMO z max " << r.sumo_z_error_m.max << " m; deepest wheel " << r.wheel_under_m.max
            << " m (" << r.wheels_under_road << " over 0.05 m); egos: sync p99 " << r.sync_error_m.p99
            << " m, " << r.resyncs << " resyncs, z p99 " << r.ego_z_error_m.p99 << " m, "
            << r.ego_steps_wheels_in_air << " steps with a wheel in the air\n";

  // 20 Hz for 300 s; at least 300 vehicles, as the issue asks; every one placed.
  EXPECT_EQ(r.steps, 6000u);
  EXPECT_GE(r.vehicles, 1000u);  // measured 1434
  EXPECT_GE(r.max_vehicles, 300u);
  EXPECT_EQ(r.unplaced, 0u);
  EXPECT_LT(r.unmapped, r.vehicle_steps / 1000);  // measured 1041 of 4.0 million
  // Every vehicle SUMO moves, set on the scene, against the same wheel contacts on the
  // OpenDRIVE surface: issue 16's p99 0.02 m and max 0.05 m.
  EXPECT_GE(r.z_error_body_m.count, r.vehicle_steps * 9 / 10);
  EXPECT_LE(r.z_error_body_m.p99, 0.02);
  EXPECT_LE(r.z_error_body_m.max, 0.05);
  EXPECT_LE(r.sumo_z_error_m.max, 0.05);  // SUMO's own lane heights on the surface
  // The deepest wheel under a rigid body is road 220's hairpin (150 degrees within 6 m on a
  // climb), where the surface twists 0.33 m over a car's wheels, in the scene and the .xodr
  // alike: issue 16's 0.05 m is not met there (README). A known failure, asserted so that a fix
  // is noticed.
  EXPECT_GT(r.wheel_under_m.max, 0.05);
  EXPECT_LT(r.wheel_under_m.max, 0.09);
  EXPECT_LT(r.wheels_under_road, 400u);  // measured 250 contacts of 16 million
  // The egos: the paper's sync error, resyncs counted; their physics bodies on the surface.
  EXPECT_EQ(r.egos, 20u);
  EXPECT_LE(r.sync_error_m.p99, 0.5);
  EXPECT_GT(r.resyncs, 0u);
  EXPECT_LE(r.ego_z_error_m.p99, 0.03);  // measured 0.018 m
  std::ifstream json(dir / "cosim" / "cosim.json");
  const nlohmann::json j = nlohmann::json::parse(json);
  EXPECT_EQ(j.at("resyncs").get<std::size_t>(), r.resyncs);
  EXPECT_EQ(j.at("ego_steps_wheels_in_air").get<std::size_t>(), r.ego_steps_wheels_in_air);
}

}  // namespace
}  // namespace relief

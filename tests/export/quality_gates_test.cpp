#include "relief/export/quality_gates.h"

#include <gtest/gtest.h>

#include <algorithm>

namespace relief {
namespace {

const Gate& gate(const std::vector<Gate>& gates, const std::string& name) {
  const auto it = std::find_if(gates.begin(), gates.end(), [&](const Gate& g) { return g.name == name; });
  if (it == gates.end()) throw std::runtime_error("no gate " + name);
  return *it;
}

RunReport good_report() {
  RunReport r;
  r.profile_method = "relief";
  FitSummary fit;
  fit.converged = true;
  r.fit = fit;
  MethodReport m;
  m.method = "relief";
  m.ground.vs_dem.rmse_m = 0.2;
  m.ground.vs_dem.max_m = 3.0;
  r.methods = {m};
  r.model_grades = ModelGrades{};
  r.opendrive = OpenDriveSummary{};
  r.sumo = SumoSummary{};
  MeshSummary mesh;
  mesh.road = MeshQuality{};
  r.mesh = mesh;
  return r;
}

TEST(QualityGates, AGoodBuildPassesEveryGate) {
  const std::vector<Gate> gates = evaluate_gates(good_report(), {});
  EXPECT_EQ(gates.size(), GateThresholds::names().size());
  EXPECT_TRUE(failed_gates(gates).empty());
  for (const Gate& g : gates) EXPECT_TRUE(g.where.empty()) << g.name;
}

TEST(QualityGates, EachFailureIsNamedWithItsValueThresholdAndPlace) {
  RunReport r = good_report();
  r.fit->converged = false;
  r.fit->solver = "iteration limit";
  FitViolation v;
  v.limit = FitLimit::clearance;
  v.road = 12;
  v.osm_way_id = 345;
  v.s_m = 67.0;
  v.value = 3.2;
  v.bound = 5.0;
  r.fit->violations = {v};
  r.methods[0].ground.vs_dem.rmse_m = 2.5;
  r.methods[0].ground.max_road = 7;
  r.methods[0].ground.max_osm_way = 4242;
  r.methods[0].ground.max_xy = Vec2(10.0, -20.0);
  r.methods[0].ground.max_error_m = -3.04;
  r.sumo->z_max_m = 0.2;
  r.sumo->z_max_lane = "17_0";
  r.sumo->height_steps = 2;
  r.sumo->first_step_lane = ":J3_0_0";
  r.mesh->road->self_intersecting_pairs = 4;
  r.mesh->junctions_failed = 1;
  r.mesh->first_failed_junction = "junction 167 at (1369.2, -779.5, 161.92)";
  r.model_grades->connecting_roads.max_excess_percent = 26.0;
  r.model_grades->connecting_roads.worst_road = 1550;
  const std::vector<Gate> failed = failed_gates(evaluate_gates(r, {}));
  ASSERT_EQ(failed.size(), 8u);
  EXPECT_EQ(gate(failed, "fit_converged").where, "iteration limit");
  EXPECT_NE(
      gate(failed, "fit_limits_violated").where.find("clearance on road 12 (OSM way 345) at s = 67.0 m"),
      std::string::npos);
  EXPECT_DOUBLE_EQ(gate(failed, "ground_vs_dem_rmse_m").value, 2.5);
  EXPECT_DOUBLE_EQ(gate(failed, "ground_vs_dem_rmse_m").threshold, 2.0);
  EXPECT_EQ(gate(failed, "ground_vs_dem_rmse_m").where,
            "largest at OSM way 4242 (10.0, -20.0), road -3.0 m from the DEM");
  EXPECT_EQ(gate(failed, "sumo_lane_z_max_m").where, "lane 17_0");
  EXPECT_NE(gate(failed, "sumo_height_steps").where.find(":J3_0_0"), std::string::npos);
  EXPECT_NE(gate(failed, "connecting_road_grade_over_cap_percent").where.find("road 1550"),
            std::string::npos);
  EXPECT_EQ(gate(failed, "junctions_open").where, "junction 167 at (1369.2, -779.5, 161.92)");
}

TEST(QualityGates, ThresholdsAreSetByName) {
  GateThresholds t;
  EXPECT_TRUE(t.set("ground_vs_dem_rmse_m", 3.0));
  EXPECT_DOUBLE_EQ(t.ground_vs_dem_rmse_m, 3.0);
  EXPECT_FALSE(t.set("no_such_gate", 1.0));
  RunReport r = good_report();
  r.methods[0].ground.vs_dem.rmse_m = 2.5;
  EXPECT_TRUE(gate(evaluate_gates(r, t), "ground_vs_dem_rmse_m").passed);
}

TEST(QualityGates, OnlyTheOutputsBuiltAreGated) {
  RunReport r;
  r.profile_method = "raw";
  EXPECT_TRUE(evaluate_gates(r, {}).empty());
}

}  // namespace
}  // namespace relief

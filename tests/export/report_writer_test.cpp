#include "relief/export/report_writer.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace relief {
namespace {

TEST(ReportWriter, CarriesTheDocumentedKeys) {
  RunReport r;
  r.name = "t";
  r.frame = GeoFrame("EPSG:32610", Vec2(552000, 4178600));
  r.network.roads = 3;
  r.network.junctions = 1;
  r.network.length_km = 0.3;
  r.heights.vs_dem = ErrorStats{0.01, 0.02, 0.05, 0.0, 200};
  r.gradient.max_percent = 12.345;
  r.gradient.by_class["residential"] = GradeClassStats{0.3, 15.0, 100.0, 12.345, 11.0};
  r.junctions.max_gap_m = 0.0;
  r.timings_s = {{"read OSM", 0.25}, {"build network", 0.5}};
  Diagnostics d;
  d.report(Severity::warning, "osm.missing_node", "way 1 misses node 2");
  r.diagnostics = &d;
  DemInfo dem;
  dem.path = "dem.tif";
  dem.implausible_cells = 2;
  dem.spike_cells = 1;
  r.dems = {dem};
  r.model_grades = ModelGrades{};
  r.model_grades->cross_slopes.max_percent = 35.604;
  r.model_grades->cross_slopes.worst_road = 934;
  r.model_grades->cross_slopes.length_over_m = 43355.0;
  r.model_grades->cross_slopes.roads_over = 1462;
  const auto j = nlohmann::json::parse(report_json(r));
  const auto& cross = j["model_grades"]["cross_slopes"];
  EXPECT_DOUBLE_EQ(cross["max_percent"].get<double>(), 35.6);
  EXPECT_EQ(cross["worst_road"], 934);
  EXPECT_DOUBLE_EQ(cross["over_8_percent_km"].get<double>(), 43.355);
  EXPECT_EQ(cross["roads_over_8_percent"], 1462);
  EXPECT_TRUE(j["model_grades"].contains("roads") && j["model_grades"].contains("connecting_roads"));
  EXPECT_EQ(j["inputs"]["dems"][0]["path"], "dem.tif");
  EXPECT_EQ(j["inputs"]["dems"][0]["implausible_cells"], 2);
  EXPECT_EQ(j["inputs"]["dems"][0]["spike_cells"], 1);
  EXPECT_EQ(j["network"]["roads"], 3);
  EXPECT_EQ(j["network"]["junctions"], 1);
  EXPECT_DOUBLE_EQ(j["network"]["length_km"].get<double>(), 0.3);
  EXPECT_DOUBLE_EQ(j["elevation"]["vs_dem"]["rmse_m"].get<double>(), 0.02);
  EXPECT_EQ(j["elevation"]["vs_dem"]["n"], 200);
  EXPECT_TRUE(j["elevation"]["vs_reference"].is_null());
  EXPECT_DOUBLE_EQ(j["gradient"]["max_percent"].get<double>(), 12.35);
  EXPECT_DOUBLE_EQ(j["gradient"]["by_class"]["residential"]["limit_percent"].get<double>(), 15.0);
  EXPECT_TRUE(j["gradient"].contains("compliance_percent"));
  EXPECT_TRUE(j["gradient"].contains("p99_percent"));
  EXPECT_DOUBLE_EQ(j["junctions"]["max_gap_m"].get<double>(), 0.0);
  EXPECT_DOUBLE_EQ(j["timings_s"]["total"].get<double>(), 0.75);
  EXPECT_EQ(j["diagnostics"]["counts"]["osm.missing_node"], 1);
  EXPECT_EQ(j["frame"]["crs"], "EPSG:32610");
  EXPECT_DOUBLE_EQ(j["frame"]["origin"][0].get<double>(), 552000.0);
  EXPECT_NE(j["attribution"].get<std::string>().find("ODbL"), std::string::npos);
}

}  // namespace
}  // namespace relief

#include "relief/export/mesh_report.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace relief {
namespace {

MeshQuality road_figures() {
  MeshQuality q;
  q.name = "Road_Road";
  q.vertices = 9;
  q.triangles = 8;
  q.components = 1;
  q.boundary_edges = 8;
  q.boundary_loops = 1;
  q.holes = 0;
  q.non_manifold_edges = 2;
  q.non_manifold_vertices = 3;
  q.inconsistent_orientation_edges = 4;
  q.upside_down_triangles = 5;
  q.self_intersecting_pairs = 6;
  q.self_intersections_checked = true;
  q.degenerate_triangles = 7;
  q.sliver_triangles = 1;
  q.min_angle_deg = 45.0;
  q.max_aspect_ratio = 2.0;
  q.area_m2 = 4.0;
  q.bounds.extend(Vec2(-1.5, 2.0));
  q.bounds.extend(Vec2(10.25, 20.0));
  q.min_z = 101.12341;
  q.max_z = 105.5;
  return q;
}

TEST(MeshReport, CarriesTheFigures) {
  MeshQuality terrain;
  terrain.name = "Terrain";  // nothing measured: no bounds, self-intersections not tested
  MeshReportExtras extras;
  extras.file = "scene.glb";
  extras.seam_road_junction_m = 0.00123;
  extras.xodr_surface_max_distance_m = 0.02;
  const auto j = nlohmann::json::parse(mesh_report_json({road_figures(), terrain}, extras));
  EXPECT_EQ(j["file"], "scene.glb");
  ASSERT_EQ(j["meshes"].size(), 2u);
  const auto& road = j["meshes"][0];
  EXPECT_EQ(road["name"], "Road_Road");
  EXPECT_EQ(road["vertices"], 9);
  EXPECT_EQ(road["triangles"], 8);
  EXPECT_EQ(road["components"], 1);
  EXPECT_EQ(road["boundary_edges"], 8);
  EXPECT_EQ(road["boundary_loops"], 1);
  EXPECT_EQ(road["holes"], 0);
  EXPECT_EQ(road["non_manifold_edges"], 2);
  EXPECT_EQ(road["non_manifold_vertices"], 3);
  EXPECT_EQ(road["inconsistent_orientation_edges"], 4);
  EXPECT_EQ(road["upside_down_triangles"], 5);
  EXPECT_EQ(road["self_intersecting_pairs"], 6);
  EXPECT_EQ(road["degenerate_triangles"], 7);
  EXPECT_EQ(road["sliver_triangles"], 1);
  EXPECT_DOUBLE_EQ(road["min_angle_deg"].get<double>(), 45.0);
  EXPECT_DOUBLE_EQ(road["max_aspect_ratio"].get<double>(), 2.0);
  EXPECT_DOUBLE_EQ(road["area_m2"].get<double>(), 4.0);
  EXPECT_DOUBLE_EQ(road["bounds"]["min_x"].get<double>(), -1.5);
  EXPECT_DOUBLE_EQ(road["bounds"]["min_y"].get<double>(), 2.0);
  EXPECT_DOUBLE_EQ(road["bounds"]["max_x"].get<double>(), 10.25);
  EXPECT_DOUBLE_EQ(road["bounds"]["max_y"].get<double>(), 20.0);
  EXPECT_NEAR(road["z"]["min"].get<double>(), 101.1234, 1e-9);  // rounded to 0.1 mm
  EXPECT_DOUBLE_EQ(road["z"]["max"].get<double>(), 105.5);
  const auto& ground = j["meshes"][1];
  EXPECT_TRUE(ground["self_intersecting_pairs"].is_null());
  EXPECT_TRUE(ground["bounds"].is_null());
  EXPECT_TRUE(ground["z"].is_null());
  EXPECT_NEAR(j["seams"]["road_junction_max_gap_m"].get<double>(), 0.0012, 1e-12);
  EXPECT_TRUE(j["seams"]["road_terrain_max_gap_m"].is_null());
  EXPECT_DOUBLE_EQ(j["xodr_surface_max_distance_m"].get<double>(), 0.02);
}

TEST(MeshReport, EmptyReportParses) {
  const auto j = nlohmann::json::parse(mesh_report_json({}, {}));
  EXPECT_TRUE(j["meshes"].is_array());
  EXPECT_TRUE(j["meshes"].empty());
  EXPECT_TRUE(j["xodr_surface_max_distance_m"].is_null());
  EXPECT_FALSE(j["relief_version"].get<std::string>().empty());
}

}  // namespace
}  // namespace relief

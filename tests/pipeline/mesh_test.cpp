// The 3D scene that `build` writes (pipeline/mesh_stage.cpp): its figures on the real San
// Francisco data, the files read back by assimp and by Blender, and tiny synthetic networks with
// exact answers.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <numbers>
#include <optional>
#include <regex>
#include <set>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "pipeline/sf_options.h"
#include "relief/export/mesh_writer.h"
#include "relief/geometry/crs_transform.h"
#include "relief/pipeline/build.h"
#include "support/blender.h"
#include "support/osm_sketch.h"
#include "support/synthetic.h"
#include "support/tar_reader.h"
#include "support/test_data.h"

namespace relief {
namespace {

// --- helpers ---------------------------------------------------------------------------------

std::string read_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

BuildOptions scene_options(BuildOptions o) {
  o.outputs = {Output::xodr, Output::mesh, Output::report};
  o.mesh_formats = {MeshFormat::glb, MeshFormat::obj, MeshFormat::fbx};
  o.compare_methods = false;  // the scene carries relief's fit either way
  return o;
}

struct SceneBuild {
  BuildOptions options;
  BuildResult result;
  nlohmann::json mesh_report;                      ///< mesh_report.json
  std::map<std::string, std::size_t> diagnostics;  ///< count per code
};

SceneBuild build_scene(const BuildOptions& options) {
  SceneBuild b{options, {}, {}, {}};
  Diagnostics d;
  b.result = build(options, d);
  b.diagnostics = d.counts();
  std::ifstream in(options.out_dir / "mesh_report.json");
  b.mesh_report = nlohmann::json::parse(in);
  return b;
}

// The default build of an SF set, shared with the other tests of its suite (test::sf_potrero):
// its scene in all three formats, with mesh_report.json read back.
SceneBuild scene_of(const test::SfBuild& sf) {
  SceneBuild b{sf.options, sf.result, {}, sf.diagnostics};
  std::ifstream in(sf.options.out_dir / "mesh_report.json");
  b.mesh_report = nlohmann::json::parse(in);
  return b;
}

const SceneBuild& potrero() {
  static const SceneBuild b = scene_of(test::sf_potrero());
  return b;
}

const SceneBuild& northeast() {
  static const SceneBuild b = scene_of(test::sf_northeast());
  return b;
}

// The report's mesh figures; throws (failing the test) when the build made no road or terrain mesh.
const MeshSummary& summary(const SceneBuild& b) {
  const auto& m = b.result.report.mesh;
  if (!m || !m->road || !m->terrain)
    throw std::runtime_error("the report has no Road_Road or Terrain figures");
  return *m;
}

void print(const std::string& name, const MeshSummary& m) {
  std::cout << name << ": junctions meshed " << m.junctions_meshed << " failed " << m.junctions_failed
            << ", xodr surface max " << m.xodr_surface_max_distance_m << " m, seams road/junction "
            << m.seam_road_junction_m << " road/terrain " << m.seam_road_terrain_m.value_or(-1.0)
            << ", Road_Road: " << m.road->triangles << " triangles, non-manifold edges "
            << m.road->non_manifold_edges << ", self-intersecting pairs " << m.road->self_intersecting_pairs
            << ", upside down " << m.road->upside_down_triangles << "; Terrain " << m.terrain->triangles
            << " triangles, max vertical error " << m.terrain_max_vertical_error_m << " m; ground holes "
            << m.ground_holes << ", tunnel mouths " << m.ground_portals << ", components "
            << m.ground_components << ", road triangles under roads " << m.ground_triangles_under_roads
            << "\n";
}

// Upper bounds of the known defects of a data set (measured; a regression goes above them).
struct KnownDefects {
  std::size_t junctions_failed = 0;
  std::size_t self_intersecting_pairs = 0;
  std::size_t upside_down_triangles = 0;
  std::size_t ground_triangles_under_roads = 0;  ///< left out of the ground (plan_overlaps)
  std::size_t ground_portals = 0;                ///< openings: tunnel mouths, underpasses (exact)
  std::size_t structure_terrain_pairs = 0;       ///< decks / tunnels x terrain, intersecting
  std::size_t ground_components = 1;             ///< roads on the ground + terrain, welded
};

void expect_scene_figures(const MeshSummary& m, const KnownDefects& known) {
  ASSERT_TRUE(m.road && m.terrain);
  EXPECT_EQ(m.road->non_manifold_edges, 0u);
  EXPECT_TRUE(m.road->self_intersections_checked);
  EXPECT_LE(m.xodr_surface_max_distance_m, 0.02 + 1e-9);
  ASSERT_TRUE(m.seam_road_terrain_m);
  EXPECT_EQ(*m.seam_road_terrain_m, 0.0);
  EXPECT_LE(m.seam_road_junction_m, 0.1);
  EXPECT_LE(m.terrain_max_vertical_error_m, 0.25 + 1e-9);  // TerrainOptions::vertical_tolerance_m
  EXPECT_LE(m.junctions_failed, known.junctions_failed);
  EXPECT_LE(m.road->self_intersecting_pairs, known.self_intersecting_pairs);
  EXPECT_LE(m.road->upside_down_triangles, known.upside_down_triangles);
  // Roads on the ground and the terrain close into one surface with one outer edge.
  EXPECT_EQ(m.ground_holes, 0u);
  EXPECT_EQ(m.ground_components, known.ground_components);
  EXPECT_LE(m.ground_triangles_under_roads, known.ground_triangles_under_roads);
  EXPECT_EQ(m.ground_portals, known.ground_portals);
  EXPECT_LE(m.structure_terrain_intersecting_pairs, known.structure_terrain_pairs);
}

// Structures crossing the terrain are reported once, with their sites, as a warning.
void expect_structure_warning(const SceneBuild& b, const MeshSummary& m) {
  const auto it = b.diagnostics.find("mesh.structure_terrain_intersections");
  EXPECT_EQ(it == b.diagnostics.end() ? 0u : it->second,
            m.structure_terrain_intersecting_pairs > 0 ? 1u : 0u);
  const auto road = b.diagnostics.find("mesh.road_self_intersections");
  EXPECT_EQ(road == b.diagnostics.end() ? 0u : road->second,
            m.road && m.road->self_intersecting_pairs > 0 ? 1u : 0u);
}

// The warning on Road_Road's self-intersections names the owners of the pairs (road and OSM
// way, connecting road and junction, or junction) and where they are.
std::string self_intersection_message(const SceneBuild& b) {
  std::ifstream in(b.options.out_dir / "report.json");
  const nlohmann::json report = nlohmann::json::parse(in);
  for (const auto& d : report.at("diagnostics").at("messages"))
    if (d.at("code") == "mesh.road_self_intersections") return d.at("message").get<std::string>();
  return {};
}

struct Box {
  Vec3 lo = Vec3::Constant(1e300);
  Vec3 hi = Vec3::Constant(-1e300);
};

// Box of the vertices the triangles use.
Box used_box(const TriangleMesh& m) {
  Box b;
  for (const auto& t : m.triangles) {
    for (const auto v : t) {
      b.lo = b.lo.cwiseMin(m.vertices[v]);
      b.hi = b.hi.cwiseMax(m.vertices[v]);
    }
  }
  return b;
}

const TriangleMesh* find_mesh(const MeshScene& scene, const std::string& name) {
  for (const TriangleMesh& m : scene.meshes)
    if (m.name == name) return &m;
  return nullptr;
}

// Height at `p` (plan) of the first of `triangles` of `m` that covers it.
std::optional<double> height_at(const TriangleMesh& m, const std::vector<std::size_t>& triangles,
                                const Vec2& p) {
  for (const std::size_t t : triangles) {
    const Vec3& a = m.vertices[m.triangles[t][0]];
    const Vec3& b = m.vertices[m.triangles[t][1]];
    const Vec3& c = m.vertices[m.triangles[t][2]];
    const double det = (b.x() - a.x()) * (c.y() - a.y()) - (c.x() - a.x()) * (b.y() - a.y());
    if (std::abs(det) < 1e-12) continue;
    const double u = ((p.x() - a.x()) * (c.y() - a.y()) - (c.x() - a.x()) * (p.y() - a.y())) / det;
    const double v = ((b.x() - a.x()) * (p.y() - a.y()) - (p.x() - a.x()) * (b.y() - a.y())) / det;
    if (u >= 0.0 && v >= 0.0 && u + v <= 1.0) return a.z() + u * (b.z() - a.z()) + v * (c.z() - a.z());
  }
  return std::nullopt;
}

// The meshes of the files (mesh_report.json also has the welded ground, which is no file mesh).
std::map<std::string, nlohmann::json> file_meshes(const nlohmann::json& mesh_report) {
  std::map<std::string, nlohmann::json> out;
  for (const auto& m : mesh_report["meshes"]) {
    const std::string name = m["name"].get<std::string>();
    if (!name.starts_with("Ground")) out[name] = m;
  }
  return out;
}

// Every mesh file written re-imports with assimp: the meshes of mesh_report.json by name, with
// its triangle counts and (0.1 mm rounded) bounds within 1 mm; triangle corners of the .obj and
// .fbx equal the .glb's within 1 mm at every 97th triangle (triangle and corner order survive).
void expect_files_reimport(const SceneBuild& b) {
  const auto expected = file_meshes(b.mesh_report);
  ASSERT_GE(expected.size(), 3u);  // Road_Road, Road_Marking, Terrain at least
  const std::string name = b.result.report.name;
  const MeshScene glb = read_mesh_file(b.options.out_dir / (name + ".glb"));
  for (const char* ext : {".glb", ".obj", ".fbx"}) {
    SCOPED_TRACE(ext);
    const MeshScene scene =
        ext == std::string(".glb") ? glb : read_mesh_file(b.options.out_dir / (name + ext));
    EXPECT_EQ(scene.meshes.size(), expected.size());
    for (const auto& [mesh_name, want] : expected) {
      SCOPED_TRACE(mesh_name);
      const TriangleMesh* m = find_mesh(scene, mesh_name);
      ASSERT_NE(m, nullptr);
      EXPECT_EQ(m->triangles.size(), want["triangles"].get<std::size_t>());
      const Box box = used_box(*m);
      constexpr double kTolM = 1e-3;
      EXPECT_NEAR(box.lo.x(), want["bounds"]["min_x"].get<double>(), kTolM);
      EXPECT_NEAR(box.lo.y(), want["bounds"]["min_y"].get<double>(), kTolM);
      EXPECT_NEAR(box.hi.x(), want["bounds"]["max_x"].get<double>(), kTolM);
      EXPECT_NEAR(box.hi.y(), want["bounds"]["max_y"].get<double>(), kTolM);
      EXPECT_NEAR(box.lo.z(), want["z"]["min"].get<double>(), kTolM);
      EXPECT_NEAR(box.hi.z(), want["z"]["max"].get<double>(), kTolM);
      const TriangleMesh* ref = find_mesh(glb, mesh_name);
      ASSERT_NE(ref, nullptr);
      ASSERT_EQ(ref->triangles.size(), m->triangles.size());
      double worst_m = 0.0;
      for (std::size_t t = 0; t < m->triangles.size(); t += 97) {
        for (int c = 0; c < 3; ++c) {
          worst_m = std::max(worst_m,
                             (m->vertices[m->triangles[t][c]] - ref->vertices[ref->triangles[t][c]]).norm());
        }
      }
      EXPECT_LE(worst_m, kTolM);
    }
  }
}

// --- San Francisco ---------------------------------------------------------------------------

TEST(SfPotrero, MeshSceneFigures) {
  RELIEF_REQUIRE_SHARED_DATA();
  const SceneBuild& b = potrero();
  const MeshSummary& m = summary(b);
  print("potrero", m);
  // Every junction meshed: junction 42's outline crossed itself until a service loop's ends
  // stopped counting the loop's far half as overlapping them (it was trimmed to 11 m); junction
  // 25 (a sharp motorway-link fork whose kerb line cut across the neighbouring end) takes
  // straight gaps. 6 road triangles lie under others in
  // plan (overlapping road ends at (-370, -242), (361, -213), and a street end 5.6 m under
  // 23rd Street's abutment at (-349, 133), which is the one opening) and are left out of the
  // ground, which had 8 holes before. Three deck triangle x terrain pairs (one before the roads
  // took their junctions' cross-slope at their ends, tilting the deck ends a few centimetres).
  // The kerb of a tight turn at (360, -213) bulged 2 cm back over the road it leaves; once the
  // road end was tilted the two surfaces crossed there, and such kerb points are now dropped.
  expect_scene_figures(m, {.junctions_failed = 0,
                           .self_intersecting_pairs = 0,
                           .upside_down_triangles = 0,
                           .ground_triangles_under_roads = 6,
                           .ground_portals = 1,
                           .structure_terrain_pairs = 3});
  expect_structure_warning(b, m);
}

TEST(SfNortheast, MeshSceneFiguresAndReimport) {
  RELIEF_REQUIRE_SHARED_DATA();
  const SceneBuild& b = northeast();
  const MeshSummary& m = summary(b);
  print("sf-ne", m);
  // Measured: 170 road triangles lie under other roads in plan (the Broadway and Stockton tunnel
  // approaches under the streets over their portals, Broadway under Hyde Street's abutments,
  // ramps, ways closer than their widths) and are left out of the ground, which had 34 holes
  // before; 11 openings: 6 tunnel mouths (Broadway's two bores and Stockton; the 1st Street
  // "tunnel" has no cover and is open) and 5 underpasses. 9 pairs of road pieces under other
  // roads x the terrain closing the step over them, at (1040, 522) and (-291, 588); 25 until the
  // terrain kept under decks (a fill slope rose through a ramp deck at (1585-1602, -1013..-1026)),
  // 220 before decks on the DEM and tunnels without cover counted as ground. The 3 Road_Road pairs that
  // intersected at (1690, -908) were the James Lick Freeway viaduct lying on Perry Street (cut off by the
  // data's edge, it followed the DEM); alongside separations now lift it. Before forks could trim
  // from the whole road, close junctions were joined and two arriving one-ways stopped getting a
  // hairpin transition road: 6 junctions open, 16 pairs, 85 upside-down triangles, 58 holes.
  // 6 Road_Road pairs at (1038, 525) until the junction's ends cleared the transition road
  // beyond Montgomery Street's short end (Columbus Avenue's end lay over it).
  expect_scene_figures(m, {.junctions_failed = 0,
                           .self_intersecting_pairs = 0,
                           .upside_down_triangles = 0,
                           // 175 before the junction patches took every point of their height
                           // surface (smaller triangles over the same overlaps), 188 before the
                           // ends at acute corners were trimmed for turns 3 m round (larger
                           // junctions there), 195 before the 0.4 mm elevation records
                           .ground_triangles_under_roads = 197,
                           // 11 before the road ends took their junctions' cross-slope, 13
                           // before the fit bounded grades between lane centres across junctions,
                           // 14 before junction patches carried their connecting roads' lane
                           // heights inside (three loops of 3, 4 and 6 vertices beside the opening
                           // at (1641, -955) are part of it now)
                           .ground_portals = 11,
                           // 9 before the fit kept design-speed vertical curves on the freeway
                           // decks and clearances over each road's paved edges (warning, sited);
                           // 12 before the ramp ends at (1645, -965), (1676, -940) were tilted
                           .structure_terrain_pairs = 21,
                           // 2 from when the fit bounded the grades between the lane centres of
                           // road ends across junctions until junction patches carried their
                           // connecting roads' lane heights inside: one piece of road on the ground
                           // joined the rest only through road pieces off it
                           .ground_components = 1});
  expect_structure_warning(b, m);
  expect_files_reimport(b);
}

TEST(SfPotrero, MeshFilesReimportWithAssimp) {
  RELIEF_REQUIRE_SHARED_DATA();
  expect_files_reimport(potrero());
}

// --mesh-tile-size: the scene cut into 250 m tiles, written beside the whole scene; read back,
// the tiles hold every triangle of every mesh once, each inside its tile's bounds, and carry
// the georeference and their place in the grid.
TEST(MeshPipeline, PotreroTilesAddUpToTheScene) {
  RELIEF_REQUIRE_SHARED_DATA();
  BuildOptions o = scene_options(test::potrero_options("mesh_potrero_tiles"));
  o.mesh_formats = {MeshFormat::glb};
  o.mesh_tile_size_m = 250.0;
  const SceneBuild b = build_scene(o);
  const MeshSummary& m = summary(b);
  ASSERT_FALSE(m.tile_files.empty());
  EXPECT_EQ(m.tile_size_m, 250.0);
  const MeshScene whole = read_mesh_file(o.out_dir / (b.result.report.name + ".glb"));
  std::map<std::string, std::size_t> triangles;
  for (const std::string& file : m.tile_files) {
    ASSERT_TRUE(file.starts_with(b.result.report.name + "_Tile_")) << file;
    const MeshScene tile = read_mesh_file(o.out_dir / file);
    ASSERT_TRUE(tile.metadata.contains("relief:tile_bounds")) << file;
    EXPECT_EQ(tile.metadata.at("relief:crs"), whole.metadata.at("relief:crs"));
    std::istringstream bounds(tile.metadata.at("relief:tile_bounds"));
    double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    bounds >> x0 >> y0 >> x1 >> y1;
    EXPECT_NEAR(x1 - x0, 250.0, 1e-9);
    for (const TriangleMesh& mesh : tile.meshes) {
      triangles[mesh.name] += mesh.triangles.size();
      for (const auto& t : mesh.triangles) {
        const Vec3 c = (mesh.vertices[t[0]] + mesh.vertices[t[1]] + mesh.vertices[t[2]]) / 3.0;
        EXPECT_GE(c.x(), x0 - 1e-3);  // float storage
        EXPECT_LE(c.x(), x1 + 1e-3);
        EXPECT_GE(c.y(), y0 - 1e-3);
        EXPECT_LE(c.y(), y1 + 1e-3);
      }
    }
  }
  for (const TriangleMesh& mesh : whole.meshes)
    EXPECT_EQ(triangles[mesh.name], mesh.triangles.size()) << mesh.name;
}

// --carla-package on Potrero: NAME.carla.tar.gz holds the package folder, its JSON naming the
// map and its files, and NAME.fbx and NAME.xodr byte for byte as the build wrote them beside it.
TEST(MeshPipeline, PotreroCarlaPackageHoldsTheFilesWritten) {
  RELIEF_REQUIRE_SHARED_DATA();
  BuildOptions o = scene_options(test::potrero_options("mesh_potrero_carla"));
  o.mesh_formats = {MeshFormat::fbx};
  o.carla_package = true;
  const SceneBuild b = build_scene(o);
  const MeshSummary& m = summary(b);
  const std::string name = b.result.report.name;
  ASSERT_EQ(m.carla_package, name + ".carla.tar.gz");
  EXPECT_TRUE(m.carla_placeholder_tiles.empty());
  const auto entries = test::read_tar_gz(read_bytes(o.out_dir / m.carla_package));
  std::vector<std::string> paths;
  for (const auto& [path, e] : entries) paths.push_back(path);
  std::vector<std::string> expected = m.carla_package_entries;
  std::sort(expected.begin(), expected.end());
  EXPECT_EQ(paths, expected);
  const std::string root = name + "/";
  const nlohmann::json j = nlohmann::json::parse(entries.at(root + name + ".json").bytes);
  EXPECT_EQ(j["maps"][0]["name"], name);
  EXPECT_EQ(j["maps"][0]["source"], "./" + name + "/" + name + ".fbx");
  EXPECT_EQ(entries.at(root + name + "/" + name + ".fbx").bytes, read_bytes(o.out_dir / (name + ".fbx")));
  EXPECT_EQ(entries.at(root + name + "/" + name + ".xodr").bytes, read_bytes(o.out_dir / (name + ".xodr")));
  std::ifstream report(o.out_dir / "report.json");
  const nlohmann::json r = nlohmann::json::parse(report);
  EXPECT_EQ(r["mesh"]["carla_package"]["file"], name + ".carla.tar.gz");
  EXPECT_EQ(r["mesh"]["carla_package"]["entries"].size(), 5u);
}

// With 250 m tiles: CARLA's large map of every FBX tile written, plus a placeholder for each
// tile of the grid's rectangle without triangles (Potrero's DEM footprint leaves the south-west
// and south-east corner tiles empty), so that CARLA's cook, which stops a row at its first
// missing tile, imports every tile.
TEST(MeshPipeline, PotreroCarlaLargeMapFillsTheTileGrid) {
  RELIEF_REQUIRE_SHARED_DATA();
  BuildOptions o = scene_options(test::potrero_options("mesh_potrero_carla_tiles"));
  o.mesh_formats = {MeshFormat::fbx};
  o.mesh_tile_size_m = 250.0;
  o.carla_package = true;
  const SceneBuild b = build_scene(o);
  const MeshSummary& m = summary(b);
  const std::string name = b.result.report.name;
  EXPECT_EQ(m.carla_placeholder_tiles, (std::vector<std::string>{"0 0", "3 0"}));
  EXPECT_EQ(b.diagnostics.count("carla.tile_grid_gap"), 1u);
  const auto entries = test::read_tar_gz(read_bytes(o.out_dir / m.carla_package));
  const nlohmann::json map = nlohmann::json::parse(entries.at(name + "/" + name + ".json").bytes)["maps"][0];
  EXPECT_EQ(map["tile_size"], 250);
  EXPECT_EQ(map["xodr"], "./" + name + ".xodr");
  std::set<std::string> listed;
  for (const auto& t : map["tiles"]) listed.insert(t.get<std::string>().substr(2));
  // Every tile written is in the package as written; the grid 0..3 x 0..3 is whole.
  for (const std::string& file : m.tile_files) {
    EXPECT_TRUE(listed.contains(file)) << file;
    EXPECT_EQ(entries.at(name + "/" + file).bytes, read_bytes(o.out_dir / file)) << file;
  }
  EXPECT_EQ(listed.size(), 16u);
  EXPECT_EQ(listed.size(), m.tile_files.size() + 2);
  const std::filesystem::path scratch = test::scratch_dir("mesh_potrero_carla_placeholder");
  for (const char* gap : {"_Tile_0_0.fbx", "_Tile_3_0.fbx"}) {
    const std::string file = name + gap;
    ASSERT_TRUE(listed.contains(file));
    EXPECT_FALSE(std::filesystem::exists(o.out_dir / file)) << "placeholders go into the package only";
    const std::filesystem::path copy = scratch / file;
    std::ofstream(copy, std::ios::binary) << entries.at(name + "/" + file).bytes;
    const MeshScene tile = read_mesh_file(copy);
    ASSERT_EQ(tile.meshes.size(), 1u);
    EXPECT_EQ(tile.meshes[0].name, "Placeholder");
    EXPECT_EQ(tile.meshes[0].triangles.size(), 1u);
  }
  // The placeholder of tile (0, 0) lies at its centre: the south-west corner of tile (1, 1), as
  // its written file's bounds give it, minus one and a half tiles.
  const MeshScene t11 = read_mesh_file(o.out_dir / (name + "_Tile_1_1.fbx"));
  std::istringstream bounds(t11.metadata.at("relief:tile_bounds"));
  double x0 = 0, y0 = 0;
  bounds >> x0 >> y0;
  const MeshScene p00 = read_mesh_file(scratch / (name + "_Tile_0_0.fbx"));
  Vec3 c = Vec3::Zero();
  for (const Vec3& v : p00.meshes[0].vertices) c += v / 3.0;
  EXPECT_NEAR(c.x(), x0 - 125.0, 0.05);
  EXPECT_NEAR(c.y(), y0 - 125.0, 0.05);
}

TEST(SfPotrero, MeshFbxImportsInBlender) {
  RELIEF_REQUIRE_SHARED_DATA();
  if (!test::have_blender()) GTEST_SKIP() << "blender is not on PATH";
  const SceneBuild& b = potrero();
  const auto fbx = b.options.out_dir / (b.result.report.name + ".fbx");
  const test::BlenderImports imports =
      test::import_in_blender({fbx}, test::scratch_dir("mesh_potrero_blender"));
  ASSERT_EQ(imports.by_file.count(fbx.string()), 1u) << imports.output;
  const nlohmann::json& objects = imports.by_file.at(fbx.string())["objects"];
  const auto expected = file_meshes(b.mesh_report);
  for (const char* name : {"Road_Road", "Road_Marking", "Terrain"})
    EXPECT_TRUE(expected.contains(name)) << name;
  EXPECT_EQ(objects.size(), expected.size()) << objects.dump();
  for (const auto& [name, want] : expected) {
    SCOPED_TRACE(name);
    ASSERT_TRUE(objects.contains(name)) << objects.dump();
    const nlohmann::json& o = objects[name];
    EXPECT_EQ(o["polygons"].get<std::size_t>(), want["triangles"].get<std::size_t>());
    // World box, Z up, metres: relief's local frame within 1 cm.
    constexpr double kTolM = 0.01;
    EXPECT_NEAR(o["min"][0].get<double>(), want["bounds"]["min_x"].get<double>(), kTolM);
    EXPECT_NEAR(o["min"][1].get<double>(), want["bounds"]["min_y"].get<double>(), kTolM);
    EXPECT_NEAR(o["min"][2].get<double>(), want["z"]["min"].get<double>(), kTolM);
    EXPECT_NEAR(o["max"][0].get<double>(), want["bounds"]["max_x"].get<double>(), kTolM);
    EXPECT_NEAR(o["max"][1].get<double>(), want["bounds"]["max_y"].get<double>(), kTolM);
    EXPECT_NEAR(o["max"][2].get<double>(), want["z"]["max"].get<double>(), kTolM);
  }
}

// --- Synthetic networks with exact answers ---------------------------------------------------

// WGS84 position of the synthetic frame's origin: sketches drawn there lie on the DEMs of
// write_local_dem.
LonLat synthetic_origin_lonlat() {
  const GeoFrame frame = test::synthetic_frame();
  const Vec2 p = CrsTransform(frame.crs(), "EPSG:4326").apply(frame.origin());
  return {p.x(), p.y()};
}

// A sketch's node in the synthetic frame (local metres), as the build projects it.
Vec2 synthetic_local(const test::OsmSketch& sketch, char letter) {
  const GeoFrame frame = test::synthetic_frame();
  const LonLat ll = sketch.lonlat(letter);
  return CrsTransform("EPSG:4326", frame.crs()).apply(Vec2(ll.lon_deg, ll.lat_deg)) - frame.origin();
}

BuildOptions synthetic_options(const std::string& name, const test::OsmSketch& sketch,
                               const std::function<double(double, double)>& ground) {
  BuildOptions o;
  const auto dir = test::scratch_dir("mesh_" + name);
  o.osm_path = sketch.write(dir / (name + ".osm"));
  o.dem_paths = {test::write_local_dem(name, 400.0, 5.0, ground)};
  o.out_dir = dir / "out";
  o.crs = test::synthetic_frame().crs();
  return scene_options(o);
}

TEST(MeshPipeline, StraightRoadOnAPlaneIsExact) {
  const test::OsmSketch sketch = test::OsmSketch(R"(
      A----------B
  )",
                                                 10.0, synthetic_origin_lonlat())
                                     .way("AB", {{"highway", "residential"}, {"lanes", "2"}, {"width", "7"}});
  // The plane rises 5 % along the road (as projected: UTM's grid is turned against the
  // meridians), level across it, so that the level cross-section lies on it.
  const Vec2 a = synthetic_local(sketch, 'A');
  const Vec2 b = synthetic_local(sketch, 'B');
  const Vec2 dir = (b - a).normalized();
  constexpr double kGrade = 0.05;
  const auto plane = [&](double x, double y) { return 20.0 + kGrade * (Vec2(x, y) - a).dot(dir); };
  BuildOptions o = synthetic_options("straight", sketch, plane);
  o.profile_method = ProfileMethod::raw;  // the drape of a plane is the plane
  const SceneBuild built = build_scene(o);
  const MeshSummary& m = summary(built);
  print("straight", m);
  ASSERT_TRUE(m.road);

  const double length_m = (b - a).norm() * std::sqrt(1.0 + kGrade * kGrade);
  EXPECT_NEAR(m.road->area_m2, length_m * 7.0, 1e-6 * length_m * 7.0);
  EXPECT_EQ(m.road->components, 1u);
  EXPECT_EQ(m.road->holes, 0u);
  EXPECT_EQ(m.ground_holes, 0u);
  EXPECT_EQ(m.ground_components, 1u);
  EXPECT_EQ(m.seam_road_terrain_m.value_or(1.0), 0.0);

  // Every road vertex on the plane (the build's frame has its own origin).
  const Vec2 shift = built.result.report.frame.origin() - test::synthetic_frame().origin();
  const MeshScene scene = read_mesh_file(o.out_dir / "straight.glb");
  const TriangleMesh* road = find_mesh(scene, "Road_Road");
  ASSERT_NE(road, nullptr);
  double worst_m = 0.0;
  for (const Vec3& v : road->vertices) {
    worst_m = std::max(worst_m, std::abs(v.z() - plane(v.x() + shift.x(), v.y() + shift.y())));
  }
  EXPECT_LE(worst_m, 1e-6 + 2e-6);  // plus the float rounding of the file (z ~ 20 m: 1e-6)
  EXPECT_LE(m.xodr_surface_max_distance_m, 1e-6);
}

// A scene 20 km from its frame's origin, where a float steps by 1.95 mm: the build says its mesh
// files are that coarse (mesh.far_from_origin, once); its --mesh-tile-size tiles each carry their
// own origin and read back exact to their quantum. At the frame's own centre nothing is said.
TEST(MeshPipeline, AFileFarFromTheFrameOriginIsSaidAndTilesKeepItExact) {
  const test::OsmSketch sketch = test::OsmSketch(R"(
      A----------B
  )",
                                                 10.0, synthetic_origin_lonlat())
                                     .way("AB", {{"highway", "residential"}, {"lanes", "2"}});
  BuildOptions o = synthetic_options("far", sketch, [](double x, double) { return 20.0 + 0.01 * x; });
  o.mesh_formats = {MeshFormat::glb};
  const SceneBuild near = build_scene(o);
  EXPECT_EQ(near.diagnostics.count("mesh.far_from_origin"), 0U);
  const LonLat centre = synthetic_origin_lonlat();
  o.frame_centre = LonLat{
      centre.lon_deg + 20.0 / (111.32 * std::cos(centre.lat_deg * std::numbers::pi / 180.0)), centre.lat_deg};
  o.mesh_tile_size_m = 500.0;
  const SceneBuild far = build_scene(o);
  EXPECT_EQ(far.diagnostics.at("mesh.far_from_origin"), 1U);
  const MeshScene whole = read_mesh_file(o.out_dir / "far.glb");
  EXPECT_FALSE(whole.file_origin.has_value());
  std::size_t tiles = 0;
  for (const auto& entry : std::filesystem::directory_iterator(o.out_dir)) {
    const std::string file = entry.path().filename().string();
    if (!file.starts_with("far_Tile_") || entry.path().extension() != ".glb") continue;
    ++tiles;
    const MeshScene tile = read_mesh_file(entry.path());
    ASSERT_TRUE(tile.file_origin.has_value()) << file;
    EXPECT_LT(tile.file_origin->at.x(), -19000.0) << file;
    EXPECT_EQ(tile.file_origin->quantum_m, std::exp2(-14.0)) << file;
    for (const TriangleMesh& m : tile.meshes)
      for (const Vec3& v : m.vertices) {
        EXPECT_EQ(v.x(), std::round(v.x() * 16384.0) / 16384.0);
        EXPECT_EQ(v.y(), std::round(v.y() * 16384.0) / 16384.0);
      }
  }
  EXPECT_GT(tiles, 0U);
}

// Two ways crossing without a shared node (a data defect): a node is put at the crossing, which
// becomes a junction meshed like any other; nothing intersects.
TEST(MeshPipeline, WaysCrossingWithoutANodeMeetAtAJunction) {
  const test::OsmSketch sketch = test::OsmSketch(R"(
      A-------C
      D-------B
  )",
                                                 10.0, synthetic_origin_lonlat())
                                     .way("AB", {{"highway", "residential"}}, 71)
                                     .way("CD", {{"highway", "residential"}}, 72);
  const auto plane = [](double x, double y) { return 20.0 + 0.03 * x + 0.02 * y; };
  const SceneBuild b = build_scene(synthetic_options("crossing", sketch, plane));
  const MeshSummary& m = summary(b);
  ASSERT_TRUE(m.road);
  EXPECT_EQ(b.diagnostics.count("osm.crossing_without_node"), 1u);
  EXPECT_EQ(m.junctions_meshed, 1u);
  EXPECT_EQ(m.junctions_failed, 0u);
  EXPECT_EQ(m.road->self_intersecting_pairs, 0u);
  EXPECT_EQ(m.road->holes, 0u);
}

// Two ways crossing on different layers (no bridge tagged) draped as they are (raw profiles, no
// fit to lift one over the other): their surfaces, level across on a sloped plane, cross. The
// warning names both roads' OSM ways and the place; the gate fails.
TEST(MeshPipeline, SelfIntersectionsAreNamedInTheirWarningAndFailTheGate) {
  const test::OsmSketch sketch = test::OsmSketch(R"(
      A-------C
      D-------B
  )",
                                                 10.0, synthetic_origin_lonlat())
                                     .way("AB", {{"highway", "residential"}, {"layer", "1"}}, 71)
                                     .way("CD", {{"highway", "residential"}}, 72);
  const auto plane = [](double x, double y) { return 20.0 + 0.03 * x + 0.02 * y; };
  BuildOptions o = synthetic_options("layers", sketch, plane);
  o.profile_method = ProfileMethod::raw;
  const SceneBuild b = build_scene(o);
  const MeshSummary& m = summary(b);
  ASSERT_TRUE(m.road);
  EXPECT_GT(m.road->self_intersecting_pairs, 0u);
  const std::string named = self_intersection_message(b);
  EXPECT_NE(named.find("(OSM way 71)"), std::string::npos) << named;
  EXPECT_NE(named.find("(OSM way 72)"), std::string::npos) << named;
  // The first pair lies at the crossing, halfway along both ways (within a lane width).
  const Vec2 shift = b.result.report.frame.origin() - test::synthetic_frame().origin();
  const Vec2 mid = 0.5 * (synthetic_local(sketch, 'A') + synthetic_local(sketch, 'B')) - shift;
  std::smatch at;
  ASSERT_TRUE(std::regex_search(named, at, std::regex(R"(at \((-?[0-9.]+), (-?[0-9.]+),)"))) << named;
  EXPECT_LT((Vec2(std::stod(at[1]), std::stod(at[2])) - mid).norm(), 3.0)
      << named << " vs " << mid.transpose();
  const auto& gates = b.result.report.gates;
  const auto gate = std::find_if(gates.begin(), gates.end(),
                                 [](const Gate& g) { return g.name == "road_self_intersections"; });
  ASSERT_NE(gate, gates.end());
  EXPECT_FALSE(gate->passed);
}

// A driveway drawn 3 m beside a parking tunnel (Portland's OSM 345752232 over 345752235 at the
// tunnel's mouth): their 5.5 m pavements overlap 2.5 m wide for 31.5 m, all of it within 20 m of
// the tunnel's portals (F, E), where no clearance fits. On a twisted ground (the driveway's side
// higher at one end, lower at the other) their profiles cross; the tunnel only has to stay
// 0.1 m under the driveway there, so the surfaces never meet.
TEST(MeshPipeline, ATunnelBesideAStreetNearItsPortalsStaysUnderIt) {
  const test::OsmSketch sketch = test::OsmSketch(R"(
  A----------------------------------B
        C--------------------D
        |                    |
        F                    E
        |                    |
        K                    L
  )",
                                                 1.5, synthetic_origin_lonlat())
                                     .way("AB", {{"highway", "service"}, {"service", "driveway"}}, 81)
                                     .way("FCDE", {{"highway", "service"}, {"tunnel", "yes"}}, 82)
                                     .way("KF", {{"highway", "service"}}, 83)
                                     .way("EL", {{"highway", "service"}}, 84);
  const Vec2 west = synthetic_local(sketch, 'C');  // the tunnel's straight, under the driveway
  const Vec2 east = synthetic_local(sketch, 'D');
  const Vec2 along = (east - west).normalized();
  const Vec2 across(-along.y(), along.x());  // towards the driveway
  const Vec2 mid = 0.5 * (west + east);
  // 4 % across the roads at the tunnel's west end, -4 % at its east end, 2 % along.
  constexpr double kTwist = 0.04;
  const auto twisted = [&](double x, double y) {
    const Vec2 d = Vec2(x, y) - mid;
    return 20.0 + 0.02 * d.dot(along) + kTwist * d.dot(across) * (-d.dot(along) / 15.75);
  };
  ASSERT_NEAR((synthetic_local(sketch, 'A') - west).dot(across), 3.0, 0.01);
  const SceneBuild built = build_scene(synthetic_options("portal_overlap", sketch, twisted));
  const MeshSummary& m = summary(built);
  print("portal_overlap", m);
  ASSERT_TRUE(m.road);
  const MethodReport& fit = built.result.report.methods.back();
  std::cout << "  ordered overlaps " << fit.overlaps_ordered << ", out of order " << fit.overlaps_out_of_order
            << "\n";
  EXPECT_GE(fit.overlaps_ordered, 4u);
  EXPECT_EQ(fit.overlaps_out_of_order, 0u);
  EXPECT_EQ(m.road->self_intersecting_pairs, 0u);
  EXPECT_EQ(m.junctions_failed, 0u);
}

TEST(MeshPipeline, TJunctionOnAPlaneIsOneCleanSurface) {
  const test::OsmSketch sketch = test::OsmSketch(R"(
      A-----B-----C
            |
            |
            D
  )",
                                                 10.0, synthetic_origin_lonlat())
                                     .way("ABC", {{"highway", "residential"}})
                                     .way("BD", {{"highway", "residential"}});
  const auto plane = [](double x, double y) { return 20.0 + 0.03 * x + 0.02 * y; };
  const SceneBuild built = build_scene(synthetic_options("tee", sketch, plane));
  const MeshSummary& m = summary(built);
  print("tee", m);
  ASSERT_TRUE(m.road);
  EXPECT_EQ(m.junctions_meshed, 1u);
  EXPECT_EQ(m.junctions_failed, 0u);
  EXPECT_EQ(m.road->components, 1u);
  EXPECT_EQ(m.road->holes, 0u);
  EXPECT_EQ(m.road->non_manifold_edges, 0u);
  EXPECT_EQ(m.road->self_intersecting_pairs, 0u);
  EXPECT_EQ(m.road->upside_down_triangles, 0u);
  EXPECT_EQ(m.seam_road_junction_m, 0.0);
  EXPECT_EQ(m.ground_holes, 0u);
  EXPECT_EQ(m.ground_components, 1u);
}

TEST(MeshPipeline, BridgeOverARoadClearsIt) {
  // CD (bridge, layer 1) crosses AB without a shared node; both on a level plane at 20 m.
  const test::OsmSketch sketch =
      test::OsmSketch(R"(
                C
                |
                |
                |
                |
      A---------+---------B
                |
                |
                |
                |
                D
  )",
                      10.0, synthetic_origin_lonlat())
          .way("AB", {{"highway", "residential"}})
          .way("CD", {{"highway", "residential"}, {"bridge", "yes"}, {"layer", "1"}});
  BuildOptions o = synthetic_options("bridge", sketch, [](double, double) { return 20.0; });
  const SceneBuild built = build_scene(o);
  const MeshSummary& m = summary(built);
  print("bridge", m);
  ASSERT_TRUE(m.road);
  EXPECT_EQ(m.road->self_intersecting_pairs, 0u);
  EXPECT_EQ(m.road->non_manifold_edges, 0u);

  // Where the deck and the ground road overlap in plan (within the 6 m x 6 m square around the
  // crossing), the vertical distance between the two surfaces, on a 0.1 m grid.
  const MeshScene scene = read_mesh_file(o.out_dir / "bridge.glb");
  const TriangleMesh* road = find_mesh(scene, "Road_Road");
  ASSERT_NE(road, nullptr);
  std::vector<std::size_t> deck, ground;
  constexpr double kDeckAboveM = 21.0;  // the plane is at 20 m; the deck reaches ~25 m
  for (std::size_t t = 0; t < road->triangles.size(); ++t) {
    bool high = true;
    for (const auto v : road->triangles[t]) high = high && road->vertices[v].z() > kDeckAboveM;
    (high ? deck : ground).push_back(t);
  }
  const Vec2 shift = built.result.report.frame.origin() - test::synthetic_frame().origin();
  const double y_ab = 0.5 * (synthetic_local(sketch, 'A').y() + synthetic_local(sketch, 'B').y()) - shift.y();
  const double x_cd = 0.5 * (synthetic_local(sketch, 'C').x() + synthetic_local(sketch, 'D').x()) - shift.x();
  constexpr double kHalfWidthM = 3.0;  // two residential lanes of 3 m
  std::optional<double> least_m, at_crossing_m;
  for (double dx = -kHalfWidthM; dx <= kHalfWidthM + 1e-9; dx += 0.1) {
    for (double dy = -kHalfWidthM; dy <= kHalfWidthM + 1e-9; dy += 0.1) {
      const Vec2 p(x_cd + dx, y_ab + dy);
      const auto upper = height_at(*road, deck, p);
      const auto lower = height_at(*road, ground, p);
      if (!upper || !lower) continue;
      least_m = std::min(least_m.value_or(1e300), *upper - *lower);
      if (std::abs(dx) < 0.05 && std::abs(dy) < 0.05) at_crossing_m = *upper - *lower;
    }
  }
  ASSERT_TRUE(least_m && at_crossing_m) << "no deck over the ground road";
  std::cout << "bridge: surfaces " << *at_crossing_m << " m apart at the crossing, " << *least_m
            << " m at least where they overlap (clearance " << o.fit.clearance_m << " m)\n";
  // The profiles keep the clearance where the centrelines cross (report: min 5.0 m)...
  EXPECT_GE(*at_crossing_m, o.fit.clearance_m - 0.01);  // 0.01: elevation records vs the fit
  // ... and over the whole overlap: the fit keeps it over each road's paved edges too (3 x 3
  // rows per crossing); between them the surfaces are straight enough. Measured 4.974 m (before
  // the edge rows: 4.868 m, the deck crested and the road beneath sagged at the crossing only).
  EXPECT_GE(*least_m, 4.95);
}

// A street through a hill in a tunnel (BC): the terrain over the tunnel meets each mouth's top
// edge, the road's end edge raised by the portal height, so the way in stays open; the ground
// (roads on the ground + terrain) keeps exactly those two openings and no hole.
TEST(MeshPipeline, TunnelMouthsStayOpen) {
  const test::OsmSketch sketch =
      test::OsmSketch(R"(
      A-----B-----C-----D
  )",
                      10.0, synthetic_origin_lonlat())
          .way("AB", {{"highway", "residential"}})
          .way("BC", {{"highway", "residential"}, {"tunnel", "yes"}, {"layer", "-1"}})
          .way("CD", {{"highway", "residential"}});
  const Vec2 b = synthetic_local(sketch, 'B');
  const Vec2 c = synthetic_local(sketch, 'C');
  const Vec2 mid = 0.5 * (b + c);
  const auto hill = [&](double x, double y) {
    const double d = (Vec2(x, y) - mid).norm();
    return 20.0 + 15.0 * std::exp(-d * d / (2.0 * 12.0 * 12.0));
  };
  BuildOptions o = synthetic_options("tunnel", sketch, hill);
  const SceneBuild built = build_scene(o);
  const MeshSummary& m = summary(built);
  print("tunnel", m);
  EXPECT_EQ(m.ground_portals, 2u);
  EXPECT_EQ(m.ground_holes, 0u);
  EXPECT_EQ(m.ground_components, 1u);
  EXPECT_EQ(m.seam_road_terrain_m.value_or(1.0), 0.0);

  // Terrain vertices straight above road vertices, the portal height up: the mouths' top edges.
  const MeshScene scene = read_mesh_file(o.out_dir / "tunnel.glb");
  const TriangleMesh* road = find_mesh(scene, "Road_Road");
  const TriangleMesh* terrain = find_mesh(scene, "Terrain");
  ASSERT_TRUE(road && terrain);
  std::size_t top_edge = 0;
  for (const Vec3& t : terrain->vertices) {
    for (const Vec3& r : road->vertices) {
      if ((t.head<2>() - r.head<2>()).norm() < 1e-3 &&
          std::abs(t.z() - r.z() - o.scene.tunnel_portal_height_m) < 1e-3)
        ++top_edge;
    }
  }
  EXPECT_EQ(top_edge, 6u);  // 3 per mouth: the two corners and the centre line of a two-lane street
}

}  // namespace
}  // namespace relief

#include "relief/viewer/view_writer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <string>

#include "core/base64.h"
#include "relief/core/errors.h"
#include "scene/bridge_world.h"
#include "support/synthetic.h"

namespace relief {
namespace {

using Json = nlohmann::json;

std::string base64(std::string_view bytes) {
  std::string out;
  detail::append_base64(out, bytes);
  return out;
}

std::string unbase64(const std::string& text) {
  static const std::string alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  std::uint32_t bits = 0;
  int count = 0;
  for (const char c : text) {
    if (c == '=') break;
    bits = bits << 6 | static_cast<std::uint32_t>(alphabet.find(c));
    count += 6;
    if (count >= 8) {
      count -= 8;
      out += static_cast<char>(bits >> count & 0xff);
    }
  }
  return out;
}

template <class T>
std::vector<T> array_of(const Json& layer, const char* key) {
  const std::string bytes = unbase64(layer.at(key).get<std::string>());
  std::vector<T> out(bytes.size() / sizeof(T));
  std::memcpy(out.data(), bytes.data(), out.size() * sizeof(T));
  return out;
}

/// The JSON object inside "RELIEF_TILE(...);" or "window.RELIEF_VIEW = ...;".
Json json_in(const std::string& script, const std::string& prefix, const std::string& suffix) {
  EXPECT_EQ(script.rfind(prefix, 0), 0u);
  EXPECT_EQ(script.substr(script.size() - suffix.size()), suffix);
  return Json::parse(script.substr(prefix.size(), script.size() - prefix.size() - suffix.size()));
}

TEST(Base64, KnownVectors) {
  // RFC 4648 section 10.
  EXPECT_EQ(base64(""), "");
  EXPECT_EQ(base64("f"), "Zg==");
  EXPECT_EQ(base64("fo"), "Zm8=");
  EXPECT_EQ(base64("foo"), "Zm9v");
  EXPECT_EQ(base64("foob"), "Zm9vYg==");
  EXPECT_EQ(base64("fooba"), "Zm9vYmE=");
  EXPECT_EQ(base64("foobar"), "Zm9vYmFy");
  EXPECT_EQ(base64(std::string("\xff\xfe\x00", 3)), "//4A");
}

// A 10 % ramp along x, 2 m above a DEM that is the same ramp: a strip of quads from x = 10 to
// 110 m (y 7 to 13, all in the grid's first tile), road 1 up to x = 60 and road 2 after it, the last quad a
// structure (off the ground), and a terrain square. Grade 10 % and height over the DEM 2 m at every paved
// vertex.
struct RampScene {
  Scene scene;
  DemSampler dem;
};

RampScene ramp_scene() {
  Scene scene;
  scene.meshes.frame = test::synthetic_frame();
  TriangleMesh road;
  road.name = "Road_Road";
  for (int i = 0; i <= 10; ++i)
    for (const double y : {7.0, 13.0})
      road.vertices.emplace_back(10.0 * i + 10.0, y, 0.1 * (10.0 * i + 10.0) + 2.0);
  for (std::uint32_t i = 0; i < 10; ++i) {
    const std::uint32_t a = 2 * i, b = a + 1, c = a + 2, d = a + 3;
    road.triangles.push_back({a, c, d});
    road.triangles.push_back({a, d, b});
    for (int k = 0; k < 2; ++k) {
      scene.roads.road_triangle_owner.push_back(i < 5 ? 1 : 2);
      scene.ground.push_back(i < 9 ? 1 : 0);
    }
  }
  TriangleMesh terrain;
  terrain.name = "Terrain";
  terrain.kind = SurfaceKind::terrain;
  terrain.vertices = {{1, 1, 0.1}, {130, 1, 13}, {130, 50, 13}, {1, 50, 0.1}};
  terrain.triangles = {{0, 1, 2}, {0, 2, 3}};
  TriangleMesh marking;
  marking.name = "Road_Marking";
  marking.kind = SurfaceKind::marking;
  marking.vertices = {{20, 9.9, 3.005}, {30, 9.9, 4.005}, {30, 10.1, 4.005}};
  marking.triangles = {{0, 1, 2}};
  scene.meshes.meshes = {road, terrain, marking};
  Aabb2 area;
  area.extend(Vec2(-60, -60));
  area.extend(Vec2(160, 60));
  DemSampler dem({test::write_local_dem("view_ramp", 200.0, 5.0, [](double x, double) { return 0.1 * x; })},
                 scene.meshes.frame, area);
  return {std::move(scene), std::move(dem)};
}

TEST(ViewTiles, GradeHeightOverTheDemAndOwnersOfARampAreExact) {
  const RampScene w = ramp_scene();
  std::map<std::string, Json> layers, coarse;
  std::vector<std::string> files;
  const ViewTiles tiles =
      view_tiles(w.scene, w.dem, [&](const std::string& filename, const std::string& script) {
        files.push_back(filename);
        const Json j = json_in(script, "RELIEF_TILE(", ");\n");
        const std::string part = j.at("part");
        EXPECT_EQ(part, filename == "tile_0_0.js" ? "base" : filename == "tile_0_0_lod.js" ? "lod" : "marks");
        for (const Json& layer : j.at("layers"))
          (part == "lod" ? coarse : layers)[layer.at("layer").get<std::string>()] = layer;
      });
  // 23 triangles over 130 m: one automatic tile (4 km, the largest), its coarse copy for afar,
  // its marks in a file of their own.
  EXPECT_EQ(files, (std::vector<std::string>{"tile_0_0.js", "tile_0_0_lod.js", "tile_0_0_marks.js"}));
  EXPECT_EQ(tiles.tile_size_m, 4000.0);
  // The coarse copy: 10 m cells; a mean of points on the ramp's plane is on it, so its grade
  // and height over the DEM stay exact; no marks.
  EXPECT_FALSE(coarse.contains("marking"));
  ASSERT_TRUE(coarse.contains("road"));
  EXPECT_LE(coarse.at("road").at("triangles").get<int>(), 18);
  EXPECT_GT(coarse.at("road").at("triangles").get<int>(), 0);
  std::size_t coarse_triangles = 0;
  for (const auto& [name, layer] : coarse) coarse_triangles += layer.at("triangles").get<std::size_t>();
  EXPECT_EQ(tiles.tiles.at(0).lod_triangles, coarse_triangles);
  for (const float g : array_of<float>(coarse.at("road"), "grade")) EXPECT_NEAR(g, 10.0, 1e-3);
  for (const float dz : array_of<float>(coarse.at("road"), "dz")) EXPECT_NEAR(dz, 2.0, 1e-3);
  for (const std::int32_t o : array_of<std::int32_t>(coarse.at("road"), "owner"))
    EXPECT_TRUE(o == 0 || o == 1);
  ASSERT_EQ(tiles.tiles.size(), 1u);
  EXPECT_EQ(tiles.tiles[0].triangles, 22u);
  EXPECT_EQ(tiles.tiles[0].marks_triangles, 1u);
  EXPECT_EQ(tiles.triangles, 23u);
  EXPECT_EQ(tiles.owners, (std::vector<int>{1, 2}));
  ASSERT_EQ(layers.size(), 4u);
  EXPECT_EQ(layers.at("marking").at("triangles"), 1);
  EXPECT_FALSE(layers.at("marking").contains("owner"));
  const Json& road = layers.at("road");
  const Json& structure = layers.at("structure");
  EXPECT_EQ(road.at("triangles"), 18);
  EXPECT_EQ(structure.at("triangles"), 2);
  EXPECT_EQ(layers.at("terrain").at("triangles"), 2);
  // The two vertices at x = 60 belong to both roads: they are split, 20 + 2 on the ground.
  EXPECT_EQ(road.at("vertices"), 22);
  EXPECT_FALSE(layers.at("terrain").contains("owner"));
  for (const Json* layer : {&road, &structure}) {
    const auto positions = array_of<float>(*layer, "positions");
    const auto owner = array_of<std::int32_t>(*layer, "owner");
    const auto grade = array_of<float>(*layer, "grade");
    const auto dz = array_of<float>(*layer, "dz");
    ASSERT_EQ(positions.size(), 3 * owner.size());
    ASSERT_EQ(grade.size(), owner.size());
    for (std::size_t i = 0; i < owner.size(); ++i) {
      // three.js axes: (x, z, -y).
      const double x = positions[3 * i], z = positions[3 * i + 1], y = -positions[3 * i + 2];
      EXPECT_NEAR(z, 0.1 * x + 2.0, 1e-5);
      EXPECT_TRUE(y == 7.0 || y == 13.0) << y;
      EXPECT_NEAR(grade[i], 10.0, 1e-4) << "vertex " << i;
      EXPECT_NEAR(dz[i], 2.0, 1e-4) << "vertex " << i;
      // Owner index 0 is road 1 (x <= 60), 1 is road 2 (x >= 60).
      EXPECT_TRUE(owner[i] == 0 ? x <= 60.0 : x >= 60.0) << x;
    }
  }
  const auto indices = array_of<std::uint32_t>(road, "indices");
  EXPECT_EQ(indices.size(), 54u);
  for (const std::uint32_t i : indices) EXPECT_LT(i, 22u);
}

TEST(ViewTiles, TrianglesGoToTheTileOfTheirCentroidAndAddUp) {
  const RampScene w = ramp_scene();
  ViewOptions o;
  o.tile_size_m = 40.0;
  std::size_t triangles = 0;
  std::set<std::string> names;
  const ViewTiles tiles = view_tiles(
      w.scene, w.dem,
      [&](const std::string& filename, const std::string& script) {
        names.insert(filename);
        const Json j = json_in(script, "RELIEF_TILE(", ");\n");
        const int tile_x = j.at("x"), tile_y = j.at("y");
        EXPECT_EQ(filename.rfind("tile_" + std::to_string(tile_x) + "_" + std::to_string(tile_y), 0), 0u);
        for (const Json& layer : j.at("layers")) {
          const auto positions = array_of<float>(layer, "positions");
          const auto indices = array_of<std::uint32_t>(layer, "indices");
          triangles += indices.size() / 3;
          for (std::size_t t = 0; t < indices.size(); t += 3) {
            double cx = 0.0, cy = 0.0;
            for (int k = 0; k < 3; ++k) {
              cx += positions[3 * indices[t + k]] / 3.0;
              cy -= positions[3 * indices[t + k] + 2] / 3.0;
            }
            // Grid lines at multiples of 40 m; column 0 holds x in [0, 40).
            EXPECT_EQ(static_cast<int>(std::floor(cx / 40.0)), tile_x);
            EXPECT_EQ(static_cast<int>(std::floor(cy / 40.0)), tile_y);
          }
        }
      },
      o);
  EXPECT_EQ(tiles.tile_size_m, 40.0);
  EXPECT_EQ(triangles, 23u);
  EXPECT_EQ(tiles.tiles.size(), 3u);  // columns 0, 1, 2 of row 0
  EXPECT_EQ(names.size(), 4u);        // and the marks of column 0
  for (const ViewTile& t : tiles.tiles) EXPECT_LE(t.z_min, t.z_max);
}

TEST(ViewTiles, OptionsOutOfRangeThrow) {
  const RampScene w = ramp_scene();
  const auto ignore = [](const std::string&, const std::string&) {};
  for (const double size : {-1.0, std::nan(""), std::numeric_limits<double>::infinity()}) {
    ViewOptions o;
    o.tile_size_m = size;
    EXPECT_THROW((void)view_tiles(w.scene, w.dem, ignore, o), InvalidInput) << size;
  }
  ViewOptions o;
  o.tile_triangles = 0;
  EXPECT_THROW((void)view_tiles(w.scene, w.dem, ignore, o), InvalidInput);
  o = {};
  o.lod_cells_per_tile = 0.5;
  EXPECT_THROW((void)view_tiles(w.scene, w.dem, ignore, o), InvalidInput);
}

TEST(ViewIndex, RoadsProfilesFindingsAndGatesOfTheBridgeWorld) {
  Diagnostics d;
  const test::BridgeWorld w = test::make_bridge_world(d);
  const Scene scene = build_scene(w.built.model, w.network, w.dem, {}, d);
  const ViewTiles tiles = view_tiles(scene, w.dem, [](const std::string&, const std::string&) {});
  const std::vector<RoadProfile> raw =
      test::drape(w.network, [](const Vec2&) { return test::kWorldGroundM; });
  std::vector<RoadProfile> fitted = raw;
  for (RoadProfile& p : fitted)
    for (double& z : p.z) z += 1.0;
  RunReport report;
  report.name = "bridge";
  report.frame = w.network.frame;
  report.gates = {{"road_self_intersections", 3, 0, false, "road 4 at (1, 2, 3)"},
                  {"fit_converged", 1, 1, true, ""},
                  {"sumo_lanes_without_z", 2, 0, false, "lane 7_0"}};
  report.mesh.emplace();
  report.mesh->ground_hole_sites = {Vec3(5, 6, 7)};
  ViewIndexInput in;
  in.report = &report;
  in.model = &w.built.model;
  in.network = &w.network;
  in.raw = &raw;
  in.fitted = &fitted;
  in.failed_junctions = {{7, Vec3(1, 2, 3)}};
  ViewOptions o;
  o.profile_points = 50;
  const Json j = json_in(view_index_script(tiles, in, o), "window.RELIEF_VIEW = ", ";\n");

  EXPECT_EQ(j.at("name"), "bridge");
  EXPECT_EQ(j.at("frame").at("crs"), w.network.frame.crs());
  EXPECT_EQ(j.at("tiles").size(), tiles.tiles.size());
  EXPECT_EQ(j.at("owners").size(), tiles.owners.size());
  EXPECT_EQ(j.at("roads").size(), w.built.model.roads.size());
  // Every network road a model road comes from has its profile: <= 50 points, both ends kept.
  std::set<int> sources;
  for (const ModelRoad& r : w.built.model.roads) {
    const Json& road = j.at("roads").at(std::to_string(r.id));
    EXPECT_NEAR(road.at("length_m").get<double>(), r.length(), 0.05);
    if (r.source_road < 0) {
      EXPECT_EQ(road.at("class"), "connecting road");
      continue;
    }
    sources.insert(r.source_road);
    EXPECT_EQ(road.at("network_road"), r.source_road);
    // The piece's place along its OSM road: as long as the piece (trimmed at junctions) within
    // the stations' 1 m spacing, inside the OSM road.
    const double s0 = road.at("profile_s")[0], s1 = road.at("profile_s")[1];
    EXPECT_GE(s0, 0.0);
    EXPECT_LE(s1, raw[static_cast<std::size_t>(r.source_road)].s.back() + 1e-9);
    EXPECT_NEAR(s1 - s0, r.length(), 1.1) << r.id;
  }
  ASSERT_EQ(j.at("profiles").size(), sources.size());
  for (const int s : sources) {
    const Json& p = j.at("profiles").at(std::to_string(s));
    const RoadProfile& r = raw[static_cast<std::size_t>(s)];
    ASSERT_LE(p.at("s").size(), 50u);
    EXPECT_EQ(p.at("s").front(), 0.0);
    EXPECT_NEAR(p.at("s").back().get<double>(), r.s.back(), 0.05);
    EXPECT_EQ(p.at("raw").size(), p.at("s").size());
    EXPECT_FALSE(p.contains("paper"));
    for (std::size_t i = 0; i < p.at("s").size(); ++i)
      EXPECT_NEAR(p.at("fit")[i].get<double>() - p.at("raw")[i].get<double>(), 1.0, 0.011);
  }
  // Findings: the failed gates (placed where their text names a point), the ground's hole and
  // the open junction.
  const Json& f = j.at("findings");
  ASSERT_EQ(f.size(), 4u);
  EXPECT_EQ(f[0].at("kind"), "gate");
  EXPECT_EQ(f[0].at("at"), Json::array({1.0, 2.0, 3.0}));
  EXPECT_NE(f[0].at("text").get<std::string>().find("road 4 at (1, 2, 3)"), std::string::npos);
  EXPECT_EQ(f[1].at("kind"), "gate");
  EXPECT_TRUE(f[1].at("at").is_null());
  EXPECT_EQ(f[2].at("kind"), "hole");
  EXPECT_EQ(f[2].at("at"), Json::array({5.0, 6.0, 7.0}));
  EXPECT_EQ(f[3].at("kind"), "junction_open");
  EXPECT_EQ(j.at("gates").size(), 3u);
  EXPECT_EQ(j.at("gates")[0].at("passed"), false);

  ViewIndexInput missing = in;
  missing.raw = nullptr;
  EXPECT_THROW((void)view_index_script(tiles, missing), InvalidInput);
  std::vector<RoadProfile> short_set(raw.begin(), raw.end() - 1);
  ViewIndexInput not_parallel = in;
  not_parallel.fitted = &short_set;
  EXPECT_THROW((void)view_index_script(tiles, not_parallel), InvalidInput);
}

TEST(ViewPage, CarriesTheBundleAndEscapesTheTitle) {
  const std::string page = view_page("a<b & \"c\"");
  EXPECT_EQ(page.find("{{"), std::string::npos);
  EXPECT_NE(page.find("<title>a&lt;b &amp; &quot;c&quot;</title>"), std::string::npos);
  EXPECT_NE(page.find("<script src=\"view/index.js\"></script>"), std::string::npos);
  // three.js bundled into the page (its licence kept), nothing from a network.
  EXPECT_NE(page.find("Three.js Authors"), std::string::npos);
  EXPECT_NE(page.find("reliefView"), std::string::npos);
  EXPECT_EQ(page.find("https://cdn"), std::string::npos);
  EXPECT_EQ(page.find("<script src=\"http"), std::string::npos);
  EXPECT_GT(page.size(), 300000u);
}

TEST(ViewPage, DataFolderScriptsAndReportLinkAreTheCallers) {
  ViewPageOptions o;
  o.data_dir = "../build/view";
  o.report = "cosim.html";
  o.scripts = {"replay.js"};
  const std::string page = view_page("replay", o);
  EXPECT_NE(page.find("window.RELIEF_VIEW_BASE = \"../build/view\";"), std::string::npos);
  EXPECT_NE(
      page.find("<script src=\"../build/view/index.js\"></script>\n<script src=\"replay.js\"></script>"),
      std::string::npos);
  EXPECT_NE(page.find("<a href=\"cosim.html\">report</a>"), std::string::npos);
  for (const char* bad : {"a\"b", "a<b", "a\\b", "a'b"}) {
    ViewPageOptions b;
    b.data_dir = bad;
    EXPECT_THROW((void)view_page("x", b), InvalidInput) << bad;
  }
}

TEST(ViewReplay, KeysTravelAsFloat32InTheirOrder) {
  ReplayTrack car;
  car.name = "car.0";
  car.length_m = 4.5;
  car.width_m = 1.8;
  car.height_m = 1.5;
  car.keys = {{1.0, Vec3(10, 20, 30), 0.5, 0.1, -0.05}, {1.5, Vec3(11, 20.5, 30.25), 0.6, 0.1, 0.0}};
  car.hide_after_s = 2.0;
  ReplayTrack empty;
  empty.name = "never";
  const Json j = json_in(view_replay_script({car, empty}), "window.RELIEF_REPLAY = ", ";\n");
  EXPECT_EQ(j.at("end_s"), 2.0);
  ASSERT_EQ(j.at("vehicles").size(), 1u);
  const Json& v = j.at("vehicles")[0];
  EXPECT_EQ(v.at("id"), "car.0");
  EXPECT_EQ(v.at("size"), Json::array({4.5, 1.8, 1.5}));
  EXPECT_EQ(v.at("hide_s"), 2.0);
  const auto keys = array_of<float>(v, "keys");
  const std::vector<float> expected = {1.0f, 10.0f, 20.0f, 30.0f,  0.5f, 0.1f, -0.05f,
                                       1.5f, 11.0f, 20.5f, 30.25f, 0.6f, 0.1f, 0.0f};
  EXPECT_EQ(keys, expected);
}

}  // namespace
}  // namespace relief

// Region tiles (issue 17): a plan's manifest, and a region built tile by tile and merged against
// the whole build of the same region in the same frame. The merge must give the same roads and
// junctions, the same plan to the bit, heights within 1 mm, and seams that close: the tiles'
// Road_Road joined is one surface without self-intersections, like the whole build's. The
// region's SUMO network, built from the merged model, has the whole build's lanes.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <numbers>
#include <pugixml.hpp>
#include <sstream>

#include "relief/core/errors.h"
#include "relief/geometry/crs_transform.h"
#include "relief/tiles/tiles.h"
#include "support/corpus.h"
#include "support/osm_sketch.h"
#include "support/synthetic.h"
#include "support/test_data.h"

namespace relief {
namespace {

TEST(TileManifest, JsonRoundTrip) {
  TileManifest m;
  m.name = "region";
  m.frame = GeoFrame("EPSG:32632", Vec2(750000.0, 5230000.0));
  m.frame_centre = {9.5, 47.15};
  m.tile_size_m = 2000.0;
  m.halo_m = 500.0;
  m.grid_origin = Vec2(-4000.0, -2000.0);
  m.inputs = {{"a.osm.pbf", std::string(64, 'a'), "osm"},
              {"/vsizip/b.zip/b.hgt", std::string(64, 'b'), "dem"}};
  m.build_args = {"--dem", "/vsizip/b.zip/b.hgt", "--no-compare"};
  TileSpec t;
  t.x = 1;
  t.y = 2;
  t.core = Aabb2{Vec2(-2000.0, 2000.0), Vec2(0.0, 4000.0)};
  t.window = {9.4, 47.1, 9.45, 47.13};
  t.road_nodes = 17;
  m.tiles = {t};
  const TileManifest back = TileManifest::from_json(m.to_json(), "test");
  EXPECT_EQ(back.to_json(), m.to_json());
  EXPECT_EQ(back.frame.origin(), m.frame.origin());
  ASSERT_NE(back.find(1, 2), nullptr);
  EXPECT_EQ(back.find(1, 2)->core.max, Vec2(0.0, 4000.0));
  EXPECT_EQ(back.find(2, 1), nullptr);
  // Another tile key for another option, grid or input.
  TileManifest other = m;
  other.build_args.push_back("--max-grade");
  EXPECT_NE(tile_key(other, t), tile_key(m, t));
  other = m;
  other.inputs[1].sha256 = std::string(64, 'c');
  EXPECT_NE(tile_key(other, t), tile_key(m, t));
  EXPECT_EQ(tile_key(back, *back.find(1, 2)), tile_key(m, t));
  EXPECT_THROW((void)TileManifest::from_json("{\"manifest_version\": 1}", "broken.json"), InvalidInput);
  EXPECT_THROW((void)TileManifest::from_json("not json", "broken.json"), InvalidInput);
}

TEST(TilePlan, RefusesATileSizeOrHaloThatIsNotAPositiveNumber) {
  TilePlanOptions o;
  o.osm_path = "does-not-matter.osm";
  o.tile_size_m = 0.0;
  EXPECT_THROW((void)plan_tiles(o), OptionError);
  o.tile_size_m = std::numeric_limits<double>::infinity();
  EXPECT_THROW((void)plan_tiles(o), OptionError);
  o.tile_size_m = 500.0;
  o.halo_m = -1.0;
  EXPECT_THROW((void)plan_tiles(o), OptionError);
  o.halo_m = 500.0;
  EXPECT_THROW((void)plan_tiles(o), IoError);  // no such file
}

struct Region {
  TileManifest manifest;
  TileMergeResult merge;
  nlohmann::json report;
  std::filesystem::path merged_net, whole_net;
};

struct NetLane {
  std::string id;
  std::vector<Vec3> shape;
};

// Every lane of a .net.xml (internal ones too) by its ends rounded to 0.1 m (ids differ between
// a merge and a whole build: the merge renumbers roads).
std::map<std::array<long, 4>, NetLane> lanes_by_ends(const std::filesystem::path& net) {
  pugi::xml_document doc;
  EXPECT_TRUE(doc.load_file(net.c_str())) << net;
  std::map<std::array<long, 4>, NetLane> out;
  for (const pugi::xml_node edge : doc.child("net").children("edge")) {
    for (const pugi::xml_node lane : edge.children("lane")) {
      NetLane l{lane.attribute("id").value(), {}};
      std::istringstream in(lane.attribute("shape").value());
      for (std::string point; in >> point;) {
        Vec3 p = Vec3::Zero();
        char comma = 0;
        std::istringstream ps(point);
        ps >> p.x() >> comma >> p.y() >> comma >> p.z();
        l.shape.push_back(p);
      }
      const auto r = [](double v) { return std::lround(v * 10.0); };
      const Vec3 a = l.shape.front(), b = l.shape.back();
      out[{r(a.x()), r(a.y()), r(b.x()), r(b.y())}] = std::move(l);
    }
  }
  return out;
}

// The plan distance from `p` to `line`, and the height difference there.
std::pair<double, double> distance_to(const Vec3& p, const std::vector<Vec3>& line) {
  std::pair<double, double> best{std::numeric_limits<double>::infinity(), 0.0};
  for (std::size_t i = 0; i + 1 < line.size(); ++i) {
    const Vec3 d = line[i + 1] - line[i];
    const double len2 = d.head<2>().squaredNorm();
    const double t = len2 > 0.0 ? std::clamp((p - line[i]).head<2>().dot(d.head<2>()) / len2, 0.0, 1.0) : 0.0;
    const Vec3 q = line[i] + t * d;
    const double xy = (p - q).head<2>().norm();
    if (xy < best.first) best = {xy, std::abs(p.z() - q.z())};
  }
  return best;
}

// Plans `osm` in tiles, builds every tile in this process, builds the whole region in the plan's
// frame and merges the tiles against it.
Region tile_and_merge(const std::filesystem::path& osm, const std::string& dem, double tile_m,
                      const std::filesystem::path& dir, double halo_m = 500.0) {
  Diagnostics d;
  TilePlanOptions plan;
  plan.osm_path = osm;
  plan.dem_paths = {dem};
  plan.tile_size_m = tile_m;
  plan.halo_m = halo_m;
  plan.build_args = {"(in-process)"};
  Region r;
  r.manifest = plan_tiles(plan);
  write_manifest(dir, r.manifest);
  BuildOptions options;
  options.dem_paths = {dem};
  options.outputs = {Output::xodr, Output::mesh, Output::report};
  options.mesh_formats = {MeshFormat::glb};
  options.compare_methods = false;
  for (const TileSpec& t : r.manifest.tiles) {
    Diagnostics td;
    const TileBuildResult b = build_tile(dir, r.manifest, t.x, t.y, options, td);
    EXPECT_EQ(b.status, "built") << t.x << "," << t.y;
    EXPECT_TRUE(b.failed_gates.empty()) << t.x << "," << t.y << ": " << b.failed_gates.front();
  }
  // A killed build's temporaries go with the next build of the tile.
  {
    const TileSpec& first = r.manifest.tiles.front();
    const std::filesystem::path stale = tile_dir(dir, first.x, first.y) / "out" / "old.xodr.tmp-99999";
    std::ofstream(stale) << "half written";
    Diagnostics forced;
    EXPECT_EQ(build_tile(dir, r.manifest, first.x, first.y, options, forced, /*force=*/true).status, "built");
    EXPECT_FALSE(std::filesystem::exists(stale));
  }
  // Up to date: nothing is built again.
  Diagnostics again;
  EXPECT_EQ(
      build_tile(dir, r.manifest, r.manifest.tiles.front().x, r.manifest.tiles.front().y, options, again)
          .status,
      "skipped");

  BuildOptions whole = options;
  whole.osm_path = osm;
  whole.out_dir = dir / "whole";
  whole.name = r.manifest.name;
  whole.frame_centre = r.manifest.frame_centre;
  whole.outputs.insert(Output::sumo);
  (void)build(whole, d);
  TileMergeOptions merge;
  merge.whole_xodr = whole.out_dir / (r.manifest.name + ".xodr");
  r.merge = merge_tiles(dir, merge, d);
  std::ifstream in(dir / "merged" / "report.json");
  r.report = nlohmann::json::parse(in);
  std::ifstream whole_mesh(whole.out_dir / "mesh_report.json");
  const nlohmann::json mesh = nlohmann::json::parse(whole_mesh);
  for (const auto& m : mesh.at("meshes")) {
    if (m.at("name") == "Road_Road") r.report["whole_road_road"] = m;
  }
  std::ifstream whole_report(whole.out_dir / "report.json");
  r.report["whole_sumo"] = nlohmann::json::parse(whole_report).at("sumo");
  r.merged_net = dir / "merged" / (r.manifest.name + ".net.xml");
  r.whole_net = whole.out_dir / (r.manifest.name + ".net.xml");
  return r;
}

// `max_dz_m`: the heights' agreement with the whole build (1 mm where the fit's optimum is well
// determined; a few roads of a mountain network come out up to a centimetre apart).
void expect_like_the_whole_build(const Region& r, double max_dz_m = 1e-3) {
  const auto& w = r.report.at("whole_build");
  std::cout << r.manifest.tiles.size() << " tiles: " << r.merge.roads << " roads, " << r.merge.junctions
            << " junctions; against the whole build " << w << "\n  seams " << r.report.at("seams")
            << "\n  joined " << r.report.at("joined") << "\n";
  EXPECT_GE(r.manifest.tiles.size(), 4u);
  EXPECT_EQ(r.report.at("opendrive").at("links_unresolved").get<int>(), 0) << r.report.at("opendrive");
  // Links across tiles join two owners' copies: their lane borders meet as in one build.
  EXPECT_EQ(r.report.at("opendrive").at("links_over_1cm").get<int>(), 0) << r.report.at("opendrive");
  EXPECT_TRUE(r.merge.failed_gates.empty()) << r.merge.failed_gates.front();
  EXPECT_EQ(w.at("unmatched").get<int>(), 0);
  EXPECT_EQ(r.merge.roads, w.at("roads").get<std::size_t>());
  EXPECT_LE(w.at("max_xy_m").get<double>(), 1e-9);     // the plan does not depend on the window
  EXPECT_LE(w.at("max_z_m").get<double>(), max_dz_m);  // the fit, to its gap tolerance
  EXPECT_GT(r.report.at("seams").at("shared_vertices").get<int>(), 0);
  EXPECT_LE(r.report.at("seams").at("max_dz_m").get<double>(), max_dz_m);
  const auto& road = r.report.at("joined").at("Road_Road");
  EXPECT_EQ(road.at("self_intersecting_pairs").get<int>(), 0);
  EXPECT_EQ(road.at("non_manifold_edges").get<int>(), 0);
  // The joined surface has the whole build's boundary: the seams are closed.
  EXPECT_EQ(road.at("boundary_loops"), r.report.at("whole_road_road").at("boundary_loops"));
  EXPECT_EQ(road.at("holes"), r.report.at("whole_road_road").at("holes"));

  // The SUMO network: the whole build's lanes, on the merged surface.
  const auto& sumo = r.report.at("sumo");
  const auto& whole_sumo = r.report.at("whole_sumo");
  std::cout << "  sumo " << sumo << "\n";
  for (const char* key : {"edges", "lanes", "internal_lanes", "junctions", "traffic_lights", "connections"})
    EXPECT_EQ(sumo.at(key), whole_sumo.at(key)) << key;
  EXPECT_EQ(sumo.at("lanes_without_z").get<int>(), 0);
  EXPECT_EQ(sumo.at("height_steps").get<int>(), 0);
  EXPECT_LE(sumo.at("z_max_m").get<double>(), 0.05);
  // Lanes matched by their ends. The two networks are the same curves, each simplified to 1 cm
  // from heights that differ by up to max_dz_m, so their points are compared with the other
  // lane's line, not point by point. netconvert splits a few internal lanes at a conflict point
  // of its own choosing, which may fall elsewhere: only those may go unmatched.
  const auto merged = lanes_by_ends(r.merged_net);
  const auto whole = lanes_by_ends(r.whole_net);
  EXPECT_EQ(merged.size(), whole.size());
  std::size_t unmatched = 0, unmatched_internal = 0, internal = 0;
  double max_xy = 0.0, max_z = 0.0;
  for (const auto& [key, lane] : whole) {
    const bool is_internal = lane.id.starts_with(":");
    internal += is_internal ? 1 : 0;
    const auto it = merged.find(key);
    if (it == merged.end()) {
      ++(is_internal ? unmatched_internal : unmatched);
      continue;
    }
    for (const auto& [from, to] :
         {std::pair(&lane.shape, &it->second.shape), std::pair(&it->second.shape, &lane.shape)}) {
      for (const Vec3& p : *from) {
        const auto [xy, z] = distance_to(p, *to);
        max_xy = std::max(max_xy, xy);
        max_z = std::max(max_z, z);
      }
    }
  }
  std::cout << "  sumo lanes: " << whole.size() << " in the whole build (" << internal << " internal); "
            << unmatched << " lanes and " << unmatched_internal
            << " internal lanes unmatched; largest distance " << max_xy << " m in plan, " << max_z
            << " m in height\n";
  EXPECT_EQ(unmatched, 0u);
  EXPECT_LE(static_cast<double>(unmatched_internal), 0.005 * static_cast<double>(internal));
  // Two 1 cm simplifications of the same curve, printed in centimetres.
  EXPECT_LE(max_xy, 0.025);
  EXPECT_LE(max_z, max_dz_m + 0.0101);
}

TEST(Tiles, OldTownMergesLikeTheWholeBuild) {
  const test::CorpusCase c = test::make_old_town(test::scratch_dir("input"));
  expect_like_the_whole_build(tile_and_merge(c.osm, c.dem, 120.0, test::scratch_dir("tiles")));
}

// A viaduct longer than the halo (Portland's Fremont Bridge in small): a 1 km road whose middle
// 600 m are three bridge ways over a valley 30 m deep, a street along the valley floor under it,
// in 200 m tiles with a 50 m halo. The fit spans the deck between its abutments, 600 m apart: a
// window that holds only the ways with a node in it cuts the deck short of one or both, and its
// fit spans it differently (before the structure chains: 0.97 m from the whole build, 8 lane
// borders apart by up to 0.83 m at links between tiles). Windows take the whole chain and the
// ground within the halo of it, so every tile spans the deck as the whole build does.
TEST(Tiles, AStructureChainLongerThanTheHaloMergesLikeTheWholeBuild) {
  const GeoFrame frame = test::synthetic_frame();
  const Vec2 west = CrsTransform(frame.crs(), "EPSG:4326").apply(frame.origin() + Vec2(-500.0, 100.0));
  // 25 m a column, 50 m a row: A-U every 50 m from x = -500 to 500, the street a-b at x = 25.
  test::OsmSketch sketch(R"(
                           a


      A-B-C-D-E-F-G-H-I-J-K-L-M-N-O-P-Q-R-S-T-U


                           b
  )",
                         25.0, {west.x(), west.y()});
  const test::OsmSketch::Tags ground{{"highway", "primary"}, {"lanes", "2"}};
  test::OsmSketch::Tags bridge = ground;
  bridge.insert(bridge.end(), {{"bridge", "yes"}, {"layer", "1"}});
  sketch.way("ABCDE", ground)
      .way("EFGHI", bridge)
      .way("IJKLM", bridge)
      .way("MNOPQ", bridge)
      .way("QRSTU", ground);
  sketch.way("ab", {{"highway", "residential"}});
  const std::filesystem::path input = test::scratch_dir("chain_input");
  const std::filesystem::path osm = sketch.write(input / "viaduct.osm");
  // Flat at 100 m but for the valley under the deck (x in [-300, 300], 30 m deep at x = 0).
  const std::string dem = test::write_local_dem("chain_valley", 800.0, 10.0, [](double x, double) {
    const double u = std::abs(x) / 300.0;
    return u >= 1.0 ? 100.0 : 100.0 - 30.0 * std::pow(std::cos(0.5 * std::numbers::pi * u), 2.0);
  });
  const std::filesystem::path dir = test::scratch_dir("chain_tiles");
  const Region r = tile_and_merge(osm, dem, 200.0, dir, 50.0);
  expect_like_the_whole_build(r);
  // Some windows took ways beyond their halo for the chain.
  std::size_t chain_ways = 0;
  for (const TileSpec& t : r.manifest.tiles) {
    std::ifstream in(tile_dir(dir, t.x, t.y) / "tile.json");
    chain_ways += nlohmann::json::parse(in).at("window").at("chain_ways").get<std::size_t>();
  }
  EXPECT_GT(chain_ways, 0u);
}

TEST(TilesRealData, NortheastIn500mTilesMergesLikeTheWholeBuild) {
  RELIEF_REQUIRE_SHARED_DATA();
  const Region r = tile_and_merge(test::shared_data("sf-ne/sf_ne_drive_2017.osm.gz"),
                                  test::shared_data("sf-ne/sf_ne_usgs24k_30m_nad27utm10_m.tif").string(),
                                  500.0, test::scratch_dir("northeast"));
  expect_like_the_whole_build(r);
  EXPECT_EQ(r.manifest.tiles.size(), 52u);
}

// A mountain country in 2 km tiles: 37 tiles, 15 616 roads. Five roads (of Vordersilumstrasse's
// kind: long climbs whose grades bind) come out 1-10 mm from the whole build (README, tiles).
TEST(TilesRealData, LiechtensteinIn2kmTilesMergesLikeTheWholeBuild) {
  RELIEF_REQUIRE_SHARED_DATA();
  const Region r = tile_and_merge(
      test::shared_data("liechtenstein/liechtenstein-latest.osm.pbf"),
      "/vsizip/" + test::shared_data("liechtenstein/N47E009.hgt.zip").string() + "/N47E009.hgt", 2000.0,
      test::scratch_dir("liechtenstein"));
  expect_like_the_whole_build(r, 0.015);
  EXPECT_EQ(r.manifest.tiles.size(), 37u);
}

}  // namespace
}  // namespace relief

#include "relief/cosim/cosim.h"

#include <gtest/gtest.h>
#include <pugixml.hpp>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <sstream>

#include "relief/core/errors.h"
#include "relief/cosim/sumo_session.h"
#include "relief/geometry/crs_transform.h"
#include "relief/pipeline/build.h"
#include "support/osm_sketch.h"
#include "support/synthetic.h"
#include "support/test_data.h"

namespace relief {
namespace {

namespace fs = std::filesystem;

// The hill fixture (a plane rising 10 % north and 6 % east, avenues and streets, a bridge and a
// signalled crossing) built once, with every output.
const fs::path& hill_build() {
  static const fs::path dir = [] {
    BuildOptions o;
    o.osm_path = test::fixture("hill/hill.osm");
    o.dem_paths = {test::fixture("hill/hill_dem.asc").string()};
    o.out_dir = test::scratch_dir("cosim_hill");
    Diagnostics d;
    (void)build(o, d);
    return fs::path(o.out_dir);
  }();
  return dir;
}

// A configuration for `net` with a flow along every edge of it (a vehicle every `period` s
// from 0 to 60 s), written beside it.
fs::path write_config(const fs::path& net, const std::string& name, double period) {
  pugi::xml_document doc;
  EXPECT_TRUE(doc.load_file(net.c_str()));
  std::ofstream routes(net.parent_path() / (name + ".rou.xml"));
  routes << "<routes>\n";
  int n = 0;
  for (const pugi::xml_node& edge : doc.child("net").children("edge")) {
    if (!edge.attribute("function").empty()) continue;
    const std::string id = edge.attribute("id").as_string();
    routes << "  <flow id=\"f" << n++ << "\" begin=\"0\" end=\"60\" period=\"" << period << "\" from=\"" << id
           << "\" to=\"" << id << "\" departSpeed=\"max\"/>\n";
  }
  routes << "</routes>\n";
  routes.close();
  fs::path config = net.parent_path() / (name + ".sumocfg");
  std::ofstream out(config);
  out << "<configuration>\n  <input>\n    <net-file value=\"" << net.filename().string()
      << "\"/>\n    <route-files value=\"" << name << ".rou.xml\"/>\n  </input>\n</configuration>\n";
  return config;
}

// A straight two-way road up a 10 % plane (level across it), built by relief; a vehicle every
// 4 s each way. Every vehicle at every step: z within 0.01 m of the plane, pitch within 0.1
// degree of atan(0.1) (up or down), roll 0.
TEST(Cosim, OnATenPercentPlaneEveryVehicleSitsOnThePlaneWithItsSlope) {
  const GeoFrame frame = test::synthetic_frame();
  const Vec2 origin = CrsTransform(frame.crs(), "EPSG:4326").apply(frame.origin());
  const test::OsmSketch sketch = test::OsmSketch(R"(
      A--------------------B
  )",
                                                 10.0, {origin.x(), origin.y()})
                                     .way("AB", {{"highway", "residential"}, {"lanes", "2"}, {"width", "7"}});
  const auto local = [&](char letter) {
    const LonLat ll = sketch.lonlat(letter);
    return Vec2(CrsTransform("EPSG:4326", frame.crs()).apply(Vec2(ll.lon_deg, ll.lat_deg)) - frame.origin());
  };
  const Vec2 a = local('A'), b = local('B');
  const Vec2 along = (b - a).normalized();
  constexpr double kGrade = 0.1;
  const auto plane = [&](double x, double y) { return 20.0 + kGrade * (Vec2(x, y) - a).dot(along); };
  BuildOptions o;
  const fs::path dir = test::scratch_dir("cosim_plane");
  o.osm_path = sketch.write(dir / "plane.osm");
  o.dem_paths = {test::write_local_dem("cosim_plane", 400.0, 5.0, plane)};
  o.out_dir = dir / "out";
  o.crs = frame.crs();
  Diagnostics build_diagnostics;
  (void)build(o, build_diagnostics);

  const fs::path config = write_config(dir / "out" / "plane.net.xml", "plane", 4.0);
  CosimOptions options;
  options.end_s = 60.0;
  const fs::path out = dir / "cosim";
  Diagnostics d;
  const CosimResult r = run_cosim(find_cosim_inputs(config), options, out, d);
  EXPECT_GE(r.vehicles, 20u);
  EXPECT_EQ(r.unplaced, 0u);
  EXPECT_LT(r.z_error_m.max, 0.01);
  EXPECT_LT(r.pitch_error_deg.max, 0.1);
  // The frame of the build is not the synthetic one: measure the plane through the outputs' rows
  // against the one the trajectories' own first and last heights give along the road.
  std::ifstream csv(out / "plane.trajectories.csv");
  std::string line;
  std::getline(csv, line);
  std::size_t rows = 0;
  double worst_pitch = 0.0, worst_roll = 0.0;
  for (; std::getline(csv, line); ++rows) {
    std::vector<std::string> f;
    std::stringstream fields(line);
    for (std::string x; std::getline(fields, x, ',');) f.push_back(x);
    ASSERT_EQ(f.size(), 11u) << line;
    worst_pitch = std::max(
        worst_pitch, std::abs(std::abs(std::stod(f[9])) - std::atan(kGrade) * 180.0 / std::numbers::pi));
    worst_roll = std::max(worst_roll, std::abs(std::stod(f[10])));
  }
  EXPECT_EQ(rows, r.vehicle_steps);
  EXPECT_LT(worst_pitch, 0.1);
  EXPECT_LT(worst_roll, 0.1);
}

// Every vehicle on the hill: z and pitch as the OpenDRIVE surface says (within the scene's
// 0.02 m chord tolerance), every wheel on the road, SUMO's z on the surface too; the outputs hold
// every step of every vehicle.
TEST(Cosim, VehiclesOnTheHillSitOnTheOpenDriveSurface) {
  const fs::path config = write_config(hill_build() / "hill.net.xml", "hill", 5.0);
  const CosimInputs inputs = find_cosim_inputs(config);
  EXPECT_EQ(inputs.xodr, hill_build() / "hill.xodr");
  EXPECT_EQ(inputs.scene, hill_build() / "hill.glb");
  CosimOptions options;
  options.end_s = 60.0;
  const fs::path out = test::scratch_dir("cosim_hill_out");
  Diagnostics d;
  const CosimResult r = run_cosim(inputs, options, out, d);
  EXPECT_EQ(r.steps, 1200u);  // 60 s at 20 Hz
  EXPECT_NEAR(r.simulated_s, 60.0, 1e-9);
  EXPECT_GE(r.vehicles, 20u);
  EXPECT_GE(r.vehicle_steps, 5000u);
  EXPECT_EQ(r.unplaced, 0u);
  EXPECT_EQ(r.wheels_under_road, 0u);
  // The scene is lofted within 0.02 m of the OpenDRIVE surface, the SUMO lanes sampled from it.
  EXPECT_LE(r.z_error_m.p99, 0.02);
  EXPECT_LE(r.z_error_m.max, 0.05);
  EXPECT_LE(r.sumo_z_error_m.max, 0.05);
  EXPECT_LT(r.pitch_error_deg.p99, 0.5);
  EXPECT_GE(r.z_error_m.count, r.vehicle_steps * 9 / 10);  // measured nearly everywhere
  // cosim.json carries the figures; the trajectories one row per placement.
  std::ifstream json(out / "cosim.json");
  const nlohmann::json j = nlohmann::json::parse(json);
  EXPECT_EQ(j.at("steps").get<std::size_t>(), r.steps);
  EXPECT_EQ(j.at("vehicles").get<std::size_t>(), r.vehicles);
  EXPECT_DOUBLE_EQ(j.at("z_error_m").at("max").get<double>(), r.z_error_m.max);
  EXPECT_NEAR(j.at("sumo_share").get<double>() + j.at("relief_share").get<double>(), 1.0, 1e-9);
  std::ifstream csv(out / "hill.trajectories.csv");
  std::size_t rows = 0;
  for (std::string line; std::getline(csv, line);) ++rows;
  EXPECT_EQ(rows, r.vehicle_steps + 1);
  pugi::xml_document fcd;
  ASSERT_TRUE(fcd.load_file((out / "hill.fcd.xml").c_str()));
  std::size_t timesteps = 0;
  for ([[maybe_unused]] const pugi::xml_node& t : fcd.child("fcd-export").children("timestep")) ++timesteps;
  EXPECT_EQ(timesteps, r.steps);
  const pugi::xml_node first = fcd.child("fcd-export").child("timestep").child("vehicle");
  EXPECT_FALSE(first.attribute("pitch").empty());
  EXPECT_FALSE(first.attribute("roll").empty());
}

TEST(Cosim, ATrajectoryPeriodThinsTheRowsAndStopEndsCleanly) {
  const fs::path config = write_config(hill_build() / "hill.net.xml", "hill_thin", 5.0);
  CosimOptions options;
  options.end_s = 30.0;
  options.trajectory_period_s = 1.0;
  int polls = 0;
  options.stop_requested = [&] { return ++polls > 200; };  // "Ctrl-C" after 200 steps (10 s)
  const fs::path out = test::scratch_dir("cosim_hill_thin");
  Diagnostics d;
  const CosimResult r = run_cosim(find_cosim_inputs(config), options, out, d);
  EXPECT_TRUE(r.stopped);
  EXPECT_EQ(r.steps, 200u);
  pugi::xml_document fcd;
  ASSERT_TRUE(fcd.load_file((out / "hill.fcd.xml").c_str()));
  std::size_t timesteps = 0;
  for ([[maybe_unused]] const pugi::xml_node& t : fcd.child("fcd-export").children("timestep")) ++timesteps;
  EXPECT_EQ(timesteps, 10u);  // t = 0.05, 1.05, ..., 9.05
  EXPECT_TRUE(fs::exists(out / kCosimReportFile));
  EXPECT_TRUE(fs::exists(out / kCosimReplayFile));
  EXPECT_FALSE(fs::exists(out / ".hill.fcd.xml.part"));
  // No replay asked for: none written.
  options.replay_period_s = 0.0;
  polls = 0;
  const fs::path bare = test::scratch_dir("cosim_hill_bare");
  (void)run_cosim(find_cosim_inputs(config), options, bare, d);
  EXPECT_TRUE(fs::exists(bare / kCosimReportFile));
  EXPECT_FALSE(fs::exists(bare / kCosimReplayFile));
}

TEST(Cosim, InputsThatCannotServeSayWhich) {
  const fs::path dir = test::scratch_dir("cosim_bad_inputs");
  EXPECT_THROW((void)find_cosim_inputs(dir / "none.sumocfg"), IoError);
  std::ofstream(dir / "no_net.sumocfg") << "<configuration><input/></configuration>";
  EXPECT_THROW((void)find_cosim_inputs(dir / "no_net.sumocfg"), InvalidInput);
  std::ofstream(dir / "not_xml.sumocfg") << "<configuration";
  EXPECT_THROW((void)find_cosim_inputs(dir / "not_xml.sumocfg"), InvalidInput);
  // A net without its build's .xodr beside it.
  fs::copy_file(hill_build() / "hill.net.xml", dir / "alone.net.xml", fs::copy_options::overwrite_existing);
  std::ofstream(dir / "alone.sumocfg")
      << "<configuration><input><net-file value=\"alone.net.xml\"/></input></configuration>";
  try {
    (void)find_cosim_inputs(dir / "alone.sumocfg");
    FAIL() << "no .xodr";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("alone.xodr"), std::string::npos) << e.what();
  }
  // SUMO's own rejection (a route file that does not exist) is bad input with SUMO's words.
  std::ofstream(hill_build() / "bad_routes.sumocfg")
      << "<configuration><input><net-file value=\"hill.net.xml\"/><route-files value=\"nowhere.rou.xml\"/>"
         "</input></configuration>";
  Diagnostics d;
  EXPECT_THROW((void)run_cosim(find_cosim_inputs(hill_build() / "bad_routes.sumocfg"), {}, dir / "out", d),
               InvalidInput);
  EXPECT_FALSE(fs::exists(dir / "out" / "cosim.json"));
}

TEST(SumoSession, OneAtATimeInAProcess) {
  const fs::path config = write_config(hill_build() / "hill.net.xml", "hill_once", 5.0);
  SumoSession first(config, 0.05);
  EXPECT_THROW(SumoSession(config, 0.05), Error);
  first.step();
  EXPECT_NEAR(first.time(), 0.05, 1e-9);
}

}  // namespace
}  // namespace relief

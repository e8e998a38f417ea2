#include "relief/cosim/cosim.h"

#include <gtest/gtest.h>
#include <pugixml.hpp>

#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <sstream>

#include "relief/core/errors.h"
#include "relief/cosim/ego_controller.h"
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

// A straight two-way road of `length_m` up a plane of `grade` (level across it), built by
// relief in `dir` as a `highway` road; the edge that climbs (on the level: either) is returned with the net.
struct StraightRoad {
  fs::path net;
  std::string uphill_edge;
};
StraightRoad build_straight_road(const fs::path& dir, double grade, int chars, const std::string& highway,
                                 const std::string& maxspeed) {
  const GeoFrame frame = test::synthetic_frame();
  const Vec2 origin = CrsTransform(frame.crs(), "EPSG:4326").apply(frame.origin());
  const std::string line = "A" + std::string(static_cast<std::size_t>(chars), '-') + "B";
  const test::OsmSketch sketch =
      test::OsmSketch("\n  " + line + "\n", 10.0, {origin.x(), origin.y()})
          .way("AB", {{"highway", highway}, {"lanes", "2"}, {"width", "7"}, {"maxspeed", maxspeed}});
  const LonLat la = sketch.lonlat('A'), lb = sketch.lonlat('B');
  const CrsTransform to_local("EPSG:4326", frame.crs());
  const Vec2 a = to_local.apply(Vec2(la.lon_deg, la.lat_deg)) - frame.origin();
  const Vec2 b = to_local.apply(Vec2(lb.lon_deg, lb.lat_deg)) - frame.origin();
  const Vec2 along = (b - a).normalized();
  BuildOptions o;
  o.osm_path = sketch.write(dir / "road.osm");
  o.dem_paths = {
      test::write_local_dem(dir.filename().string(), 2.0 * (b - a).norm() + 200.0, 5.0,
                            [&](double x, double y) { return 20.0 + grade * (Vec2(x, y) - a).dot(along); })};
  o.out_dir = dir / "out";
  o.crs = frame.crs();
  o.sumo.max_grade_percent.clear();  // no class kept off the climb
  Diagnostics d;
  (void)build(o, d);
  StraightRoad road{dir / "out" / "road.net.xml", {}};
  pugi::xml_document doc;
  EXPECT_TRUE(doc.load_file(road.net.c_str()));
  for (const pugi::xml_node& edge : doc.child("net").children("edge")) {
    if (!edge.attribute("function").empty()) continue;
    std::stringstream shape(edge.child("lane").attribute("shape").as_string());
    std::vector<double> z;
    for (std::string point; shape >> point;) z.push_back(std::stod(point.substr(point.rfind(',') + 1)));
    if (road.uphill_edge.empty() || (z.size() >= 2 && z.back() > z.front()))
      road.uphill_edge = edge.attribute("id").as_string();
  }
  return road;
}

// One vehicle of the given type up `edge`, and a configuration for it beside the net.
fs::path write_single_vehicle_config(const fs::path& net, const std::string& edge, const std::string& vtype) {
  std::ofstream(net.parent_path() / "one.rou.xml")
      << "<routes>\n  " << vtype << "\n  <vehicle id=\"ego\" type=\"t\" depart=\"0\" departSpeed=\"max\">"
      << "<route edges=\"" << edge << "\"/></vehicle>\n</routes>\n";
  const fs::path config = net.parent_path() / "one.sumocfg";
  std::ofstream(config) << "<configuration><input><net-file value=\"" << net.filename().string()
                        << "\"/><route-files value=\"one.rou.xml\"/></input></configuration>";
  return config;
}

// The paper's check: an ego driven by the physics along a flat straight road keeps within
// 0.5 m of where SUMO has it (its lane) for 60 s, with no resync, and sits on the road.
TEST(Cosim, AnEgoOnAFlatStraightRoadKeepsWithinHalfAMetreOfSumoFor60Seconds) {
  const StraightRoad road =
      build_straight_road(test::scratch_dir("cosim_ego_flat"), 0.0, 80, "residential", "30");
  const fs::path config = write_single_vehicle_config(
      road.net, road.uphill_edge,
      R"(<vType id="t" vClass="passenger" length="4.5" width="1.8" speedDev="0"/>)");
  CosimOptions options;
  options.end_s = 60.0;
  options.egos = {"ego"};
  Diagnostics d;
  const CosimResult r = run_cosim(find_cosim_inputs(config), options, config.parent_path() / "cosim_flat", d);
  EXPECT_EQ(r.egos, 1u);
  EXPECT_GE(r.ego_steps, 1190u);  // driven the whole minute
  EXPECT_EQ(r.resyncs, 0u);
  EXPECT_LT(r.sync_error_m.max, 0.5);
  EXPECT_LT(r.sync_error_m.p99, 0.1);
  EXPECT_LT(r.ego_speed_gap_mps.p99, 0.2);  // SUMO's speed of it is the physics' speed
  EXPECT_LT(r.z_error_m.max, 0.02);
  EXPECT_EQ(r.wheels_under_road, 0u);
  std::ifstream json(config.parent_path() / "cosim_flat" / "cosim.json");
  const nlohmann::json j = nlohmann::json::parse(json);
  EXPECT_EQ(j.at("egos").get<std::size_t>(), 1u);
  EXPECT_DOUBLE_EQ(j.at("sync_error_m").at("max").get<double>(), r.sync_error_m.max);
  EXPECT_EQ(j.at("resyncs").get<std::size_t>(), 0u);
}

// An HDL-32E on the ego for 5 s: one sweep a turn (10 Hz), a point cloud each simulated second
// in both formats with the same points, every return on the flat road 1.9 m under the sensor
// (or the terrain beside it), and the rays CARLA's model casts: round(695 000 x 0.05 / 32) per
// channel and step.
TEST(Cosim, ALidarOnTheEgoWritesItsSweeps) {
  const StraightRoad road =
      build_straight_road(test::scratch_dir("cosim_lidar"), 0.0, 80, "residential", "30");
  const fs::path config = write_single_vehicle_config(
      road.net, road.uphill_edge,
      R"(<vType id="t" vClass="passenger" length="4.5" width="1.8" speedDev="0"/>)");
  CosimOptions options;
  options.end_s = 5.0;
  options.egos = {"ego"};
  options.lidars = {LidarMount{"hdl-32e", "", 1.9}};
  Diagnostics d;
  const fs::path out = config.parent_path() / "cosim_lidar";
  const CosimResult r = run_cosim(find_cosim_inputs(config), options, out, d);
  const LidarFigures& l = r.lidar;
  EXPECT_EQ(l.sensors, 1u);
  EXPECT_GE(l.sweeps, 48u);  // 100 steps, half a turn each, from the ego's first step
  EXPECT_LE(l.sweeps, 50u);
  EXPECT_EQ(l.rays, 2 * l.sweeps * 32u * 1086u);
  EXPECT_EQ(l.checked, 0u);  // no other vehicle
  EXPECT_GE(l.sweeps_written, 4u);
  ASSERT_GE(l.written.size(), 2u);
  const auto header_count = [](const fs::path& file, const std::string& key) {
    std::ifstream in(file, std::ios::binary);
    std::string line;
    while (std::getline(in, line))
      if (line.rfind(key, 0) == 0) return std::stoul(line.substr(key.size()));
    return 0UL;
  };
  const unsigned long points = header_count(out / l.written[0], "POINTS ");
  EXPECT_GT(points, 10000UL);
  EXPECT_EQ(header_count(out / l.written[1], "element vertex "), points);
  // An independent reader: Open3D (Debian's python3-open3d) reads both with that many points.
  const std::string script =
      "import open3d as o3d\nfor f in ('" + (out / l.written[0]).string() + "', '" +
      (out / l.written[1]).string() +
      "'):\n    assert len(o3d.io.read_point_cloud(f).points) == " + std::to_string(points) + ", f\n";
  std::ofstream(out / "open3d_check.py") << script;
  EXPECT_EQ(std::system(("/usr/bin/python3 " + (out / "open3d_check.py").string()).c_str()), 0);
  std::ifstream json(out / "cosim.json");
  const nlohmann::json j = nlohmann::json::parse(json);
  EXPECT_EQ(j.at("lidar").at("sweeps").get<std::size_t>(), l.sweeps);
  EXPECT_EQ(j.at("lidar").at("files").at(0).get<std::string>(), "lidar/ego/0_hdl-32e/000001.pcd");
  EXPECT_EQ(j.at("lidar").at("crests").size(), 0u);
  // cosim.html: the figures and the LiDAR section (no plot: no vehicle in range).
  std::ifstream html(out / "cosim.html");
  const std::string page((std::istreambuf_iterator<char>(html)), std::istreambuf_iterator<char>());
  EXPECT_NE(page.find("<h2>LiDAR</h2>"), std::string::npos);
  EXPECT_NE(page.find("sweeps"), std::string::npos);
}

// A loaded truck as the ego up a long 15 % climb, SUMO wanting 50 km/h: it settles where its
// power carries the climb (P = m g v (sin a + c_rr cos a) + drag, within 10 %), and SUMO has
// it at that speed too.
TEST(Cosim, AHeavyEgoOnAFifteenPercentClimbSlowsToItsPowerLimitAndSumoSeesIt) {
  constexpr double kGrade = 0.15;
  const StraightRoad road =
      build_straight_road(test::scratch_dir("cosim_ego_climb"), kGrade, 90, "secondary", "50");
  const fs::path config = write_single_vehicle_config(
      road.net, road.uphill_edge,
      R"(<vType id="t" vClass="truck" length="7.1" width="2.4" height="3.4" speedDev="0" accel="1.3"/>)");
  CosimOptions options;
  options.end_s = 70.0;
  options.egos = {"ego"};
  options.trajectory_period_s = 1.0;
  Diagnostics d;
  const fs::path out = config.parent_path() / "cosim_climb";
  const CosimResult r = run_cosim(find_cosim_inputs(config), options, out, d);
  EXPECT_EQ(r.egos, 1u);
  EXPECT_EQ(r.resyncs, 0u);
  // The last 20 s of the trajectory: speed and pitch.
  std::ifstream csv(out / "road.trajectories.csv");
  std::string line;
  std::getline(csv, line);
  double speed = 0.0, pitch = 0.0;
  int n = 0;
  for (; std::getline(csv, line);) {
    std::vector<std::string> f;
    std::stringstream fields(line);
    for (std::string x; std::getline(fields, x, ',');) f.push_back(x);
    ASSERT_EQ(f.size(), 11u) << line;
    if (std::stod(f[0]) < 50.0) continue;
    speed += std::stod(f[8]);
    pitch += std::stod(f[9]);
    ++n;
  }
  ASSERT_GE(n, 15);
  speed /= n;
  pitch /= n;
  EXPECT_NEAR(pitch, std::atan(kGrade) * 180.0 / std::numbers::pi, 1.0);  // the road climbs 15 %
  const double expected = power_limited_speed(ego_spec_for("truck", 7.1, 2.4, 3.4), kGrade);
  EXPECT_NEAR(speed, expected, 0.1 * expected);
  EXPECT_LT(r.ego_speed_gap_mps.p99, 0.1 * expected);
}

TEST(SumoSession, OneAtATimeInAProcess) {
  const fs::path config = write_config(hill_build() / "hill.net.xml", "hill_once", 5.0);
  SumoSession first(config, 0.05);
  EXPECT_THROW(SumoSession(config, 0.05), Error);
  first.step();
  EXPECT_NEAR(first.time(), 0.05, 1e-9);
}

// libsumo 1.15 keeps the vehicles moved for the next step in a static list that closing does not
// clear: a session that ended right after a move crashed the next one at its first step.
TEST(SumoSession, AVehicleMovedJustBeforeTheEndDoesNotHauntTheNextSession) {
  const fs::path config = write_config(hill_build() / "hill.net.xml", "hill_moved", 2.0);
  {
    SumoSession first(config, 0.05);
    std::vector<SumoVehicleState> vehicles;
    for (int i = 0; i < 100 && vehicles.empty(); ++i) {
      first.step();
      vehicles = first.vehicles();
    }
    ASSERT_FALSE(vehicles.empty());
    const SumoVehicleState& v = vehicles.front();
    first.move_to(v.id, v.lane, Vec2(v.front.x(), v.front.y()), v.angle_deg);
  }
  SumoSession second(config, 0.05);
  for (int i = 0; i < 40; ++i) second.step();
  EXPECT_NEAR(second.time(), 2.0, 1e-9);
  EXPECT_FALSE(second.vehicles().empty());
}

// A SUMO the user started with --remote-port: the session attaches to it and runs the same
// traffic as in this process; one whose step differs from the session's is refused, naming both,
// and a port where nothing answers is bad input.
TEST(SumoSession, AttachesToASumoRunningWithARemotePort) {
  const fs::path config = write_config(hill_build() / "hill.net.xml", "hill_remote", 2.0);
  std::vector<SumoVehicleState> in_process;
  {
    SumoSession sumo(config, 0.05);
    for (int i = 0; i < 100; ++i) sumo.step();
    in_process = sumo.vehicles();
  }
  ASSERT_GE(in_process.size(), 3u);
  const int port = 20000 + static_cast<int>(::getpid() % 20000);
  const auto start_sumo = [&](double step) {
    const std::string command = "cd '" + config.parent_path().string() + "' && sumo -c '" + config.string() +
                                "' --step-length " + std::to_string(step) + " --remote-port " +
                                std::to_string(port) + " --no-step-log true >/dev/null 2>&1 &";
    ASSERT_EQ(std::system(command.c_str()), 0);
  };
  SumoEndpoint remote;
  remote.mode = SumoEndpoint::Mode::attach;
  remote.port = port;
  start_sumo(0.05);
  {
    SumoSession sumo(config, 0.05, {}, remote);
    for (int i = 0; i < 100; ++i) sumo.step();
    EXPECT_NEAR(sumo.time(), 5.0, 1e-9);
    const std::vector<SumoVehicleState> attached = sumo.vehicles();
    ASSERT_EQ(attached.size(), in_process.size());
    for (std::size_t i = 0; i < attached.size(); ++i) {
      EXPECT_EQ(attached[i].id, in_process[i].id);
      EXPECT_EQ(attached[i].lane, in_process[i].lane);
      EXPECT_NEAR((attached[i].front - in_process[i].front).norm(), 0.0, 1e-9) << attached[i].id;
      EXPECT_NEAR(attached[i].speed_mps, in_process[i].speed_mps, 1e-9);
    }
  }
  start_sumo(0.1);
  try {
    SumoSession sumo(config, 0.05, {}, remote);
    ADD_FAILURE() << "a SUMO stepping 0.1 s was taken for 0.05 s";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("--step-length 0.05"), std::string::npos) << e.what();
  }
  SumoEndpoint nowhere = remote;
  nowhere.port = 1;
  nowhere.connect_attempts = 1;
  EXPECT_THROW(SumoSession(config, 0.05, {}, nowhere), InvalidInput);
  // And a session can start after each of those.
  SumoSession after(config, 0.05);
  after.step();
  EXPECT_NEAR(after.time(), 0.05, 1e-9);
}

}  // namespace
}  // namespace relief

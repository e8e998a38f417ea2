// The OpenDRIVE written by `build` on the real SF data: schema-valid, read back exactly, lane
// borders continuous at every link, and imported by SUMO's netconvert with our heights.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <regex>
#include <sstream>

#include "pipeline/sf_options.h"
#include "relief/pipeline/build.h"
#include "relief/roads/opendrive_reader.h"
#include "relief/roads/road_surface.h"
#include "support/test_data.h"

namespace relief {
namespace {

bool have(const char* tool) {
  return std::system((std::string("command -v ") + tool + " >/dev/null 2>&1").c_str()) == 0;
}

struct Built {
  RunReport report;
  std::filesystem::path xodr;
};

// The OpenDRIVE of an SF set's default build, shared with the other tests of its suite
// (test::sf_potrero); the tests write only into their own scratch directories.
Built shared_build(const test::SfBuild& sf) {
  const RunReport& r = sf.result.report;
  return {r, sf.options.out_dir / (r.name + ".xodr")};
}

// `max_crossing_step_m`: the largest height step allowed where two connecting roads' lane
// centres cross (they follow their junction's one height surface, leaving it only where it is
// steeper along them than their grade bound; measured on 2026-11-28: Potrero 0.010 m, NE 0.017
// m, no junction over 0.02 m; 0.061 and 0.22 m, one junction over in each, when a road too steep
// on the surface took the cubic between its ends instead). `max_over_road_step_m`: the
// largest height difference where a connecting road's lane centre runs over one of its
// junction's roads (a road end lying between others; measured with the ends trimmed out of the
// connecting roads' way: Potrero 0.017 m, NE 0.020 m; 0.027 and 0.133 m before, NE's at J235).
void check_set(const Built& b, double max_crossing_step_m, double max_over_road_step_m) {
  ASSERT_TRUE(b.report.opendrive);
  const OpenDriveSummary& o = *b.report.opendrive;
  std::cout << b.report.name << ": " << o.roads << " roads, " << o.junctions << " junctions, "
            << o.connecting_roads << " connecting roads, link gap " << o.max_link_gap_m << " m / step "
            << o.max_link_step_m << " m over " << o.link_borders_checked << " borders, round trip "
            << o.round_trip_max_xy_m << " / " << o.round_trip_max_z_m << " m, elevation vs fit "
            << o.elevation_max_deviation_m << " m\n";
  // One OpenDRIVE junction per intersection of the network, but for intersections where no
  // movement is possible (the NE extract has one: three one-ways leaving a node whose feeder
  // is outside it), which are reported, and intersections joined into a neighbour's junction
  // (one per road absorbed at least: a cluster of k intersections holds k - 1 roads or more);
  // besides, one per two-road bend too tight for a transition road.
  EXPECT_EQ(o.junctions + o.junctions_without_movements + o.junctions_joined,
            b.report.network.intersections + o.transitions_as_junctions);
  EXPECT_GE(o.roads_absorbed, o.junctions_joined);
  EXPECT_LE(o.junctions_without_movements, 1u);
  EXPECT_GT(o.connecting_roads, 2 * o.junctions);
  EXPECT_LT(o.max_link_gap_m, 0.01);
  EXPECT_LT(o.max_link_step_m, 0.01);
  EXPECT_LT(o.round_trip_max_xy_m, 0.02);
  EXPECT_LT(o.round_trip_max_z_m, 0.02);
  EXPECT_LT(o.elevation_max_deviation_m, 0.02);
  std::cout << "  connecting roads off their junction's surface " << o.connecting_roads_off_surface
            << "; crossing step " << o.crossing_max_step_m << " m, " << o.crossing_junctions_over
            << " junctions over 0.02 m\n";
  EXPECT_LE(o.connecting_roads_off_surface, o.connecting_roads / 100);
  EXPECT_LE(o.crossing_max_step_m, max_crossing_step_m);
  EXPECT_EQ(o.crossing_junctions_over, 0u);
  std::cout << "  connecting roads over a road's pavement: step " << o.over_road_max_step_m
            << " m at junction " << o.over_road_worst_junction << " (road " << o.over_road_worst_road << "), "
            << o.over_road_junctions_over << " junctions over 0.02 m\n";
  EXPECT_LE(o.over_road_max_step_m, max_over_road_step_m);

  // The ASAM schema.
  if (!have("xmllint")) GTEST_SKIP() << "xmllint not installed";
  // xmllint cannot compile the schema through a path with "..": its includes resolve twice.
  const std::string xsd =
      std::filesystem::weakly_canonical(test::shared_data("").parent_path().parent_path() /
                                        "opendrive-xsd/1.7.0/opendrive_17_core.xsd")
          .string();
  const auto log = test::scratch_dir("odr_xmllint") / (b.xodr.filename().string() + ".xmllint");
  const std::string cmd =
      "xmllint --noout --schema '" + xsd + "' '" + b.xodr.string() + "' 2>" + log.string();
  EXPECT_EQ(std::system(cmd.c_str()), 0) << "see " << log;
}

TEST(SfPotrero, OpenDriveValidatesAndReadsBack) {
  RELIEF_REQUIRE_SHARED_DATA();
  check_set(shared_build(test::sf_potrero()), 0.02, 0.022);
}

TEST(SfNortheast, OpenDriveValidatesAndReadsBack) {
  RELIEF_REQUIRE_SHARED_DATA();
  check_set(shared_build(test::sf_northeast()), 0.025, 0.025);
}

TEST(SfPotrero, NetconvertImportsOpenDriveWithOurHeights) {
  RELIEF_REQUIRE_SHARED_DATA();
  if (!have("netconvert")) GTEST_SKIP() << "SUMO netconvert not installed";
  const Built b = shared_build(test::sf_potrero());
  const auto dir = test::scratch_dir("odr_netconvert");
  const auto net = dir / "imported.net.xml";
  const auto log = dir / "netconvert.log";
  const std::string cmd = "SUMO_HOME=${SUMO_HOME:-/usr/share/sumo} netconvert --opendrive-files '" +
                          b.xodr.string() + "' -o '" + net.string() +
                          "' --offset.disable-normalization true 2>'" + log.string() + "'";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << "see " << log;
  std::ifstream log_in(log);
  std::stringstream log_text;
  log_text << log_in.rdbuf();
  EXPECT_EQ(log_text.str().find("Error"), std::string::npos) << log_text.str();

  // Heights: every point of every lane shape netconvert wrote lies at our surface's height at
  // the nearest station of the same road (edge "-12" or "12.0" came from road 12).
  const RoadModel model = read_opendrive(b.xodr);
  std::ifstream in(net);
  std::stringstream text;
  text << in.rdbuf();
  const std::string xml = text.str();
  const std::regex lane_shape(R"re(<lane id="-?([0-9]+)[^"]*"[^>]*shape="([^"]+)")re");
  double worst = 0.0;
  std::size_t points = 0;
  std::vector<double> errors;
  for (auto it = std::sregex_iterator(xml.begin(), xml.end(), lane_shape); it != std::sregex_iterator();
       ++it) {
    const int index = model.road_index(std::stoi((*it)[1].str()));
    if (index < 0) continue;
    const ModelRoad& road = model.roads[index];
    std::stringstream shape((*it)[2].str());
    std::vector<Vec3> pts;
    for (std::string triple; shape >> triple;) {
      double x = 0, y = 0, z = 0;
      if (std::sscanf(triple.c_str(), "%lf,%lf,%lf", &x, &y, &z) == 3) pts.emplace_back(x, y, z);
    }
    // The first and last points are netconvert's junction nodes, one height per node (its
    // junction flattening): compare the points along the road.
    for (std::size_t k = 1; k + 1 < pts.size(); ++k) {
      const double x = pts[k].x(), y = pts[k].y(), z = pts[k].z();
      double best = 1e9, best_z = 0.0;
      for (double st = 0.0; st <= road.length() + 0.05; st += 0.1) {
        const Vec3 p = surface_point(road, std::min(st, road.length()), 0.0);
        const double d = (p.head<2>() - Vec2(x, y)).norm();
        if (d < best) {
          best = d;
          best_z = p.z();
        }
      }
      worst = std::max(worst, std::abs(z - best_z));
      errors.push_back(std::abs(z - best_z));
      ++points;
    }
  }
  std::sort(errors.begin(), errors.end());
  const double p99 = errors.empty() ? 0.0 : errors[errors.size() * 99 / 100];
  const double median = errors.empty() ? 0.0 : errors[errors.size() / 2];
  std::cout << "netconvert heights vs relief's: " << points << " lane points inside edges, median " << median
            << " m, p99 " << p99 << " m, worst " << worst << " m\n";
  EXPECT_GT(points, 500u);
  EXPECT_LT(median, 0.01);
  EXPECT_LT(p99, 0.1);
}

}  // namespace
}  // namespace relief

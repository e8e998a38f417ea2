// Golden OpenDRIVE files of small hand-made networks (relief's road model + writer together).
// Regenerate after an intended change with RELIEF_UPDATE_GOLDEN=1 and review the diff.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>

#include "relief/export/opendrive_writer.h"
#include "relief/roads/profile_fit.h"
#include "relief/roads/road_model_builder.h"
#include "relief/roads/road_model_checks.h"
#include "support/synthetic.h"
#include "support/test_data.h"

namespace relief {
namespace {

WayAttributes street(HighwayClass cls, int forward, int backward, bool oneway = false) {
  WayAttributes a;
  a.highway = cls;
  a.lanes_forward = forward;
  a.lanes_backward = backward;
  a.oneway = oneway;
  a.lane_width_m = 3.25;
  return a;
}

// Writes the model of `net` draped on `ground` and fitted, and compares it with the golden file.
// Where connecting roads cross, their surfaces lie within `max_crossing_step_m` of each other
// (they lie on their junction's one height surface).
void check_golden(const std::string& name, const RoadNetwork& net,
                  const std::function<double(const Vec2&)>& ground, double max_crossing_step_m) {
  const std::vector<RoadProfile> raw = test::drape(net, ground);
  Diagnostics d;
  const ProfileFitResult fit = fit_profiles(net, raw, {}, d);
  RoadModelBuild built = build_road_model(net, fit.profiles, {}, d);
  built.model.name = name;
  const LinkContinuity c = check_link_continuity(built.model);
  EXPECT_LT(c.max_horizontal_m, 1e-6) << name;
  EXPECT_LT(c.max_vertical_m, 1e-6) << name;
  const ConnectingRoadCrossings crossings = check_connecting_road_crossings(built.model);
  std::cout << name << ": " << crossings.crossings << " crossings of connecting roads, largest step "
            << crossings.max_step_m << " m\n";
  EXPECT_LE(crossings.max_step_m, max_crossing_step_m) << name;
  OpenDriveOptions o;
  o.decimals = 4;
  o.date = "2026-01-01T00:00:00Z";
  std::ostringstream out;
  write_opendrive(out, built.model, o);
  const auto golden = std::filesystem::path(RELIEF_SOURCE_DIR) / "tests/pipeline/golden" / (name + ".xodr");
  if (std::getenv("RELIEF_UPDATE_GOLDEN")) {
    std::ofstream(golden) << out.str();
    GTEST_SKIP() << "updated " << golden;
  }
  std::ifstream in(golden);
  ASSERT_TRUE(in) << "missing golden file " << golden;
  std::stringstream expected;
  expected << in.rdbuf();
  EXPECT_EQ(out.str(), expected.str()) << "differs from " << golden;
}

TEST(OpenDriveGolden, TJunctionOnASlope) {
  const RoadNetwork net =
      test::make_network({{{-80, 0}, {0, 0}}, {{0, 0}, {80, 0}}, {{0, 0}, {0, -80}}},
                         {street(HighwayClass::residential, 1, 1), street(HighwayClass::residential, 1, 1),
                          street(HighwayClass::residential, 1, 1)});
  // 5.7 mm: the road ends carry only the share of the plane's roll their roads determine
  // (junction_planes.h), so their planes differ a little from the ground's (4.5 mm before the
  // junction's height surface, when each connecting road ran its own cubic between its ends).
  check_golden(
      "t_junction_slope", net, [](const Vec2& p) { return 20.0 + 0.06 * p.x() + 0.04 * p.y(); }, 0.007);
}

TEST(OpenDriveGolden, FourWayCrossing) {
  const RoadNetwork net =
      test::make_network({{{-60, 0}, {0, 0}}, {{0, 0}, {60, 0}}, {{0, -60}, {0, 0}}, {{0, 0}, {0, 60}}},
                         {street(HighwayClass::primary, 2, 2), street(HighwayClass::primary, 2, 2),
                          street(HighwayClass::residential, 1, 1), street(HighwayClass::residential, 1, 1)});
  check_golden(
      "four_way", net, [](const Vec2&) { return 12.0; }, 1e-6);
}

TEST(OpenDriveGolden, OneWayPair) {
  // Two one-way streets in opposite directions joined by a two-way cross street.
  const RoadNetwork net = test::make_network(
      {{{-50, 10}, {0, 10}},
       {{0, 10}, {50, 10}},
       {{50, -10}, {0, -10}},
       {{0, -10}, {-50, -10}},
       {{0, -10}, {0, 10}}},
      {street(HighwayClass::secondary, 2, 0, true), street(HighwayClass::secondary, 2, 0, true),
       street(HighwayClass::secondary, 2, 0, true), street(HighwayClass::secondary, 2, 0, true),
       street(HighwayClass::residential, 1, 1)});
  check_golden(
      "oneway_pair", net, [](const Vec2& p) { return 5.0 + 0.02 * p.x(); }, 1e-3);
}

TEST(OpenDriveGolden, BridgeOverAValley) {
  WayAttributes bridge = street(HighwayClass::secondary, 1, 1);
  bridge.bridge = true;
  bridge.layer = 1;
  const RoadNetwork net = test::make_network(
      {{{0, 0}, {100, 0}}, {{100, 0}, {220, 0}}, {{220, 0}, {320, 0}}},
      {street(HighwayClass::secondary, 1, 1), bridge, street(HighwayClass::secondary, 1, 1)});
  check_golden(
      "bridge", net, [](const Vec2& p) { return 30.0 - std::max(0.0, 20.0 - 0.3 * std::abs(p.x() - 160.0)); },
      1e-6);
}

}  // namespace
}  // namespace relief

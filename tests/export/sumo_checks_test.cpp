#include "relief/export/sumo_checks.h"
#include "relief/export/sumo_drape.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <numbers>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "relief/core/errors.h"
#include "support/sumo_ramp.h"

namespace relief {
namespace {

using test::ramp_model;

// atan(0.1) in degrees: SUMO's slope on a 10 % ramp.
const double kRampDeg = std::atan(0.1) * 180.0 / std::numbers::pi;

const char* const kNet = test::ramp_net_xml();

std::string fcd_sample(const std::string& id, double x, double y, double z, double slope,
                       const std::string& lane) {
  return "    <vehicle id=\"" + id + "\" x=\"" + std::to_string(x) + "\" y=\"" + std::to_string(y) +
         "\" z=\"" + std::to_string(z) + "\" angle=\"90.00\" speed=\"10.00\" lane=\"" + lane + "\" slope=\"" +
         std::to_string(slope) + "\"/>\n";
}

TEST(SumoChecks, NetLanesOnARampMapToTheirRoadsIncludingInternalLanes) {
  const RoadModel model = ramp_model();
  const SumoNetCheck check = check_sumo_net(kNet, model, "ramp.net.xml");
  EXPECT_EQ(check.edges, 3u);
  EXPECT_EQ(check.lanes, 3u);
  EXPECT_EQ(check.internal_lanes, 1u);
  EXPECT_EQ(check.junctions, 3u);
  EXPECT_EQ(check.points, 8u);
  EXPECT_EQ(check.points_unmapped, 0u);  // the internal lane through the model's junction
  EXPECT_NEAR(check.z_max_m, 0.0, 1e-9);
  EXPECT_NEAR(check.xy_max_m, 0.0, 1e-9);
  EXPECT_NEAR(check.max_lane_grade_percent, 10.0, 1e-9);
  EXPECT_NEAR(check.max_internal_lane_grade_percent, 10.0, 1e-9);
  EXPECT_EQ(check.handovers, 2u);  // 1 -> :J_0_0 and :J_0_0 -> 3
  EXPECT_NEAR(check.max_handover_step_m, 0.0, 1e-9);
  EXPECT_NEAR(check.max_handover_gap_m, 0.0, 1e-9);
  EXPECT_EQ(check.disallowed_lanes, 1u);
}

TEST(SumoChecks, AHandOverWhoseLanesDoNotMeetIsAGap) {
  // netconvert cut edge 3 at an outline of its own: its lane starts 6 m on from where the
  // internal lane ends (on the same ramp, so no height step), and a vehicle jumps 6 m there.
  std::string net = kNet;
  const std::string lane3 = "shape=\"110,-1.5,11 210,-1.5,21\"";
  net.replace(net.find(lane3), lane3.size(), "shape=\"116,-1.5,11.6 210,-1.5,21\"");
  const SumoNetCheck check = check_sumo_net(net, ramp_model(), "ramp.net.xml");
  EXPECT_NEAR(check.max_handover_gap_m, 6.0, 1e-9);
  EXPECT_EQ(check.handover_gap_lanes, ":J_0_0 -> 3_0");
  EXPECT_NEAR(check.handover_gap_point.x(), 110.0, 1e-9);
  EXPECT_NEAR(check.max_handover_step_m, 0.6, 1e-9);
  EXPECT_EQ(check.height_steps, 0u);  // 0.6 m over 6 m is no step
}

TEST(SumoChecks, NamesTheLanesOfTheWorstPoints) {
  const RoadModel model = ramp_model();
  std::string net = kNet;
  // Lane 3_0's far end 0.03 m high and 0.2 m off its lane centre; the plane z = 0.1 x keeps
  // the surface height at the moved point.
  const std::string end = "210,-1.5,21\"";
  net.replace(net.find(end), end.size(), "210,-1.7,21.03\"");
  const SumoNetCheck check = check_sumo_net(net, model, "ramp.net.xml");
  EXPECT_NEAR(check.z_max_m, 0.03, 1e-9);
  EXPECT_EQ(check.z_max_lane, "3_0");
  EXPECT_LT((check.z_max_point - Vec3(210.0, -1.7, 21.03)).norm(), 1e-9);
  EXPECT_NEAR(check.xy_max_m, 0.2, 1e-9);
  EXPECT_EQ(check.xy_max_lane, "3_0");
}

TEST(SumoDrape, LanePointsNetconvertLeftOffTheSurfaceTakeItsHeight) {
  const RoadModel model = ramp_model();
  std::string net = kNet;
  // Lane 1_0 cut and interpolated by netconvert: its end 0.6 m high, a point in its middle
  // 0.25 m low; the internal lane gains a point 0.5 m low and one without z.
  const std::string end = "0,-1.5,0 100,-1.5,10\"";
  net.replace(net.find(end), end.size(), "0,-1.5,0 50,-1.5,4.75 100,-1.5,10.6\"");
  const std::string internal = "shape=\"100,-1.5,10 110,-1.5,11\"/>";
  net.replace(net.find(internal), internal.size(),
              "shape=\"100,-1.5,10 104,-1.5,9.9 106,-1.5 110,-1.5,11\"/>");
  EXPECT_GT(check_sumo_net(net, model, "ramp.net.xml").z_max_m, 0.59);
  const SumoDrape drape = drape_sumo_net(net, model, "ramp.net.xml");
  EXPECT_EQ(drape.points, 11u);
  EXPECT_EQ(drape.points_unmapped, 0u);
  EXPECT_EQ(drape.points_moved, 4u);  // 0.6, 0.25, 0.5 and the point without z (10.6 m)
  EXPECT_NEAR(drape.max_move_m, 10.6, 1e-9);
  EXPECT_EQ(drape.max_move_lane, ":J_0_0");
  // x and y as they were, z on the plane z = 0.1 x (3 decimals), params kept: the check finds
  // every point on the surface and every lane on its road.
  EXPECT_NE(net.find("50,-1.5,5.000 "), std::string::npos) << net;
  EXPECT_NE(net.find("106,-1.5,10.600 "), std::string::npos) << net;
  const SumoNetCheck check = check_sumo_net(net, model, "ramp.net.xml");
  EXPECT_EQ(check.points, 11u);
  EXPECT_EQ(check.points_unmapped, 0u);
  EXPECT_EQ(check.lanes_without_z, 0u);
  EXPECT_LT(check.z_max_m, 5e-4);
  EXPECT_LT(check.xy_max_m, 1e-9);
  std::string not_a_net = "<osm/>";
  EXPECT_THROW((void)drape_sumo_net(not_a_net, model, "x.net.xml"), InvalidInput);
}

// A spiral ramp: an arc of radius `radius` about the origin from (0, -radius), `length` long,
// climbing `climb`, with one 3 m lane on its right (centre at t = -1.5).
RoadModel spiral_model(double radius, double length, double climb) {
  ModelRoad road;
  road.id = 1;
  PlanGeometry arc;
  arc.kind = PlanGeometry::Kind::arc;
  arc.start = Vec2(0.0, -radius);
  arc.heading = 0.0;
  arc.curvature = 1.0 / radius;
  arc.length = length;
  road.plan = PlanView({arc});
  road.elevation = CubicProfile({CubicPiece{0.0, {0.0, climb, 0.0, 0.0}}});
  road.lane_offset = CubicProfile::constant(0.0);
  LaneModel lane;
  lane.id = -1;
  lane.width = CubicProfile({CubicPiece{0.0, {3.0, 0.0, 0.0, 0.0}}});
  LaneSection section;
  section.right = {lane};
  road.sections = {section};
  RoadModel model;
  model.roads = {road};
  return model;
}

TEST(SumoDrape, ARoadOverItselfInPlanGivesEachTurnItsOwnHeight) {
  // A spiral ramp: two full turns of radius 20 m about the origin climbing 10 %, one 3 m lane
  // (centre at t = -1.5, radius 21.5 m). Every point of the second turn lies on one of the
  // first, 12.57 m lower; projected on the whole road it took the first turn's height (a
  // 12.6 m jump where the lane passes from one turn to the other's plan). Each point is now
  // looked for along the road from the one before.
  constexpr double kRadius = 20.0, kLength = 4.0 * std::numbers::pi * kRadius;
  const RoadModel model = spiral_model(kRadius, kLength, 0.1);

  // The lane every 2 degrees, all heights 0 (as if netconvert had dropped them).
  std::ostringstream shape;
  const int points = 360;
  for (int i = 0; i <= points; ++i) {
    const double a = 2.0 * (2.0 * std::numbers::pi) * i / points - 0.5 * std::numbers::pi;
    shape << (i == 0 ? "" : " ") << 21.5 * std::cos(a) << "," << 21.5 * std::sin(a) << ",0";
  }
  std::string net = R"(<net version="1.9">
  <edge id="1" from="A" to="B">
    <lane id="1_0" index="0" speed="10" length="270" shape=")" +
                    shape.str() + R"(">
      <param key="odr.lane" value="-1"/>
    </lane>
    <param key="odr.road" value="1"/>
  </edge>
  <junction id="A" type="dead_end" x="0" y="-20"/>
  <junction id="B" type="dead_end" x="0" y="-20"/>
</net>
)";
  const SumoDrape drape = drape_sumo_net(net, model, "spiral.net.xml");
  EXPECT_EQ(drape.points_unmapped, 0u);
  const SumoNetCheck check = check_sumo_net(net, model, "spiral.net.xml");
  EXPECT_EQ(check.points_unmapped, 0u);
  EXPECT_LT(check.z_max_m, 5e-4);
  EXPECT_EQ(check.height_steps, 0u);
  // The lane's last point, over its first, at the top: 0.1 x 251.3 m.
  const std::size_t last = net.rfind(' ', net.find("\">", net.find("shape=\"")));
  const std::string end = net.substr(last + 1, net.find("\">", last) - last - 1);
  EXPECT_NEAR(std::stod(end.substr(end.rfind(',') + 1)), 0.1 * kLength, 1e-3) << end;
}

// Generated spirals (radius, turns and climb at random) whose lane shapes have points at random
// angles, from 2 to 170 degrees apart, all heights 0: wherever the drape's bisection puts points
// and whatever the shape's gaps, the check, reading the final shape point by point, finds every
// point on the surface and no step. (The drape located an original point from the original point
// before it, the check from the point before it in the final shape, inserted points included;
// where those led to different turns, the check found the point off the surface.)
// A net of one edge with one lane of that shape on OpenDRIVE road 1, lane -1.
std::string one_lane_net(const std::string& shape, double length) {
  return R"(<net version="1.9">
  <edge id="1" from="A" to="B">
    <lane id="1_0" index="0" speed="10" length=")" +
         std::to_string(length) + R"(" shape=")" + shape + R"(">
      <param key="odr.lane" value="-1"/>
    </lane>
    <param key="odr.road" value="1"/>
  </edge>
</net>
)";
}

TEST(SumoDrape, SparseShapesOnGeneratedSpiralsLieOnTheSurfaceAsTheCheckReadsThem) {
  std::mt19937 rng(11U);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::size_t reheighted = 0;
  for (int seed = 0; seed < 200; ++seed) {
    const double radius = 12.0 + 30.0 * unit(rng), turns = 1.3 + 2.0 * unit(rng),
                 climb = 0.04 + 0.12 * unit(rng);
    const double length = 2.0 * std::numbers::pi * radius * turns;
    const RoadModel model = spiral_model(radius, length, climb);
    const double r = radius + 1.5, total = 2.0 * std::numbers::pi * turns;
    std::ostringstream shape;
    shape.precision(10);
    for (double a = 0.0;; a += (2.0 + 168.0 * unit(rng)) * std::numbers::pi / 180.0) {
      const double at = std::min(a, total) - 0.5 * std::numbers::pi;
      shape << (a == 0.0 ? "" : " ") << r * std::cos(at) << "," << r * std::sin(at) << ",0";
      if (a >= total) break;
    }
    std::string net = one_lane_net(shape.str(), length);
    const SumoDrape drape = drape_sumo_net(net, model, "spiral.net.xml");
    reheighted += drape.points_reheighted;
    const SumoNetCheck check = check_sumo_net(net, model, "spiral.net.xml");
    SCOPED_TRACE("spiral " + std::to_string(seed) + ": radius " + std::to_string(radius) + " m, " +
                 std::to_string(turns) + " turns");
    EXPECT_EQ(check.points_unmapped, 0u);
    EXPECT_LT(check.z_max_m, 5e-4);
    EXPECT_EQ(check.height_steps, 0u);
  }
  std::cout << "spirals: " << reheighted << " points took another height in the final order\n";
}

TEST(SumoChecks, AStepIsSteeperThanItsRoadMayBe) {
  // A lane climbing 70 % on its surface, points 0.4 m apart: a step on a street (35 % cap: steps
  // from 50 %), none on a footway fitted to its 100 % cap (steps from 115 %), one again on the
  // footway where a point sits 0.8 m high.
  const double radius = 400.0, length = 60.0;
  const RoadModel model = spiral_model(radius, length, 0.7);
  const double r = radius + 1.5;
  std::ostringstream shape;
  shape.precision(10);
  for (double s = 0.0; s <= length + 1e-9; s += 0.4) {
    const double at = s / radius - 0.5 * std::numbers::pi;
    shape << (s == 0.0 ? "" : " ") << r * std::cos(at) << "," << r * std::sin(at) << ",0";
  }
  std::string net = one_lane_net(shape.str(), length);
  (void)drape_sumo_net(net, model, "steep.net.xml");
  EXPECT_EQ(check_sumo_net(net, model, "steep.net.xml").height_steps, 1u);
  EXPECT_EQ(check_sumo_net(net, model, "steep.net.xml", {0.35}).height_steps, 1u);
  const SumoNetCheck path = check_sumo_net(net, model, "steep.net.xml", {1.0});
  EXPECT_EQ(path.height_steps, 0u);
  EXPECT_LT(path.z_max_m, 5e-4);
  // A 0.8 m jump within 0.4 m (200 %) is a step whatever the road.
  const std::size_t third = net.find(' ', net.find(' ', net.find("shape=\"") + 1) + 1);
  const std::size_t comma = net.rfind(',', net.find(' ', third + 1));
  const double z = std::stod(net.substr(comma + 1));
  net.replace(comma + 1, net.find(' ', third + 1) - comma - 1, std::to_string(z + 0.8));
  EXPECT_EQ(check_sumo_net(net, model, "steep.net.xml", {1.0}).height_steps, 1u);
}

TEST(SumoDrape, AChordOverACrestGetsPointsUntilItLiesOnTheSurface) {
  // Road 1 climbs over a crest, z = 0.3 s - 0.002 s^2 (0 and 10 m at its ends as on the ramp, 5 m
  // above the ramp at s = 50). Its lanes have a point at each end only: SUMO would carry a
  // vehicle along the chord, 5 m under the crest. The chord error of the parabola over h metres
  // is 0.002 h^2 / 4: bisection stops at 100 / 32 = 3.1 m (0.005 m), 31 points in each lane.
  RoadModel model = ramp_model();
  for (ModelRoad& road : model.roads)
    if (road.id == 1) road.elevation = CubicProfile({CubicPiece{0.0, Poly3{0.0, 0.3, -0.002, 0.0}}});
  std::string net = kNet;
  const SumoDrape drape = drape_sumo_net(net, model, "ramp.net.xml");
  EXPECT_EQ(drape.points_added, 62u);
  const SumoNetCheck check = check_sumo_net(net, model, "ramp.net.xml");
  EXPECT_EQ(check.points, 8u + 62u);
  EXPECT_LE(check.z_max_m, 5e-4 + 1e-9);  // z written to 3 decimals
  // Between every two points of the lanes of road 1, the chord within 0.01 m of the surface.
  const std::size_t at = net.find("id=\"1_0\"");
  ASSERT_NE(at, std::string::npos);
  const std::size_t from = net.find("shape=\"", at) + 7;
  std::istringstream in(net.substr(from, net.find('"', from) - from));
  std::vector<Vec3> points;
  for (std::string token; in >> token;) {
    double x = 0, y = 0, z = 0;
    ASSERT_EQ(std::sscanf(token.c_str(), "%lf,%lf,%lf", &x, &y, &z), 3) << token;
    points.emplace_back(x, y, z);
  }
  ASSERT_EQ(points.size(), 33u);
  for (std::size_t i = 0; i + 1 < points.size(); ++i) {
    const double s = 0.5 * (points[i].x() + points[i + 1].x());
    EXPECT_NEAR(0.5 * (points[i].z() + points[i + 1].z()), 0.3 * s - 0.002 * s * s, 0.01) << s;
  }
}

TEST(SumoChecks, InternalLanesNetconvertDrewAreMeasuredApart) {
  const RoadModel model = ramp_model();
  std::string net = kNet;
  const std::string shape = R"( shape="100,-1.5,10 110,-1.5,11" via)";
  net.replace(net.find(shape), shape.size(), " via");
  // netconvert's own curve for it: 0.3 m beside the lane centre, 0.04 m above the surface.
  const std::string lane = R"(shape="100,-1.5,10 110,-1.5,11")";
  const std::size_t at = net.find(lane, net.find(":J_0_0"));
  ASSERT_NE(at, std::string::npos);
  net.replace(at, lane.size(), R"(shape="100,-1.8,10.04 110,-1.8,11")");
  const SumoNetCheck check = check_sumo_net(net, model, "ramp.net.xml");
  EXPECT_EQ(check.points, 6u);
  EXPECT_EQ(check.points_netconvert_shape, 2u);
  EXPECT_NEAR(check.netconvert_shape_z_max_m, 0.04, 1e-9);
  EXPECT_NEAR(check.z_max_m, 0.0, 1e-9);
  EXPECT_NEAR(check.xy_max_m, 0.0, 1e-9);  // off the lane centre, but netconvert drew it
  EXPECT_EQ(check.points_unmapped, 0u);
}

TEST(SumoChecks, FcdHeightsAndSlopesAgainstTheRamp) {
  const RoadModel model = ramp_model();
  const std::string fcd =
      "<fcd-export>\n  <timestep time=\"0.00\">\n" + fcd_sample("up", 10.0, -1.5, 1.0, kRampDeg, "1_0") +
      // Against s the ramp goes down; this one is 0.2 m above the surface.
      fcd_sample("down", 50.0, 1.5, 5.2, -kRampDeg, "-1_0") +
      fcd_sample("junction", 105.0, -1.5, 10.5, kRampDeg, ":J_0_0") +
      "  </timestep>\n  <timestep time=\"1.00\">\n" +
      // One degree steeper than the ramp.
      fcd_sample("up", 20.0, -1.5, 2.0, kRampDeg + 1.0, "1_0") +
      fcd_sample("lost", 20.0, -1.5, 2.0, kRampDeg, "nowhere_0") + "  </timestep>\n</fcd-export>\n";
  const FcdCheck check = check_sumo_fcd(fcd, kNet, model, "ramp.fcd.xml");
  EXPECT_EQ(check.timesteps, 2u);
  EXPECT_EQ(check.vehicles, 4u);
  EXPECT_EQ(check.samples, 4u);
  EXPECT_EQ(check.slope_samples, 4u);
  EXPECT_EQ(check.samples_unmapped, 1u);
  EXPECT_EQ(check.samples_netconvert_shape, 0u);
  EXPECT_NEAR(check.z_max_m, 0.2, 1e-9);
  EXPECT_NEAR(check.z_p99_m, 0.0, 1e-9);  // rank floor(0.99 * 3) = 2 of {0, 0, 0, 0.2}
  EXPECT_NEAR(check.slope_max_deg, 1.0, 1e-5);
  EXPECT_NEAR(check.slope_p99_deg, 0.0, 1e-5);
}

TEST(SumoChecks, FcdWithoutZOrSlopeLeavesThoseFiguresOut) {
  const RoadModel model = ramp_model();
  const std::string fcd =
      "<fcd-export><timestep time=\"0\"><vehicle id=\"v\" x=\"10\" y=\"-1.5\" lane=\"1_0\"/></timestep>"
      "</fcd-export>";
  const FcdCheck check = check_sumo_fcd(fcd, kNet, model, "bare.fcd.xml");
  EXPECT_EQ(check.vehicles, 1u);
  EXPECT_EQ(check.samples, 0u);
  EXPECT_EQ(check.slope_samples, 0u);
  EXPECT_EQ(check.samples_unmapped, 0u);
}

TEST(SumoChecks, NotFcdOrNotANetworkThrows) {
  const RoadModel model = ramp_model();
  EXPECT_THROW((void)check_sumo_fcd("<fcd-export", kNet, model, "cut.fcd.xml"), InvalidInput);
  EXPECT_THROW((void)check_sumo_fcd("<routes/>", kNet, model, "routes.xml"), InvalidInput);
  EXPECT_THROW((void)check_sumo_fcd("<fcd-export/>", "<routes/>", model, "a.fcd.xml"), InvalidInput);
  EXPECT_THROW((void)check_sumo_net("<routes/>", model, "routes.xml"), InvalidInput);
  EXPECT_THROW((void)check_sumo_net("not xml <", model, "junk.xml"), InvalidInput);
}

}  // namespace
}  // namespace relief

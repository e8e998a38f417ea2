#include "export/sumo_seams.h"

#include <gtest/gtest.h>

#include <string>

#include "relief/export/sumo_checks.h"
#include "relief/export/sumo_drape.h"
#include "relief/roads/road_surface.h"
#include "support/sumo_ramp.h"

namespace relief {
namespace {

using test::ramp_model;

// The ramp network (support/sumo_ramp.h: lanes on z = 0.1 x, internal lane :J_0_0 from x 100
// to 110 at y = -1.5) with `what` replaced by `with`.
std::string ramp_net_with(const std::string& what, const std::string& with) {
  std::string net = test::ramp_net_xml();
  const std::size_t at = net.find(what);
  EXPECT_NE(at, std::string::npos) << what;
  if (at != std::string::npos) net.replace(at, what.size(), with);
  return net;
}

// The shape and length of lane `id` in `net`.
std::pair<std::string, double> lane_of(const std::string& net, const std::string& id) {
  pugi::xml_document doc;
  EXPECT_TRUE(doc.load_string(net.c_str()));
  for (const pugi::xml_node& edge : doc.child("net").children("edge")) {
    for (const pugi::xml_node& lane : edge.children("lane")) {
      if (id == lane.attribute("id").as_string())
        return {lane.attribute("shape").as_string(), lane.attribute("length").as_double()};
    }
  }
  ADD_FAILURE() << "no lane " << id;
  return {};
}

TEST(SumoSeams, ALaneCutShortOfItsInternalLaneIsMetByExtendingTheInternalLaneAlongIt) {
  // netconvert cut lane 3_0 at an outline reaching 6 m over road 3: it starts at x = 116. The
  // internal lane is extended along road 3's lane centre (on the ramp, z = 0.1 x) to meet it.
  std::string net = ramp_net_with("shape=\"110,-1.5,11 210,-1.5,21\"", "shape=\"116,-1.5,11.6 210,-1.5,21\"");
  ASSERT_NEAR(check_sumo_net(net, ramp_model(), "ramp.net.xml").max_handover_gap_m, 6.0, 1e-9);
  const SumoDrape drape = drape_sumo_net(net, ramp_model(), "ramp.net.xml");
  EXPECT_EQ(drape.ends_extended, 1u);
  EXPECT_NEAR(drape.max_extension_m, 6.0, 1e-9);
  EXPECT_EQ(drape.max_extension_lane, ":J_0_0");
  EXPECT_EQ(drape.ends_snapped, 0u);
  const auto [shape, length] = lane_of(net, ":J_0_0");
  EXPECT_EQ(shape, "100.00,-1.50,10.000 110.00,-1.50,11.000 116.00,-1.50,11.600");
  EXPECT_NEAR(length, 16.05, 1e-9);
  const SumoNetCheck check = check_sumo_net(net, ramp_model(), "ramp.net.xml");
  EXPECT_NEAR(check.max_handover_gap_m, 0.0, 1e-9);
  EXPECT_LT(check.z_max_m, 5e-4);
  EXPECT_EQ(check.points_unmapped, 0u);
}

TEST(SumoSeams, ALaneCutShortBeforeTheJunctionIsMetAtTheInternalLanesStart) {
  // Lane 1_0 (into the junction) ends at x = 94, 6 m before the internal lane starts.
  std::string net = ramp_net_with("shape=\"0,-1.5,0 100,-1.5,10\"", "shape=\"0,-1.5,0 94,-1.5,9.4\"");
  const SumoDrape drape = drape_sumo_net(net, ramp_model(), "ramp.net.xml");
  EXPECT_EQ(drape.ends_extended, 1u);
  EXPECT_NEAR(drape.max_extension_m, 6.0, 1e-9);
  const auto [shape, length] = lane_of(net, ":J_0_0");
  EXPECT_EQ(shape, "94.00,-1.50,9.400 100.00,-1.50,10.000 110.00,-1.50,11.000");
  EXPECT_NEAR(length, 16.05, 1e-9);
  EXPECT_NEAR(check_sumo_net(net, ramp_model(), "ramp.net.xml").max_handover_gap_m, 0.0, 1e-9);
}

TEST(SumoSeams, TheFunctionCountsItsExtensionsWithTheirPlanLength) {
  // Lane 3_0 cut 30 m in: the locator maps its start to road 3, lane -1, 30 m along.
  std::string net = ramp_net_with("shape=\"110,-1.5,11 210,-1.5,21\"", "shape=\"140,-1.5,14 210,-1.5,21\"");
  pugi::xml_document doc;
  ASSERT_TRUE(doc.load_string(net.c_str()));
  const RoadModel model = ramp_model();
  detail::LaneLocator locator(doc.child("net"), model);
  const detail::SumoSeams seams = detail::close_handover_gaps(doc.child("net"), locator);
  EXPECT_EQ(seams.extended, 1u);
  EXPECT_NEAR(seams.max_extension_m, 30.0, 1e-9);
}

TEST(SumoSeams, AnInternalLaneEndBesideOrBehindItsLanesEndIsMovedOntoIt) {
  // netconvert offset lane 3_0 by 0.2 m: the internal lane's end moves 0.2 m onto its start.
  std::string net = ramp_net_with("shape=\"110,-1.5,11 210,-1.5,21\"", "shape=\"110,-1.3,11 210,-1.5,21\"");
  SumoDrape drape = drape_sumo_net(net, ramp_model(), "ramp.net.xml");
  EXPECT_EQ(drape.ends_extended, 0u);
  EXPECT_EQ(drape.ends_snapped, 1u);
  EXPECT_NEAR(drape.max_snap_m, 0.2, 1e-9);
  EXPECT_EQ(lane_of(net, ":J_0_0").first, "100.00,-1.50,10.000 110.00,-1.30,11.000");
  EXPECT_NEAR(check_sumo_net(net, ramp_model(), "ramp.net.xml").max_handover_gap_m, 0.0, 1e-9);

  // netconvert drew lane 3_0 from x = 107, 3 m into the junction: the internal lane ends there.
  net = ramp_net_with("shape=\"110,-1.5,11 210,-1.5,21\"", "shape=\"107,-1.5,10.7 210,-1.5,21\"");
  drape = drape_sumo_net(net, ramp_model(), "ramp.net.xml");
  EXPECT_EQ(drape.ends_snapped, 1u);
  EXPECT_NEAR(drape.max_snap_m, 3.0, 1e-9);
  const auto [shape, length] = lane_of(net, ":J_0_0");
  EXPECT_EQ(shape, "100.00,-1.50,10.000 107.00,-1.50,10.700");
  EXPECT_NEAR(length, 7.05, 1e-9);
}

TEST(SumoSeams, ALaneDrawnOnIntoTheJunctionTakesTheConnectingRoadsHeightThere) {
  // netconvert drew lane 1_0 on to x = 106, 6 m past road 1's end into the junction (NE's J216:
  // 7.7 m). Its last point lies on connecting road 2 (z = 10.6 on the ramp), not on road 1's last
  // cross-section drawn on (z = 10), and so does the internal lane's start, cut to meet it: no
  // height step at the hand-over.
  std::string net = ramp_net_with("shape=\"0,-1.5,0 100,-1.5,10\"", "shape=\"0,-1.5,0 106,-1.5,10\"");
  const SumoDrape drape = drape_sumo_net(net, ramp_model(), "ramp.net.xml");
  EXPECT_EQ(drape.ends_snapped, 1u);
  EXPECT_EQ(lane_of(net, "1_0").first, "0,-1.5,0.000 106,-1.5,10.600");
  EXPECT_EQ(lane_of(net, ":J_0_0").first, "106.00,-1.50,10.600 110.00,-1.50,11.000");
  const SumoNetCheck check = check_sumo_net(net, ramp_model(), "ramp.net.xml");
  EXPECT_EQ(check.height_steps, 0u);
  EXPECT_LT(check.max_handover_step_m, 1e-9);
  EXPECT_LT(check.z_max_m, 5e-4);
}

TEST(SumoSeams, AnInternalLaneStretchedPastAOneMetreRoadTakesTheRoadAfterItsHeight) {
  // Road 3 ends 1 m after the junction, where road 4 goes on (a dead end trimmed to 1 m before a
  // transition road; Fuzz seed 29), and netconvert stretched the internal lane to x = 116, 5 m
  // past road 3's end. That point lies on road 4 (z = 11.6 on the ramp): held at connecting road
  // 2's end height (11.0), the lane stepped 0.51 m onto the lane it hands over to.
  RoadModel model = ramp_model();
  ModelRoad& r3 = model.roads[2];
  ModelRoad r4 = r3;
  PlanGeometry first, rest;
  first.start = Vec2(110.0, 0.0);
  first.length = 1.0;
  rest.start = Vec2(111.0, 0.0);
  rest.length = 99.0;
  r3.plan = PlanView({first});
  r3.successor = RoadLink{RoadLink::Element::road, 4, RoadLink::Contact::start};
  r4.id = 4;
  r4.plan = PlanView({rest});
  r4.elevation = CubicProfile({CubicPiece{0.0, {11.1, 0.1, 0.0, 0.0}}});
  r4.predecessor = RoadLink{RoadLink::Element::road, 3, RoadLink::Contact::end};
  model.roads.push_back(r4);
  std::string net = ramp_net_with("shape=\"100,-1.5,10 110,-1.5,11\"", "shape=\"100,-1.5,10 116,-1.5,11\"");
  const std::string lane3 = "shape=\"110,-1.5,11 210,-1.5,21\"";
  net.replace(net.find(lane3), lane3.size(), "shape=\"116,-1.5,11 210,-1.5,21\"");
  pugi::xml_document doc;
  ASSERT_TRUE(doc.load_string(net.c_str()));
  detail::LaneLocator locator(doc.child("net"), model);
  const auto at = locator.locate(":J_0_0", Vec2(116.0, -1.5));
  ASSERT_TRUE(at.has_value());
  EXPECT_EQ(at->road->id, 4);
  EXPECT_NEAR(surface_z(*at->road, at->s, at->t), 11.6, 1e-9);
  (void)drape_sumo_net(net, model, "ramp.net.xml");
  const std::string shape = lane_of(net, ":J_0_0").first;
  EXPECT_EQ(shape.substr(shape.rfind(' ') + 1), "116,-1.5,11.600") << shape;
  const SumoNetCheck check = check_sumo_net(net, model, "ramp.net.xml");
  EXPECT_EQ(check.height_steps, 0u);
  EXPECT_LT(check.max_handover_step_m, 1e-3);
}

TEST(SumoSeams, NetconvertsOwnCentimetresAreLeftAlone) {
  // 4 cm apart (under the 5 cm tolerance): nothing changes but the heights.
  std::string net = ramp_net_with("shape=\"110,-1.5,11 210,-1.5,21\"", "shape=\"110,-1.46,11 210,-1.5,21\"");
  const SumoDrape drape = drape_sumo_net(net, ramp_model(), "ramp.net.xml");
  EXPECT_EQ(drape.ends_extended + drape.ends_snapped, 0u);
  EXPECT_EQ(lane_of(net, ":J_0_0").second, 10.05);
  EXPECT_NEAR(check_sumo_net(net, ramp_model(), "ramp.net.xml").max_handover_gap_m, 0.04, 1e-9);
}

}  // namespace
}  // namespace relief

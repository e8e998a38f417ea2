#include "relief/export/sumo_network.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#include "relief/core/diagnostic_codes.h"
#include "relief/core/errors.h"
#include "support/sumo_ramp.h"

namespace relief {
namespace {

using test::ramp_model;

const SumoNode& node(const SumoPlainNetwork& net, const std::string& id) {
  const auto it =
      std::find_if(net.nodes.begin(), net.nodes.end(), [&](const SumoNode& n) { return n.id == id; });
  if (it == net.nodes.end()) throw std::out_of_range("no node " + id);
  return *it;
}

const SumoEdge& edge(const SumoPlainNetwork& net, const std::string& id) {
  const auto it =
      std::find_if(net.edges.begin(), net.edges.end(), [&](const SumoEdge& e) { return e.id == id; });
  if (it == net.edges.end()) throw std::out_of_range("no edge " + id);
  return *it;
}

void expect_near(const Vec3& a, const Vec3& b, double tolerance) {
  EXPECT_NEAR(a.x(), b.x(), tolerance);
  EXPECT_NEAR(a.y(), b.y(), tolerance);
  EXPECT_NEAR(a.z(), b.z(), tolerance);
}

// The ramp: dead ends at both far ends, one junction node between the road ends at x = 100
// and 110, an edge each way on road 1 and one along road 3, all on the plane z = 0.1 x.
TEST(SumoNetwork, RampGivesNodesAndEdgesOnItsSurface) {
  Diagnostics diagnostics;
  const SumoPlainNetwork net = build_sumo_network(ramp_model(), {}, SumoOptions{}, diagnostics);

  ASSERT_EQ(net.nodes.size(), 3u);
  EXPECT_EQ(node(net, "D1s").type, "dead_end");
  EXPECT_EQ(node(net, "D3e").type, "dead_end");
  const SumoNode& j = node(net, "J100");
  EXPECT_EQ(j.type, "priority");
  EXPECT_EQ(j.junction, 100);
  expect_near(j.position, Vec3(105.0, 0.0, 10.5), 1e-9);  // mean of the two road ends' centres
  expect_near(node(net, "D1s").position, Vec3(0.0, 0.0, 0.0), 1e-9);
  expect_near(node(net, "D3e").position, Vec3(210.0, 0.0, 21.0), 1e-9);

  ASSERT_EQ(net.edges.size(), 3u);  // 1, -1 and 3 (road 3 has no left lane, road 2 is internal)
  const SumoEdge& up = edge(net, "1");
  EXPECT_EQ(up.from, "D1s");
  EXPECT_EQ(up.to, "J100");
  EXPECT_TRUE(up.along_s);
  EXPECT_EQ(up.odr_road, 1);
  EXPECT_EQ(up.type, "highway.residential");
  ASSERT_EQ(up.lanes.size(), 1u);
  EXPECT_EQ(up.lanes[0].odr_lane, -1);
  EXPECT_DOUBLE_EQ(up.lanes[0].width_m, 3.0);
  // A straight, evenly rising line needs no point between its ends: the edge shape is the
  // reference line, the lane shape its centre 1.5 m to the right.
  ASSERT_EQ(up.shape.size(), 2u);
  expect_near(up.shape.front(), Vec3(0.0, 0.0, 0.0), 1e-9);
  expect_near(up.shape.back(), Vec3(100.0, 0.0, 10.0), 1e-9);
  ASSERT_GE(up.lanes[0].shape.size(), 2u);
  expect_near(up.lanes[0].shape.front(), Vec3(0.0, -1.5, 0.0), 1e-9);
  expect_near(up.lanes[0].shape.back(), Vec3(100.0, -1.5, 10.0), 1e-9);

  const SumoEdge& down = edge(net, "-1");
  EXPECT_EQ(down.from, "J100");
  EXPECT_EQ(down.to, "D1s");
  EXPECT_FALSE(down.along_s);
  ASSERT_EQ(down.lanes.size(), 1u);
  EXPECT_EQ(down.lanes[0].odr_lane, 1);
  expect_near(down.lanes[0].shape.front(), Vec3(100.0, 1.5, 10.0), 1e-9);  // in travel direction
  expect_near(down.lanes[0].shape.back(), Vec3(0.0, 1.5, 0.0), 1e-9);
  EXPECT_EQ(edge(net, "3").from, "J100");
  EXPECT_EQ(edge(net, "3").to, "D3e");

  EXPECT_NEAR(net.stats.max_edge_grade_percent, 10.0, 1e-9);
  EXPECT_EQ(net.stats.nodes, 3u);
  EXPECT_EQ(net.stats.edges, 3u);
}

// The junction's one lane link becomes one connection from lane 0 of "1" to lane 0 of "3",
// its shape the connecting road's lane centre, joined exactly to both lanes' ends.
TEST(SumoNetwork, ConnectingRoadBecomesAConnectionWithItsShape) {
  Diagnostics diagnostics;
  const SumoPlainNetwork net = build_sumo_network(ramp_model(), {}, SumoOptions{}, diagnostics);
  ASSERT_EQ(net.connections.size(), 1u);
  const SumoConnection& c = net.connections.front();
  EXPECT_EQ(c.from, "1");
  EXPECT_EQ(c.to, "3");
  EXPECT_EQ(c.from_lane, 0);
  EXPECT_EQ(c.to_lane, 0);
  EXPECT_EQ(c.odr_road, 2);
  EXPECT_EQ(c.odr_lane, -1);
  ASSERT_GE(c.shape.size(), 2u);
  EXPECT_EQ(c.shape.front(), edge(net, "1").lanes[0].shape.back());
  EXPECT_EQ(c.shape.back(), edge(net, "3").lanes[0].shape.front());
  expect_near(c.shape.back(), Vec3(110.0, -1.5, 11.0), 1e-9);
  EXPECT_EQ(net.stats.internal_lanes_by_netconvert, 0u);
}

// A dead end shorter than min_dead_end_length_m gets no edge and no connection, and is said:
// the ramp's two 100 m roads under a 150 m minimum (the default, 2 m, keeps them).
TEST(SumoNetwork, ADeadEndShorterThanTheMinimumGetsNoEdge) {
  SumoOptions options;
  options.min_dead_end_length_m = 150.0;
  Diagnostics diagnostics;
  const SumoPlainNetwork net = build_sumo_network(ramp_model(), {}, options, diagnostics);
  EXPECT_TRUE(net.edges.empty());
  EXPECT_TRUE(net.connections.empty());
  EXPECT_EQ(diagnostics.count(codes::kSumoDeadEndSkipped.code), 2u);
  Diagnostics none;
  EXPECT_EQ(build_sumo_network(ramp_model(), {}, SumoOptions{}, none).edges.size(), 3u);
  EXPECT_EQ(none.count(codes::kSumoDeadEndSkipped.code), 0u);
}

// Classes are kept off lanes steeper than their limit: the 10 % ramp is too steep for a
// 5 % class on every edge and within a 20 % one.
TEST(SumoNetwork, ClassesOverTheirGradeAreDisallowed) {
  SumoOptions options;
  options.max_grade_percent = {{"truck", 5.0}, {"bus", 20.0}};
  Diagnostics diagnostics;
  const SumoPlainNetwork net = build_sumo_network(ramp_model(), {}, options, diagnostics);
  for (const SumoEdge& e : net.edges) {
    EXPECT_EQ(e.disallow, std::vector<std::string>{"truck"}) << e.id;
    EXPECT_NEAR(e.max_grade_percent, 10.0, 1e-9) << e.id;
  }
  EXPECT_EQ(net.stats.restricted_edges.at("truck"), 3u);
  EXPECT_EQ(net.stats.restricted_edges.count("bus"), 0u);
}

// A signalled junction gets a traffic light; a signal on a junction without a node is reported.
TEST(SumoNetwork, SignalledJunctionsGetTrafficLights) {
  SumoOptions options;
  options.signalled_junctions = {100, 7};
  Diagnostics diagnostics;
  const SumoPlainNetwork net = build_sumo_network(ramp_model(), {}, options, diagnostics);
  EXPECT_EQ(node(net, "J100").type, "traffic_light");
  EXPECT_EQ(net.stats.traffic_lights, 1u);
  EXPECT_EQ(diagnostics.count(codes::kSumoSignalWithoutNode), 1u);
}

// Road classes set the edge type, priority and speed (road speed first, class default else).
TEST(SumoNetwork, RoadInfoSetsTypePriorityAndSpeed) {
  RoadModel model = ramp_model();
  model.roads[2].speed_mps = 20.0;
  const std::vector<SumoRoadInfo> info(model.roads.size(), SumoRoadInfo{HighwayClass::primary});
  Diagnostics diagnostics;
  const SumoPlainNetwork net = build_sumo_network(model, info, SumoOptions{}, diagnostics);
  EXPECT_EQ(edge(net, "1").type, "highway.primary");
  EXPECT_EQ(edge(net, "1").priority, 12);
  EXPECT_DOUBLE_EQ(edge(net, "1").speed_mps, default_speed_mps(HighwayClass::primary));
  EXPECT_DOUBLE_EQ(edge(net, "3").speed_mps, 20.0);
}

TEST(SumoNetwork, OptionsOutOfRangeThrow) {
  Diagnostics diagnostics;
  SumoOptions options;
  options.shape_tolerance_m = 0.0;
  EXPECT_THROW((void)build_sumo_network(ramp_model(), {}, options, diagnostics), InvalidInput);
  const std::vector<SumoRoadInfo> too_few(1);
  EXPECT_THROW((void)build_sumo_network(ramp_model(), too_few, SumoOptions{}, diagnostics), InvalidInput);
}

}  // namespace
}  // namespace relief

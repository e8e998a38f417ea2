#include "roads/way_crossings.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "relief/roads/network_builder.h"

#include "support/osm_sketch.h"

namespace relief::detail {
namespace {

// Ways drawn in metres east and north of lon 9.5, lat 47.1.
constexpr double kLat0 = 47.1, kLon0 = 9.5;
LonLat at(double east_m, double north_m) {
  return test::offset_lonlat({kLon0, kLat0}, east_m, north_m);
}

struct Sketch {
  OsmRoads osm;
  std::int64_t next_node = 100;
  Sketch& way(std::int64_t id, std::vector<Vec2> points, WayAttributes attributes = street()) {
    OsmWay w;
    w.id = id;
    for (const Vec2& p : points) {
      w.node_ids.push_back(next_node++);
      w.nodes.push_back(at(p.x(), p.y()));
    }
    w.attributes = attributes;
    osm.ways.push_back(std::move(w));
    return *this;
  }
  // A way through existing nodes (by id) and new ones (id 0: a new node at the point).
  Sketch& way_through(std::int64_t id, std::vector<std::pair<std::int64_t, Vec2>> nodes) {
    OsmWay w;
    w.id = id;
    for (const auto& [node, p] : nodes) {
      w.node_ids.push_back(node != 0 ? node : next_node++);
      w.nodes.push_back(at(p.x(), p.y()));
    }
    w.attributes = street();
    osm.ways.push_back(std::move(w));
    return *this;
  }
  OsmRoads done() {
    osm.bounds = {kLon0 - 0.01, kLat0 - 0.01, kLon0 + 0.01, kLat0 + 0.01};
    return osm;
  }
  static WayAttributes street() {
    WayAttributes a;
    a.highway = HighwayClass::residential;
    return a;
  }
};

TEST(WayCrossings, TwoWaysCrossingWithoutANodeGetOneThereAndMakeAJunction) {
  OsmRoads osm = Sketch().way(1, {{-50, 0}, {50, 0}}).way(2, {{0, -50}, {10, 50}}).done();
  Diagnostics d;
  EXPECT_EQ(join_crossing_ways(osm, d), 1u);
  EXPECT_EQ(d.count("osm.crossing_without_node"), 1u);
  ASSERT_EQ(osm.ways[0].node_ids.size(), 3u);
  ASSERT_EQ(osm.ways[1].node_ids.size(), 3u);
  EXPECT_EQ(osm.ways[0].node_ids[1], osm.ways[1].node_ids[1]);
  EXPECT_LT(osm.ways[0].node_ids[1], 0);  // below every id of the input
  // The crossing (5, 0) in both ways, to a millimetre.
  const LonLat x = at(5, 0);
  for (const OsmWay& w : osm.ways) {
    EXPECT_NEAR(w.nodes[1].lon_deg, x.lon_deg, 1e-8);
    EXPECT_NEAR(w.nodes[1].lat_deg, x.lat_deg, 1e-8);
  }
  // Built, the crossing is a four-way intersection.
  Diagnostics d2;
  const OsmRoads input = Sketch().way(1, {{-50, 0}, {50, 0}}).way(2, {{0, -50}, {10, 50}}).done();
  const RoadNetwork net = build_network(input, GeoFrame::utm_at({kLon0, kLat0}), d2);
  EXPECT_EQ(net.roads.size(), 4u);
  EXPECT_EQ(net.count(JunctionKind::intersection), 1u);
  EXPECT_EQ(d2.count("osm.crossing_without_node"), 1u);
}

TEST(WayCrossings, TwoNodesAtOnePlaceAreMergedAndANodeOnAWayJoinsIt) {
  // Way 2 passes through (0, 0) with its own node where way 1 has one (Liechtenstein's
  // Burkatstrasse and a service road); way 3 ends on way 1's segment (10, 0)-(50, 0) at (30, 0).
  OsmRoads osm = Sketch()
                     .way_through(1, {{0, {-50, 0}}, {7, {0, 0}}, {0, {50, 0}}})
                     .way_through(2, {{0, {-20, -40}}, {8, {0, 0}}, {0, {20, 40}}})
                     .way_through(3, {{0, {30, -60}}, {0, {30, 0}}})
                     .done();
  Diagnostics d;
  EXPECT_EQ(join_crossing_ways(osm, d), 2u);
  EXPECT_EQ(osm.ways[1].node_ids[1], 7);  // merged into way 1's node
  ASSERT_EQ(osm.ways[0].node_ids.size(), 4u);
  EXPECT_EQ(osm.ways[0].node_ids[2], osm.ways[2].node_ids[1]);  // way 3's end node, now on way 1
  EXPECT_EQ(d.count("osm.crossing_without_node"), 2u);
}

TEST(WayCrossings, ThreeNodesAtOnePlaceBecomeOne) {
  // Three ways through (0, 0), each with its own node there: one node, whichever pairs are met
  // first (no chain of merges left unresolved, no cycle).
  OsmRoads osm = Sketch()
                     .way_through(1, {{0, {-50, 0}}, {7, {0, 0}}, {0, {50, 0}}})
                     .way_through(2, {{0, {0, -50}}, {8, {0, 0}}, {0, {0, 50}}})
                     .way_through(3, {{0, {-40, -40}}, {9, {0, 0}}, {0, {40, 40}}})
                     .done();
  Diagnostics d;
  EXPECT_EQ(join_crossing_ways(osm, d), 2u);
  for (const OsmWay& w : osm.ways) EXPECT_EQ(w.node_ids[1], 7) << "way " << w.id;
}

TEST(WayCrossings, WaysOnDifferentLevelsOrApartAreLeftAlone) {
  WayAttributes bridge = Sketch::street();
  bridge.bridge = true;
  WayAttributes upper = Sketch::street();
  upper.layer = 1;
  OsmRoads osm = Sketch()
                     .way(1, {{-50, 0}, {50, 0}})
                     .way(2, {{0, -50}, {0, 50}}, bridge)
                     .way(3, {{20, -50}, {20, 50}}, upper)
                     .way_through(4, {{0, {-70, -60}}, {0, {-55, 40}}})  // passes 6 m from way 1's end
                     .done();
  const OsmRoads before = osm;
  Diagnostics d;
  EXPECT_EQ(join_crossing_ways(osm, d), 0u);
  for (std::size_t w = 0; w < osm.ways.size(); ++w) EXPECT_EQ(osm.ways[w].node_ids, before.ways[w].node_ids);
  EXPECT_EQ(d.count("osm.crossing_without_node"), 0u);
}

TEST(WayCrossings, ManyCrossingsOfALongGridAreAllFoundOnce) {
  // 30 east-west and 30 north-south ways 1.5 km long, 50 m apart: 900 crossings, each once
  // (segments cross many grid cells).
  Sketch sketch;
  for (int k = 0; k < 30; ++k) sketch.way(1 + k, {{-10, 50.0 * k}, {1500, 50.0 * k}});
  for (int k = 0; k < 30; ++k) sketch.way(101 + k, {{50.0 * k + 7, -10}, {50.0 * k + 7, 1500}});
  OsmRoads osm = sketch.done();
  Diagnostics d;
  EXPECT_EQ(join_crossing_ways(osm, d), 900u);
  for (const OsmWay& w : osm.ways) EXPECT_EQ(w.node_ids.size(), 32u);
}

}  // namespace
}  // namespace relief::detail

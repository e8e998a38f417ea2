#include "roads/way_folds.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <utility>
#include <vector>

#include "support/osm_sketch.h"

namespace relief::detail {
namespace {

// Ways drawn in metres east and north of lon 9.5, lat 47.1. Residential: 2 lanes of 3 m, 6 m wide.
constexpr double kLat0 = 47.1, kLon0 = 9.5;
LonLat at(double east_m, double north_m) {
  return test::offset_lonlat({kLon0, kLat0}, east_m, north_m);
}

// One way with nodes 1, 2, ... at the points.
OsmRoads one_way(const std::vector<Vec2>& points) {
  OsmRoads osm;
  OsmWay w;
  w.id = 7;
  for (std::size_t i = 0; i < points.size(); ++i) {
    w.node_ids.push_back(static_cast<std::int64_t>(i + 1));
    w.nodes.push_back(at(points[i].x(), points[i].y()));
  }
  osm.ways.push_back(std::move(w));
  return osm;
}

std::vector<std::vector<std::int64_t>> node_lists(const OsmRoads& osm) {
  std::vector<std::vector<std::int64_t>> out;
  for (const OsmWay& w : osm.ways) {
    EXPECT_EQ(w.id, 7);
    EXPECT_EQ(w.node_ids.size(), w.nodes.size());
    out.push_back(w.node_ids);
  }
  return out;
}

using Ids = std::vector<std::vector<std::int64_t>>;

TEST(WayFolds, HairpinToOneNodeWithinTheRoadsWidthIsBuiltOnce) {
  // Out 50 m and back 20 m, 2 m to the side at its end (turn 174.3 degrees): the return leg lies
  // on the outgoing leg's pavement. The way runs 1-3 and on to 2, the tip, as the stretch 3-2.
  OsmRoads osm = one_way({{0, 0}, {50, 0}, {30, 2}});
  Diagnostics d;
  EXPECT_EQ(split_folds(osm, d), 1u);
  EXPECT_EQ(node_lists(osm), (Ids{{1, 3}, {3, 2}}));
  ASSERT_EQ(d.count("osm.way_turns_back"), 1u);
  const Diagnostic& msg = d.kept().front();
  EXPECT_EQ(msg.osm_way_id, 7);
  EXPECT_EQ(msg.osm_node_id, 2);
  EXPECT_NE(msg.message.find("turns 174.29 degrees"), std::string::npos) << msg.message;
  EXPECT_NE(msg.message.find("20.10 m to node 3, lies 2.00 m"), std::string::npos) << msg.message;
}

TEST(WayFolds, ReturnLongerThanTheWayOutKeepsTheReturn) {
  // Out 20 m and back 50 m: the way out (1-2) lies on the return's pavement; the way runs 1-3.
  OsmRoads osm = one_way({{0, 0}, {20, 0}, {-30, 3}});
  Diagnostics d;
  EXPECT_EQ(split_folds(osm, d), 1u);
  EXPECT_EQ(node_lists(osm), (Ids{{1, 3}, {1, 2}}));
}

TEST(WayFolds, FoldsUncoveredByARemovalAreRemovedInTurn) {
  // 1-2-3-4: the fold at 3 (legs 20 and 50 m) leaves 1-2-4, which folds at 2 (legs 40 and 30 m).
  OsmRoads osm = one_way({{0, 0}, {40, 0}, {60, 0}, {10, 1}});
  Diagnostics d;
  EXPECT_EQ(split_folds(osm, d), 2u);
  EXPECT_EQ(node_lists(osm), (Ids{{1, 4}, {2, 3}, {4, 2}}));
  EXPECT_EQ(d.count("osm.way_turns_back"), 2u);
}

TEST(WayFolds, HairpinsWhoseLegsPartWiderThanTheRoadAndBendsUnder150DegreesStay) {
  for (const std::vector<Vec2>& points : std::vector<std::vector<Vec2>>{
           {{0, 0}, {50, 0}, {0, 20}},         // turn 158 degrees, legs 18.6 m apart at the end
           {{0, 0}, {50, 0}, {30, 6.5}},       // turn 162 degrees, 6.2 m apart: wider than 6 m
           {{0, 0}, {50, 0}, {45, 4.2}},       // turn 140 degrees, 4.2 m apart
           {{0, 0}, {50, 0}, {100, 0}},        // straight on
           {{0, 0}, {50, 0}, {50, 0.005}}}) {  // a leg of 5 mm has no direction
    OsmRoads osm = one_way(points);
    Diagnostics d;
    EXPECT_EQ(split_folds(osm, d), 0u);
    EXPECT_EQ(node_lists(osm), (Ids{{1, 2, 3}}));
    EXPECT_EQ(d.count("osm.way_turns_back"), 0u);
  }
}

TEST(WayFolds, WiderRoadsFoldWiderApart) {
  // 6.2 m apart: a fold for a road of 2 x 2 lanes of 3.5 m (14 m), not for 2 x 1 of 3 m.
  OsmRoads osm = one_way({{0, 0}, {50, 0}, {30, 6.5}});
  osm.ways[0].attributes.lanes_forward = 2;
  osm.ways[0].attributes.lanes_backward = 2;
  osm.ways[0].attributes.lane_width_m = 3.5;
  Diagnostics d;
  EXPECT_EQ(split_folds(osm, d), 1u);
}

}  // namespace
}  // namespace relief::detail

#include "roads/road_stubs.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "relief/core/diagnostic_codes.h"

namespace relief {
namespace {

// A two-way residential road of 2 x 3 m lanes (half width 3 m) from node `from` to node `to`.
Road road(const Polyline2& points, std::int64_t from, std::int64_t to, std::int64_t way) {
  Road r;
  r.points = points;
  r.osm_node_ids.assign(points.size(), 0);
  for (std::size_t k = 1; k + 1 < points.size(); ++k)
    r.osm_node_ids[k] = way * 100 + static_cast<std::int64_t>(k);
  r.osm_node_ids.front() = from;
  r.osm_node_ids.back() = to;
  r.osm_way_ids = {way};
  r.attributes.highway = HighwayClass::residential;
  r.attributes.lanes_forward = r.attributes.lanes_backward = 1;
  r.attributes.lane_width_m = 3.0;
  return r;
}

std::vector<std::int64_t> ways(const std::vector<Road>& roads) {
  std::vector<std::int64_t> out;
  out.reserve(roads.size());
  for (const Road& r : roads) out.push_back(r.osm_way_ids.front());
  return out;
}

TEST(RoadStubs, AStubCutByAClipBoxBesideAJunctionIsDropped) {
  // A street through node 1 (two roads), a cross street ending there, and a 0.9 m piece of a
  // fourth way from node 1 to the clip edge (node 9): its pavement (3 m each side) cannot reach
  // past the others' (6 m in all).
  std::vector<Road> roads = {road({{-100, 0}, {0, 0}}, 2, 1, 10), road({{0, 0}, {100, 0}}, 1, 3, 11),
                             road({{0, 0}, {0, -100}}, 1, 4, 12), road({{0, 0}, {0, 0.9}}, 1, 9, 13)};
  Diagnostics d;
  EXPECT_EQ(detail::drop_stubs(roads, d), 1u);
  EXPECT_EQ(ways(roads), (std::vector<std::int64_t>{10, 11, 12}));
  for (std::size_t i = 0; i < roads.size(); ++i) EXPECT_EQ(roads[i].id, static_cast<int>(i));
  ASSERT_EQ(d.count(std::string(codes::kNetworkStubDropped.code)), 1u);
  const std::string& text = d.kept().front().message;
  EXPECT_NE(text.find("OSM way 13 is a dead end 0.9 m long"), std::string::npos) << text;
  EXPECT_NE(text.find("they reach 6 m"), std::string::npos) << text;
}

TEST(RoadStubs, AStubContinuingARoadOrAcrossAStraightRoadIsDropped) {
  Diagnostics d;
  // A road ending at node 1, continued 2 m by another way to a dead end.
  std::vector<Road> end = {road({{-100, 0}, {0, 0}}, 2, 1, 10), road({{0, 0}, {2, 0}}, 1, 9, 11)};
  EXPECT_EQ(detail::drop_stubs(end, d), 1u);
  EXPECT_EQ(ways(end), (std::vector<std::int64_t>{10}));
  // A road straight through node 1 (10 degrees off), a 5.9 m stub off its side.
  std::vector<Road> through = {road({{-100, 0}, {0, 0}}, 2, 1, 10), road({{0, 0}, {98.5, 17.4}}, 1, 3, 11),
                               road({{0, 0}, {0, 5.9}}, 1, 9, 12)};
  EXPECT_EQ(detail::drop_stubs(through, d), 1u);
  EXPECT_EQ(ways(through), (std::vector<std::int64_t>{10, 11}));
}

TEST(RoadStubs, StubsSharingANodeAreDroppedTogether) {
  // A clip box's edge beside a junction: a one-way's 1.1 m piece and a service road's 1.5 m
  // piece end there with one long road; each alone would leave the other and the long road at a
  // corner, together they leave a plain road end. At a corner of two long roads they stay.
  std::vector<Road> edge = {road({{0, 0}, {-100, 0}}, 1, 2, 10), road({{0, 0}, {1.1, 0.1}}, 1, 8, 11),
                            road({{0, 0}, {0.4, 1.4}}, 1, 9, 12)};
  Diagnostics d;
  EXPECT_EQ(detail::drop_stubs(edge, d), 2u);
  EXPECT_EQ(ways(edge), (std::vector<std::int64_t>{10}));
  // At a corner of two long roads the longest stub stays, to keep the junction; the other goes
  // (Portland: two service roads cut 2.9 and 3.2 m past a corner by a box's edge).
  std::vector<Road> corner = {road({{0, 0}, {-100, 0}}, 1, 2, 10), road({{0, 0}, {0, -100}}, 1, 3, 11),
                              road({{0, 0}, {2.9, 0.1}}, 1, 8, 12), road({{0, 0}, {0.4, 3.2}}, 1, 9, 13)};
  EXPECT_EQ(detail::drop_stubs(corner, d), 1u);
  EXPECT_EQ(ways(corner), (std::vector<std::int64_t>{10, 11, 13}));
  // Under 1 m (Portland's Myrtle Street and 19th Avenue cut at a box's edge, 0.5 and 0.19 m):
  // no trim can keep them clear, they go even at a corner.
  std::vector<Road> tiny = {road({{0, 0}, {-100, 0}}, 1, 2, 10), road({{0, 0}, {0, -100}}, 1, 3, 11),
                            road({{0, 0}, {0.5, 0.0}}, 1, 8, 12), road({{0, 0}, {0.0, 0.19}}, 1, 9, 13)};
  EXPECT_EQ(detail::drop_stubs(tiny, d), 2u);
  EXPECT_EQ(ways(tiny), (std::vector<std::int64_t>{10, 11}));
}

TEST(RoadStubs, LongerDeadEndsCornersAndLoneRoadsStay) {
  Diagnostics d;
  // 6.1 m: its pavement reaches past the others' 6 m.
  std::vector<Road> longer = {road({{-100, 0}, {0, 0}}, 2, 1, 10), road({{0, 0}, {100, 0}}, 1, 3, 11),
                              road({{0, 0}, {0, 6.1}}, 1, 9, 12)};
  EXPECT_EQ(detail::drop_stubs(longer, d), 0u);
  // Two roads at a right-angled corner and a 2 m stub on it: without the stub the corner would
  // be a bend of two wide roads; with it, a junction.
  std::vector<Road> corner = {road({{-100, 0}, {0, 0}}, 2, 1, 10), road({{0, 0}, {0, -100}}, 1, 3, 11),
                              road({{0, 0}, {1.4, 1.4}}, 1, 9, 12)};
  EXPECT_EQ(detail::drop_stubs(corner, d), 0u);
  // A lone 2 m road (both ends dead): nothing it lies on.
  std::vector<Road> lone = {road({{0, 0}, {2, 0}}, 1, 2, 10)};
  EXPECT_EQ(detail::drop_stubs(lone, d), 0u);
  EXPECT_EQ(d.count(std::string(codes::kNetworkStubDropped.code)), 0u);
}

}  // namespace
}  // namespace relief

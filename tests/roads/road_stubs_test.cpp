#include "roads/road_stubs.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <numbers>
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

TEST(RoadStubs, AStubAtAnAcuteAngleToACornerRoadGoesEvenThere) {
  // Liechtenstein clipped by --bbox (9.54734,47.09975,9.61734,47.14875): a street bending 43
  // degrees at node 1, and a 1.84 m piece of a way cut by the box leaving 43 degrees from the
  // street's other road. Kept to make the bend a junction, it lay on that road's pavement
  // (trimmed to 1 m, its junction's outline crossed itself and SUMO's lanes stepped 0.47 m).
  // Clear of the other road only after (3 + 3 cos 43) / sin 43 = 7.6 m: it goes.
  const double a = 43.0 * std::numbers::pi / 180.0;
  const Vec2 bend(100.0 * std::cos(a), 100.0 * std::sin(a));
  const Vec2 stub(1.84 * std::cos(2.0 * a), 1.84 * std::sin(2.0 * a));
  std::vector<Road> acute = {road({{-100, 0}, {0, 0}}, 2, 1, 10), road({{0, 0}, bend}, 1, 3, 11),
                             road({{0, 0}, stub}, 1, 9, 12)};
  Diagnostics d;
  EXPECT_EQ(detail::drop_stubs(acute, d), 1u);
  EXPECT_EQ(ways(acute), (std::vector<std::int64_t>{10, 11}));
  // The same stub 7.7 m long reaches clear of it (and is no stub: it reaches past 6 m).
  const Vec2 longer(7.7 * std::cos(2.0 * a), 7.7 * std::sin(2.0 * a));
  std::vector<Road> kept = {road({{-100, 0}, {0, 0}}, 2, 1, 10), road({{0, 0}, bend}, 1, 3, 11),
                            road({{0, 0}, longer}, 1, 9, 12)};
  EXPECT_EQ(detail::drop_stubs(kept, d), 0u);
  // A 5 m stub into a right-angled corner, 45 degrees from both roads: on their pavements until
  // (3 + 3 cos 45) / sin 45 = 7.2 m, it goes; 5 m out of the corner, 135 degrees from both, is
  // clear of them after (3 - 3 cos 45) / sin 45 = 1.2 m and stays.
  std::vector<Road> inside = {road({{-100, 0}, {0, 0}}, 2, 1, 10), road({{0, 0}, {0, -100}}, 1, 3, 11),
                              road({{0, 0}, {-3.54, -3.54}}, 1, 9, 12)};
  EXPECT_EQ(detail::drop_stubs(inside, d), 1u);
  std::vector<Road> outside = {road({{-100, 0}, {0, 0}}, 2, 1, 10), road({{0, 0}, {0, -100}}, 1, 3, 11),
                               road({{0, 0}, {3.54, 3.54}}, 1, 9, 12)};
  EXPECT_EQ(detail::drop_stubs(outside, d), 0u);
}

// A one-way road of `lanes` lanes of 3.65 m (half width 1.825 m per lane) from `from` to `to`.
Road one_way(const Polyline2& points, std::int64_t from, std::int64_t to, std::int64_t way, int lanes) {
  Road r = road(points, from, to, way);
  r.attributes.oneway = true;
  r.attributes.lanes_forward = lanes;
  r.attributes.lanes_backward = 0;
  r.attributes.lane_width_m = 3.65;
  return r;
}

TEST(RoadStubs, ADeadEndForkingAlongAnotherRoadIsDroppedWhereNoMoveCouldPartThem) {
  // Portland clipped by --bbox (-122.7222,45.48657,-122.6872,45.51107): the Stadium Freeway (3
  // lanes) and a one-lane link merge at node 1, both cut by the box upstream, 6.2 degrees apart.
  // At the link's far end (31.7 m) their centre lines are 3.42 m apart where 5.475 + 1.825 + 0.2 m
  // are needed: 4.08 m more, more than road_separation moves a road (3 m). The link goes, the
  // freeway stays (of two branches along each other, the narrower is judged first).
  const double a = 6.2 * std::numbers::pi / 180.0;
  std::vector<Road> merge = {one_way({{0, 40}, {0, 0}}, 2, 1, 10, 3),
                             one_way({{31.7 * std::sin(a), 31.7 * std::cos(a)}, {0, 0}}, 3, 1, 11, 1),
                             one_way({{0, 0}, {0, -100}}, 1, 4, 12, 3)};
  Diagnostics d;
  EXPECT_EQ(detail::drop_stubs(merge, d), 1u);
  EXPECT_EQ(ways(merge), (std::vector<std::int64_t>{10, 12}));
  ASSERT_EQ(d.count(std::string(codes::kNetworkStubDropped.code)), 1u);
  const std::string& text = d.kept().front().message;
  EXPECT_NE(text.find("along OSM way 10, 4.08 m too close to it at its end"), std::string::npos) << text;
  // Potrero's two one-lane links forking at 4.1 degrees, the dead one 42.9 m long: 0.78 m too
  // close at its end, which road_separation can move apart: it stays.
  const double b = 4.1 * std::numbers::pi / 180.0;
  std::vector<Road> links = {one_way({{0, -100}, {0, 0}}, 2, 1, 20, 1),
                             one_way({{0, 0}, {100 * std::sin(b), 100 * std::cos(b)}}, 1, 3, 21, 1),
                             one_way({{0, 0}, {0, 42.9}}, 1, 9, 22, 1)};
  EXPECT_EQ(detail::drop_stubs(links, d), 0u);
  // Two dead ends forking at a node of two roads only (a hairpin's apex drawn as two ways) are a
  // bend, not a fork: both stay.
  std::vector<Road> apex = {one_way({{0, 40}, {0, 0}}, 2, 1, 30, 3),
                            one_way({{0, 0}, {31.7 * std::sin(a), 31.7 * std::cos(a)}}, 1, 3, 31, 1)};
  EXPECT_EQ(detail::drop_stubs(apex, d), 0u);
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

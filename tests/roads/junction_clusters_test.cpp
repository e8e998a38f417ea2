#include "roads/junction_clusters.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "support/synthetic.h"

namespace relief {
namespace {

// Two intersections A (0, 0) and B (8, 0) joined by road 0, each with two 100 m arms to dead
// ends (roads 1..4), and optionally a second road A -> B over (4, 6) (road 5). Junctions: A 0,
// B 1, the arms' ends 2..5. Radii: 5 m at A and B, 0 at the dead ends.
struct Cross {
  RoadNetwork net;
  std::vector<double> radius;
  std::vector<double> length;
  std::vector<std::uint8_t> has_height;
};

Cross two_intersections(double stub_length, bool second_road = false, double second_length = 0.0,
                        const WayAttributes& stub = {}) {
  std::vector<Polyline2> lines{
      {{0, 0}, {8, 0}}, {{0, 0}, {0, 100}}, {{0, 0}, {0, -100}}, {{8, 0}, {8, 100}}, {{8, 0}, {8, -100}}};
  if (second_road) lines.push_back({{0, 0}, {4, 6}, {8, 0}});
  Cross c;
  c.net = test::make_network(lines, {stub});
  c.radius = {5, 5, 0, 0, 0, 0};
  c.length = {stub_length, 100, 100, 100, 100};
  if (second_road) c.length.push_back(second_length);
  c.has_height.assign(lines.size(), 1);
  return c;
}

constexpr double kMinKept = 2.0;  // so roads shorter than 5 + 5 + 2 = 12 m join A and B

detail::JunctionClusters join(const Cross& c, const std::vector<std::uint8_t>& used_up = {}) {
  return detail::join_junctions(c.net, c.radius, c.length, c.has_height, kMinKept, used_up);
}

void expect_unjoined(const detail::JunctionClusters& jc, std::size_t junctions) {
  ASSERT_EQ(jc.representative.size(), junctions);
  ASSERT_EQ(jc.members.size(), junctions);
  for (std::size_t j = 0; j < junctions; ++j) {
    EXPECT_EQ(jc.representative[j], static_cast<int>(j));
    EXPECT_EQ(jc.members[j], std::vector<int>{static_cast<int>(j)});
  }
  for (const std::uint8_t a : jc.absorbed) EXPECT_EQ(a, 0);
}

TEST(JunctionClusters, EmptyNetworkGivesEmptyClusters) {
  const RoadNetwork net;
  const detail::JunctionClusters jc = detail::join_junctions(net, {}, {}, {}, kMinKept, {});
  EXPECT_TRUE(jc.representative.empty());
  EXPECT_TRUE(jc.members.empty());
  EXPECT_TRUE(jc.absorbed.empty());
}

TEST(JunctionClusters, RoadShorterThanBothRadiiPlusKeptLengthJoinsItsIntersections) {
  // 11.9 m < 5 + 5 + 2 = 12 m: A and B join, A (the first intersection) represents them.
  const Cross c = two_intersections(11.9);
  const detail::JunctionClusters jc = join(c);
  EXPECT_EQ(jc.representative, (std::vector<int>{0, 0, 2, 3, 4, 5}));
  EXPECT_EQ(jc.members[0], (std::vector<int>{0, 1}));
  EXPECT_TRUE(jc.members[1].empty());
  for (int j = 2; j < 6; ++j) EXPECT_EQ(jc.members[j], std::vector<int>{j});
  EXPECT_EQ(jc.absorbed, (std::vector<std::uint8_t>{1, 0, 0, 0, 0}));
}

TEST(JunctionClusters, RoadExactlyAtTheThresholdOrLongerIsKept) {
  // Joined only while strictly shorter than 12 m.
  expect_unjoined(join(two_intersections(12.0)), 6);
  expect_unjoined(join(two_intersections(30.0)), 6);
}

TEST(JunctionClusters, RoadWithoutHeightOrAJunctionTakingNoRoomIsNotJoined) {
  Cross no_height = two_intersections(3.0);
  no_height.has_height[0] = 0;
  expect_unjoined(join(no_height), 6);
  Cross no_room = two_intersections(3.0);
  no_room.radius[1] = 0.0;
  expect_unjoined(join(no_room), 6);
}

TEST(JunctionClusters, RoadWithAnOpenEndIsNotJoined) {
  Cross open = two_intersections(3.0);
  open.net.roads[0].end_junction = -1;
  expect_unjoined(join(open), 6);
}

TEST(JunctionClusters, UsedUpRoadsJoinWhateverTheirLength) {
  // 50 m is far above 12 m, but the trims used the road up.
  const Cross c = two_intersections(50.0);
  const detail::JunctionClusters jc = join(c, {1, 0, 0, 0, 0});
  EXPECT_EQ(jc.representative[1], 0);
  EXPECT_EQ(jc.members[0], (std::vector<int>{0, 1}));
  EXPECT_EQ(jc.absorbed[0], 1);
  // An empty used_up marks none.
  expect_unjoined(join(c, {}), 6);
}

TEST(JunctionClusters, AnIntersectionJoinsABendButTwoBendsDoNotJoin) {
  Cross bend = two_intersections(3.0);
  bend.net.junctions[0].kind = JunctionKind::attribute_change;
  const detail::JunctionClusters jc = join(bend);
  // The cluster's intersection B represents it, and comes first among its members, though A
  // has the lower index.
  EXPECT_EQ(jc.representative[0], 1);
  EXPECT_EQ(jc.representative[1], 1);
  EXPECT_EQ(jc.members[1], (std::vector<int>{1, 0}));
  EXPECT_TRUE(jc.members[0].empty());
  EXPECT_EQ(jc.absorbed[0], 1);

  Cross bends = bend;
  bends.net.junctions[1].kind = JunctionKind::attribute_change;
  expect_unjoined(join(bends), 6);
}

TEST(JunctionClusters, ShortRoadsChainIntoOneCluster) {
  // A (0,0) - B (8,0) - C (16,0), both links 8 m; each of A, B, C has arms to dead ends.
  const RoadNetwork net = test::make_network({{{0, 0}, {8, 0}},
                                              {{8, 0}, {16, 0}},
                                              {{0, 0}, {0, 50}},
                                              {{0, 0}, {0, -50}},
                                              {{8, 0}, {8, 50}},
                                              {{16, 0}, {16, 50}},
                                              {{16, 0}, {16, -50}}});
  // Junctions in order of first appearance: A 0, B 1, C 2, then the dead ends 3..7.
  const std::vector<double> radius{5, 5, 5, 0, 0, 0, 0, 0};
  const std::vector<double> length{8, 8, 50, 50, 50, 50, 50};
  const std::vector<std::uint8_t> has_height(7, 1);
  const detail::JunctionClusters jc = detail::join_junctions(net, radius, length, has_height, kMinKept, {});
  EXPECT_EQ(jc.representative[0], 0);
  EXPECT_EQ(jc.representative[1], 0);
  EXPECT_EQ(jc.representative[2], 0);
  EXPECT_EQ(jc.members[0], (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(jc.absorbed, (std::vector<std::uint8_t>{1, 1, 0, 0, 0, 0, 0}));
}

TEST(JunctionClusters, ARoadBetweenMembersIsAbsorbedUpToTenMetresBeyondTheJoinLength) {
  // Road 0 (8 m) joins A and B; road 5 runs between them too. It lies inside the cluster while
  // shorter than 12 + 10 = 22 m.
  const detail::JunctionClusters inside = join(two_intersections(8.0, true, 21.9));
  EXPECT_EQ(inside.absorbed, (std::vector<std::uint8_t>{1, 0, 0, 0, 0, 1}));
  const detail::JunctionClusters outside = join(two_intersections(8.0, true, 22.0));
  EXPECT_EQ(outside.absorbed, (std::vector<std::uint8_t>{1, 0, 0, 0, 0, 0}));
  // Without height it is never absorbed.
  Cross flat = two_intersections(8.0, true, 15.0);
  flat.has_height[5] = 0;
  EXPECT_EQ(join(flat).absorbed[5], 0);
}

TEST(JunctionClusters, JoinLeavesLoopWhenAnotherRoadBetweenTheEndsIsTooLongToLieInside) {
  // Nothing joined yet (road 0 is 30 m). Joining A and B over road 0 would leave road 5 between
  // them: a loop when it is at least 5 + 5 + 2 + 10 = 22 m long.
  for (const auto& [second, loop] :
       std::vector<std::pair<double, bool>>{{21.9, false}, {22.0, true}, {40, true}}) {
    const Cross c = two_intersections(30.0, true, second);
    const detail::JunctionClusters jc = join(c);
    expect_unjoined(jc, 6);
    EXPECT_EQ(detail::join_leaves_loop(c.net, jc, c.radius, c.length, c.has_height, kMinKept, c.net.roads[0]),
              loop)
        << second;
    // The same question asked for road 5 looks at road 0 (30 m >= 22 m): a loop.
    EXPECT_TRUE(
        detail::join_leaves_loop(c.net, jc, c.radius, c.length, c.has_height, kMinKept, c.net.roads[5]));
  }
  // A road without height between them, or no other road at all, leaves no loop.
  Cross flat = two_intersections(30.0, true, 40.0);
  flat.has_height[5] = 0;
  EXPECT_FALSE(detail::join_leaves_loop(flat.net, join(flat), flat.radius, flat.length, flat.has_height,
                                        kMinKept, flat.net.roads[0]));
  const Cross single = two_intersections(30.0);
  EXPECT_FALSE(detail::join_leaves_loop(single.net, join(single), single.radius, single.length,
                                        single.has_height, kMinKept, single.net.roads[0]));
  // A road with an open end joins nothing.
  Road open = single.net.roads[0];
  open.start_junction = -1;
  EXPECT_FALSE(detail::join_leaves_loop(single.net, join(single), single.radius, single.length,
                                        single.has_height, kMinKept, open));
}

WayAttributes one_way() {
  WayAttributes a;
  a.oneway = true;
  a.lanes_forward = 1;
  a.lanes_backward = 0;
  return a;
}

TEST(JunctionClusters, ReachableFollowsAbsorbedRoadsInTheirDirectionOfTravel) {
  // Road 0 one-way A -> B, absorbed: B is reachable from A, not A from B.
  const Cross c = two_intersections(8.0, false, 0.0, one_way());
  const detail::JunctionClusters jc = join(c);
  ASSERT_EQ(jc.absorbed[0], 1);
  EXPECT_TRUE(jc.reachable(c.net, 0, 1));
  EXPECT_FALSE(jc.reachable(c.net, 1, 0));
  EXPECT_TRUE(jc.reachable(c.net, 1, 1));  // a member reaches itself
  // Two-way: both ways.
  const Cross two_way = two_intersections(8.0);
  const detail::JunctionClusters both = join(two_way);
  EXPECT_TRUE(both.reachable(two_way.net, 0, 1));
  EXPECT_TRUE(both.reachable(two_way.net, 1, 0));
  // Two-way but tagged with no lanes against it: one way only.
  WayAttributes no_back;
  no_back.lanes_backward = 0;
  const Cross lopsided = two_intersections(8.0, false, 0.0, no_back);
  const detail::JunctionClusters lj = join(lopsided);
  EXPECT_TRUE(lj.reachable(lopsided.net, 0, 1));
  EXPECT_FALSE(lj.reachable(lopsided.net, 1, 0));
}

TEST(JunctionClusters, ReachableDoesNotUseRoadsLeftOutOfTheCluster) {
  // Road 0 one-way A -> B absorbed; road 5 B -> A (reversed) is 40 m: not absorbed, so it does
  // not take traffic from B back to A inside the junction.
  std::vector<Polyline2> lines{{{0, 0}, {8, 0}},   {{0, 0}, {0, 100}},  {{0, 0}, {0, -100}},
                               {{8, 0}, {8, 100}}, {{8, 0}, {8, -100}}, {{8, 0}, {4, 6}, {0, 0}}};
  WayAttributes ow = one_way();
  const RoadNetwork net = test::make_network(lines, {ow, {}, {}, {}, {}, ow});
  const std::vector<double> radius{5, 5, 0, 0, 0, 0};
  const std::vector<std::uint8_t> has_height(6, 1);
  const detail::JunctionClusters far =
      detail::join_junctions(net, radius, {8, 100, 100, 100, 100, 40}, has_height, kMinKept, {});
  ASSERT_EQ(far.absorbed[5], 0);
  EXPECT_FALSE(far.reachable(net, 1, 0));
  // 15 m: absorbed, and B -> A is driveable over it.
  const detail::JunctionClusters near =
      detail::join_junctions(net, radius, {8, 100, 100, 100, 100, 15}, has_height, kMinKept, {});
  ASSERT_EQ(near.absorbed[5], 1);
  EXPECT_TRUE(near.reachable(net, 1, 0));
}

}  // namespace
}  // namespace relief

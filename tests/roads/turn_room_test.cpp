#include "roads/turn_room.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "support/synthetic.h"

namespace relief::detail {
namespace {

// A road end `trim` metres from a node at the origin, its road leaving the node along
// `heading`; the end's cross-section `width` wide (its corners only matter through their middle).
EndShape end_at(double heading, double trim, double width) {
  const Vec2 along(std::cos(heading), std::sin(heading));
  const Vec2 normal(-along.y(), along.x());
  EndShape e;
  e.out = -along;
  e.left = trim * along + 0.5 * width * normal;
  e.right = trim * along - 0.5 * width * normal;
  return e;
}

EndLanes two_way(int each_way, double lane_width) {
  EndLanes l;
  l.arriving = l.departing = each_way;
  l.lane_width = lane_width;
  l.width = 2 * each_way * lane_width;
  return l;
}

constexpr double kPi = std::numbers::pi;

TEST(TurnRoom, RightAngleTurnsAreAsRoundAsTheirTangents) {
  // From the west end (arriving eastbound on its southern lane, centre y = -1.5) right into the
  // south end (departing southbound, centre x = -1.5): the lines cross at (-1.5, -1.5), both
  // tangents trim - 1.5, and a right angle's radius is its tangent. Left into the north end
  // (centre x = +1.5): tangents trim + 1.5.
  const EndLanes lanes = two_way(1, 3.0);
  const EndShape west = end_at(kPi, 5.0, 6.0), south = end_at(-0.5 * kPi, 5.0, 6.0),
                 north = end_at(0.5 * kPi, 5.0, 6.0), east = end_at(0.0, 5.0, 6.0);
  EXPECT_NEAR(turn_room(west, lanes, south, lanes).radius, 3.5, 1e-12);
  EXPECT_NEAR(turn_room(west, lanes, north, lanes).radius, 6.5, 1e-12);
  // Straight through needs no room.
  EXPECT_TRUE(std::isinf(turn_room(west, lanes, east, lanes).radius));
  // Three lanes each way: a right turn from the outermost lane (centre 7.5 m from the axis), a left
  // turn from the innermost (1.5 m).
  const EndLanes wide = two_way(3, 3.0);
  const EndShape west_wide = end_at(kPi, 11.0, 18.0), south_wide = end_at(-0.5 * kPi, 11.0, 18.0),
                 north_wide = end_at(0.5 * kPi, 11.0, 18.0);
  EXPECT_NEAR(turn_room(west_wide, wide, south_wide, wide).radius, 11.0 - 7.5, 1e-12);
  EXPECT_NEAR(turn_room(west_wide, wide, north_wide, wide).radius, 11.0 + 1.5, 1e-12);
}

TEST(TurnRoom, AnAcuteTurnNeedsLongTangentsAndNamesTheShorterEnd) {
  // Two roads 40 degrees apart, a leaving the node eastwards and b 40 degrees south of it: from b
  // right into a turns by 140 degrees. Lane centres d = 1.5 m inside the roads' axes cross on the
  // bisector d / sin(20°) from the node, whose projection on either axis lies d / tan(20°) out: a
  // tangent of trim - d / tan(20°) and a radius of that over tan(70°). From a into b is a left
  // turn around the outside of the wedge: its lanes cross d / tan(20°) beyond the node.
  const double half = 20.0 * kPi / 180.0;
  const EndLanes lanes = two_way(1, 3.0);
  const double trim = 12.0;
  const EndShape a = end_at(0.0, trim, 6.0), b = end_at(-2.0 * half, trim, 6.0);
  const TurnRoom room = turn_room(b, lanes, a, lanes);
  const double tangent = trim - 1.5 / std::tan(half);
  EXPECT_NEAR(room.radius, tangent / std::tan(0.5 * kPi - half), 1e-9);
  EXPECT_NEAR(room.radius, 2.87, 0.01);
  EXPECT_NEAR(turn_room(a, lanes, b, lanes).radius,
              (trim + 1.5 / std::tan(half)) / std::tan(0.5 * kPi - half), 1e-9);
  // The end nearer the node is the shorter.
  EXPECT_EQ(turn_room(end_at(-2.0 * half, trim + 2.0, 6.0), lanes, a, lanes).shorter, 1);
  EXPECT_EQ(turn_room(b, lanes, end_at(0.0, trim + 2.0, 6.0), lanes).shorter, 0);
  // Lanes crossing behind the ends: no room at all.
  EXPECT_EQ(turn_room(end_at(-2.0 * half, 2.0, 6.0), lanes, end_at(0.0, 2.0, 6.0), lanes).radius, 0.0);
}

TEST(TurnRoom, OnlyTurnsThatLanesMakeNeedRoom) {
  // A one-way leading away from the junction has no arriving lane; U-turns are left out.
  const EndShape west = end_at(kPi, 5.0, 6.0), south = end_at(-0.5 * kPi, 5.0, 6.0);
  EndLanes away = two_way(1, 3.0);
  away.arriving = 0;
  away.width = 3.0;
  EXPECT_TRUE(std::isinf(turn_room(west, away, south, two_way(1, 3.0)).radius));
  EndLanes inbound = two_way(1, 3.0);
  inbound.departing = 0;
  EXPECT_TRUE(std::isinf(turn_room(west, two_way(1, 3.0), south, inbound).radius));
  const EndShape back = end_at(kPi + 0.2, 5.0, 6.0);  // 11 degrees from the west end: a U-turn
  EXPECT_TRUE(std::isinf(turn_room(west, two_way(1, 3.0), back, two_way(1, 3.0)).radius));
}

TEST(TurnRoom, EndLanesFollowTheRoadsDirection) {
  Road road;
  road.attributes.lanes_forward = 2;
  road.attributes.lanes_backward = 1;
  road.attributes.lane_width_m = 3.5;
  const EndLanes at_end = end_lanes(road, false), at_start = end_lanes(road, true);
  EXPECT_EQ(at_end.arriving, 2);
  EXPECT_EQ(at_end.departing, 1);
  EXPECT_EQ(at_start.arriving, 1);
  EXPECT_EQ(at_start.departing, 2);
  EXPECT_DOUBLE_EQ(at_end.width, 10.5);
  road.attributes.oneway = true;
  road.attributes.lanes_backward = 0;
  EXPECT_EQ(end_lanes(road, true).arriving, 0);
  EXPECT_DOUBLE_EQ(end_lanes(road, true).width, 7.0);
}

}  // namespace
}  // namespace relief::detail

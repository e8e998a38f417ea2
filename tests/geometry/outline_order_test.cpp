#include "geometry/outline_order.h"

#include <gtest/gtest.h>

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wconversion"
#pragma GCC diagnostic ignored "-Wshadow"
#pragma GCC diagnostic ignored "-Wpedantic"
#pragma GCC diagnostic ignored "-Wunused-parameter"
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_2.h>
#pragma GCC diagnostic pop

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

namespace relief::detail {
namespace {

Vec2 polar(double radius, double degrees) {
  const double a = degrees * std::numbers::pi / 180.0;
  return {radius * std::cos(a), radius * std::sin(a)};
}

// The order as a cycle starting at chain 0, given chains listed in `expected` cyclic order.
std::vector<std::size_t> shuffled_answer(const std::vector<std::size_t>& shuffle) {
  // shuffle[i] = the position in the true cyclic order of input chain i.
  std::vector<std::size_t> by_position(shuffle.size());
  for (std::size_t i = 0; i < shuffle.size(); ++i) by_position[shuffle[i]] = i;
  std::vector<std::size_t> out;
  const std::size_t start = shuffle[0];
  for (std::size_t k = 0; k < shuffle.size(); ++k) out.push_back(by_position[(start + k) % shuffle.size()]);
  return out;
}

Polyline2 outline(const std::vector<Polyline2>& chains, const std::vector<std::size_t>& order) {
  Polyline2 out;
  for (const std::size_t k : order) {
    for (const Vec2& p : chains[k]) {
      if (out.empty() || p != out.back()) out.push_back(p);
    }
  }
  return out;
}

bool simple_and_counter_clockwise(const std::vector<Polyline2>& chains,
                                  const std::vector<std::size_t>& order) {
  using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
  CGAL::Polygon_2<Kernel> polygon;
  for (const Vec2& p : outline(chains, order)) polygon.push_back(Kernel::Point_2(p.x(), p.y()));
  return polygon.is_simple() && polygon.is_counterclockwise_oriented();
}

double gap_length(const std::vector<Polyline2>& chains, const std::vector<std::size_t>& order) {
  double total = 0.0;
  for (std::size_t k = 0; k < order.size(); ++k)
    total += (chains[order[(k + 1) % order.size()]].front() - chains[order[k]].back()).norm();
  return total;
}

TEST(SimpleOutlineOrder, FindsTheCounterClockwiseOrderOfACrossingGivenInAnyOrder) {
  // A four-way crossing, 6 m wide streets, ends 5 m out: east, north, west, south; each from its
  // right corner to its left looking out along its road.
  const std::vector<Polyline2> ccw = {
      {{5, -3}, {5, 0}, {5, 3}}, {{3, 5}, {-3, 5}}, {{-5, 3}, {-5, 0}, {-5, -3}}, {{-3, -5}, {3, -5}}};
  std::vector<std::size_t> shuffle = {0, 1, 2, 3};
  do {
    std::vector<Polyline2> chains(4);
    for (std::size_t i = 0; i < 4; ++i) chains[i] = ccw[shuffle[i]];
    const auto order = simple_outline_order(chains);
    ASSERT_TRUE(order);
    EXPECT_EQ(*order, shuffled_answer(shuffle));
  } while (std::next_permutation(shuffle.begin(), shuffle.end()));
}

TEST(SimpleOutlineOrder, FindsTheShortestSimpleOutlineOfAHorseshoe) {
  // A horseshoe opening east (outer radius 20, inner 10, from 30 to 330 degrees) with road ends
  // on its outer arc, across its two tips and on its inner arc, listed shuffled. Its own outline
  // is simple, but a shorter one is too (cutting across its hole, in the order of the ends'
  // angles around its centre): the search returns a simple counter-clockwise outline no longer.
  const std::vector<Polyline2> ccw = {{polar(20, 60), polar(20, 75)},    // outer arc, counter-clockwise
                                      {polar(20, 170), polar(20, 190)},  //
                                      {polar(20, 285), polar(20, 300)},  //
                                      {polar(20, 330), polar(10, 330)},  // lower tip, outwards in
                                      {polar(10, 280), polar(10, 260)},  // inner arc, clockwise
                                      {polar(10, 100), polar(10, 80)},   //
                                      {polar(10, 30), polar(20, 30)}};   // upper tip
  const std::vector<std::size_t> shuffle = {3, 6, 0, 5, 1, 4, 2};
  std::vector<Polyline2> chains(ccw.size());
  for (std::size_t i = 0; i < ccw.size(); ++i) chains[i] = ccw[shuffle[i]];
  const auto order = simple_outline_order(chains);
  ASSERT_TRUE(order);
  // A simple counter-clockwise outline (checked by CGAL), no longer than the horseshoe's own.
  EXPECT_TRUE(simple_and_counter_clockwise(chains, *order));
  EXPECT_LE(gap_length(chains, *order), gap_length(chains, shuffled_answer(shuffle)) + 1e-9);
  EXPECT_TRUE(simple_and_counter_clockwise(chains, shuffled_answer(shuffle)));
}

TEST(SimpleOutlineOrder, EndsThatCrossEachOtherHaveNoOrder) {
  // Two road ends lying across each other (an X): no outline through both is simple.
  EXPECT_FALSE(simple_outline_order({{{-5, -5}, {5, 5}}, {{5, -5}, {-5, 5}}, {{10, 0}, {10, 3}}}));
  // Ends that only fit clockwise (their road outside would be inside the outline).
  EXPECT_FALSE(simple_outline_order({{{5, 3}, {5, -3}}, {{-5, -3}, {-5, 3}}}));
}

TEST(SimpleOutlineOrder, StopsWithinItsBudget) {
  // 12 ends of a star shuffled: found with the default budget, not with a budget of 3 steps.
  std::vector<Polyline2> chains;
  for (int k = 0; k < 12; ++k) chains.push_back({polar(10, 30.0 * k - 5.0), polar(10, 30.0 * k + 5.0)});
  std::mt19937 random(7);
  std::shuffle(chains.begin() + 1, chains.end(), random);
  const auto order = simple_outline_order(chains);
  ASSERT_TRUE(order);
  for (std::size_t k = 1; k < order->size(); ++k) {
    const Vec2 a = chains[(*order)[k - 1]].front(), b = chains[(*order)[k]].front();
    EXPECT_GT(a.x() * b.y() - a.y() * b.x(), 0.0) << "not counter-clockwise at step " << k;
  }
  EXPECT_FALSE(simple_outline_order(chains, 3));
}

// The cyclic order `order` rotated to start at `first`.
std::vector<std::size_t> starting_at(std::vector<std::size_t> order, std::size_t first) {
  std::rotate(order.begin(), std::find(order.begin(), order.end(), first), order.end());
  return order;
}

TEST(JunctionEndOrder, AnEndBesideTheCentreSortsByItsRoadsDirection) {
  // NE's J286 in small: road A leaves east from an end lying west of the ends' centroid, B south,
  // C north. By its midpoint's angle A would come after C (the ring then crosses itself and,
  // in netconvert, cut A's lane metres in); by a point ahead along its road, between B and C.
  const std::vector<PlanEnd> ends = {
      {{-5, -3}, {-5, 3}, {1, 0}},   // A: looking east, right is south
      {{-6, -8}, {0, -8}, {0, -1}},  // B: looking south, right is west
      {{0, 6}, {-8, 6}, {0, 1}},     // C: looking north, right is east
  };
  std::vector<Polyline2> chains;
  for (const PlanEnd& e : ends) chains.push_back({e.right, e.left});
  EXPECT_FALSE(is_simple_outline(chains, {1, 2, 0})) << "the midpoint order this test guards against";
  const std::vector<std::size_t> order = junction_end_order(ends);
  EXPECT_EQ(starting_at(order, 1), (std::vector<std::size_t>{1, 0, 2}));
  EXPECT_TRUE(is_simple_outline(chains, order));
  EXPECT_TRUE(simple_and_counter_clockwise(chains, order));
}

TEST(JunctionEndOrder, ASimpleOrderIsFoundWhereTheDirectionsMislead) {
  // A joined junction: two ends far apart both leaving north, a third between them leaving
  // south-west across under the first. Whatever the sort gives, the result must be simple.
  const std::vector<PlanEnd> ends = {
      {{30, 0}, {24, 0}, {0, 1}},        // leaves north, east side
      {{-24, 0}, {-30, 0}, {0, 1}},      // leaves north, west side
      {{-2, -3}, {4, -3}, {0.6, -0.8}},  // leaves south between them
  };
  std::vector<Polyline2> chains;
  for (const PlanEnd& e : ends) chains.push_back({e.right, e.left});
  const std::vector<std::size_t> order = junction_end_order(ends);
  ASSERT_EQ(order.size(), 3u);
  EXPECT_TRUE(simple_and_counter_clockwise(chains, order));
}

TEST(JunctionEndOrder, FewerThanTwoEndsKeepTheirOrder) {
  EXPECT_TRUE(junction_end_order({}).empty());
  EXPECT_EQ(junction_end_order({{{0, 0}, {1, 0}, {0, -1}}}), (std::vector<std::size_t>{0}));
}

}  // namespace
}  // namespace relief::detail

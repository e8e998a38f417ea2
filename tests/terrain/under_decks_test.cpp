#include "terrain/under_decks.h"

#include <gtest/gtest.h>

#include <vector>

namespace relief {
namespace {

using namespace terrain_detail;

// A terrain TIN over [0, 100]^2 flat at `z` (its four corners), optionally with extra vertices.
Tin flat_terrain(double z) {
  Tin tin;
  for (const auto& [x, y] : std::vector<std::pair<double, double>>{{0, 0}, {100, 0}, {100, 100}, {0, 100}})
    tin.insert(Point(x, y, z));
  return tin;
}

// A square deck over [x0, x0 + 10] x [y0, y0 + 10], its height z0 + slope * (x - x0): two
// triangles, counter-clockwise.
TriangleMesh deck(double x0, double y0, double z0, double slope = 0.0) {
  TriangleMesh m;
  m.vertices = {
      {x0, y0, z0}, {x0 + 10, y0, z0 + 10 * slope}, {x0 + 10, y0 + 10, z0 + 10 * slope}, {x0, y0 + 10, z0}};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  return m;
}

std::size_t constrained_edges(const Tin& tin) {
  std::size_t n = 0;
  for (auto e = tin.finite_edges_begin(); e != tin.finite_edges_end(); ++e)
    n += tin.is_constrained(*e) ? 1 : 0;
  return n;
}

// Height of the TIN vertex at (x, y); NaN when there is none.
double vertex_z(const Tin& tin, double x, double y) {
  for (auto v = tin.finite_vertices_begin(); v != tin.finite_vertices_end(); ++v)
    if (v->point().x() == x && v->point().y() == y) return v->point().z();
  return std::nan("");
}

TEST(UnderDecks, NoDecksChangeNothing) {
  Tin tin = flat_terrain(10.0);
  const UnderDecks r = keep_under_decks(tin, TriangleMesh{}, {}, 2.0);
  EXPECT_EQ(r.edges_constrained, 0u);
  EXPECT_EQ(r.edges_skipped, 0u);
  EXPECT_EQ(r.vertices_lowered, 0u);
  EXPECT_EQ(tin.number_of_vertices(), 4u);
}

TEST(UnderDecks, ADeckHighAboveTheTerrainGetsItsOutlineAsConstraintsAtTerrainHeight) {
  // Terrain at 0, deck at 5, clearance 2: the terrain is already 3 m below it; the outline's
  // four edges go in at the terrain's height, nothing is lowered.
  Tin tin = flat_terrain(0.0);
  const UnderDecks r = keep_under_decks(tin, deck(40, 40, 5.0), {}, 2.0);
  EXPECT_EQ(r.edges_constrained, 4u);
  EXPECT_EQ(r.edges_skipped, 0u);
  EXPECT_EQ(r.vertices_lowered, 0u);
  EXPECT_EQ(tin.number_of_vertices(), 8u);
  EXPECT_EQ(constrained_edges(tin), 4u);
  EXPECT_EQ(vertex_z(tin, 40, 40), 0.0);
  EXPECT_EQ(vertex_z(tin, 50, 50), 0.0);
}

TEST(UnderDecks, TerrainRisingThroughADeckIsLoweredToTheClearanceUnderIt) {
  // Terrain at 10, a deck rising from 4 m (x = 40) to 5 m (x = 50), clearance 2. Its corners
  // go in at 2 and 3 m (4 lowered); the terrain vertex at (45, 45) goes to 4.5 - 2 = 2.5 m (one
  // more); an outline vertex at (48, 48) stays at 10 m; the TIN's corners are not under it.
  Tin tin = flat_terrain(10.0);
  tin.insert(Point(45, 45, 10));
  const VertexHandle kept = tin.insert(Point(48, 48, 10));
  kept->info().outline = true;
  const UnderDecks r = keep_under_decks(tin, deck(40, 40, 4.0, 0.1), {}, 2.0);
  EXPECT_EQ(r.edges_constrained, 4u);
  EXPECT_EQ(r.vertices_lowered, 5u);
  EXPECT_NEAR(vertex_z(tin, 40, 40), 2.0, 1e-12);
  EXPECT_NEAR(vertex_z(tin, 40, 50), 2.0, 1e-12);
  EXPECT_NEAR(vertex_z(tin, 50, 40), 3.0, 1e-12);
  EXPECT_NEAR(vertex_z(tin, 45, 45), 2.5, 1e-12);
  EXPECT_EQ(vertex_z(tin, 48, 48), 10.0);
  EXPECT_EQ(vertex_z(tin, 0, 0), 10.0);
}

TEST(UnderDecks, TerrainExactlyTheClearanceBelowIsNotLowered) {
  // Terrain at 2, deck at 5, clearance 3: already 3 m below, nothing is lowered.
  Tin tin = flat_terrain(2.0);
  tin.insert(Point(45, 45, 2.0));
  const UnderDecks r = keep_under_decks(tin, deck(40, 40, 5.0), {}, 3.0);
  EXPECT_EQ(r.edges_constrained, 4u);
  EXPECT_EQ(r.vertices_lowered, 0u);
  EXPECT_EQ(vertex_z(tin, 45, 45), 2.0);
  // 1 mm higher: the deck's four corners (step 1) and the vertex (step 2) go down to 2 m.
  Tin higher = flat_terrain(2.001);
  higher.insert(Point(45, 45, 2.001));
  const UnderDecks h = keep_under_decks(higher, deck(40, 40, 5.0), {}, 3.0);
  EXPECT_EQ(h.vertices_lowered, 5u);
  EXPECT_EQ(vertex_z(higher, 45, 45), 2.0);
  EXPECT_EQ(vertex_z(higher, 40, 40), 2.0);
  EXPECT_EQ(vertex_z(higher, 50, 50), 2.0);
}

TEST(UnderDecks, UnderStackedDecksTheLowestCounts) {
  // A deck at 5 m over [40, 50]^2 and one at 12 m over [42, 52]^2, clearance 2, terrain at 10:
  // the vertex at (45, 45), under both, goes 2 m under the lower (3 m); the one at (51, 51),
  // under the upper only, is already 2 m under it and stays.
  Tin tin = flat_terrain(10.0);
  tin.insert(Point(45, 45, 10));
  tin.insert(Point(51, 51, 10));
  TriangleMesh decks = deck(40, 40, 5.0);
  const TriangleMesh upper = deck(42, 42, 12.0);
  for (const Vec3& v : upper.vertices) decks.vertices.push_back(v);
  for (const auto& t : upper.triangles) decks.triangles.push_back({t[0] + 4, t[1] + 4, t[2] + 4});
  const UnderDecks r = keep_under_decks(tin, decks, {}, 2.0);
  EXPECT_EQ(r.edges_constrained, 8u);
  EXPECT_NEAR(vertex_z(tin, 45, 45), 3.0, 1e-12);
  EXPECT_EQ(vertex_z(tin, 51, 51), 10.0);
}

TEST(UnderDecks, EdgesCrossingTheRoadOutlineOrInThePavedAreaAreLeftOut) {
  // A road outline strip 44 <= x <= 46 along y crosses the deck's bottom and top edges: those
  // two are skipped, its sides constrained.
  const std::vector<Polyline3> road{{{44, 0, 0}, {46, 0, 0}, {46, 100, 0}, {44, 100, 0}}};
  Tin crossed = flat_terrain(0.0);
  const UnderDecks r = keep_under_decks(crossed, deck(40, 40, 5.0), road, 2.0);
  EXPECT_EQ(r.edges_constrained, 2u);
  EXPECT_EQ(r.edges_skipped, 2u);
  EXPECT_EQ(constrained_edges(crossed), 2u);
  // Every terrain face paved: every edge is skipped, vertices under the deck still lowered.
  Tin paved = flat_terrain(10.0);
  paved.insert(Point(45, 45, 10));
  for (auto f = paved.finite_faces_begin(); f != paved.finite_faces_end(); ++f) f->info().paved = true;
  const UnderDecks p = keep_under_decks(paved, deck(40, 40, 5.0), {}, 2.0);
  EXPECT_EQ(p.edges_constrained, 0u);
  EXPECT_EQ(p.edges_skipped, 4u);
  EXPECT_EQ(p.vertices_lowered, 1u);
  EXPECT_NEAR(vertex_z(paved, 45, 45), 3.0, 1e-12);
}

TEST(UnderDecks, ADeckBeyondTheTerrainIsLeftOut) {
  Tin tin = flat_terrain(0.0);
  const UnderDecks r = keep_under_decks(tin, deck(200, 200, 5.0), {}, 2.0);
  EXPECT_EQ(r.edges_constrained, 0u);
  EXPECT_EQ(r.edges_skipped, 4u);
  EXPECT_EQ(r.vertices_lowered, 0u);
  EXPECT_EQ(tin.number_of_vertices(), 4u);
}

}  // namespace
}  // namespace relief

// The region's paved surface at its owners' heights (src/tiles/owner_surface.h): analytic cases
// of two tiles' files, the owners' vertices and what the merge makes of them.

#include "tiles/owner_surface.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "relief/core/errors.h"
#include "support/test_data.h"
#include "tiles/scene_seams.h"

namespace relief {
namespace {

TriangleMesh strip(const std::string& name, const std::vector<Vec3>& vertices) {
  TriangleMesh m;
  m.name = name;
  m.vertices = vertices;
  for (std::uint32_t i = 0; i + 2 < vertices.size(); ++i) m.triangles.push_back({i, i + 1, i + 2});
  return m;
}

// A road 6 m wide along x from x = 0 to 20 crossing the tile line x = 10, on a 10 % climb as its
// owner (tile A) fitted it; tile B fitted it 5 cm higher. A's file holds x 0..10, B's x 10..20
// (cut by centroid), each from its own fit. The terrain in B meets the road's edge at y = 6: it
// stands over an opening 3 m above the road at x = 15, it reaches over the line x = 10 to the
// road's edge at x = 5 (a vertex only A's file holds), and it has a vertex of its own on the
// road's edge at x = 17.5 (where a tile line would cross it).
struct TwoTiles {
  std::vector<MeshScene> files;
  std::vector<Aabb2> cores;  // A: x 0..10, B: x 10..20
  std::vector<detail::OwnedSurface> owned;
};

Aabb2 box(double x0, double y0, double x1, double y1) {
  Aabb2 b;
  b.extend(Vec2(x0, y0));
  b.extend(Vec2(x1, y1));
  return b;
}

double owner_z(double x) {
  return 100.0 + 0.1 * x;
}

TwoTiles road_across_a_tile_line() {
  TwoTiles t;
  const auto road = [](double x0, double x1, double dz) {
    std::vector<Vec3> v;
    for (double x = x0; x <= x1; x += 5.0)
      for (const double y : {0.0, 6.0}) v.emplace_back(x, y, owner_z(x) + dz);
    return v;
  };
  MeshScene a, b;
  a.meshes.push_back(strip("Road_Road", road(0.0, 10.0, 0.0)));
  b.meshes.push_back(strip("Road_Road", road(10.0, 20.0, 0.05)));
  b.meshes.push_back(
      strip("Terrain", {Vec3(10.0, 6.0, owner_z(10.0) + 0.05), Vec3(15.0, 6.0, owner_z(15.0) + 3.05),
                        Vec3(17.5, 30.0, 90.0), Vec3(20.0, 6.0, owner_z(20.0) + 0.05),
                        Vec3(17.5, 6.0, owner_z(17.5) + 0.05), Vec3(5.0, 6.0, owner_z(5.0) + 0.05)}));
  t.files = {a, b};
  t.cores = {box(0.0, -50.0, 10.0, 50.0), box(10.0, -50.0, 20.0, 50.0)};
  detail::OwnedSurface owner;  // A owns the whole road, over its window
  owner.vertices["Road_Road"] = road(0.0, 20.0, 0.0);
  t.owned = {owner, detail::OwnedSurface{}};
  return t;
}

TEST(OwnerSurface, EveryPavedVertexTakesItsOwnersHeightAndTheTerrainEdgeMovesWithIt) {
  TwoTiles t = road_across_a_tile_line();
  const detail::OwnerHeights h = detail::take_owner_heights(t.files, t.cores, t.owned);
  EXPECT_EQ(h.vertices, 12u);  // 6 of each tile's Road_Road
  EXPECT_EQ(h.moved, 6u);      // B's
  EXPECT_EQ(h.unmatched, 0u);
  EXPECT_NEAR(h.max_dz_m, 0.05, 1e-9);
  EXPECT_EQ(h.owners_apart, 0u);
  for (const MeshScene& file : t.files) {
    for (const Vec3& v : file.meshes[0].vertices) EXPECT_EQ(v.z(), owner_z(v.x())) << v.transpose();
  }
  // The terrain on the road's edge came down with it; the opening's top, 3 m over the road, and
  // the terrain away from the road did not move.
  const std::vector<Vec3>& terrain = t.files[1].meshes[1].vertices;
  EXPECT_EQ(h.terrain_moved, 3u);
  EXPECT_EQ(terrain[0].z(), owner_z(10.0));
  EXPECT_EQ(terrain[1].z(), owner_z(15.0) + 3.05);
  EXPECT_EQ(terrain[2].z(), 90.0);
  EXPECT_EQ(terrain[3].z(), owner_z(20.0));
  EXPECT_EQ(terrain[5].z(), owner_z(5.0));
  // Where a road's edge crosses a tile line the terrain has a vertex of its own, from its own
  // fit, on no road vertex: one only this file holds is not moved (where two files hold it, the
  // terrain border rule of the next test but one takes one tile's copy).
  EXPECT_EQ(terrain[4].z(), owner_z(17.5) + 0.05);
  // The vertex both files hold at the tile line is one: the weld finds nothing apart.
  const detail::SeamWeld weld = detail::weld_seams(t.files);
  EXPECT_EQ(weld.shared_vertices, 2u);
  EXPECT_TRUE(weld.left_apart.empty());
  EXPECT_EQ(weld.max_dz_m, 0.0);
}

// A vertex no owner has: a station the owner's loft did not make takes its neighbours' change,
// ring by ring; one with no path to a vertex an owner has is left as built. All are counted.
TEST(OwnerSurface, AVertexNoOwnerHasFollowsItsNeighboursOrIsLeftAsBuilt) {
  TwoTiles t = road_across_a_tile_line();
  std::vector<Vec3>& owner = t.owned[0].vertices["Road_Road"];
  owner.erase(owner.begin() + 4, owner.begin() + 6);  // A made no station at x = 10
  detail::OwnerHeights h = detail::take_owner_heights(t.files, t.cores, t.owned);
  EXPECT_EQ(h.unmatched, 4u);  // both files' vertices at x = 10
  EXPECT_EQ(h.interpolated, 4u);
  EXPECT_EQ(h.unmatched_at, Vec3(10.0, 0.0, owner_z(10.0)));
  for (const MeshScene& file : t.files) {
    for (const Vec3& v : file.meshes[0].vertices) EXPECT_NEAR(v.z(), owner_z(v.x()), 1e-12) << v.transpose();
  }

  // Two stations in a row (x = 5 and 10): the one next to no owner's vertex follows the other.
  t = road_across_a_tile_line();
  std::vector<Vec3>& two = t.owned[0].vertices["Road_Road"];
  two.erase(two.begin() + 2, two.begin() + 6);
  h = detail::take_owner_heights(t.files, t.cores, t.owned);
  EXPECT_EQ(h.unmatched, 6u);
  EXPECT_EQ(h.interpolated, 6u);
  for (const MeshScene& file : t.files) {
    for (const Vec3& v : file.meshes[0].vertices) EXPECT_NEAR(v.z(), owner_z(v.x()), 1e-12) << v.transpose();
  }

  t = road_across_a_tile_line();
  t.owned[0].vertices["Road_Road"].resize(6);  // A's window ended at x = 10
  h = detail::take_owner_heights(t.files, t.cores, t.owned);
  EXPECT_EQ(h.unmatched, 4u);     // B's vertices at x = 15 and 20
  EXPECT_EQ(h.interpolated, 4u);  // ring by ring from x = 10
  EXPECT_EQ(h.moved, 6u);         // and B's at x = 10
  EXPECT_NEAR(t.files[1].meshes[0].vertices.back().z(), owner_z(20.0), 1e-12);
  // A piece of road no owner made at all stays as built.
  t = road_across_a_tile_line();
  t.files[1].meshes.push_back(strip("Road_Road", {Vec3(50, 50, 7), Vec3(55, 50, 7), Vec3(50, 55, 7)}));
  h = detail::take_owner_heights(t.files, t.cores, t.owned);
  EXPECT_EQ(h.unmatched, 3u);
  EXPECT_EQ(h.interpolated, 0u);
  for (const Vec3& v : t.files[1].meshes.back().vertices) EXPECT_EQ(v.z(), 7.0);
  // The tolerance is the plan's: a vertex 2 mm off its owner's is no match.
  TwoTiles off = road_across_a_tile_line();
  for (Vec3& v : off.owned[0].vertices["Road_Road"]) v.x() += 0.002;
  EXPECT_EQ(detail::take_owner_heights(off.files, off.cores, off.owned).unmatched, 12u);
  TwoTiles near = road_across_a_tile_line();
  for (Vec3& v : near.owned[0].vertices["Road_Road"]) v.x() += 0.0005;
  EXPECT_EQ(detail::take_owner_heights(near.files, near.cores, near.owned).unmatched, 0u);
}

// A road of tile A ends where a junction of tile B begins; the two fits put that edge 2 cm apart.
// The first owner's height is taken by both files, and the difference is reported where it is.
TEST(OwnerSurface, WhereTwoOwnersMeetTheFirstsHeightIsTakenAndTheirDifferenceReported) {
  TwoTiles t = road_across_a_tile_line();
  detail::OwnedSurface junction;
  junction.vertices["Road_Road"] = {Vec3(20.0, 0.0, owner_z(20.0) + 0.02),
                                    Vec3(20.0, 6.0, owner_z(20.0) + 0.0005), Vec3(25.0, 3.0, owner_z(25.0))};
  t.owned[1] = junction;
  const detail::OwnerHeights h = detail::take_owner_heights(t.files, t.cores, t.owned);
  EXPECT_EQ(h.owners_apart, 1u);  // 0.5 mm is within the 1 mm the report leaves out
  EXPECT_NEAR(h.owners_apart_max_m, 0.02, 1e-9);
  EXPECT_EQ(h.owners_apart_at, Vec3(20.0, 0.0, owner_z(20.0) + 0.02));
  EXPECT_EQ(t.files[1].meshes[0].vertices[4].z(), owner_z(20.0));
}

// The terrain beside the road, cut at the tile line x = 10: each tile's batter followed its own
// fit of the road, so the two files' copies of a vertex on the line 6 m from the road's edge
// stand 5 cm apart (a crack in the ground). Both take the copy of the tile whose road did not
// move there (A, the owner). A vertex on the line 39 m from any road, farther than the batter
// reaches, is no road's doing: it is left to the weld.
TEST(OwnerSurface, TheTerrainOnATileLineBesideARoadTakesTheCopyOfTheTileWhoseRoadMovedLeast) {
  TwoTiles t = road_across_a_tile_line();
  // (The last vertex, 5 m over the first at its place, is another: an opening's top.)
  t.files[0].meshes.push_back(
      strip("Terrain", {Vec3(10.0, 12.0, owner_z(10.0) + 1.0), Vec3(5.0, 12.0, 99.0), Vec3(10.0, 45.0, 50.0),
                        Vec3(10.0, 12.0, owner_z(10.0) + 6.0)}));
  t.files[1].meshes.push_back(
      strip("Terrain", {Vec3(10.0, 12.0, owner_z(10.0) + 1.05), Vec3(15.0, 12.0, 99.0),
                        Vec3(10.0, 45.0, 50.02), Vec3(10.0, 12.0, owner_z(10.0) + 6.01)}));
  const detail::OwnerHeights h = detail::take_owner_heights(t.files, t.cores, t.owned);
  EXPECT_EQ(h.terrain_seams, 2u);  // the ground and the opening's top, each apart
  EXPECT_NEAR(h.terrain_seams_max_dz_m, 0.05, 1e-9);
  EXPECT_EQ(h.terrain_seams_at.head<2>(), Vec2(10.0, 12.0));
  const std::vector<Vec3>& a = t.files[0].meshes[1].vertices;
  const std::vector<Vec3>& b = t.files[1].meshes[2].vertices;
  EXPECT_EQ(a[0].z(), owner_z(10.0) + 1.0);
  EXPECT_EQ(b[0].z(), a[0].z());  // the same bits: no crack
  EXPECT_EQ(b[1].z(), 99.0);      // off the line: as built
  EXPECT_EQ(a[3].z(), owner_z(10.0) + 6.0);
  EXPECT_EQ(b[3].z(), a[3].z());  // the opening's top joined with its own copy, not the ground's
  EXPECT_EQ(a[2].z(), 50.0);
  EXPECT_EQ(b[2].z(), 50.02);
  const detail::SeamWeld weld = detail::weld_seams(t.files);
  EXPECT_EQ(weld.left_apart.at("Terrain").vertices, 1u);  // the one far from the road: 2 cm
  // Where it was B that owned the road (A's copy of it moved), B's terrain is taken.
  TwoTiles swapped = road_across_a_tile_line();
  std::swap(swapped.owned[0], swapped.owned[1]);
  for (Vec3& v : swapped.owned[1].vertices["Road_Road"]) v.z() += 0.05;  // B's fit
  swapped.files[0].meshes.push_back(t.files[0].meshes[1]);
  swapped.files[0].meshes[1].vertices[0].z() = owner_z(10.0) + 1.0;
  swapped.files[1].meshes.push_back(t.files[1].meshes[2]);
  swapped.files[1].meshes[2].vertices[0].z() = owner_z(10.0) + 1.05;
  EXPECT_EQ(detail::take_owner_heights(swapped.files, swapped.cores, swapped.owned).terrain_seams, 1u);
  EXPECT_EQ(swapped.files[0].meshes[1].vertices[0].z(), owner_z(10.0) + 1.05);
}

TEST(OwnerSurface, FileRoundTripsAndABrokenOneIsRefused) {
  const std::filesystem::path dir = test::scratch_dir("owned_surface");
  const TwoTiles t = road_across_a_tile_line();
  detail::OwnedSurface surface = t.owned[0];
  surface.vertices["Road_Marking"] = {Vec3(1.5, -2.25, 0.125)};
  detail::write_owned_surface(dir / "s.bin", surface);
  const detail::OwnedSurface back = detail::read_owned_surface(dir / "s.bin");
  EXPECT_EQ(back.vertices, surface.vertices);
  const auto size = std::filesystem::file_size(dir / "s.bin");
  std::filesystem::resize_file(dir / "s.bin", size - 3);
  EXPECT_THROW((void)detail::read_owned_surface(dir / "s.bin"), InvalidInput);
  std::ofstream(dir / "t.bin") << "relief-tile-holds 1\n";
  EXPECT_THROW((void)detail::read_owned_surface(dir / "t.bin"), InvalidInput);
  EXPECT_THROW((void)detail::read_owned_surface(dir / "none.bin"), IoError);
}

}  // namespace
}  // namespace relief

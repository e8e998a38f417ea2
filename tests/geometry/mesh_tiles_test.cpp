#include "relief/geometry/mesh_tiles.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <tuple>

#include "relief/core/errors.h"

namespace relief {
namespace {

// A 30 m x 10 m grid of 1 m squares (two triangles each) from (-5, -5), on the plane z = x.
TriangleMesh grid() {
  TriangleMesh m;
  m.name = "Terrain";
  m.kind = SurfaceKind::terrain;
  const int nx = 30, ny = 10;
  for (int j = 0; j <= ny; ++j) {
    for (int i = 0; i <= nx; ++i) m.vertices.emplace_back(-5.0 + i, -5.0 + j, -5.0 + i);
  }
  const auto at = [&](int i, int j) { return static_cast<std::uint32_t>(j * (nx + 1) + i); };
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      m.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      m.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  }
  m.normals.assign(m.vertices.size(), Vec3::UnitZ());
  return m;
}

TEST(MeshTiles, TrianglesGoWholeToTheTileOfTheirCentroid) {
  MeshScene scene;
  scene.meshes = {grid()};
  scene.meshes.push_back(grid());
  scene.meshes.back().name = "Road_Road";
  scene.meshes.back().triangles.resize(20);  // only the first row, x in [-5, 5)
  scene.metadata["relief:crs"] = "EPSG:32610";
  // 10 m tiles: columns -1..2 (x from -10), rows -1..0; the grid covers x in [-5, 25].
  const std::vector<SceneTile> tiles = split_into_tiles(scene, 10.0);
  ASSERT_EQ(tiles.size(), 8u);
  std::size_t terrain = 0, road = 0;
  std::set<std::tuple<double, double, double>> positions;
  for (const SceneTile& t : tiles) {
    EXPECT_GE(t.x, 0);
    EXPECT_LE(t.x, 3);
    EXPECT_GE(t.y, 0);
    EXPECT_LE(t.y, 1);
    EXPECT_NEAR(t.bounds.max.x() - t.bounds.min.x(), 10.0, 1e-12);
    EXPECT_EQ(t.scene.metadata.at("relief:crs"), "EPSG:32610");
    EXPECT_EQ(t.scene.metadata.at("relief:tile"), std::to_string(t.x) + " " + std::to_string(t.y));
    for (const TriangleMesh& m : t.scene.meshes) {
      EXPECT_FALSE(m.empty());
      EXPECT_EQ(m.normals.size(), m.vertices.size());
      (m.name == "Terrain" ? terrain : road) += m.triangles.size();
      for (const auto& tri : m.triangles) {
        const Vec3 c = (m.vertices[tri[0]] + m.vertices[tri[1]] + m.vertices[tri[2]]) / 3.0;
        EXPECT_GE(c.x(), t.bounds.min.x());
        EXPECT_LT(c.x(), t.bounds.max.x());
        EXPECT_GE(c.y(), t.bounds.min.y());
        EXPECT_LT(c.y(), t.bounds.max.y());
        for (const std::uint32_t v : tri) EXPECT_NEAR(m.vertices[v].z(), m.vertices[v].x(), 1e-12);
      }
      for (const Vec3& p : m.vertices) positions.insert({p.x(), p.y(), p.z()});
    }
  }
  EXPECT_EQ(terrain, 600u);  // every triangle once
  EXPECT_EQ(road, 20u);
  // Tiles share the positions along their common edges: together they use exactly the grid's.
  EXPECT_EQ(positions.size(), 31u * 11u);
  // The first tile (row-major) holds the south-west corner.
  EXPECT_EQ(tiles.front().x, 0);
  EXPECT_EQ(tiles.front().y, 0);
  EXPECT_NEAR(tiles.front().bounds.min.x(), -10.0, 1e-12);
  EXPECT_NEAR(tiles.front().bounds.min.y(), -10.0, 1e-12);
  EXPECT_EQ(tiles.front().scene.metadata.at("relief:tile_bounds"), "-10.000 -10.000 0.000 0.000");
}

TEST(MeshTiles, EmptyScenesAndBadSizes) {
  EXPECT_TRUE(split_into_tiles(MeshScene{}, 100.0).empty());
  MeshScene scene;
  scene.meshes = {grid()};
  EXPECT_THROW((void)split_into_tiles(scene, 0.0), InvalidInput);
  EXPECT_THROW((void)split_into_tiles(scene, std::nan("")), InvalidInput);
  scene.meshes[0].triangles.push_back({0, 1, 9999});
  EXPECT_THROW((void)split_into_tiles(scene, 10.0), InvalidInput);
}

}  // namespace
}  // namespace relief

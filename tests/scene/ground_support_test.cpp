#include "scene/ground_support.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "support/synthetic.h"

namespace relief {
namespace {

using Flags = std::vector<std::uint8_t>;

WayAttributes structure(bool bridge, bool tunnel) {
  WayAttributes a;
  a.bridge = bridge;
  a.tunnel = tunnel;
  return a;
}

TEST(GroundSupport, TriangleSupportFollowsTheAttributesOfEachTrianglesRoad) {
  // Network roads: 0 plain, 1 bridge, 2 tunnel. Model roads (ids unlike their indices): 10 from
  // road 2, 20 from road 0, 30 from road 1, 40 a connecting road (no source).
  RoadNetwork network;
  for (const WayAttributes& a : {structure(false, false), structure(true, false), structure(false, true)}) {
    Road r;
    r.id = static_cast<int>(network.roads.size());
    r.attributes = a;
    network.roads.push_back(r);
  }
  RoadModel model;
  for (const auto& [id, source] : std::vector<std::pair<int, int>>{{10, 2}, {20, 0}, {30, 1}, {40, -1}}) {
    ModelRoad road;
    road.id = id;
    road.source_road = source;
    model.roads.push_back(road);
  }
  RoadMeshes meshes;
  // Triangles owned by roads 20, 30, 10, junction 0 (-1), connecting road 40, unknown road 99.
  meshes.road_triangle_owner = {20, 30, 10, -1, 40, 99};
  meshes.road.triangles.assign(meshes.road_triangle_owner.size(), {0, 0, 0});
  const GroundSupport s = triangle_support(meshes, model, network);
  // Only the bridge's and the tunnel's triangles are off the ground; junction patches and
  // triangles of roads without an OSM way count as ground.
  EXPECT_EQ(s.ground, (Flags{1, 0, 0, 1, 1, 1}));
  EXPECT_EQ(s.tunnel, (Flags{0, 0, 1, 0, 0, 0}));
  EXPECT_EQ(s.counted_as_ground, (Flags(6, 0)));
  EXPECT_EQ(s.decks_on_ground, 0u);
  EXPECT_EQ(s.tunnels_open, 0u);
}

TEST(GroundSupport, TriangleSupportOfAnEmptyMeshIsEmpty) {
  const GroundSupport s = triangle_support(RoadMeshes{}, RoadModel{}, RoadNetwork{});
  EXPECT_TRUE(s.ground.empty());
  EXPECT_TRUE(s.tunnel.empty());
  EXPECT_TRUE(s.counted_as_ground.empty());
}

// A flat DEM at 20 m over local [-100, 100]^2, and small triangles side by side along x at the
// given corner heights (one triangle per entry; each corner its own vertex).
struct Scene {
  TriangleMesh road;
  GroundSupport support;
};

constexpr double kDemZ = 20.0;

DemSampler flat_dem() {
  Aabb2 area;
  area.extend(Vec2(-90, -90));
  area.extend(Vec2(90, 90));
  return DemSampler(
      {test::write_local_dem("ground_support_flat", 100.0, 5.0, [](double, double) { return kDemZ; })},
      test::synthetic_frame(), area);
}

Scene triangles(const std::vector<std::array<double, 3>>& corner_z, const Flags& ground,
                const Flags& tunnel) {
  Scene sc;
  for (std::size_t i = 0; i < corner_z.size(); ++i) {
    const double x0 = -80.0 + 10.0 * static_cast<double>(i);
    const auto v = static_cast<std::uint32_t>(sc.road.vertices.size());
    sc.road.vertices.emplace_back(x0, 0.0, corner_z[i][0]);
    sc.road.vertices.emplace_back(x0 + 3.0, 0.0, corner_z[i][1]);
    sc.road.vertices.emplace_back(x0, 3.0, corner_z[i][2]);
    sc.road.triangles.push_back({v, v + 1, v + 2});
  }
  sc.support.ground = ground;
  sc.support.tunnel = tunnel;
  sc.support.counted_as_ground.assign(corner_z.size(), 0);
  return sc;
}

TEST(GroundSupport, DecksWithinOneMetreOfTheDemAndTunnelsWithoutCoverCountAsGround) {
  const DemSampler dem = flat_dem();
  // With a 5 m mouth height, over a DEM at 20 m:
  //  0 ground road at 50 m       - ground already, untouched;
  //  1 deck 0.999 m above the DEM - on it (within 1 m);
  //  2 deck 1.001 m above          - a structure;
  //  3 deck 5 m below the DEM      - on it (below counts too);
  //  4 deck 10 m up but its first corner 0.5 m up - on it (one corner is enough);
  //  5 tunnel under 4.99 m of DEM  - open (less than the mouth height);
  //  6 tunnel under 5.01 m         - a tunnel;
  //  7 tunnel 3 m above the DEM    - open (no cover at all);
  //  8 tunnel under 10 m but its first corner under 2 m - open (one corner is enough).
  Scene sc = triangles({{{50, 50, 50}},
                        {{20.999, 20.999, 20.999}},
                        {{21.001, 21.001, 21.001}},
                        {{15, 15, 15}},
                        {{20.5, 30, 30}},
                        {{15.01, 15.01, 15.01}},
                        {{14.99, 14.99, 14.99}},
                        {{23, 23, 23}},
                        {{18, 10, 10}}},
                       {1, 0, 0, 0, 0, 0, 0, 0, 0}, {0, 0, 0, 0, 0, 1, 1, 1, 1});
  structures_on_the_ground(sc.road, dem, 5.0, sc.support);
  EXPECT_EQ(sc.support.ground, (Flags{1, 1, 0, 1, 1, 1, 0, 1, 1}));
  EXPECT_EQ(sc.support.tunnel, (Flags{0, 0, 0, 0, 0, 0, 1, 0, 0}));
  EXPECT_EQ(sc.support.counted_as_ground, (Flags{0, 1, 0, 1, 1, 2, 0, 2, 2}));
  EXPECT_EQ(sc.support.decks_on_ground, 3u);
  EXPECT_EQ(sc.support.tunnels_open, 3u);
}

TEST(GroundSupport, StructuresWithoutDemUnderThemStayStructures) {
  // Corners at x >= 120 lie beyond the DEM: no height, neither on it nor without cover.
  const DemSampler dem = flat_dem();
  Scene sc = triangles({{{20, 20, 20}}, {{20, 20, 20}}}, {0, 0}, {0, 1});
  for (Vec3& v : sc.road.vertices) v.x() += 200.0;
  structures_on_the_ground(sc.road, dem, 5.0, sc.support);
  EXPECT_EQ(sc.support.ground, (Flags{0, 0}));
  EXPECT_EQ(sc.support.tunnel, (Flags{0, 1}));
  EXPECT_EQ(sc.support.decks_on_ground + sc.support.tunnels_open, 0u);
}

TEST(GroundSupport, CoveringStructuresReturnToStructures) {
  // Triangles 1 (a deck) and 4 (a tunnel) were counted as ground, 2 was a ground road, 3 a
  // deck counted too. Overlaps with 1, 4 and 2 on top: 1 and 4 go back to a deck and a tunnel,
  // 2 (never a structure) and 3 (not on top of anything) stay ground.
  GroundSupport s;
  s.ground = {1, 1, 1, 1, 1};
  s.tunnel = {0, 0, 0, 0, 0};
  s.counted_as_ground = {0, 1, 0, 1, 2};
  s.decks_on_ground = 2;
  s.tunnels_open = 1;
  PlanOverlaps overlaps;
  overlaps.lower_upper = {{0, 1}, {3, 4}, {0, 2}, {2, 1}};  // 1 twice: counted back once
  EXPECT_TRUE(keep_covering_structures(overlaps, s));
  EXPECT_EQ(s.ground, (Flags{1, 0, 1, 1, 0}));
  EXPECT_EQ(s.tunnel, (Flags{0, 0, 0, 0, 1}));
  EXPECT_EQ(s.counted_as_ground, (Flags{0, 0, 0, 1, 0}));
  EXPECT_EQ(s.decks_on_ground, 1u);
  EXPECT_EQ(s.tunnels_open, 0u);
  // Nothing left to return.
  EXPECT_FALSE(keep_covering_structures(overlaps, s));
  EXPECT_FALSE(keep_covering_structures(PlanOverlaps{}, s));
  EXPECT_EQ(s.decks_on_ground, 1u);
}

}  // namespace
}  // namespace relief

#include "relief/scene/road_mesh.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <set>
#include <utility>

#include "relief/core/errors.h"
#include "relief/geometry/mesh_quality.h"
#include "relief/roads/opendrive_reader.h"
#include "relief/roads/road_surface.h"
#include "support/road_models.h"

namespace relief {
namespace {

using Edge = std::pair<std::uint32_t, std::uint32_t>;

std::filesystem::path golden(const std::string& name) {
  return std::filesystem::path(RELIEF_SOURCE_DIR) / "tests/pipeline/golden" / name;
}

using test::all_facing_up;
using test::straight_road;

std::map<Edge, int> edge_uses(const TriangleMesh& mesh) {
  std::map<Edge, int> uses;
  for (const auto& t : mesh.triangles) {
    for (std::size_t i = 0; i < 3; ++i) {
      const std::uint32_t a = t[i], b = t[(i + 1) % 3];
      ++uses[{std::min(a, b), std::max(a, b)}];
    }
  }
  return uses;
}

std::size_t non_manifold_edges(const TriangleMesh& mesh) {
  std::size_t count = 0;
  for (const auto& [edge, n] : edge_uses(mesh)) count += n > 2 ? 1 : 0;
  return count;
}

// Edge-connected components of the triangles (union-find over shared edges).
std::size_t components(const TriangleMesh& mesh) {
  std::vector<std::size_t> parent(mesh.triangles.size());
  std::iota(parent.begin(), parent.end(), 0);
  const auto find = [&](std::size_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  std::map<Edge, std::size_t> first;
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
    const auto& t = mesh.triangles[i];
    for (std::size_t k = 0; k < 3; ++k) {
      const Edge e{std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3])};
      const auto [it, inserted] = first.emplace(e, i);
      if (!inserted) parent[find(i)] = find(it->second);
    }
  }
  std::size_t count = 0;
  for (std::size_t i = 0; i < parent.size(); ++i) count += find(i) == i ? 1 : 0;
  return count;
}

TEST(RoadMesh, StraightRoadOnAPlaneHasElevenStationsAndExactArea) {
  RoadModel model;
  model.roads = {straight_road(7, Vec2(10.0, 20.0), 0.3, 100.0, 5.0, 0.03)};
  Diagnostics diagnostics;
  RoadMeshOptions options;
  options.markings = false;
  const RoadMeshes meshes = build_road_meshes(model, options, diagnostics);
  // 0, 10, ..., 100 m (flat and straight: max_spacing_m decides), three borders each.
  EXPECT_EQ(meshes.road.vertices.size(), 33u);
  EXPECT_EQ(meshes.road.triangles.size(), 40u);
  EXPECT_EQ(meshes.road.normals.size(), 33u);
  EXPECT_EQ(meshes.road.uvs.size(), 33u);
  EXPECT_TRUE(meshes.sidewalk.empty());
  EXPECT_EQ(meshes.road_triangle_owner, std::vector<int>(40, 7));
  // Every vertex on the plane z = 5 + 0.03 * (distance along the heading from the start).
  const Vec2 dir(std::cos(0.3), std::sin(0.3));
  for (const Vec3& v : meshes.road.vertices) {
    EXPECT_NEAR(v.z(), 5.0 + 0.03 * (v.head<2>() - Vec2(10.0, 20.0)).dot(dir), 1e-9);
  }
  EXPECT_NEAR(test::mesh_area(meshes.road), 100.0 * std::sqrt(1.0 + 0.03 * 0.03) * 6.5, 1e-9);
  EXPECT_LT(meshes.max_surface_deviation_m, 1e-9);
  EXPECT_TRUE(all_facing_up(meshes.road));
  for (const Vec3& n : meshes.road.normals) EXPECT_GT(n.z(), 0.99);
  EXPECT_EQ(diagnostics.total(), 0u);
}

TEST(RoadMesh, CurvedRoadMeetsTheToleranceAndVerticesLieOnTheSurface) {
  // 40 m of arc, radius 30 m, with a crest: the tolerance, not max_spacing_m, sets the stations.
  ModelRoad road = straight_road(3, Vec2::Zero(), 0.0, 40.0, 10.0, 0.05);
  PlanGeometry arc = test::line_record(0.0, Vec2::Zero(), 0.0, 40.0);
  arc.kind = PlanGeometry::Kind::arc;
  arc.curvature = 1.0 / 30.0;
  road.plan = PlanView({arc});
  road.elevation = CubicProfile({CubicPiece{0.0, {10.0, 0.05, -0.002, 0.0}}});
  road.superelevation = CubicProfile({CubicPiece{0.0, {0.0, 0.002, 0.0, 0.0}}});
  RoadModel model;
  model.roads = {road};
  std::size_t previous_vertices = 0;
  for (const double tolerance : {0.05, 0.01, 0.002}) {
    Diagnostics diagnostics;
    RoadMeshOptions options;
    options.tolerance_m = tolerance;
    options.markings = false;
    const RoadMeshes meshes = build_road_meshes(model, options, diagnostics);
    EXPECT_GT(meshes.max_surface_deviation_m, 0.0);
    EXPECT_LE(meshes.max_surface_deviation_m, tolerance);
    EXPECT_GT(meshes.road.vertices.size(), previous_vertices);
    previous_vertices = meshes.road.vertices.size();
    EXPECT_TRUE(all_facing_up(meshes.road));
    // uv = (t, s): each vertex is S(road, s, t), and the midpoint of each border edge (same t,
    // consecutive s) is within the tolerance of S at the mid-station.
    double vertex_deviation = 0.0, chord_deviation = 0.0;
    for (std::size_t i = 0; i < meshes.road.vertices.size(); ++i) {
      const Vec2& uv = meshes.road.uvs[i];
      vertex_deviation =
          std::max(vertex_deviation, (meshes.road.vertices[i] - surface_point(road, uv.y(), uv.x())).norm());
    }
    for (const auto& [edge, uses] : edge_uses(meshes.road)) {
      const Vec2& a = meshes.road.uvs[edge.first];
      const Vec2& b = meshes.road.uvs[edge.second];
      if (std::abs(a.x() - b.x()) > 1e-12) continue;
      const Vec3 mid = 0.5 * (meshes.road.vertices[edge.first] + meshes.road.vertices[edge.second]);
      chord_deviation =
          std::max(chord_deviation, (mid - surface_point(road, 0.5 * (a.y() + b.y()), a.x())).norm());
    }
    EXPECT_LT(vertex_deviation, 1e-9);
    EXPECT_LE(chord_deviation, tolerance);
    EXPECT_GT(chord_deviation, 0.1 * tolerance);
  }
}

TEST(RoadMesh, SectionStartsAndRecordBoundariesAreStations) {
  ModelRoad road = straight_road(1, Vec2::Zero(), 0.0, 30.0, 0.0, 0.0);
  road.plan = PlanView(
      {test::line_record(0.0, Vec2::Zero(), 0.0, 12.5), test::line_record(12.5, Vec2(12.5, 0.0), 0.0, 17.5)});
  LaneSection second = road.sections.front();
  second.s = 20.0;
  second.left = {test::constant_lane(1, 3.0), test::constant_lane(2, 2.0)};
  road.sections.push_back(second);
  RoadModel model;
  model.roads = {road};
  Diagnostics diagnostics;
  RoadMeshOptions options;
  options.markings = false;
  const RoadMeshes meshes = build_road_meshes(model, options, diagnostics);
  std::set<double> stations;
  for (const Vec2& uv : meshes.road.uvs) stations.insert(uv.y());
  // Section 0: 0, 6.25, 12.5 (record boundary), 20; section 1: 30 (at most 10 m apart).
  EXPECT_EQ(stations, (std::set<double>{0.0, 6.25, 12.5, 20.0, 30.0}));
  // At s = 20 the three common borders are shared; lane 2 adds one vertex there.
  std::size_t at_seam = 0;
  for (const Vec2& uv : meshes.road.uvs) at_seam += uv.y() == 20.0 ? 1 : 0;
  EXPECT_EQ(at_seam, 4u);
  EXPECT_NEAR(test::mesh_area(meshes.road), 30.0 * 6.5 + 10.0 * 2.0, 1e-9);
  EXPECT_EQ(non_manifold_edges(meshes.road), 0u);
  EXPECT_EQ(components(meshes.road), 1u);
}

TEST(RoadMesh, RoadsLinkedEndToEndShareTheirSeamVertices) {
  ModelRoad a = straight_road(1, Vec2::Zero(), 0.0, 50.0, 2.0, 0.02);
  ModelRoad b = straight_road(2, Vec2(50.0, 0.0), 0.0, 50.0, 3.0, 0.02);
  a.successor = RoadLink{RoadLink::Element::road, 2, RoadLink::Contact::start};
  b.predecessor = RoadLink{RoadLink::Element::road, 1, RoadLink::Contact::end};
  RoadModel model;
  model.roads = {a, b};
  Diagnostics diagnostics;
  RoadMeshOptions options;
  options.markings = false;
  const RoadMeshes meshes = build_road_meshes(model, options, diagnostics);
  EXPECT_EQ(meshes.road.vertices.size(), 2u * 18u - 3u);
  EXPECT_EQ(components(meshes.road), 1u);
  EXPECT_EQ(boundary_loops(meshes.road).size(), 1u);
  EXPECT_EQ(diagnostics.count("mesh.weld_unmatched"), 0u);
}

TEST(RoadMesh, GoldenBridgeRoadsAreWeldedIntoOneSurface) {
  const RoadModel model = read_opendrive(golden("bridge.xodr"));
  Diagnostics diagnostics;
  const RoadMeshes meshes = build_road_meshes(model, {}, diagnostics);
  EXPECT_EQ(components(meshes.road), 1u);
  EXPECT_EQ(boundary_loops(meshes.road).size(), 1u);
  EXPECT_EQ(non_manifold_edges(meshes.road), 0u);
  EXPECT_LE(meshes.max_surface_deviation_m, 0.02);
  EXPECT_EQ(diagnostics.count("mesh.weld_unmatched"), 0u);
  EXPECT_FALSE(meshes.marking.empty());
}

TEST(RoadMesh, MarksOfLinkedRoadsContinueOnSharedVertices) {
  // Road b starts 0.5 mm before a ends (a link within the weld tolerance): unwelded, the two
  // roads' mark strips would overlap there by 0.5 mm.
  ModelRoad a = straight_road(1, Vec2::Zero(), 0.0, 50.0, 2.0, 0.02);
  ModelRoad b = straight_road(2, Vec2(50.0 - 5e-4, 0.0), 0.0, 50.0, 3.0 - 1e-5, 0.02);
  for (ModelRoad* r : {&a, &b}) {
    r->sections[0].left[0].mark.type = RoadMark::Type::solid;
    r->sections[0].right[0].mark.type = RoadMark::Type::solid;
  }
  a.successor = RoadLink{RoadLink::Element::road, 2, RoadLink::Contact::start};
  b.predecessor = RoadLink{RoadLink::Element::road, 1, RoadLink::Contact::end};
  RoadModel model;
  model.roads = {a, b};
  Diagnostics diagnostics;
  const RoadMeshes meshes = build_road_meshes(model, {}, diagnostics);
  const MeshQuality marks = analyse_mesh(meshes.marking);
  EXPECT_EQ(marks.components, 2u);  // one strip per border, over both roads
  EXPECT_EQ(marks.self_intersecting_pairs, 0u);
  EXPECT_EQ(marks.non_manifold_edges, 0u);
}

TEST(RoadMesh, BridgeOverARoadDoesNotIntersectIt) {
  // Road 1 along x at z = 0, road 2 along y over it at z = 6: two separate surfaces.
  RoadModel model;
  model.roads = {straight_road(1, Vec2(-50.0, 0.0), 0.0, 100.0, 0.0, 0.0),
                 straight_road(2, Vec2(0.0, -50.0), std::numbers::pi / 2.0, 100.0, 6.0, 0.0)};
  Diagnostics diagnostics;
  const RoadMeshes meshes = build_road_meshes(model, {}, diagnostics);
  EXPECT_EQ(components(meshes.road), 2u);
  const MeshQuality quality = analyse_mesh(meshes.road);
  EXPECT_EQ(quality.self_intersecting_pairs, 0u);
  EXPECT_EQ(quality.non_manifold_edges, 0u);
  // The same with road 2 at z = 0 does intersect (the check can fail).
  model.roads[1].elevation = CubicProfile::constant(0.0);
  const RoadMeshes flat = build_road_meshes(model, {}, diagnostics);
  EXPECT_GT(analyse_mesh(flat.road).self_intersecting_pairs, 0u);
}

TEST(RoadMesh, GoldenTJunctionIsOneWeldedSurface) {
  const RoadModel model = read_opendrive(golden("t_junction_slope.xodr"));
  Diagnostics diagnostics;
  const RoadMeshes meshes = build_road_meshes(model, {}, diagnostics);
  EXPECT_EQ(meshes.junctions_meshed, 1u);
  EXPECT_EQ(meshes.junctions_failed, 0u);
  EXPECT_EQ(diagnostics.count("mesh.junction_failed"), 0u);
  EXPECT_EQ(components(meshes.road), 1u);
  EXPECT_EQ(non_manifold_edges(meshes.road), 0u);
  EXPECT_TRUE(all_facing_up(meshes.road));
  const MeshQuality quality = analyse_mesh(meshes.road);
  EXPECT_EQ(quality.self_intersecting_pairs, 0u);
  EXPECT_EQ(quality.holes, 0u);

  // Junction triangles: their vertices are road-end vertices or kerb points, and each road end
  // edge is shared by one road and one junction triangle (no boundary edge across a road end).
  ASSERT_EQ(meshes.road_triangle_owner.size(), meshes.road.triangles.size());
  std::set<std::uint32_t> road_vertices;
  double junction_area = 0.0;
  std::map<Edge, std::pair<int, int>> owners;  // edge -> (road triangles, junction triangles)
  for (std::size_t i = 0; i < meshes.road.triangles.size(); ++i) {
    const auto& t = meshes.road.triangles[i];
    const bool junction = meshes.road_triangle_owner[i] < 0;
    if (junction) {
      EXPECT_EQ(meshes.road_triangle_owner[i], -1 - 1);
      const Vec3& a = meshes.road.vertices[t[0]];
      junction_area += 0.5 * (meshes.road.vertices[t[1]] - a).cross(meshes.road.vertices[t[2]] - a).norm();
    } else {
      road_vertices.insert(t.begin(), t.end());
    }
    for (std::size_t k = 0; k < 3; ++k) {
      const Edge e{std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3])};
      (junction ? owners[e].second : owners[e].first) += 1;
    }
  }
  std::size_t seam_edges = 0;
  for (const auto& [edge, count] : owners) {
    if (count.first > 0 && count.second > 0) {
      EXPECT_EQ(count, std::make_pair(1, 1));
      ++seam_edges;
    }
  }
  // Three road ends of two lanes each.
  EXPECT_EQ(seam_edges, 6u);
  // 10.5 m between the ends of roads 1 and 2, 6.5 m wide, plus the half-bay towards road 3
  // bounded by two kerb arcs: between the 10.5 x 8.5 rectangle less the corners and it.
  EXPECT_GT(junction_area, 10.5 * 6.5);
  EXPECT_LT(junction_area, 10.5 * 8.5);
  // Heights: the junction's vertices are the roads' (no new vertex on a road end).
  for (std::size_t i = 0; i < meshes.road.triangles.size(); ++i) {
    if (meshes.road_triangle_owner[i] >= 0) continue;
    for (const std::uint32_t v : meshes.road.triangles[i]) {
      const Vec3& p = meshes.road.vertices[v];
      if (road_vertices.count(v) == 0) {
        // A kerb point: on the turn, between the three road ends' heights.
        EXPECT_GT(p.z(), 19.0);
        EXPECT_LT(p.z(), 20.6);
      }
    }
  }
}

TEST(RoadMesh, GoldenFourWayAndOnewayPairJunctionsAreMeshed) {
  for (const std::string name : {"four_way.xodr", "oneway_pair.xodr"}) {
    SCOPED_TRACE(name);
    const RoadModel model = read_opendrive(golden(name));
    Diagnostics diagnostics;
    const RoadMeshes meshes = build_road_meshes(model, {}, diagnostics);
    EXPECT_EQ(meshes.junctions_meshed, model.junctions.size());
    EXPECT_EQ(meshes.junctions_failed, 0u);
    EXPECT_EQ(components(meshes.road), 1u);
    EXPECT_EQ(non_manifold_edges(meshes.road), 0u);
    EXPECT_TRUE(all_facing_up(meshes.road));
    EXPECT_EQ(analyse_mesh(meshes.road).self_intersecting_pairs, 0u);
    EXPECT_LE(meshes.max_surface_deviation_m, 0.02);
  }
}

TEST(RoadMesh, JunctionWithCrossingRoadEndsIsReportedAndLeftOpen) {
  // Two roads ending at the same junction with end cross-sections that cross (an X).
  ModelRoad a = straight_road(1, Vec2(-40.0, -40.0), std::numbers::pi / 4.0, 40.0 * std::sqrt(2.0), 0.0, 0.0);
  ModelRoad b = straight_road(2, Vec2(-40.0, 40.0), -std::numbers::pi / 4.0, 40.0 * std::sqrt(2.0), 0.0, 0.0);
  a.successor = RoadLink{RoadLink::Element::junction, 9, RoadLink::Contact::start};
  b.successor = RoadLink{RoadLink::Element::junction, 9, RoadLink::Contact::start};
  RoadModel model;
  model.roads = {a, b};
  JunctionModel junction;
  junction.id = 9;
  model.junctions = {junction};
  Diagnostics diagnostics;
  const RoadMeshes meshes = build_road_meshes(model, {}, diagnostics);
  EXPECT_EQ(meshes.junctions_meshed, 0u);
  EXPECT_EQ(meshes.junctions_failed, 1u);
  EXPECT_EQ(diagnostics.count("mesh.junction_failed"), 1u);
  for (const int owner : meshes.road_triangle_owner) EXPECT_GE(owner, 0);
}

TEST(RoadMesh, MarkingsAreStripsOnTheirBorders) {
  ModelRoad road = straight_road(1, Vec2::Zero(), 0.0, 100.0, 4.0, 0.0);
  road.sections[0].centre_mark.type = RoadMark::Type::broken;
  road.sections[0].right[0].mark.type = RoadMark::Type::solid;
  road.sections[0].left[0].mark.type = RoadMark::Type::solid_solid;
  RoadModel model;
  model.roads = {road};
  Diagnostics diagnostics;
  RoadMeshOptions options;
  options.marking_lift_m = 0.01;
  const RoadMeshes meshes = build_road_meshes(model, options, diagnostics);
  // Solid: 100 m x 0.12 m; double solid: twice that; broken: 3 m every 9 m from s = 0, the
  // last dash (s = 99) cut to 1 m.
  EXPECT_NEAR(test::mesh_area(meshes.marking), 3.0 * 100.0 * 0.12 + (11.0 * 3.0 + 1.0) * 0.12, 1e-9);
  for (const Vec3& v : meshes.marking.vertices) {
    EXPECT_NEAR(v.z(), 4.01, 1e-12);
    const double y = v.y();
    const bool near_border = std::abs(y) < 0.07 || std::abs(y + 3.5) < 0.07 || std::abs(y - 3.12) < 0.07 ||
                             std::abs(y - 2.88) < 0.07;
    EXPECT_TRUE(near_border) << y;
  }
  EXPECT_TRUE(all_facing_up(meshes.marking));
  options.markings = false;
  EXPECT_TRUE(build_road_meshes(model, options, diagnostics).marking.empty());
}

TEST(RoadMesh, SidewalkLanesGoToTheSidewalkMesh) {
  ModelRoad road = straight_road(1, Vec2::Zero(), 0.0, 20.0, 0.0, 0.0);
  LaneModel walk = test::constant_lane(-2, 2.0);
  walk.type = "sidewalk";
  road.sections[0].right.push_back(walk);
  RoadModel model;
  model.roads = {road};
  Diagnostics diagnostics;
  const RoadMeshes meshes = build_road_meshes(model, {}, diagnostics);
  EXPECT_NEAR(test::mesh_area(meshes.road), 20.0 * 6.5, 1e-9);
  EXPECT_NEAR(test::mesh_area(meshes.sidewalk), 20.0 * 2.0, 1e-9);
  EXPECT_EQ(meshes.sidewalk.vertices.size(), 6u);
}

TEST(RoadMesh, OptionsOutOfRangeThrow) {
  const RoadModel model;
  Diagnostics diagnostics;
  RoadMeshOptions options;
  options.tolerance_m = 0.0;
  EXPECT_THROW((void)build_road_meshes(model, options, diagnostics), InvalidInput);
  options = {};
  options.max_spacing_m = -1.0;
  EXPECT_THROW((void)build_road_meshes(model, options, diagnostics), InvalidInput);
  options = {};
  options.marking_lift_m = std::nan("");
  EXPECT_THROW((void)build_road_meshes(model, options, diagnostics), InvalidInput);
}

}  // namespace
}  // namespace relief

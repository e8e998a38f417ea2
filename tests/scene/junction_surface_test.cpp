#include "scene/junction_surface.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <numbers>

#include "relief/roads/road_surface.h"
#include "support/road_models.h"

namespace relief::detail {
namespace {

using test::all_facing_up;
using test::mesh_area;

// An end whose vertices are new mesh vertices at `points` (right corner to left corner).
JunctionEnd add_end(MeshBuilder& mesh, int road_index, const std::vector<Vec3>& points) {
  JunctionEnd end;
  end.road_index = road_index;
  end.at_start = true;
  for (const Vec3& p : points) end.vertices.push_back(mesh.add_vertex(p, p.head<2>()));
  return end;
}

// Four roads 6 m wide start 5 m from the centre, east, north, west and south (road k heading
// k x 90 degrees), level at 2 m.
RoadModel four_roads() {
  RoadModel model;
  for (int k = 0; k < 4; ++k) {
    const double heading = k * std::numbers::pi / 2.0;
    const Vec2 dir(std::cos(heading), std::sin(heading));
    model.roads.push_back(test::straight_road(k + 1, 5.0 * dir, heading, 50.0, 2.0, 0.0));
  }
  return model;
}

// The end of four_roads' road k, its vertices new in `mesh`: looking out along the road, its
// right is the road's own right, t = -3, 0, +3.
JunctionEnd four_roads_end(MeshBuilder& mesh, int k) {
  const double heading = k * std::numbers::pi / 2.0;
  const Vec2 dir(std::cos(heading), std::sin(heading));
  const Vec2 left(-dir.y(), dir.x());
  std::vector<Vec3> points;
  for (const double t : {-3.0, 0.0, 3.0}) {
    const Vec2 xy = 5.0 * dir + t * left;
    points.emplace_back(xy.x(), xy.y(), 2.0);
  }
  return add_end(mesh, k, points);
}

// Four roads 6 m wide (3 m each side of the reference line) start 5 m from the centre, east,
// north, west and south: the outline is the 10 m square less four corner triangles of legs 2 m,
// 92 m2, with the ends given in any order. Its 12 end vertices, a point on the height surface
// in the middle of each 2.83 m corner side, and the surface's 2 m grid inside (x, y in -3, -1,
// 1, 3: 16 points) make 32 vertices, all at the roads' height 2 m, and 16 - 2 + 2 x 16 = 46
// triangles.
TEST(JunctionSurface, CrossingOfFourRoadEndsIsItsOctagon) {
  const RoadModel model = four_roads();
  MeshBuilder mesh;
  std::vector<JunctionEnd> ends;
  for (const int k : {2, 0, 3, 1}) ends.push_back(four_roads_end(mesh, k));
  JunctionModel junction;
  junction.id = 7;
  const std::string failed = build_junction_surface(model, junction, ends, {}, {}, mesh).problem;
  EXPECT_EQ(failed, "");
  EXPECT_EQ(mesh.mesh.vertices.size(), 32u);
  for (const Vec3& v : mesh.mesh.vertices) EXPECT_NEAR(v.z(), 2.0, 1e-12);
  EXPECT_EQ(mesh.mesh.triangles.size(), 46u);
  EXPECT_NEAR(mesh_area(mesh.mesh), 100.0 - 4.0 * 2.0, 1e-9);
  EXPECT_EQ(mesh.owner, std::vector<int>(46, -8));
  EXPECT_TRUE(all_facing_up(mesh.mesh));
}

// The octagon's crossing with a fifth road end lying on the east road (bad data: a way's end drawn
// onto another road's pavement; footways along a main road whose ends still overlap it after
// trimming). Across the east end's edge, (4.5, -2) to (6, 2), crossing it at (5, -0.67), no
// outline joining all five ends is simple in any order, and the junction was left open; 2 m
// behind that edge and facing the same way, an outline reaching round to it paved over the east
// road. Now the junction is the octagon of the other four (92 m2, as without the fifth), that end
// is named as left out, none of its vertices is in a triangle and nothing lies past x = 5.
TEST(JunctionSurface, AnEndLyingAcrossOrOnAnotherEndsRoadIsLeftOut) {
  struct Fifth {
    Vec2 start;
    double heading;
    Vec3 right, left;
  };
  for (const Fifth& f :
       {Fifth{Vec2(5.25, 0.0), std::atan2(-1.5, 4.0), Vec3(4.5, -2.0, 2.0), Vec3(6.0, 2.0, 2.0)},
        Fifth{Vec2(7.0, 1.5), 0.0, Vec3(7.0, 0.5, 2.0), Vec3(7.0, 2.5, 2.0)}}) {
    SCOPED_TRACE("fifth end at " + std::to_string(f.start.x()));
    RoadModel model = four_roads();
    model.roads.push_back(test::straight_road(5, f.start, f.heading, 50.0, 2.0, 0.0));
    MeshBuilder mesh;
    std::vector<JunctionEnd> ends;
    ends.reserve(5);
    for (int k = 0; k < 4; ++k) ends.push_back(four_roads_end(mesh, k));
    ends.push_back(add_end(mesh, 4, {f.right, f.left}));
    JunctionModel junction;
    junction.id = 7;
    const JunctionSurfaceResult built = build_junction_surface(model, junction, ends, {}, {}, mesh);
    EXPECT_EQ(built.problem, "");
    EXPECT_EQ(built.left_out, (std::vector<std::pair<int, bool>>{{4, true}}));
    EXPECT_NEAR(mesh_area(mesh.mesh), 100.0 - 4.0 * 2.0, 1e-9);
    EXPECT_TRUE(all_facing_up(mesh.mesh));
    for (const auto& t : mesh.mesh.triangles) {
      for (const std::uint32_t v : t) {
        EXPECT_TRUE(v < 12 || v > 13) << "vertex " << v << " of the fifth end";
        EXPECT_LE(mesh.mesh.vertices[v].x(), 5.0 + 1e-9) << "over the east road";
      }
    }
  }

  // The first five ends as one outline, in the junction's order and with straight sides: CGAL
  // finds the crossing.
  MeshBuilder mesh;
  std::vector<JunctionEnd> ends;
  ends.reserve(5);
  for (int k = 0; k < 4; ++k) ends.push_back(four_roads_end(mesh, k));
  ends.push_back(add_end(mesh, 4, {Vec3(4.5, -2.0, 2.0), Vec3(6.0, 2.0, 2.0)}));
  const std::vector<JunctionEnd> sorted{ends[0], ends[4], ends[1], ends[2], ends[3]};
  EXPECT_NE(triangulate_junction(sorted, std::vector<OutlineGap>(5), 7, mesh).find("not simple"),
            std::string::npos);
}

// Four roads 6 m wide starting 5 m from the centre, east, north, west and south, at 2 m: the
// east and west ones climb 12 % away from it, the north and south ones are level.
RoadModel crossing_in_a_valley() {
  RoadModel model;
  for (int k = 0; k < 4; ++k) {
    const double heading = k * std::numbers::pi / 2.0;
    const Vec2 dir(std::cos(heading), std::sin(heading));
    model.roads.push_back(test::straight_road(k + 1, 5.0 * dir, heading, 50.0, 2.0, k % 2 == 0 ? 0.12 : 0.0));
  }
  return model;
}

// The same crossing in a valley: the east and west roads climb 12 % away from it, the north and
// south ones are level. The junction's height surface (relief/roads/junction_height.h) sags
// between the ends, so a plane through the corners is not it: every vertex the patch adds (on
// the straight corner sides and inside) lies on the surface, and the middle of a corner side
// lies 0.044 m below its chord, as connecting roads there do.
TEST(JunctionSurface, ThePatchBetweenTheEndsFollowsTheJunctionsHeightSurface) {
  const RoadModel model = crossing_in_a_valley();
  MeshBuilder mesh;
  std::vector<JunctionEnd> ends;
  std::vector<EndPlane> planes;
  for (int k = 0; k < 4; ++k) {
    const ModelRoad& road = model.roads[static_cast<std::size_t>(k)];
    std::vector<Vec3> points;
    for (const double t : {-3.0, 0.0, 3.0}) points.push_back(surface_point(road, 0.0, t));
    ends.push_back(add_end(mesh, k, points));
    planes.push_back(end_plane(road, true));
  }
  const JunctionHeight surface(planes);
  JunctionModel junction;
  junction.id = 7;
  ASSERT_EQ(build_junction_surface(model, junction, ends, {}, {}, mesh).problem, "");
  ASSERT_EQ(mesh.mesh.vertices.size(), 32u);
  for (std::size_t v = 12; v < mesh.mesh.vertices.size(); ++v) {
    const Vec3& p = mesh.mesh.vertices[v];
    EXPECT_NEAR(p.z(), surface.at(p.head<2>()).first, 1e-9) << p.transpose();
  }
  // The side from the east end's left corner (5, 3) to the north end's right corner (3, 5).
  const auto side_middle =
      std::find_if(mesh.mesh.vertices.begin(), mesh.mesh.vertices.end(),
                   [](const Vec3& p) { return (p.head<2>() - Vec2(4.0, 4.0)).norm() < 1e-9; });
  ASSERT_NE(side_middle, mesh.mesh.vertices.end());
  const double chord =
      0.5 * (surface_point(model.roads[0], 0.0, 3.0).z() + surface_point(model.roads[1], 0.0, -3.0).z());
  EXPECT_LT(side_middle->z(), chord - 0.03);  // 0.044 m below
  EXPECT_TRUE(all_facing_up(mesh.mesh));
}

// The surface grid beside a lane point 0.6 m over the surface (a connecting road that left it):
// no grid point within 1 m of it, those within 4 m raised by a share of 0.6 m that falls with
// their distance, those farther on the surface; a lane point on the surface moves nothing.
TEST(JunctionSurface, TheGridTakesTheDepartureOfALaneThatLeftTheSurface) {
  const RoadModel model = crossing_in_a_valley();
  std::vector<EndPlane> planes;
  for (const ModelRoad& road : model.roads) planes.push_back(end_plane(road, true));
  const JunctionHeight surface(planes);
  const std::vector<Vec2> outline{{-10.0, -10.0}, {10.0, -10.0}, {10.0, 10.0}, {-10.0, 10.0}};
  const Vec2 lane(0.5, 0.5);
  const double raised = surface.at(lane).first + 0.6;
  const std::vector<Vec3> on_surface =
      surface_grid(outline, {Vec3(lane.x(), lane.y(), raised - 0.6)}, surface);
  const std::vector<Vec3> beside = surface_grid(outline, {Vec3(lane.x(), lane.y(), raised)}, surface);
  ASSERT_EQ(on_surface.size(), beside.size());
  ASSERT_EQ(beside.size(), 11u * 11u - 1u);  // every 2 m from -10 to 10, less the one at (0, 0)
  int raised_points = 0;
  double previous_share = 1.0;
  std::vector<std::pair<double, double>> by_distance;
  for (std::size_t k = 0; k < beside.size(); ++k) {
    const Vec2 p = beside[k].head<2>();
    const double d = (p - lane).norm();
    EXPECT_NEAR(on_surface[k].z(), surface.at(p).first, 1e-12) << p.transpose();
    const double share = (beside[k].z() - surface.at(p).first) / 0.6;
    if (d >= 4.0) {
      EXPECT_NEAR(share, 0.0, 1e-12) << p.transpose();
    } else {
      EXPECT_GT(share, 0.0) << p.transpose();
      EXPECT_LT(share, 1.0) << p.transpose();
      by_distance.emplace_back(d, share);
      ++raised_points;
    }
  }
  std::sort(by_distance.begin(), by_distance.end());
  for (const auto& [d, share] : by_distance) {
    EXPECT_LE(share, previous_share + 1e-12) << d;
    previous_share = share;
  }
  // Within 4 m of (0.5, 0.5): (+-2, 0), (0, +-2), (+-2, +-2), (4, 0), (0, 4), (4, 2), (2, 4).
  EXPECT_EQ(raised_points, 12);
  EXPECT_GT(by_distance.front().second, 0.4);  // 1.58 m away
}

// The L-shaped outline with interior points: one in the middle of the arm at (7, 2) 0.5 m
// above the outline's heights is a vertex of the surface (its height kept); one 0.2 m from the
// outline, one in the notch and one outside are not.
TEST(JunctionSurface, InteriorPointsInsideTheOutlineAreVerticesOfTheSurface) {
  MeshBuilder mesh;
  const std::vector<JunctionEnd> ends{add_end(mesh, 0, {Vec3(0.0, 0.0, 1.0), Vec3(10.0, 0.0, 1.0)}),
                                      add_end(mesh, 1, {Vec3(4.0, 10.0, 1.0), Vec3(0.0, 10.0, 1.0)})};
  const std::vector<OutlineGap> gaps{{{Vec3(10.0, 4.0, 1.0), Vec3(4.0, 4.0, 1.0)}, {}}, {}};
  const std::vector<Vec3> interior{Vec3(7.0, 2.0, 1.5), Vec3(9.8, 2.0, 1.0), Vec3(7.0, 7.0, 1.0),
                                   Vec3(20.0, 2.0, 1.0)};
  EXPECT_EQ(triangulate_junction(ends, gaps, 3, mesh, interior), "");
  ASSERT_EQ(mesh.mesh.vertices.size(), 7u);
  EXPECT_EQ(mesh.mesh.vertices[6], Vec3(7.0, 2.0, 1.5));
  EXPECT_EQ(mesh.mesh.triangles.size(), 6u);  // 4 + 2 for the interior vertex
  double plan_area = 0.0;
  for (const auto& t : mesh.mesh.triangles) {
    const Vec3 &a = mesh.mesh.vertices[t[0]], &b = mesh.mesh.vertices[t[1]], &c = mesh.mesh.vertices[t[2]];
    plan_area += 0.5 * ((b.x() - a.x()) * (c.y() - a.y()) - (c.x() - a.x()) * (b.y() - a.y()));
  }
  EXPECT_NEAR(plan_area, 64.0, 1e-9);
  EXPECT_TRUE(all_facing_up(mesh.mesh));
}

// Interior points of two crossing connecting roads, one lane each way: every 2 m along each
// lane centre but for the first and last metre, and where the two roads' lanes come within 1 m
// of each other, one point at their mean height.
TEST(JunctionSurface, InteriorPointsFollowTheConnectingRoadsLanesAndMergeWhereTheyCross) {
  RoadModel model;
  // Road 0 along x from (-10, 0) at z 1, road 1 along y from (0, -10) at z 2, 20 m each, level.
  model.roads.push_back(test::straight_road(1, Vec2(-10.0, 0.0), 0.0, 20.0, 1.0, 0.0));
  model.roads.push_back(test::straight_road(2, Vec2(0.0, -10.0), std::numbers::pi / 2.0, 20.0, 2.0, 0.0));
  const std::vector<Vec3> points = junction_interior(model, {0, 1});
  ASSERT_FALSE(points.empty());
  // Lane centres (the helper's lanes: 3 m on the left, 3.5 m on the right): road 0's at y = 1.5
  // and -1.75, road 1's at x = -1.5 and 1.75; they cross at four points.
  std::size_t merged = 0;
  for (const Vec3& p : points) {
    const bool lane_x = std::abs(p.y() - 1.5) < 1e-9 || std::abs(p.y() + 1.75) < 1e-9;
    const bool lane_y = std::abs(p.x() + 1.5) < 1e-9 || std::abs(p.x() - 1.75) < 1e-9;
    if (lane_x) {
      EXPECT_DOUBLE_EQ(p.z(), 1.0) << p.transpose();
    }
    if (lane_y) {
      EXPECT_DOUBLE_EQ(p.z(), 2.0) << p.transpose();
    }
    if (!lane_x && !lane_y) {
      // A merged point: its mean height, near a crossing.
      ++merged;
      EXPECT_GT(p.z(), 1.0);
      EXPECT_LT(p.z(), 2.0);
      EXPECT_LT(std::min(std::abs(p.x() + 1.5), std::abs(p.x() - 1.75)), 1.0) << p.transpose();
      EXPECT_LT(std::min(std::abs(p.y() - 1.5), std::abs(p.y() + 1.75)), 1.0) << p.transpose();
    }
    EXPECT_LE(std::abs(p.x()), 9.0 + 1e-9);
    EXPECT_LE(std::abs(p.y()), 9.0 + 1e-9);
  }
  EXPECT_GE(merged, 3u);
  EXPECT_EQ(points.size() + merged, 40u);  // 2 roads x 2 lanes x 10 stations, one less per merge
}

TEST(JunctionSurface, EndsWithoutAnEdgeAreNoSurface) {
  MeshBuilder mesh;
  const std::vector<JunctionEnd> ends{add_end(mesh, 0, {Vec3(0.0, 0.0, 0.0)})};
  EXPECT_EQ(build_junction_surface(RoadModel{}, JunctionModel{}, ends, {}, {}, mesh).problem, "no road ends");
  EXPECT_TRUE(mesh.mesh.triangles.empty());
}

// An L-shaped outline: two ends and a kerb of two points around the inner corner. The notch
// (inside the convex hull, outside the outline) stays open: 6 vertices, 4 triangles, 64 m2.
TEST(JunctionSurface, ConcaveOutlineWithKerbPointsLeavesItsNotchOpen) {
  MeshBuilder mesh;
  const std::vector<JunctionEnd> ends{add_end(mesh, 0, {Vec3(0.0, 0.0, 1.0), Vec3(10.0, 0.0, 1.0)}),
                                      add_end(mesh, 1, {Vec3(4.0, 10.0, 1.0), Vec3(0.0, 10.0, 1.0)})};
  const std::vector<OutlineGap> gaps{{{Vec3(10.0, 4.0, 1.5), Vec3(4.0, 4.0, 1.5)}, {}}, {}};
  EXPECT_EQ(triangulate_junction(ends, gaps, 3, mesh), "");
  ASSERT_EQ(mesh.mesh.vertices.size(), 6u);  // the kerb points were added, uv = (x, y)
  EXPECT_EQ(mesh.mesh.vertices[4], Vec3(10.0, 4.0, 1.5));
  EXPECT_EQ(mesh.mesh.uvs[5], Vec2(4.0, 4.0));
  EXPECT_EQ(mesh.mesh.triangles.size(), 4u);
  EXPECT_EQ(mesh.owner, std::vector<int>(4, -4));
  EXPECT_TRUE(all_facing_up(mesh.mesh));
  double plan_area = 0.0;
  for (const auto& t : mesh.mesh.triangles) {
    const auto& v = mesh.mesh.vertices;
    const Vec2 a = (v[t[1]] - v[t[0]]).head<2>(), b = (v[t[2]] - v[t[0]]).head<2>();
    plan_area += 0.5 * (a.x() * b.y() - a.y() * b.x());
  }
  EXPECT_NEAR(plan_area, 100.0 - 36.0, 1e-9);
  // No triangle in the notch x > 4, y > 4.
  for (const auto& t : mesh.mesh.triangles) {
    const Vec3 c = (mesh.mesh.vertices[t[0]] + mesh.mesh.vertices[t[1]] + mesh.mesh.vertices[t[2]]) / 3.0;
    EXPECT_FALSE(c.x() > 4.0 && c.y() > 4.0) << c.transpose();
  }
}

// A junction 50 m long whose south side runs from road a's left corner (0, 0) to road b's right
// corner (50, 0), with road a leaving along that side at a few degrees (Portland's J3789 beside
// US 26): a's left edge bows 0.4 m into the junction over 30 m, then turns away. The side
// follows that edge through the road mesh's own vertices, so the patch ends at the pavement's
// edge instead of lying over it; b's edge leaves at once and adds nothing.
TEST(JunctionSurface, AStraightSideFollowsTheEdgeOfARoadRunningAlongIt) {
  MeshBuilder mesh;
  JunctionEnd a = add_end(mesh, 0, {Vec3(0.0, -3.0, 1.0), Vec3(0.0, 0.0, 1.0)});
  JunctionEnd b = add_end(mesh, 1, {Vec3(50.0, 0.0, 1.0), Vec3(50.0, 8.0, 1.0)});
  const JunctionEnd c = add_end(mesh, 2, {Vec3(40.0, 12.0, 1.0), Vec3(-5.0, 12.0, 1.0)});
  a.left_edge = {a.vertices.back()};
  for (const Vec2& xy :
       {Vec2(10.0, 0.3), Vec2(20.0, 0.4), Vec2(30.0, 0.2), Vec2(40.0, -0.5), Vec2(45.0, -2.0),
        Vec2(35.0, 0.5)})  // the last one after the edge has turned away: not taken
    a.left_edge.push_back(mesh.add_vertex(Vec3(xy.x(), xy.y(), 1.1), xy));
  b.right_edge = {b.vertices.front(), mesh.add_vertex(Vec3(60.0, -1.0, 1.0), Vec2(60.0, -1.0))};
  const OutlineGap side = along_road_edges(a, b, mesh.mesh.vertices);
  ASSERT_EQ(side.vertices.size(), 3u);
  EXPECT_EQ(side.vertices, std::vector<std::uint32_t>(a.left_edge.begin() + 1, a.left_edge.begin() + 4));
  EXPECT_EQ(side.points.size(), 3u);
  EXPECT_EQ(side.points[1], Vec3(20.0, 0.4, 1.1));
  // The other way round (c's left corner to a's right corner) no edge comes inside.
  EXPECT_TRUE(along_road_edges(c, a, mesh.mesh.vertices).points.empty());

  const std::size_t before = mesh.mesh.vertices.size();
  EXPECT_EQ(triangulate_junction({a, b, c}, {side, {}, {}}, 0, mesh), "");
  EXPECT_EQ(mesh.mesh.vertices.size(), before);  // the edge's vertices are shared, none added
  // Shoelace area of (0,-3) (0,0) (10,.3) (20,.4) (30,.2) (50,0) (50,8) (40,12) (-5,12).
  const std::vector<Vec2> ring{{0, -3}, {0, 0},  {10, 0.3}, {20, 0.4}, {30, 0.2},
                               {50, 0}, {50, 8}, {40, 12},  {-5, 12}};
  double twice = 0.0;
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const Vec2& p = ring[i];
    const Vec2& q = ring[(i + 1) % ring.size()];
    twice += p.x() * q.y() - q.x() * p.y();
  }
  double plan_area = 0.0;
  for (const auto& t : mesh.mesh.triangles) {
    const auto& v = mesh.mesh.vertices;
    const Vec2 u = (v[t[1]] - v[t[0]]).head<2>(), w = (v[t[2]] - v[t[0]]).head<2>();
    plan_area += 0.5 * (u.x() * w.y() - u.y() * w.x());
    // No patch triangle reaches below the road's edge between x = 0 and 30.
    const Vec3 centre = (v[t[0]] + v[t[1]] + v[t[2]]) / 3.0;
    if (centre.x() > 0.0 && centre.x() < 30.0) {
      EXPECT_GT(centre.y(), 0.2) << centre.transpose();
    }
  }
  EXPECT_NEAR(plan_area, 0.5 * twice, 1e-9);
}

// Outlines that cannot be a surface are reported, and nothing is added to the mesh.
TEST(JunctionSurface, BadOutlinesAreReportedAndAddNothing) {
  MeshBuilder mesh;
  const JunctionEnd bottom = add_end(mesh, 0, {Vec3(0.0, 0.0, 0.0), Vec3(10.0, 0.0, 0.0)});
  const JunctionEnd top = add_end(mesh, 1, {Vec3(10.0, 10.0, 0.0), Vec3(0.0, 10.0, 0.0)});
  const JunctionEnd crossed = add_end(mesh, 1, {Vec3(0.0, 10.0, 0.0), Vec3(10.0, 10.0, 0.0)});
  const std::size_t vertices = mesh.mesh.vertices.size();
  const auto expect_failure = [&](const std::vector<JunctionEnd>& ends, const std::vector<OutlineGap>& gaps,
                                  const std::string& reason) {
    const std::string failed = triangulate_junction(ends, gaps, 0, mesh);
    EXPECT_NE(failed.find(reason), std::string::npos) << failed;
    EXPECT_TRUE(mesh.mesh.triangles.empty());
    EXPECT_EQ(mesh.mesh.vertices.size(), vertices);
  };
  expect_failure({bottom, top, bottom}, {}, "passes twice");
  expect_failure({bottom}, {}, "fewer than three");
  // The square walked clockwise.
  JunctionEnd reversed_bottom = bottom;
  JunctionEnd reversed_top = top;
  std::reverse(reversed_bottom.vertices.begin(), reversed_bottom.vertices.end());
  std::reverse(reversed_top.vertices.begin(), reversed_top.vertices.end());
  expect_failure({reversed_top, reversed_bottom}, {}, "not counter-clockwise");
  // A bow tie with a kerb point that keeps its signed area positive: its edges cross.
  expect_failure({bottom, crossed}, {{{Vec3(20.0, 5.0, 0.0)}, {}}, {}}, "not simple");
  // The square itself is fine: 2 triangles of 100 m2 together.
  EXPECT_EQ(triangulate_junction({bottom, top}, {}, 0, mesh), "");
  EXPECT_NEAR(mesh_area(mesh.mesh), 100.0, 1e-9);
}

}  // namespace
}  // namespace relief::detail

#include "scene/lane_loft.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <iterator>
#include <set>
#include <utility>

#include "relief/core/errors.h"
#include "support/plan_records.h"
#include "support/road_models.h"

namespace relief::detail {
namespace {

using test::constant_lane;
using test::mesh_area;
using test::straight_road;

RoadMeshOptions no_markings() {
  RoadMeshOptions options;
  options.markings = false;
  return options;
}

std::vector<Vec3> positions(const TriangleMesh& mesh, const std::vector<std::uint32_t>& indices) {
  std::vector<Vec3> out;
  for (const std::uint32_t i : indices) out.push_back(mesh.vertices[i]);
  return out;
}

void expect_points(const std::vector<Vec3>& actual, const std::vector<Vec3>& expected, double tolerance) {
  ASSERT_EQ(actual.size(), expected.size());
  for (std::size_t i = 0; i < actual.size(); ++i) {
    EXPECT_LT((actual[i] - expected[i]).norm(), tolerance) << i << ": " << actual[i].transpose();
  }
}

// 100 m east at z = 5 with lane 1 (3 m) and lane -1 (3.5 m): flat and straight, so
// max_spacing_m (10 m) sets the 11 stations; three borders each, two quads per step.
TEST(LaneLoft, StraightFlatRoadHasItsStationsAreaAndEnds) {
  const ModelRoad road = straight_road(4, Vec2(0.0, 0.0), 0.0, 100.0, 5.0, 0.0);
  MeshBuilder road_mesh, sidewalk;
  const LoftedRoad lofted = loft_road(road, no_markings(), road_mesh, sidewalk, nullptr);
  EXPECT_EQ(lofted.stations, 11u);
  EXPECT_EQ(road_mesh.mesh.vertices.size(), 33u);
  EXPECT_EQ(road_mesh.mesh.triangles.size(), 40u);
  EXPECT_EQ(road_mesh.owner, std::vector<int>(40, 4));
  EXPECT_NEAR(mesh_area(road_mesh.mesh), 100.0 * 6.5, 1e-9);
  EXPECT_LT(lofted.max_deviation_m, 1e-12);
  EXPECT_TRUE(sidewalk.mesh.empty());
  // Each vertex at a station (x = s, a multiple of 10 m) on a border (y = t: 3, 0 or -3.5),
  // with uv = (t, s).
  for (std::size_t i = 0; i < road_mesh.mesh.vertices.size(); ++i) {
    const Vec3& v = road_mesh.mesh.vertices[i];
    EXPECT_NEAR(std::remainder(v.x(), 10.0), 0.0, 1e-9) << v.transpose();
    EXPECT_TRUE(std::abs(v.y() - 3.0) < 1e-12 || std::abs(v.y()) < 1e-12 || std::abs(v.y() + 3.5) < 1e-12)
        << v.transpose();
    EXPECT_DOUBLE_EQ(v.z(), 5.0);
    EXPECT_NEAR(road_mesh.mesh.uvs[i].x(), v.y(), 1e-12);
    EXPECT_NEAR(road_mesh.mesh.uvs[i].y(), v.x(), 1e-9);
  }
  // End cross-sections by decreasing t (left to right looking along +s).
  expect_points(positions(road_mesh.mesh, lofted.start.road_vertices),
                {Vec3(0.0, 3.0, 5.0), Vec3(0.0, 0.0, 5.0), Vec3(0.0, -3.5, 5.0)}, 1e-12);
  expect_points(positions(road_mesh.mesh, lofted.end.road_vertices),
                {Vec3(100.0, 3.0, 5.0), Vec3(100.0, 0.0, 5.0), Vec3(100.0, -3.5, 5.0)}, 1e-9);
  EXPECT_TRUE(lofted.start.sidewalk_vertices.empty());
  EXPECT_TRUE(lofted.start.marking_vertices.empty());
}

// A plan view of three lines east over 20 m, the middle one a millimetre long (as the plan fit joins two
// arcs whose tangents all but meet): its two ends are one break, so no two stations lie a
// millimetre apart (triangles that thin fold over once a file rounds them). A record 6 cm long
// keeps both its ends, and so does a short one that turns.
TEST(LaneLoft, PlanRecordsAMillimetreApartAreOneBreakNotASliver) {
  const auto road_with_middle = [](double middle_m) {
    ModelRoad road = straight_road(5, Vec2::Zero(), 0.0, 10.0, 5.0, 0.0);
    road.plan =
        PlanView({test::line_record(0.0, Vec2(0.0, 0.0), 0.0, 10.0),
                  test::line_record(10.0, Vec2(10.0, 0.0), 0.0, middle_m),
                  test::line_record(10.0 + middle_m, Vec2(10.0 + middle_m, 0.0), 0.0, 10.0 - middle_m)});
    return road;
  };
  for (const auto& [middle_m, stations] : {std::pair(0.001, 3u), std::pair(0.06, 4u)}) {
    MeshBuilder road_mesh, sidewalk;
    const LoftedRoad lofted =
        loft_road(road_with_middle(middle_m), no_markings(), road_mesh, sidewalk, nullptr);
    EXPECT_EQ(lofted.stations, stations) << middle_m;
    EXPECT_NEAR(mesh_area(road_mesh.mesh), 20.0 * 6.5, 1e-9);
    std::set<double> s;
    for (const Vec2& uv : road_mesh.mesh.uvs) s.insert(uv.y());
    for (auto it = std::next(s.begin()); it != s.end(); ++it)
      EXPECT_GE(*it - *std::prev(it), 0.05) << middle_m;
  }
  // A short piece that turns keeps its station: a 3 cm arc of 1/3 m radius (5 degrees) between
  // the two lines. Without it the cross-section after the bend would turn against the one before.
  ModelRoad bend = straight_road(6, Vec2::Zero(), 0.0, 10.0, 5.0, 0.0);
  const PlanGeometry arc = test::arc_record(10.0, Vec2(10.0, 0.0), 0.0, 0.03, 3.0);
  const Pose2 after = PlanView({arc}).at(10.03);
  bend.plan = PlanView({test::line_record(0.0, Vec2(0.0, 0.0), 0.0, 10.0), arc,
                        test::line_record(10.03, after.position, after.heading, 9.97)});
  MeshBuilder road_mesh, sidewalk;
  EXPECT_EQ(loft_road(bend, no_markings(), road_mesh, sidewalk, nullptr).stations, 4u);
}

// Every triangle counter-clockwise seen from above (normals up), on a road heading north-west.
TEST(LaneLoft, TrianglesFaceUpWhateverTheHeading) {
  const ModelRoad road = straight_road(1, Vec2(3.0, -2.0), 2.5, 40.0, 0.0, 0.04);
  MeshBuilder road_mesh, sidewalk;
  (void)loft_road(road, no_markings(), road_mesh, sidewalk, nullptr);
  EXPECT_EQ(road_mesh.mesh.triangles.size(), 2u * 4u * 2u);  // 5 stations, 10 m apart
  EXPECT_TRUE(test::all_facing_up(road_mesh.mesh));
  EXPECT_NEAR(mesh_area(road_mesh.mesh), 40.0 * std::sqrt(1.0 + 0.04 * 0.04) * 6.5, 1e-9);
}

// A crest z = -c s^2: the chord of a step h leaves the parabola by c h^2 / 4 at its middle, in
// height only (the quads are planar). With c = 0.001 and a 0.01 m tolerance, 10 m steps
// (0.025 m) are halved once to 5 m (0.00625 m): 21 stations over 100 m.
TEST(LaneLoft, CrestIsBisectedToTheToleranceWithTheChordErrorItMeasures) {
  ModelRoad road = straight_road(2, Vec2::Zero(), 0.0, 100.0, 20.0, 0.0);
  const double c = 0.001;
  road.elevation = CubicProfile({CubicPiece{0.0, {20.0, 0.0, -c, 0.0}}});
  RoadMeshOptions options = no_markings();
  options.tolerance_m = 0.01;
  MeshBuilder road_mesh, sidewalk;
  const LoftedRoad lofted = loft_road(road, options, road_mesh, sidewalk, nullptr);
  EXPECT_EQ(lofted.stations, 21u);
  EXPECT_NEAR(lofted.max_deviation_m, c * 5.0 * 5.0 / 4.0, 1e-9);
  for (const Vec3& v : road_mesh.mesh.vertices) EXPECT_NEAR(v.z(), 20.0 - c * v.x() * v.x(), 1e-9);
}

// A sidewalk lane goes to the sidewalk mesh; each end lists the vertices of its own mesh.
TEST(LaneLoft, SidewalkEndsAreListedInTheSidewalkMesh) {
  ModelRoad road = straight_road(3, Vec2::Zero(), 0.0, 20.0, 0.0, 0.0);
  LaneModel walk = constant_lane(-2, 2.0);
  walk.type = "sidewalk";
  road.sections[0].right.push_back(walk);
  MeshBuilder road_mesh, sidewalk;
  const LoftedRoad lofted = loft_road(road, no_markings(), road_mesh, sidewalk, nullptr);
  EXPECT_NEAR(mesh_area(sidewalk.mesh), 20.0 * 2.0, 1e-12);
  EXPECT_NEAR(mesh_area(road_mesh.mesh), 20.0 * 6.5, 1e-12);
  expect_points(positions(sidewalk.mesh, lofted.end.sidewalk_vertices),
                {Vec3(20.0, -3.5, 0.0), Vec3(20.0, -5.5, 0.0)}, 1e-12);
  EXPECT_EQ(lofted.end.road_vertices.size(), 3u);  // the sidewalk's inner border is in both meshes
}

// Marks reaching s = 0 and the road's end hand their end edges over for welding: a solid
// centre line gives a left and a right vertex at each end, lifted by marking_lift_m.
TEST(LaneLoft, MarksReachingTheEndsAreListedForWelding) {
  ModelRoad road = straight_road(5, Vec2::Zero(), 0.0, 30.0, 1.0, 0.0);
  road.sections[0].centre_mark.type = RoadMark::Type::solid;
  RoadMeshOptions options;
  options.marking_lift_m = 0.01;
  MeshBuilder road_mesh, sidewalk, marking;
  const LoftedRoad lofted = loft_road(road, options, road_mesh, sidewalk, &marking);
  EXPECT_NEAR(mesh_area(marking.mesh), 30.0 * 0.12, 1e-12);
  expect_points(positions(marking.mesh, lofted.start.marking_vertices),
                {Vec3(0.0, 0.06, 1.01), Vec3(0.0, -0.06, 1.01)}, 1e-12);
  expect_points(positions(marking.mesh, lofted.end.marking_vertices),
                {Vec3(30.0, 0.06, 1.01), Vec3(30.0, -0.06, 1.01)}, 1e-12);
}

TEST(LaneLoft, RoadWithoutPlanViewOrLanesIsInvalidInput) {
  MeshBuilder road_mesh, sidewalk;
  ModelRoad no_lanes = straight_road(6, Vec2::Zero(), 0.0, 10.0, 0.0, 0.0);
  no_lanes.sections.clear();
  EXPECT_THROW((void)loft_road(no_lanes, {}, road_mesh, sidewalk, nullptr), InvalidInput);
  ModelRoad no_plan = straight_road(7, Vec2::Zero(), 0.0, 10.0, 0.0, 0.0);
  no_plan.plan = PlanView();
  EXPECT_THROW((void)loft_road(no_plan, {}, road_mesh, sidewalk, nullptr), InvalidInput);
  EXPECT_THROW((void)sample_lane_border(no_plan, -1, {}), InvalidInput);
}

// The outer border of lane -1 lies 3.5 m right of the reference line, sampled at the loft's
// stations; a lane the section lacks is InvalidInput.
TEST(LaneLoft, LaneBorderIsSampledLikeTheLanes) {
  const ModelRoad road = straight_road(8, Vec2(10.0, 0.0), 0.0, 50.0, 2.0, 0.1);
  const std::vector<Vec3> border = sample_lane_border(road, -1, {});
  std::vector<Vec3> expected;
  for (int i = 0; i <= 5; ++i) expected.emplace_back(10.0 + 10.0 * i, -3.5, 2.0 + 1.0 * i);
  expect_points(border, expected, 1e-9);
  const std::vector<Vec3> centre = sample_lane_border(road, 0, {});
  ASSERT_EQ(centre.size(), 6u);
  EXPECT_LT((centre.back() - Vec3(60.0, 0.0, 7.0)).norm(), 1e-9);
  EXPECT_THROW((void)sample_lane_border(road, -2, {}), InvalidInput);
}

}  // namespace
}  // namespace relief::detail

#include "relief/roads/road_surface.h"

#include <gtest/gtest.h>

#include <cmath>

#include "relief/core/errors.h"

namespace relief {
namespace {

constexpr double kRadius = 100.0;

double elevation(double s) {
  return 100.0 + 0.02 * s + 1e-4 * s * s - 1e-6 * s * s * s;
}

LaneModel lane(int id, double width, double width_slope = 0.0) {
  LaneModel l;
  l.id = id;
  l.width = CubicProfile({CubicPiece{0.0, {width, width_slope, 0.0, 0.0}}});
  return l;
}

// 50 m east from the origin, then 50 m of a left arc of radius 100 m (centre (50, 100)).
// Section 0: lanes 1 (3 m), -1 and -2 (3.5 m); section 1 from s = 60: lane -1 widening by
// 1 cm per metre, no left lane. Lane offset 0.5 m, elevation a known cubic.
ModelRoad test_road() {
  ModelRoad road;
  road.id = 42;
  PlanGeometry line;
  line.kind = PlanGeometry::Kind::line;
  line.length = 50.0;
  PlanGeometry arc;
  arc.kind = PlanGeometry::Kind::arc;
  arc.s = 50.0;
  arc.start = Vec2(50.0, 0.0);
  arc.length = 50.0;
  arc.curvature = 1.0 / kRadius;
  road.plan = PlanView({line, arc});
  road.elevation = CubicProfile({CubicPiece{0.0, {100.0, 0.02, 1e-4, -1e-6}}});
  road.lane_offset = CubicProfile::constant(0.5);
  LaneSection first;
  first.left = {lane(1, 3.0)};
  first.right = {lane(-1, 3.5), lane(-2, 3.5)};
  LaneSection second;
  second.s = 60.0;
  second.right = {lane(-1, 3.5, 0.01)};
  road.sections = {first, second};
  return road;
}

TEST(RoadSurface, SectionAtPicksTheLastSectionStartingBeforeS) {
  const ModelRoad road = test_road();
  EXPECT_EQ(&section_at(road, -5.0), &road.sections[0]);
  EXPECT_EQ(&section_at(road, 59.9), &road.sections[0]);
  EXPECT_EQ(&section_at(road, 60.0), &road.sections[1]);
  EXPECT_EQ(&section_at(road, 500.0), &road.sections[1]);
  ModelRoad bare = road;
  bare.sections.clear();
  EXPECT_THROW((void)section_at(bare, 1.0), InvalidInput);
}

TEST(RoadSurface, LaneBordersAddWidthsOutwardsFromTheOffsetCentre) {
  const ModelRoad road = test_road();
  EXPECT_NEAR(lane_border_t(road, 10.0, 0), 0.5, 1e-12);
  EXPECT_NEAR(lane_border_t(road, 10.0, 1), 3.5, 1e-12);
  EXPECT_NEAR(lane_border_t(road, 10.0, -1), -3.0, 1e-12);
  EXPECT_NEAR(lane_border_t(road, 10.0, -2), -6.5, 1e-12);
  EXPECT_NEAR(lane_centre_t(road, 10.0, 1), 2.0, 1e-12);
  EXPECT_NEAR(lane_centre_t(road, 10.0, -1), -1.25, 1e-12);
  EXPECT_NEAR(lane_centre_t(road, 10.0, -2), -4.75, 1e-12);
  // Second section: width 3.5 + 0.01 ds with ds from s = 60.
  EXPECT_NEAR(lane_border_t(road, 70.0, -1), 0.5 - 3.6, 1e-12);
  EXPECT_NEAR(lane_centre_t(road, 90.0, -1), 0.5 - 0.5 * 3.8, 1e-12);
}

TEST(RoadSurface, UnknownLanesThrow) {
  const ModelRoad road = test_road();
  EXPECT_THROW((void)lane_border_t(road, 10.0, 2), InvalidInput);
  EXPECT_THROW((void)lane_border_t(road, 10.0, -3), InvalidInput);
  EXPECT_THROW((void)lane_border_t(road, 70.0, 1), InvalidInput);  // no left lane there
  EXPECT_THROW((void)lane_border_t(road, 70.0, -2), InvalidInput);
  EXPECT_THROW((void)lane_centre_t(road, 10.0, 0), InvalidInput);
  EXPECT_THROW((void)lane_centre_t(road, 10.0, 5), InvalidInput);
}

TEST(RoadSurface, SurfacePointOnTheLine) {
  const ModelRoad road = test_road();
  const Vec3 p = surface_point(road, 10.0, lane_border_t(road, 10.0, -2));
  EXPECT_NEAR(p.x(), 10.0, 1e-12);
  EXPECT_NEAR(p.y(), -6.5, 1e-12);
  EXPECT_NEAR(p.z(), elevation(10.0), 1e-12);
  const Vec3 left = surface_point(road, 25.0, 2.0);
  EXPECT_NEAR(left.y(), 2.0, 1e-12);
  EXPECT_NEAR(left.z(), elevation(25.0), 1e-12);
  EXPECT_NEAR(heading_at(road, 25.0), 0.0, 1e-15);
}

TEST(RoadSurface, SurfacePointOnTheArcIsConcentric) {
  const ModelRoad road = test_road();
  const Vec2 centre(50.0, kRadius);
  for (const double s : {50.0, 63.0, 81.5, 100.0}) {
    const double phi = (s - 50.0) / kRadius;
    EXPECT_NEAR(heading_at(road, s), phi, 1e-12) << s;
    for (const int lane_id : {1, -1}) {
      const double t = lane_border_t(road, s, lane_id == 1 && s >= 60.0 ? 0 : lane_id);
      const Vec3 p = surface_point(road, s, t);
      // Left of the reference line is towards the centre: radius 100 - t at angle phi - 90°.
      EXPECT_NEAR(p.x(), centre.x() + (kRadius - t) * std::sin(phi), 1e-9) << s;
      EXPECT_NEAR(p.y(), centre.y() - (kRadius - t) * std::cos(phi), 1e-9) << s;
      EXPECT_NEAR(p.z(), elevation(s), 1e-9) << s;
    }
  }
}

TEST(RoadSurface, SuperelevationTiltsAcrossTheRoad) {
  ModelRoad road = test_road();
  road.superelevation = CubicProfile::constant(0.05);
  const Vec3 right = surface_point(road, 30.0, -6.5);
  const Vec3 left = surface_point(road, 30.0, 3.5);
  EXPECT_NEAR(right.z(), elevation(30.0) - 6.5 * std::tan(0.05), 1e-12);
  EXPECT_NEAR(left.z(), elevation(30.0) + 3.5 * std::tan(0.05), 1e-12);
  // The height alone, and the point from a pose evaluated once, are the same numbers.
  EXPECT_EQ(surface_z(road, 30.0, -6.5), right.z());
  EXPECT_EQ(surface_z(road, 150.0, 3.5), surface_point(road, 100.0, 3.5).z());  // clamped
  const Vec3 again = surface_point(road, road.plan.at(30.0), 30.0, 3.5);
  EXPECT_EQ(again, left);
}

TEST(RoadSurface, SurfacePointClampsToTheRoad) {
  const ModelRoad road = test_road();
  const Vec3 beyond = surface_point(road, 150.0, 0.0);
  const Vec3 end = surface_point(road, 100.0, 0.0);
  EXPECT_NEAR((beyond - end).norm(), 0.0, 1e-12);
  EXPECT_NEAR(end.z(), elevation(100.0), 1e-12);
  ModelRoad no_plan = road;
  no_plan.plan = PlanView();
  EXPECT_THROW((void)surface_point(no_plan, 1.0, 0.0), InvalidInput);
  EXPECT_THROW((void)heading_at(no_plan, 1.0), InvalidInput);
}

TEST(RoadSurface, RoadIndexFindsRoadsById) {
  RoadModel model;
  model.roads.resize(3);
  model.roads[0].id = 7;
  model.roads[1].id = 3;
  model.roads[2].id = 11;
  EXPECT_EQ(model.road_index(7), 0);
  EXPECT_EQ(model.road_index(3), 1);
  EXPECT_EQ(model.road_index(11), 2);
  EXPECT_EQ(model.road_index(9), -1);
}

}  // namespace
}  // namespace relief

#include "relief/roads/validation.h"

#include <gtest/gtest.h>

#include "relief/core/errors.h"
#include "support/synthetic.h"

namespace relief {
namespace {

// A profile along x with z = z0 + grade * x sampled every metre.
RoadProfile ramp(double length, double z0, double grade) {
  RoadProfile p;
  for (int i = 0; i <= static_cast<int>(length); ++i) {
    p.s.push_back(i);
    p.xy.emplace_back(i, 0.0);
    p.z.push_back(z0 + grade * i);
    p.at_node.push_back(0);
    p.filled.push_back(0);
  }
  return p;
}

TEST(Validation, ErrorStats) {
  const std::vector<double> v{1.0, 2.0, 3.0, 4.0};
  const std::vector<std::optional<double>> ref{1.5, 2.0, std::nullopt, 2.0};
  const ErrorStats e = error_stats(v, ref);
  EXPECT_EQ(e.n, 3u);
  EXPECT_NEAR(e.mae_m, (0.5 + 0.0 + 2.0) / 3.0, 1e-12);
  EXPECT_NEAR(e.rmse_m, std::sqrt((0.25 + 4.0) / 3.0), 1e-12);
  EXPECT_NEAR(e.max_m, 2.0, 1e-12);
  EXPECT_NEAR(e.bias_m, (-0.5 + 2.0) / 3.0, 1e-12);
  EXPECT_EQ(e.max_at, 3u);  // the value of the largest error
}

TEST(Validation, PaperGradeLimitsAndOverrides) {
  GradeLimits limits = GradeLimits::paper();
  EXPECT_EQ(limits.limit_for(HighwayClass::motorway), 8.0);
  EXPECT_EQ(limits.limit_for(HighwayClass::trunk_link), 8.0);
  EXPECT_EQ(limits.limit_for(HighwayClass::secondary), 12.0);
  EXPECT_EQ(limits.limit_for(HighwayClass::residential), 15.0);
  limits.apply_overrides("highway=6,residential=20");
  EXPECT_EQ(limits.limit_for(HighwayClass::motorway_link), 6.0);
  EXPECT_EQ(limits.limit_for(HighwayClass::residential), 20.0);
  EXPECT_EQ(limits.limit_for(HighwayClass::service), 15.0);
  EXPECT_THROW(limits.apply_overrides("motorway"), InvalidInput);
  EXPECT_THROW(limits.apply_overrides("boulevard=5"), InvalidInput);
  EXPECT_THROW(limits.apply_overrides("motorway=-2"), InvalidInput);
}

TEST(Validation, GradeComplianceByClass) {
  WayAttributes motorway, street;
  motorway.highway = HighwayClass::motorway;
  street.highway = HighwayClass::residential;
  const RoadNetwork net = test::make_network({{{0, 0}, {100, 0}}, {{0, 10}, {300, 10}}}, {motorway, street});
  const std::vector<RoadProfile> profiles{ramp(100, 0, 0.10), ramp(300, 0, 0.10)};
  const GradeStats g = grade_stats(net, profiles, GradeLimits::paper());
  EXPECT_NEAR(g.max_percent, 10.0, 1e-9);
  EXPECT_NEAR(g.p99_percent, 10.0, 1e-9);
  EXPECT_NEAR(g.by_class.at("motorway").compliance_percent, 0.0, 1e-9);       // 10 % > 8 %
  EXPECT_NEAR(g.by_class.at("residential").compliance_percent, 100.0, 1e-9);  // 10 % <= 15 %
  EXPECT_NEAR(g.compliance_percent, 75.0, 1e-9);                              // 300 of 400 m comply
  EXPECT_NEAR(g.by_class.at("motorway").length_km, 0.1, 1e-12);
}

TEST(Validation, P99IsWeightedByLength) {
  const RoadNetwork net = test::make_network({{{0, 0}, {100, 0}}});
  RoadProfile p = ramp(100, 0, 0.02);
  p.z[100] = p.z[99] + 0.5;  // one steep metre: 50 % over 1 % of the length
  const GradeStats g = grade_stats(net, {p}, GradeLimits::paper());
  EXPECT_NEAR(g.max_percent, 50.0, 1e-9);
  EXPECT_NEAR(g.p99_percent, 2.0, 1e-9);
  EXPECT_NEAR(g.compliance_percent, 99.0, 1e-9);
}

TEST(Validation, JunctionGapIsTheSpreadOfRoadEnds) {
  const RoadNetwork net =
      test::make_network({{{0, 0}, {100, 0}}, {{100, 0}, {200, 0}}, {{100, 0}, {100, 100}}});
  std::vector<RoadProfile> profiles{ramp(100, 0, 0.1), ramp(100, 10.3, 0.0), ramp(100, 10.05, 0.0)};
  const JunctionGapStats j = junction_gaps(net, profiles);
  EXPECT_NEAR(j.max_gap_m, 0.3, 1e-9);
  EXPECT_EQ(j.over_bound, 1u);
  EXPECT_EQ(j.checked, 1u);  // dead ends have a single road end
  EXPECT_EQ(j.worst_junction, net.roads[0].end_junction);
}

TEST(Validation, NetworkCounts) {
  WayAttributes bridge;
  bridge.bridge = true;
  const RoadNetwork net = test::make_network(
      {{{0, 0}, {100, 0}}, {{100, 0}, {200, 0}}, {{100, 0}, {100, 100}}}, {WayAttributes{}, bridge});
  const NetworkStats s = network_stats(net);
  EXPECT_EQ(s.roads, 3u);
  EXPECT_EQ(s.intersections, 1u);
  EXPECT_EQ(s.dead_ends, 3u);
  EXPECT_EQ(s.junctions, 1u);
  EXPECT_EQ(s.bridges, 1u);
  EXPECT_NEAR(s.length_km, 0.3, 1e-12);
  EXPECT_NEAR(s.bridge_km, 0.1, 1e-12);
}

TEST(Validation, HeightsOnAPlaneHaveNoErrorAndAReferenceOffsetShows) {
  const auto plane = [](double x, double y) { return 20.0 + 0.05 * x + 0.01 * y; };
  const std::string dem = test::write_local_dem("val_plane", 300, 10, plane);
  const std::string ref =
      test::write_local_dem("val_ref", 300, 10, [&](double x, double y) { return plane(x, y) - 0.7; });
  RoadProfile p;
  for (int i = 0; i <= 200; ++i) {
    const Vec2 xy(-100.0 + i * 0.6, -50.0 + i * 0.8);
    p.s.push_back(i);
    p.xy.push_back(xy);
    p.z.push_back(plane(xy.x(), xy.y()));
  }
  Aabb2 area{Vec2(-200, -200), Vec2(200, 200)};
  const DemSampler d({dem}, test::synthetic_frame(), area);
  const DemSampler r({ref}, test::synthetic_frame(), area);
  const HeightValidation v = HeightValidator({p}, d, &r).validate({p});
  EXPECT_EQ(v.vs_dem.n, 200u);
  EXPECT_LT(v.vs_dem.max_m, 1e-9);
  EXPECT_LT(v.error_3d_max_m, 1e-9);
  ASSERT_TRUE(v.vs_reference);
  EXPECT_NEAR(v.vs_reference->bias_m, 0.7, 1e-9);
  EXPECT_NEAR(v.vs_reference->rmse_m, 0.7, 1e-9);
}

TEST(Validation, ThreeDErrorIsThePointToSurfaceDistance) {
  // A 100 % slope (45 degrees): a road 1 m above it is 1/sqrt(2) m from the surface.
  const std::string dem = test::write_local_dem("val_slope", 300, 10, [](double x, double) { return x; });
  RoadProfile p;
  for (int i = 0; i <= 10; ++i) {
    p.s.push_back(i);
    p.xy.emplace_back(0.0, i);
    p.z.push_back(1.0);
  }
  const DemSampler d({dem}, test::synthetic_frame(), Aabb2{Vec2(-50, -50), Vec2(50, 50)});
  const HeightValidation v = HeightValidator({p}, d, nullptr).validate({p});
  EXPECT_NEAR(v.vs_dem.max_m, 1.0, 1e-9);
  EXPECT_NEAR(v.error_3d_max_m, 1.0 / std::sqrt(2.0), 1e-9);
  EXPECT_FALSE(v.vs_reference);
  // The largest error's place: every midpoint is 1 m off, the first counts.
  EXPECT_EQ(v.max_road, 0);
  EXPECT_NEAR(v.max_error_m, 1.0, 1e-9);
  EXPECT_NEAR((v.max_xy - Vec2(0.0, 0.5)).norm(), 0.0, 1e-12);
}

TEST(Validation, TheLargestDepartureFromTheDemIsPlaced) {
  // A flat DEM at 0; the second road dips 2.5 m at its 4th midpoint.
  const std::string dem = test::write_local_dem("val_flat", 300, 10, [](double, double) { return 0.0; });
  std::vector<RoadProfile> roads(2);
  for (int r = 0; r < 2; ++r) {
    for (int i = 0; i <= 10; ++i) {
      roads[static_cast<std::size_t>(r)].s.push_back(i);
      roads[static_cast<std::size_t>(r)].xy.emplace_back(10.0 * r, i);
      roads[static_cast<std::size_t>(r)].z.push_back(r == 1 && (i == 3 || i == 4) ? -2.5 : 0.0);
    }
  }
  const DemSampler d({dem}, test::synthetic_frame(), Aabb2{Vec2(-50, -50), Vec2(50, 50)});
  const HeightValidation v = HeightValidator(roads, d, nullptr).validate(roads);
  EXPECT_NEAR(v.vs_dem.max_m, 2.5, 1e-9);
  EXPECT_EQ(v.max_road, 1);
  EXPECT_NEAR(v.max_error_m, -2.5, 1e-9);
  EXPECT_NEAR((v.max_xy - Vec2(10.0, 3.5)).norm(), 0.0, 1e-12);
}

}  // namespace
}  // namespace relief

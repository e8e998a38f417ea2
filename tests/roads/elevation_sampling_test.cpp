#include "relief/roads/elevation_sampling.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "relief/core/errors.h"
#include "support/synthetic.h"

namespace relief {
namespace {

const auto plane = [](double x, double y) { return 50.0 + 0.04 * x - 0.03 * y; };

DemSampler sampler(const std::string& path, const RoadNetwork& net) {
  Aabb2 area;
  for (const Road& r : net.roads)
    for (const Vec2& p : r.points) area.extend(p);
  return DemSampler({path}, net.frame, area);
}

TEST(ElevationSampling, StraightHundredMetreRoadGives101Samples) {
  const RoadNetwork net = test::make_network({{{0, 0}, {100, 0}}});
  const RoadProfile p = make_stations(net.roads[0], 1.0);
  ASSERT_EQ(p.size(), 101u);
  EXPECT_EQ(p.at_node.front(), 1);
  EXPECT_EQ(p.at_node.back(), 1);
  EXPECT_EQ(std::count(p.at_node.begin(), p.at_node.end(), 1), 2);
  EXPECT_NEAR(p.xy[37].x(), 37.0, 1e-12);
}

TEST(ElevationSampling, OsmNodesBetweenStationsAreSampledToo) {
  const RoadNetwork net = test::make_network({{{0, 0}, {50.5, 0}, {100, 0}}});
  const RoadProfile p = make_stations(net.roads[0], 1.0);
  ASSERT_EQ(p.size(), 102u);
  EXPECT_NEAR(p.s[51], 50.5, 1e-12);
  EXPECT_EQ(p.at_node[51], 1);
}

TEST(ElevationSampling, HeightsOnAPlaneAreExact) {
  const std::string dem = test::write_local_dem("es_plane", 300, 10, plane);
  const RoadNetwork net = test::make_network({{{-100, -50}, {120, 80}}, {{120, 80}, {120, -90}}});
  Diagnostics d;
  const ElevationSamples s = sample_elevation(net, sampler(dem, net), {}, d);
  ASSERT_EQ(s.profiles.size(), 2u);
  EXPECT_EQ(s.void_samples, 0u);
  EXPECT_EQ(d.total(), 0u);
  for (const RoadProfile& p : s.profiles) {
    for (std::size_t i = 0; i < p.size(); ++i) EXPECT_NEAR(p.z[i], plane(p.xy[i].x(), p.xy[i].y()), 1e-6);
  }
}

TEST(ElevationSampling, VoidsAreFilledAlongTheRoadAndReported) {
  // A nodata band 60 m wide across the road (x in [-30, 30]).
  const auto holed = [](double x, double y) { return std::abs(x) < 30.0 ? -9999.0 : plane(x, y); };
  const std::string dem = test::write_local_dem("es_void", 300, 10, holed, -9999.0);
  const RoadNetwork net = test::make_network({{{-150, 0}, {150, 0}}});
  Diagnostics d;
  const ElevationSamples s = sample_elevation(net, sampler(dem, net), {}, d);
  EXPECT_GT(s.void_samples, 40u);
  EXPECT_EQ(d.count("elevation.void"), 1u);
  const RoadProfile& p = s.profiles[0];
  // Away from the void the DEM's plane; within a cell of its edge the renormalised bilinear
  // value of the valid corners; inside, a straight line between the last valid samples.
  std::size_t first_filled = p.size(), last_filled = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (std::abs(p.xy[i].x()) >= 35.0) {
      EXPECT_NEAR(p.z[i], plane(p.xy[i].x(), 0.0), 1e-6) << p.s[i];
    }
    if (p.filled[i]) {
      first_filled = std::min(first_filled, i);
      last_filled = i;
    }
  }
  ASSERT_LT(first_filled, last_filled);
  const std::size_t a = first_filled - 1, b = last_filled + 1;
  for (std::size_t i = first_filled; i <= last_filled; ++i) {
    EXPECT_EQ(p.filled[i], 1);
    const double t = (p.s[i] - p.s[a]) / (p.s[b] - p.s[a]);
    EXPECT_NEAR(p.z[i], p.z[a] + t * (p.z[b] - p.z[a]), 1e-9);
  }

  SamplingOptions strict;
  strict.nodata_fill = NodataFill::error;
  EXPECT_THROW((void)sample_elevation(net, sampler(dem, net), strict, d), InvalidInput);
}

TEST(ElevationSampling, RoadsOutsideTheDemAreACoverageError) {
  const std::string dem = test::write_local_dem("es_small", 100, 10, plane);
  const RoadNetwork net = test::make_network({{{0, 0}, {300, 0}}});
  Diagnostics d;
  const DemSampler dem_sampler({dem}, net.frame, Aabb2{Vec2(-100, -100), Vec2(100, 100)});
  try {
    (void)sample_elevation(net, dem_sampler, {}, d);
    FAIL() << "expected CoverageError";
  } catch (const CoverageError& e) {
    // 200 of the 301 samples lie beyond x = 100 (give or take the border cell).
    EXPECT_NEAR(e.uncovered_percent(), 100.0 * 200.0 / 301.0, 2.0);
    EXPECT_NE(std::string(e.what()).find("--allow-partial"), std::string::npos);
  }
  SamplingOptions partial;
  partial.allow_partial = true;
  const ElevationSamples s = sample_elevation(net, dem_sampler, partial, d);
  EXPECT_GT(s.uncovered_samples, 150u);
  EXPECT_EQ(d.count("elevation.uncovered"), 1u);
  EXPECT_TRUE(s.profiles[0].has_height);
}

TEST(ElevationSampling, ImplausibleDemCellsUnderARoadAreFilledLikeNodata) {
  // A 1e30 cell and a +100 m spike on the road's line, without a nodata flag; and the same
  // plane with those two cells flagged: the road gets the same heights from both.
  const auto bad_cell = [](double x, double y, double at_x) {
    return std::abs(x - at_x) < 1.0 && std::abs(y - 5.0) < 1.0;
  };
  const auto bad = [&](double x, double y) {
    if (bad_cell(x, y, 45.0)) return plane(x, y) + 100.0;
    if (bad_cell(x, y, -55.0)) return 1e30;
    return plane(x, y);
  };
  const auto flagged = [&](double x, double y) {
    return bad_cell(x, y, 45.0) || bad_cell(x, y, -55.0) ? -9999.0 : plane(x, y);
  };
  const RoadNetwork net = test::make_network({{{-150, 5}, {150, 5}}});
  const Aabb2 area{Vec2(-150, 5), Vec2(150, 5)};
  Diagnostics d, d_flagged;
  const DemSampler bad_dem({test::write_local_dem("es_bad", 300, 10, bad)}, net.frame, area, {}, &d);
  const DemSampler flagged_dem({test::write_local_dem("es_flagged", 300, 10, flagged, -9999.0)}, net.frame,
                               area, {}, &d_flagged);
  const ElevationSamples s = sample_elevation(net, bad_dem, {}, d);
  const ElevationSamples f = sample_elevation(net, flagged_dem, {}, d_flagged);
  EXPECT_EQ(d.count("dem.spike"), 1u);
  EXPECT_EQ(d.count("dem.implausible_height"), 1u);
  EXPECT_EQ(s.void_samples, f.void_samples);
  EXPECT_GE(s.void_samples, 2u);  // the samples at the two cells' centres, filled along the road
  EXPECT_EQ(d.count("elevation.void"), 1u);
  EXPECT_EQ(d_flagged.count("elevation.void"), 1u);
  const RoadProfile& p = s.profiles[0];
  ASSERT_EQ(p.size(), f.profiles[0].size());
  double worst = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    EXPECT_NEAR(p.z[i], f.profiles[0].z[i], 1e-9) << p.s[i];
    EXPECT_EQ(p.filled[i], f.profiles[0].filled[i]) << p.s[i];
    worst = std::max(worst, std::abs(p.z[i] - plane(p.xy[i].x(), p.xy[i].y())));
  }
  // Renormalised bilinear next to a void: at most the gradient (0.05) times a cell (10 m).
  EXPECT_LT(worst, 0.5);
}

TEST(ElevationSampling, SampleEstimateCountsEverySpacingAndEveryNode) {
  // 100 m of 2 nodes at 1 m: 101 samples, estimated 100 + 2; a node at 50.5 m: 102 and 103.
  const RoadNetwork one = test::make_network({{{0, 0}, {100, 0}}});
  EXPECT_DOUBLE_EQ(estimate_sample_count(one, 1.0), 102.0);
  const RoadNetwork bent = test::make_network({{{0, 0}, {50.5, 0}, {100, 0}}});
  EXPECT_DOUBLE_EQ(estimate_sample_count(bent, 1.0), 103.0);
  EXPECT_DOUBLE_EQ(estimate_sample_count(bent, 1e-6), 1e8 + 3.0);
  // An upper bound within a sample per road and node of the stations made.
  const RoadNetwork net =
      test::make_network({{{0, 0}, {37.3, 12.0}, {80, -5}}, {{80, -5}, {80, 90}}, {{0, 0}, {-3, 0.4}}});
  for (double spacing : {0.1, 1.0, 7.0, 50.0}) {
    double made = 0.0, bound = 0.0;
    for (const Road& road : net.roads) {
      made += static_cast<double>(make_stations(road, spacing).size());
      bound += 1.0 + static_cast<double>(road.points.size());
    }
    const double estimate = estimate_sample_count(net, spacing);
    EXPECT_GE(estimate, made) << spacing;
    EXPECT_LE(estimate, made + bound) << spacing;
  }
  for (double bad : {0.0, -1.0, std::nan(""), std::numeric_limits<double>::infinity()}) {
    EXPECT_THROW((void)estimate_sample_count(one, bad), OptionError) << bad;
  }
}

TEST(ElevationSampling, SpacingThatWouldExhaustMemoryIsRefusedWithTheSpacingThatFits) {
  // 10 km of road, 2 nodes: 1e-6 m would be 1e10 samples.
  const RoadNetwork net = test::make_network({{{0, 0}, {10000, 0}}});
  SamplingOptions o;
  o.spacing_m = 1e-6;
  try {
    check_sample_budget(net, o);
    FAIL() << "expected OptionError";
  } catch (const OptionError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("sample spacing 1e-06 m would take 1e+10 elevation samples for 10.0 km of road and 2 "
                        "OSM nodes, about 7 TB of memory (limit 1.5e+07 samples, 10 GB)"),
              std::string::npos)
        << what;
    // 10000 m / (1.5e7 - 2) = 6.67e-4 m, rounded up.
    EXPECT_NE(what.find("use a spacing of at least 0.00067 m"), std::string::npos) << what;
  }
  o.spacing_m = 0.00067;  // the spacing suggested fits ...
  EXPECT_NO_THROW(check_sample_budget(net, o));
  o.spacing_m = 0.00066;  // ... and one just finer does not
  EXPECT_THROW(check_sample_budget(net, o), OptionError);
  // The default spacing on this road is far below the limit; a lower limit refuses it.
  o.spacing_m = 1.0;
  EXPECT_NO_THROW(check_sample_budget(net, o));
  o.max_samples = 1000.0;
  EXPECT_THROW(check_sample_budget(net, o), OptionError);
  // Nodes alone over the limit: no spacing helps.
  o.max_samples = 1.0;
  try {
    check_sample_budget(net, o);
    FAIL() << "expected OptionError";
  } catch (const OptionError& e) {
    EXPECT_NE(std::string(e.what()).find("nodes alone exceed it"), std::string::npos) << e.what();
  }
  o.max_samples = 0.0;
  EXPECT_THROW(check_sample_budget(net, o), OptionError);
  o.max_samples = 1.5e7;
  o.spacing_m = std::nan("");
  EXPECT_THROW(check_sample_budget(net, o), OptionError);

  // sample_elevation refuses before reading any height.
  const std::string dem = test::write_local_dem("es_budget", 100, 10, plane);
  const RoadNetwork small = test::make_network({{{0, 0}, {50, 0}}});
  SamplingOptions tiny;
  tiny.spacing_m = 1e-9;
  Diagnostics d;
  EXPECT_THROW((void)sample_elevation(small, sampler(dem, small), tiny, d), OptionError);
  tiny.spacing_m = 0.0;
  EXPECT_THROW((void)sample_elevation(small, sampler(dem, small), tiny, d), InvalidInput);
}

TEST(ElevationSampling, ParseFillPolicy) {
  EXPECT_EQ(parse_nodata_fill("interpolate"), NodataFill::interpolate);
  EXPECT_EQ(parse_nodata_fill("error"), NodataFill::error);
  EXPECT_FALSE(parse_nodata_fill("zero"));
}

}  // namespace
}  // namespace relief

// A fuzzer for the whole build: random road graphs with random tags (lanes, one-way, width,
// bridges and tunnels with their layers, classes from motorway link to service) over random
// steep analytic DEMs with voids. Every build must finish with every output written and every
// quality gate evaluated (the CLI then exits 0 or 4), junctions exactly continuous, and never
// throw, crash or hang. 30 seeds in CI (about 5 s); more by hand:
// RELIEF_FUZZ_SEEDS=1000 build/tests/relief_pipeline_tests --gtest_filter="Fuzz.Random*" (1000
// seeds, 6.6 min on one core, 2026-11-28: all built, every fit converged, 995 by the interior
// point and 5 by the method of multipliers after it stalled (2 before); 892 passed every gate,
// 845 before the rows between road ends held at the lane centres where the model cuts them and
// transition roads whose inner lane climbs past the cap became junctions, 840 before two-road
// bends too tight for a transition road became junctions; the 108 others, which exit 4, all
// fail the ground's RMSE on the steepest terrains (roads capped at their grade cannot follow
// them: 118 before), and none connecting roads' grade (51 before), SUMO height steps (15: an
// inner lane of a tight transition bend), a limit the fit left violated (1) or a
// self-intersection (2)).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <iomanip>
#include <iostream>
#include <numbers>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "relief/geometry/crs_transform.h"
#include "relief/pipeline/build.h"
#include "support/synthetic.h"
#include "support/test_data.h"

namespace relief {
namespace {

struct FuzzCase {
  std::filesystem::path osm;
  std::string dem;
  std::size_t ways = 0;
};

// A jittered grid of nodes, 3..5 on a side, 35..80 m apart, with random edges left out and a
// random diagonal now and then; each edge is a way of 2 or 3 nodes with random tags. With
// `defects`, the errors of real OSM data besides (JOSM's validator finds them all), drawn from
// a random stream of their own so that the network is the same: ways drawn twice (reversed
// too), ways drawn out to a node and straight back, ways running past their end node and
// turning back to it at 170-178 degrees (a hairpin drawn to one node), and ways ending at a
// node of their own on top of a grid node (two nodes at one place).
FuzzCase make_case(unsigned seed, const std::filesystem::path& dir, bool defects = false) {
  std::mt19937 rng(seed);
  std::mt19937 defect_rng(seed * 7919u + 1u);
  std::uniform_real_distribution<double> du(0.0, 1.0);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const GeoFrame frame = test::synthetic_frame();
  const CrsTransform to_wgs84(frame.crs(), "EPSG:4326");
  const int n = 3 + static_cast<int>(u(rng) * 3);
  const double spacing = 35.0 + 45.0 * u(rng);
  const double half = 0.5 * spacing * (n - 1);
  std::ostringstream xml;
  xml << std::setprecision(10) << "<?xml version='1.0' encoding='UTF-8'?>\n<osm version=\"0.6\">\n";
  std::int64_t next_node = 1;
  const auto node = [&](double x, double y) {
    const Vec2 ll = to_wgs84.apply(frame.to_crs(Vec2(x, y)));
    xml << "  <node id=\"" << next_node << "\" version=\"1\" lat=\"" << ll.y() << "\" lon=\"" << ll.x()
        << "\"/>\n";
    return next_node++;
  };
  std::vector<std::int64_t> grid(static_cast<std::size_t>(n * n));
  std::vector<Vec2> at(grid.size());
  for (int i = 0; i < n; ++i) {
    for (int k = 0; k < n; ++k) {
      const std::size_t g = static_cast<std::size_t>(i * n + k);
      at[g] = Vec2(k * spacing - half + (u(rng) - 0.5) * 0.3 * spacing,
                   i * spacing - half + (u(rng) - 0.5) * 0.3 * spacing);
      grid[g] = node(at[g].x(), at[g].y());
    }
  }
  static const char* const kClasses[] = {"residential", "residential", "tertiary",     "secondary",
                                         "primary",     "service",     "unclassified", "motorway_link"};
  std::ostringstream ways;
  FuzzCase c;
  const auto way = [&](std::size_t a, std::size_t b) {
    std::vector<std::int64_t> refs{grid[a]};
    if (u(rng) < 0.5) {  // a bent way: a middle node off the straight line
      const Vec2 m = 0.5 * (at[a] + at[b]);
      const Vec2 d = at[b] - at[a];
      refs.push_back(node(m.x() - d.y() * 0.2 * (u(rng) - 0.5), m.y() + d.x() * 0.2 * (u(rng) - 0.5)));
    }
    refs.push_back(grid[b]);
    const double defect = defects ? du(defect_rng) : 1.0;
    if (defect < 0.08) {  // out to a node beside the way and straight back
      const Vec2 d = at[b] - at[a];
      const Vec2 tip = at[a] + 0.3 * d + Vec2(-d.y(), d.x()) * (0.3 * (du(defect_rng) - 0.5));
      refs.insert(refs.begin() + 1, {node(tip.x(), tip.y()), grid[a]});
    } else if (defect < 0.14) {  // past the end node and back to it, a hairpin drawn to one node
      const Vec2 d = (at[b] - at[a]).normalized();
      const double turn = (170.0 + 8.0 * du(defect_rng)) * std::numbers::pi / 180.0;
      const double len = 15.0 + 25.0 * du(defect_rng);
      const Vec2 apex = at[b] + len * d;
      const Vec2 back(std::cos(turn) * d.x() - std::sin(turn) * d.y(),
                      std::sin(turn) * d.x() + std::cos(turn) * d.y());
      refs.back() = node(apex.x(), apex.y());
      refs.push_back(node(apex.x() + 0.9 * len * back.x(), apex.y() + 0.9 * len * back.y()));
    } else if (defect < 0.19) {  // ending on a node of its own where grid node b is
      refs.back() = node(at[b].x(), at[b].y());
    }
    const bool twice = defect >= 0.19 && defect < 0.27;
    ways << "  <way id=\"" << ++c.ways << "\" version=\"1\">\n";
    for (const std::int64_t r : refs) ways << "    <nd ref=\"" << r << "\"/>\n";
    const auto tag = [&](const std::string& k, const std::string& v) {
      ways << "    <tag k=\"" << k << "\" v=\"" << v << "\"/>\n";
    };
    tag("highway", kClasses[static_cast<int>(u(rng) * 8)]);
    tag("lanes", std::to_string(1 + static_cast<int>(u(rng) * 3)));
    if (u(rng) < 0.2) tag("oneway", "yes");
    if (u(rng) < 0.3) tag("width", std::to_string(4 + static_cast<int>(u(rng) * 9)));
    const double s = u(rng);
    if (s < 0.1) {
      tag("bridge", "yes");
      tag("layer", "1");
    } else if (s < 0.15) {
      tag("tunnel", "yes");
      tag("layer", "-1");
    }
    ways << "  </way>\n";
    if (twice) {  // the same way again, half the time reversed, as a residential street
      if (du(defect_rng) < 0.5) std::reverse(refs.begin(), refs.end());
      ways << "  <way id=\"" << ++c.ways << "\" version=\"1\">\n";
      for (const std::int64_t r : refs) ways << "    <nd ref=\"" << r << "\"/>\n";
      ways << "    <tag k=\"highway\" v=\"residential\"/>\n  </way>\n";
    }
  };
  for (int i = 0; i < n; ++i) {
    for (int k = 0; k < n; ++k) {
      const std::size_t g = static_cast<std::size_t>(i * n + k);
      if (k + 1 < n && u(rng) < 0.85) way(g, g + 1);
      if (i + 1 < n && u(rng) < 0.85) way(g, g + static_cast<std::size_t>(n));
      if (k + 1 < n && i + 1 < n && u(rng) < 0.15) way(g, g + static_cast<std::size_t>(n) + 1);
    }
  }
  xml << ways.str() << "</osm>\n";
  c.osm = dir / "fuzz.osm";
  std::ofstream(c.osm) << xml.str();

  // A tilted plane, a ridge or valley and waves of 40..200 m: grades up to about 60 %; voids
  // (holes of 10..25 m) at random places; 5 or 30 m cells.
  const double gx = 0.3 * (u(rng) - 0.5), gy = 0.3 * (u(rng) - 0.5);
  const double ridge = 60.0 * (u(rng) - 0.5), width = 40.0 + 80.0 * u(rng), angle = u(rng) * std::numbers::pi;
  const double wave = 8.0 * u(rng), lx = 40.0 + 160.0 * u(rng), ly = 40.0 + 160.0 * u(rng);
  std::vector<Vec2> holes;
  for (int h = 0; h < 3; ++h) holes.emplace_back((u(rng) - 0.5) * 2.0 * half, (u(rng) - 0.5) * 2.0 * half);
  const double hole_r = 10.0 + 15.0 * u(rng);
  const double cell = u(rng) < 0.5 ? 5.0 : 30.0;
  const auto ground = [=](double x, double y) {
    for (const Vec2& h : holes)
      if ((Vec2(x, y) - h).norm() < hole_r) return -9999.0;
    const double across = -std::sin(angle) * x + std::cos(angle) * y;
    return 100.0 + gx * x + gy * y + ridge * std::exp(-across * across / (width * width)) +
           wave * std::sin(2.0 * std::numbers::pi * x / lx) * std::cos(2.0 * std::numbers::pi * y / ly);
  };
  c.dem = test::write_local_dem("fuzz_" + std::to_string(seed), half + 200.0, cell, ground, -9999.0);
  return c;
}

// Writes seed's case into a scratch folder and builds it with every output into its out/.
BuildResult build_seed(unsigned seed, FuzzCase& c, Diagnostics& d, bool defects = false) {
  const std::filesystem::path dir =
      test::scratch_dir((defects ? "fuzz_defects_" : "fuzz_") + std::to_string(seed));
  c = make_case(seed, dir, defects);
  BuildOptions o;
  o.osm_path = c.osm;
  o.dem_paths = {c.dem};
  o.out_dir = dir / "out";
  o.crs = test::synthetic_frame().crs();
  return build(o, d);
}

// Builds each of `seeds` (with OSM's errors when `defects`) and hands its result and what it
// reported to `check(seed, result, diagnostics)`.
template <typename Check>
void check_seeds(std::initializer_list<unsigned> seeds, bool defects, Check check) {
  for (const unsigned seed : seeds) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    FuzzCase c;
    Diagnostics d;
    BuildResult result;
    ASSERT_NO_THROW(result = build_seed(seed, c, d, defects));
    check(seed, result, d);
  }
}

// Builds seeds first..last (RELIEF_FUZZ_SEEDS=N: 1..N instead, without the floor) and checks
// each; at least `min_passed` must pass every gate (what was measured: a regression shows). A
// seed's files are removed once checked (each seed writes about 10 MB), unless
// RELIEF_KEEP_TEST_OUTPUT=1.
void build_and_check_seeds(bool defects, unsigned first, unsigned last, unsigned min_passed) {
  const char* env = std::getenv("RELIEF_FUZZ_SEEDS");
  if (env != nullptr) {
    first = 1;
    last = static_cast<unsigned>(std::max(1, std::atoi(env)));
  }
  unsigned passed = 0;
  for (unsigned seed = first; seed <= last; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    FuzzCase c;
    Diagnostics d;
    BuildResult result;
    ASSERT_NO_THROW(result = build_seed(seed, c, d, defects));
    const RunReport& r = result.report;
    // Every output written, every gate evaluated with a finite value.
    EXPECT_GE(result.written.size(), 10u);
    for (const auto& p : result.written) {
      EXPECT_TRUE(std::filesystem::exists(p)) << p;
      EXPECT_GT(std::filesystem::file_size(p), 0u) << p;
    }
    EXPECT_GE(r.gates.size(), 13u);
    std::string failed;
    for (const Gate& g : r.gates) {
      EXPECT_TRUE(std::isfinite(g.value)) << g.name;
      if (!g.passed) failed += " " + g.name + "=" + std::to_string(g.value) + " (" + g.where + ")";
    }
    // Junctions are exactly continuous and the fit always ends (soft limits: no infeasibility).
    EXPECT_EQ(r.junctions.max_gap_m, 0.0);
    ASSERT_TRUE(r.fit);
    EXPECT_TRUE(r.fit->converged) << r.fit->solver;
    passed += failed.empty() ? 1u : 0u;
    std::cout << (defects ? "fuzz (OSM defects) seed " : "fuzz seed ") << seed << ": " << c.ways << " ways, "
              << r.network.roads << " roads, " << r.network.junctions << " junctions, fit " << r.fit->solver
              << ", failed gates:" << (failed.empty() ? std::string(" none") : failed) << "\n";
    if (!test::keep_test_output()) {
      std::filesystem::remove_all(c.osm.parent_path());
      std::filesystem::remove_all(std::filesystem::path(c.dem).parent_path());
    }
  }
  std::cout << passed << " of " << (last - first + 1) << " seeds passed every gate\n";
  if (env == nullptr) {
    EXPECT_GE(passed, min_passed);
  }
}

TEST(Fuzz, RandomNetworksOnRandomTerrainBuildAndCheckThemselves) {
  build_and_check_seeds(false, 1, 30, 28);  // measured 28 of 30 (2026-11-29)
}

// Seeds 31..300 of both fuzzers, in the Release suite only (about 100 s each; .ci/run leaves
// `Seeds31To300` out of the sanitizer pass, which runs seeds 1..30 above). Measured 2026-11-29
// (0b865d0 and the drape past short roads): without errors 245 of 270 pass every gate (1..300:
// 273, the others ground_vs_dem_rmse_m on the steepest terrains); with OSM's errors 219 of 270
// (1..300: 241; ground_vs_dem_rmse_m 33, fit_limits_violated 27, road_self_intersections 13,
// connecting_road_grade_over_cap_percent 4, sumo_height_steps 3, road_grade_over_cap_percent 1,
// ground_holes 1; 21 fits by the method of multipliers, with a crossing's clearance rows sharing
// its price; before, 34, 27, 11, 5, 7, 1, 1 and 28). Since the fit's rows take the roll of a
// joined junction's two-end members and bound each road end's cross slope (12 %), and connecting
// roads lie across their junction's surface within their cap: 218 of 270 (ground_vs_dem_rmse_m
// 30, fit_limits_violated 24, road_self_intersections 10, sumo_height_steps 4, connecting roads
// none; 17 by the method of multipliers). Seed 31 no longer passes: netconvert stretches an
// internal lane 20.8 m past the junction relief builds, and its start, draped on a connecting
// road the new junction plane moved, lies 0.52 m over the lane before it. Every seed builds,
// converges and keeps its junctions exactly continuous.
TEST(Fuzz, RandomNetworksOnRandomTerrainSeeds31To300) {
  if (std::getenv("RELIEF_FUZZ_SEEDS") != nullptr)
    GTEST_SKIP() << "RELIEF_FUZZ_SEEDS: the 1..N test runs them";
  build_and_check_seeds(false, 31, 300, 245);
}

TEST(Fuzz, RandomNetworksWithOsmDataErrorsSeeds31To300) {
  if (std::getenv("RELIEF_FUZZ_SEEDS") != nullptr)
    GTEST_SKIP() << "RELIEF_FUZZ_SEEDS: the 1..N test runs them";
  build_and_check_seeds(true, 31, 300, 218);
}

// The same networks with OSM's data errors in them (make_case): each is reported and handled,
// and the build still ends with every output and gate. Measured on 2026-11-29 with
// RELIEF_FUZZ_SEEDS=100: all 100 built, junctions exactly continuous (seed 9's 0.16 m road
// between two crossings had one station and left a 3.0 m gap, before sample_stations kept both
// ends), every fit converged; 36 passed every gate against 87 of the same seeds without the
// errors, most of the others where a hairpin drawn to one node folded its return leg along its
// way past a junction (junctions_open 38, sumo_height_steps 46, ground_holes 8). Such a way is
// now built once where its legs' pavements overlap (osm.way_turns_back): 55 passed; and a dead
// end keeps the roll its junction gives it instead of twisting to level within a stub (seed 19's
// 1 m spur): 60 passed (8 fits by the method of multipliers); 61 once SUMO lanes were located
// again in order. Two bridges of one layer that cross without a node (a way drawn past its end
// across another bridge) are now a grade separation instead of decks through each other: seed 37
// passes, seed 1's 48 self-intersecting pairs are 5, and seed 75, which passed with its decks
// through each other, now leaves that separation's clearance violated (reported: the fit finds
// no room for 5 m there under its higher-priority limits) with 9 pairs: still 61 (measured
// 2026-11-29, 9 fits by the method of multipliers). Junctions whose ends cannot all join in a
// simple outline are paved without the end lying on another road, and dead ends the junction's
// room used up to 1 m get no SUMO edge: 67 pass. The fit bounding the grades across joined
// junctions and from roads trimmed to their last metre, and SUMO lanes draped past a 1 m road
// onto the road after it: 73 pass (measured 2026-11-29, 12 fits by the method of multipliers).
// The others fail ground_vs_dem_rmse_m 15 (the steepest terrains, as without the errors),
// fit_limits_violated 11 (clearance of a bridge that crosses a road a few metres from its
// junction: no room for 5 m; junction grades), road_self_intersections 6, and seed 58
// connecting_road_grade_over_cap_percent and sumo_height_steps (13 and 8 seeds before; there the
// fit reports its junction grade left violated), ground_holes 1. With the rows taking the roll of
// a joined junction's two-end members, each road end's cross slope bounded and connecting roads
// across their surface within their cap: still 73, self-intersections 5, connecting roads none,
// SUMO height steps 1 (seed 31, whose netconvert internal lane is stretched 20.8 m).
TEST(Fuzz, RandomNetworksWithOsmDataErrorsBuildAndCheckThemselves) {
  build_and_check_seeds(true, 1, 30, 22);  // measured 22 of 30 (11 before ways folding onto themselves)
}

// Seeds whose two-road bends were too sharp for their short roads to be trimmed back far enough:
// a transition road's inner lane border passed the bend's centre and Road_Road intersected
// itself (11 and 10 pairs). Such a bend is now a junction (model.transition_as_junction): seed
// 234's is; seed 309's roads, with the heights fitted since the rows between road ends hold at
// their cuts, are trimmed back far enough for a transition road whose lanes do not fold.
TEST(Fuzz, BendsTooTightForATransitionRoadAreJunctionsThatDoNotFold) {
  check_seeds({234u, 309u}, false, [](unsigned seed, const BuildResult& result, const Diagnostics& d) {
    const RunReport& r = result.report;
    if (seed == 234u) {
      EXPECT_GE(d.count("model.transition_as_junction"), 1u);
    }
    ASSERT_TRUE(r.opendrive);
    EXPECT_EQ(r.opendrive->transitions_as_junctions, d.count("model.transition_as_junction"));
    int checked = 0;
    for (const Gate& g : r.gates) {
      if (g.name != "road_self_intersections" && g.name != "sumo_height_steps") continue;
      EXPECT_EQ(g.value, 0.0) << g.name << " " << g.where;
      ++checked;
    }
    EXPECT_EQ(checked, 2);
    EXPECT_EQ(r.junctions.max_gap_m, 0.0);
  });
}

// Seeds whose connecting roads climbed 45 to 58 % under a 35 % cap (gate values 15.4, 22.6, 14.9
// and 16.8 % over it) although no fit limit was left violated: the rows between road ends held
// at the station beyond each cut and on the reference lines, while the lane ends the connecting
// roads join are lifted and lowered by the roll of the junction's plane (seed 350: 2 m apart in
// height at the ends of a 4 m connecting road). The rows now hold between the lane centres at
// the cuts, rolls included.
TEST(Fuzz, ConnectingRoadsBetweenRolledLaneEndsKeepTheirCap) {
  check_seeds({350u, 400u, 602u, 774u}, false, [](unsigned, const BuildResult& result, const Diagnostics&) {
    int checked = 0;
    for (const Gate& g : result.report.gates) {
      if (g.name == "connecting_road_grade_over_cap_percent" || g.name == "road_grade_over_cap_percent") {
        EXPECT_LE(g.value, 2.0) << g.name << " " << g.where;  // measured: at most 1.59 %
        EXPECT_TRUE(g.passed) << g.name;
        ++checked;
      }
      if (g.name == "fit_limits_violated") {
        EXPECT_EQ(g.value, 0.0) << g.where;
      }
    }
    EXPECT_EQ(checked, 2);
    EXPECT_EQ(result.report.junctions.max_gap_m, 0.0);
  });
}

// OSM-error seeds with dead ends the junction's room trims down to 1 m (17: a way drawn on 23 m
// past a junction and back; 21: a 14 m primary stub; 55 and 94: stubs ending on a neighbour's
// pavement). netconvert drew such a lane on past the road's end, off the OpenDRIVE surface, and
// the internal lane into it stepped (sumo_height_steps 1, 3, 0 and 2, 0.18 m at 21); at 55 and 94
// no outline joined the junction's ends and it was left open (junctions_open 1). Such a dead end
// now gets no SUMO edge (SumoOptions::min_dead_end_length_m), the junction's surface leaves out
// the end lying on another road, and every gate passes.
TEST(Fuzz, ADeadEndTrimmedTo1mGetsNoSumoEdgeAndEveryGatePasses) {
  check_seeds({17u, 21u, 55u, 94u}, true, [](unsigned seed, const BuildResult& result, const Diagnostics& d) {
    EXPECT_GE(d.count("sumo.dead_end_skipped"), 1u);
    EXPECT_EQ(d.count("mesh.junction_end_left_out"), seed == 55u || seed == 94u ? 1u : 0u);
    for (const Gate& g : result.report.gates)
      EXPECT_TRUE(g.passed) << g.name << " " << g.value << " " << g.where;
  });
}

// A bridge crossing a road a few metres from the bridge's own junction, where the 5 m clearance
// conflicts with the junction's grades: grades outrank clearances, so only the clearance is
// left violated. Before a crossing's 9 rows shared the clearance's price (as a junction's pair
// of ends shares the grade's), they outweighed the pair rows: seeds 58, 64 and 188 left junction
// grades at 41-46 % under their 31.5 % bound and connecting roads 12-23 % over the cap. Seed
// 188's 12 m bridge leaves a two-end member of a joined junction, whose plane the model rolls
// it by 0.33 rad: until the fit's rows took that roll too, its connecting road climbed 44.7 %
// under a 35 % cap (9.7 % over) with every row held (0.06 % over now; seeds 58 and 188, 12.4 and
// 9.7 % over before, are within the 2 % gate).
TEST(Fuzz, AClearanceBesideAJunctionGivesWayToItsGrades) {
  check_seeds({58u, 64u, 188u}, true, [](unsigned, const BuildResult& result, const Diagnostics&) {
    ASSERT_TRUE(result.report.fit);
    ASSERT_TRUE(result.report.model_grades);
    EXPECT_LE(result.report.model_grades->connecting_roads.max_excess_percent, 2.0);
    bool clearance = false;
    for (const FitViolation& v : result.report.fit->violations) {
      clearance |= v.limit == FitLimit::clearance;
      EXPECT_TRUE(v.limit == FitLimit::clearance || v.limit == FitLimit::vertical_curve)
          << to_string(v.limit) << " on road " << v.road << ": " << v.value << " against " << v.bound;
    }
    EXPECT_TRUE(clearance);
  });
}

}  // namespace
}  // namespace relief

// The stress corpus (issue 14, item 7): the generated mountain at 1, 30 and 90 m and the old town
// on a steep coast (tests/support/corpus.h), each built with every output. Every build must
// finish, evaluate every gate, converge and keep its junctions exactly continuous; the figures
// the geometry answers exactly are asserted with their tolerances; and every gate must pass,
// except the ones listed in kFailingGates with the reason, which are asserted to fail so that a
// fix shows up here (and the list must then be edited).
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "relief/geometry/crs_transform.h"
#include "relief/pipeline/build.h"
#include "support/corpus.h"
#include "support/synthetic.h"
#include "support/test_data.h"

namespace relief {
namespace {

// A road of the build as the GeoJSON gives it: every elevation sample in the local frame.
struct BuiltRoad {
  int id = 0;
  std::string highway;
  bool bridge = false, tunnel = false, roundabout = false;
  std::vector<std::int64_t> way_ids;
  std::vector<Vec3> samples;

  [[nodiscard]] bool from_any(const std::vector<std::int64_t>& ways) const {
    return std::any_of(way_ids.begin(), way_ids.end(),
                       [&](std::int64_t w) { return std::find(ways.begin(), ways.end(), w) != ways.end(); });
  }
  // Largest |grade| between consecutive samples (fraction), over runs of 0.5 m or more: the
  // GeoJSON rounds heights to 1 mm and positions to 1e-7 degrees (about 1 cm), which over a
  // 5 cm run next to a road's end made a 10.0 % road read 10.5 %.
  [[nodiscard]] double max_grade() const {
    double g = 0.0;
    for (std::size_t i = 1; i < samples.size(); ++i) {
      const double run = (samples[i] - samples[i - 1]).head<2>().norm();
      if (run >= 0.5) g = std::max(g, std::abs(samples[i].z() - samples[i - 1].z()) / run);
    }
    return g;
  }
};

struct Built {
  RunReport report;
  std::vector<BuiltRoad> roads;
  double seconds = 0.0;
};

std::vector<BuiltRoad> read_geojson(const std::filesystem::path& path) {
  const GeoFrame frame = test::synthetic_frame();
  const CrsTransform to_local("EPSG:4326", frame.crs());
  std::ifstream in(path);
  const nlohmann::json doc = nlohmann::json::parse(in);
  std::vector<BuiltRoad> roads;
  for (const auto& feature : doc.at("features")) {
    const auto& p = feature.at("properties");
    BuiltRoad r;
    r.id = p.at("id").get<int>();
    r.highway = p.at("class").get<std::string>();
    r.bridge = p.at("bridge").get<bool>();
    r.tunnel = p.at("tunnel").get<bool>();
    r.roundabout = p.at("roundabout").get<bool>();
    r.way_ids = p.at("osm_way_ids").get<std::vector<std::int64_t>>();
    for (const auto& c : feature.at("geometry").at("coordinates")) {
      const Vec2 xy = frame.to_local(to_local.apply(Vec2(c[0].get<double>(), c[1].get<double>())));
      r.samples.emplace_back(xy.x(), xy.y(), c[2].get<double>());
    }
    roads.push_back(std::move(r));
  }
  return roads;
}

Built build_case(const test::CorpusCase& c, const std::filesystem::path& dir) {
  BuildOptions o;
  o.osm_path = c.osm;
  o.dem_paths = {c.dem};
  o.out_dir = dir / "out";
  o.crs = test::synthetic_frame().crs();
  o.osm.bbox = c.bbox;
  // An Int16 DEM is quantised to whole metres: a terrain tolerance under half a metre meshes the
  // staircase of a 1 m DEM cell by cell (572 000 TIN vertices, 14 s, 0.7 GB on the hairpins).
  if (c.cell_m < 10.0) o.scene.terrain_options.vertical_tolerance_m = 1.0;
  Diagnostics d;
  const auto t0 = std::chrono::steady_clock::now();
  BuildResult result = build(o, d);
  Built b;
  b.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  b.report = std::move(result.report);
  b.roads = read_geojson(o.out_dir / (o.osm_path.stem().string() + ".geojson"));
  return b;
}

// What every corpus build must show, and the gates: all pass but `failing`, which must fail.
void expect_sound_build(const Built& b, const std::set<std::string>& failing) {
  const RunReport& r = b.report;
  EXPECT_EQ(r.gates.size(), GateThresholds::names().size());
  ASSERT_TRUE(r.fit);
  EXPECT_TRUE(r.fit->converged) << r.fit->solver;
  EXPECT_EQ(r.junctions.max_gap_m, 0.0);
  std::cout << r.name << ": " << r.network.roads << " roads, " << r.network.junctions << " junctions ("
            << r.network.intersections << " intersections), " << r.network.length_km << " km, "
            << r.network.bridges << " bridge roads, " << r.network.tunnels << " tunnel roads, "
            << r.void_samples << " void samples, fit " << r.fit->solver << ", " << b.seconds << " s\n";
  for (const Gate& g : r.gates) {
    std::cout << "  gate " << g.name << " = " << g.value << " (threshold " << g.threshold << ")"
              << (g.passed ? "" : " FAILED at " + g.where) << "\n";
    EXPECT_TRUE(std::isfinite(g.value)) << g.name;
    if (failing.count(g.name) != 0) {
      EXPECT_FALSE(g.passed) << g.name << " passes now: take it off the failing list";
    } else {
      EXPECT_TRUE(g.passed) << g.name << " = " << g.value << " over " << g.threshold << " at " << g.where;
    }
  }
  ASSERT_TRUE(r.mesh);
  ASSERT_TRUE(r.opendrive);
  ASSERT_TRUE(r.sumo);
}

// A figure with an exact answer: holds, or is on the case's list of known failures (then it must
// still fail, so that a fix is noticed and the list edited).
void expect_figure(const std::string& name, bool holds, const std::set<std::string>& failing) {
  if (failing.count(name) != 0) {
    EXPECT_FALSE(holds) << name << " holds now: take it off the failing list";
  } else {
    EXPECT_TRUE(holds) << name;
  }
}

// Nearest sample to `p` in plan among `roads` passing `keep`.
const Vec3* nearest_sample(const std::vector<BuiltRoad>& roads, const Vec2& p,
                           const std::function<bool(const BuiltRoad&)>& keep) {
  const Vec3* best = nullptr;
  double d_best = std::numeric_limits<double>::infinity();
  for (const BuiltRoad& r : roads) {
    if (!keep(r)) continue;
    for (const Vec3& s : r.samples) {
      const double d = (s.head<2>() - p).norm();
      if (d < d_best) {
        d_best = d;
        best = &s;
      }
    }
  }
  return d_best < 5.0 ? best : nullptr;
}

double distance_to_nearest(const Vec2& p, const std::vector<Vec2>& points) {
  double d = std::numeric_limits<double>::infinity();
  for (const Vec2& q : points) d = std::min(d, (p - q).norm());
  return d;
}

// Gates and figures known to fail on a case today, each with its reason at the call.
struct KnownFailures {
  std::set<std::string> gates;
  std::set<std::string> figures;
};

void check_mountain(double cell_m, const KnownFailures& failing) {
  const auto dir = test::scratch_dir("mountain");
  const test::CorpusCase c = test::make_mountain(cell_m, dir);
  const test::MountainFeatures& f = test::mountain_features();
  std::cout << "mountain " << cell_m << " m: " << c.ways << " ways, " << c.road_km
            << " km written, trunk climb " << f.trunk_climb_m << " m at " << 100.0 * f.trunk_design_grade
            << " %, loop clearance " << f.loop_design_clearance_m << " m, crest " << f.crest_m
            << " m, trunk cut/fill RMS " << f.trunk_cut_fill_rms_m << " m, max " << f.trunk_cut_fill_max_m
            << " m\n";
  const Built b = build_case(c, dir);
  expect_sound_build(b, failing.gates);
  const RunReport& r = b.report;

  // The trunk's grade as fitted, bridge included: its cap (10 % for trunks) + 0.5 %.
  double trunk_grade = 0.0;
  for (const BuiltRoad& road : b.roads)
    if (road.from_any(f.trunk.way_ids)) trunk_grade = std::max(trunk_grade, road.max_grade());
  std::cout << "  trunk max grade " << 100.0 * trunk_grade << " %\n";
  expect_figure("trunk_grade", trunk_grade <= 0.105, failing.figures);

  // The spiral's bridge over the trunk's first leg.
  const Vec3* upper = nearest_sample(
      b.roads, f.loop_crossing, [&](const BuiltRoad& road) { return road.from_any({f.loop_bridge_way}); });
  const Vec3* lower = nearest_sample(b.roads, f.loop_crossing, [&](const BuiltRoad& road) {
    return road.from_any(f.trunk.way_ids) && !road.bridge;
  });
  ASSERT_TRUE(upper != nullptr && lower != nullptr);
  std::cout << "  loop crossing clearance " << upper->z() - lower->z() << " m (designed "
            << f.loop_design_clearance_m << ")\n";
  expect_figure("loop_clearance", upper->z() - lower->z() >= 4.5, failing.figures);

  if (cell_m >= 10.0) {
    // The base tunnel keeps its clearance under the ridge beyond 50 m from its portals, and
    // its designed line (0.5 % between portals that lie on the ground): no data term pulls a
    // tunnel anchored at its portals, so its grade stays under 2 %.
    double min_cover = std::numeric_limits<double>::infinity();
    double max_tunnel_z = -1e9, tunnel_grade = 0.0;
    for (const BuiltRoad& road : b.roads) {
      if (!road.from_any(f.tunnel_ways)) continue;
      tunnel_grade = std::max(tunnel_grade, road.max_grade());
      for (const Vec3& s : road.samples) {
        max_tunnel_z = std::max(max_tunnel_z, s.z());
        if (distance_to_nearest(s.head<2>(), f.tunnel_portals) > 50.0)
          min_cover = std::min(min_cover, c.ground(s.head<2>()) - s.z());
      }
    }
    std::cout << "  tunnel min cover " << min_cover << " m, highest point " << max_tunnel_z
              << " m, max grade " << 100.0 * tunnel_grade << " %\n";
    expect_figure("tunnel_cover", min_cover >= 5.0, failing.figures);
    expect_figure("tunnel_grade", tunnel_grade <= 0.02, failing.figures);
    // Each tunnel road (the tunnel to its branch, the branch, the tunnel on) stays near the chord
    // between its ends beyond 100 m from them: nothing but the smoothing and its span shapes it
    // there, besides the ramps from portals off the designed line (tunnel_grade below). Before
    // the fit pulled every structure station towards its span, the smoothing alone left shapes
    // of next to no cost free and the solver's tolerance put humps in them: 11.1 m off the chords
    // (30 m and 90 m DEMs); with the pull 2.2 m and 2.0 m, the portals' ramps.
    double max_off_chord = 0.0;
    for (const BuiltRoad& road : b.roads) {
      if (!road.from_any(f.tunnel_ways) || road.samples.size() < 2) continue;
      const Vec3& a = road.samples.front();
      const Vec3& z = road.samples.back();
      const double length = (z.head<2>() - a.head<2>()).norm();
      for (const Vec3& s : road.samples) {
        const double t = (s.head<2>() - a.head<2>()).norm();
        if (t < 100.0 || length - t < 100.0) continue;
        max_off_chord = std::max(max_off_chord, std::abs(s.z() - (a.z() + (z.z() - a.z()) * t / length)));
      }
    }
    std::cout << "  tunnel roads off their chords by up to " << max_off_chord << " m\n";
    expect_figure("tunnel_chord", max_off_chord <= 3.0, failing.figures);

    // The viaduct stays above the valley beyond 100 m from its abutments (the valley's rims are
    // rounded over 30 m, 60 m in from the abutments).
    double min_height = std::numeric_limits<double>::infinity(), max_height = 0.0;
    for (const BuiltRoad& road : b.roads) {
      if (!road.from_any({f.viaduct_way})) continue;
      for (const Vec3& s : road.samples) {
        if (distance_to_nearest(s.head<2>(), {f.viaduct_abutment_south, f.viaduct_abutment_north}) > 100.0) {
          min_height = std::min(min_height, s.z() - c.ground(s.head<2>()));
          max_height = std::max(max_height, s.z() - c.ground(s.head<2>()));
        }
      }
    }
    std::cout << "  viaduct height over the valley " << min_height << " .. " << max_height << " m\n";
    expect_figure("viaduct_height", min_height >= 5.0, failing.figures);

    // The roundabout on the 12 % apron: its ring climbs and falls with it.
    double ring_grade = 0.0;
    for (const BuiltRoad& road : b.roads)
      if (road.roundabout) ring_grade = std::max(ring_grade, road.max_grade());
    std::cout << "  roundabout ring max grade " << 100.0 * ring_grade << " %\n";
    expect_figure("roundabout_grade", ring_grade <= f.roundabout_slope + 0.01, failing.figures);
    EXPECT_EQ(r.network.roundabouts, 1u);
  }
}

// Known failures (measured at this commit):
// - tunnel_grade: the base tunnel (designed at 0.5 % between portals on the ground) reaches its
//   class's 12 % at a portal: the portal heights come from the ground roads meeting there, which
//   follow the 30 m / 90 m DEM of the 35 % flank, metres off the designed portal, and the
//   tunnel takes that step at its cap near the portal. Its line between the portals is straight now
//   (it humped up to 859 m under the crest when the weak pull of a structure went to the DEM
//   above it, and 18 m over its portals with a bridge deck's stiffness; cover now >= 7 m).
// - ground_vs_dem_rmse_m (90 m only): a 90 m cell cannot show the trunk's platform, whose
//   designed cut and fill reaches 23 m (RMS 12 m) where the hairpins turn on the 35 % flank; the
//   fit holds the trunk to 10 % and so departs from the blurred DEM (RMSE 2.95 m over 2 m).
TEST(Corpus, MountainAt30m) {
  check_mountain(30.0, {{}, {"tunnel_grade"}});
}
TEST(Corpus, MountainAt90m) {
  check_mountain(90.0, {{"ground_vs_dem_rmse_m"}, {"tunnel_grade"}});
}
TEST(Corpus, MountainAt1m) {
  check_mountain(1.0, {});
}

// Two mountains side by side (the generator of the scale benchmark, bench/mountain_range.sh):
// the terrain joins without a step, the valley link joins the two networks, and the build is as
// sound as one mountain's.
TEST(Corpus, MountainRangeOfTwo) {
  const auto dir = test::scratch_dir("mountain_range");
  const test::CorpusCase one = test::make_mountain(30.0, dir);
  const test::CorpusCase c = test::make_mountain_range(2, 30.0, dir);
  EXPECT_EQ(c.ways, 2 * one.ways + 1);
  EXPECT_NEAR(c.road_km, 2.0 * one.road_km + 0.4, 1e-9);
  EXPECT_EQ(c.void_centres.size(), 2 * one.void_centres.size());
  double step = 0.0;  // across the seam at x = 2400, over the DEM's whole height
  for (double y = -2250.0; y <= 5050.0; y += 10.0)
    step = std::max(step, std::abs(c.ground(Vec2(2400.01, y)) - c.ground(Vec2(2399.99, y))));
  EXPECT_LT(step, 0.01);
  EXPECT_THROW((void)test::make_mountain_range(0, 30.0, dir), std::invalid_argument);

  const Built b = build_case(c, dir);
  expect_sound_build(b, {});
  EXPECT_NEAR(b.report.network.length_km, c.road_km, 0.05 * c.road_km);
}

TEST(Corpus, OldTownOnASteepCoast) {
  const auto dir = test::scratch_dir("old_town");
  const test::CorpusCase c = test::make_old_town(dir);
  const test::OldTownFeatures& f = test::old_town_features();
  std::cout << "old town: " << c.ways << " ways, " << c.road_km << " km written\n";
  const Built b = build_case(c, dir);
  expect_sound_build(b, {});

  // Steps and footways are not built (BuildOptions::osm.include_non_motor is off).
  for (const BuiltRoad& road : b.roads) EXPECT_FALSE(road.from_any(f.path_ways)) << road.id;
  // The tunnel under the hill keeps its clearance beyond 50 m from its mouths.
  double min_cover = std::numeric_limits<double>::infinity();
  for (const BuiltRoad& road : b.roads) {
    if (!road.from_any(f.tunnel_ways)) continue;
    for (const Vec3& s : road.samples)
      if (distance_to_nearest(s.head<2>(), f.tunnel_portals) > 50.0)
        min_cover = std::min(min_cover, c.ground(s.head<2>()) - s.z());
  }
  std::cout << "  tunnel min cover " << min_cover << " m\n";
  EXPECT_GE(min_cover, 5.0);
  EXPECT_EQ(b.report.network.tunnels, 1u);
  // Streets up the 20 % slope.
  double grade = 0.0;
  for (const BuiltRoad& road : b.roads)
    if (road.from_any(f.oneway_ways)) grade = std::max(grade, road.max_grade());
  std::cout << "  one-way streets max grade " << 100.0 * grade << " %\n";
  // The 20 % slope steepens to 32 % on the hill's foot at the top row: the street cap (35 %).
  EXPECT_LE(grade, 0.355);
  EXPECT_GE(grade, 0.20);
}

}  // namespace
}  // namespace relief

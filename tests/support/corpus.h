#pragma once
// The stress corpus (issue 14, item 7): two generated worlds, an Alpine mountain and an old town
// on a steep coast, each an OSM XML file and an SRTM-like DEM (Int16 whole metres, nodata
// -32768, with voids) made by code, with the analytic answers the tests assert against.
//
// Both live in the synthetic frame (synthetic.h, UTM 10N); x is east and y north in metres.
// Every ground road the generator designs at its own grade is embedded in the terrain the way a
// lidar DEM shows a real road: a 7 m platform at the designed height, batters of 1.5:1 back to
// the natural slope. So the DEM under such a road IS its design profile (up to the Int16
// rounding and the cell size), and a fitted profile has an exact answer to be compared with.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "relief/geometry/types.h"

namespace relief::test {

/// A road of the corpus as written to the OSM file: its way ids (a road split into several ways
/// keeps them in order) and its centreline in the local frame.
struct CorpusRoad {
  std::vector<std::int64_t> way_ids;
  Polyline2 centreline;
};

struct CorpusCase {
  std::filesystem::path osm;
  std::string dem;
  double cell_m = 0.0;
  std::optional<LonLatBox> bbox;  ///< clip the roads to this box (the 1 m mountain: its hairpins)
  std::size_t ways = 0;           ///< ways written (before any clipping)
  double road_km = 0.0;           ///< plan length of the highway ways written (before clipping)
  /// Height of the terrain the DEM samples (natural ground + embedded road platforms), local
  /// frame, before the Int16 rounding and without the voids.
  std::function<double(const Vec2&)> ground;
  std::vector<Vec2> void_centres;  ///< holes of the DEM
  std::vector<double> void_radii_m;
};

/// The mountain's named features, shared by the three resolutions.
struct MountainFeatures {
  double crest_m = 0.0;  ///< natural height of the ridge's crest line
  /// Trunk road from the valley road up the south flank: 3 ways (climb to the loop, the loop's
  /// bridge, the rest of the climb) that share their end nodes.
  CorpusRoad trunk;
  double trunk_design_grade = 0.0;  ///< grade of its designed profile on the flank (fraction)
  double trunk_climb_m = 0.0;       ///< designed climb, foot to top
  /// Designed minus natural height along the trunk's ground parts (the cut and fill its
  /// platform needs): RMS and largest. A DEM too coarse to show the platform gives the natural.
  double trunk_cut_fill_rms_m = 0.0, trunk_cut_fill_max_m = 0.0;
  std::int64_t loop_bridge_way = 0;       ///< the spiral hairpin's bridge (bridge=yes, layer=1)
  Vec2 loop_crossing = Vec2::Zero();      ///< where the bridge passes over the trunk's lower leg
  double loop_design_clearance_m = 0.0;   ///< designed height of the upper pass over the lower
  std::vector<std::int64_t> tunnel_ways;  ///< main tunnel (2 ways, split at the inner junction) + side branch
  std::vector<Vec2> tunnel_portals;       ///< south, north, branch
  std::int64_t viaduct_way = 0;           ///< the bridge part of the valley crossing
  Vec2 viaduct_abutment_south = Vec2::Zero(), viaduct_abutment_north = Vec2::Zero();
  Vec2 roundabout_centre = Vec2::Zero();
  double roundabout_radius_m = 0.0;
  double roundabout_slope = 0.0;  ///< terrain grade at the roundabout (fraction)
};

/// The mountain world's features (no files written).
[[nodiscard]] const MountainFeatures& mountain_features();

/// Writes the mountain at `cell_m` (1, 30 or 90) into `dir`: the whole world for 30 and 90 m; for
/// cells under 10 m only the hairpin flank (about 1.4 x 2.5 km of DEM) with `bbox` set to clip the
/// roads to it.
[[nodiscard]] CorpusCase make_mountain(double cell_m, const std::filesystem::path& dir);

/// Writes `copies` mountains side by side (3.5 km apart west to east, each valley road linked to
/// the next by a 400 m road) with one DEM at `cell_m` into `dir`: the scale benchmark's network
/// (issue 14, item 8; 18 copies are about 410 km of road).
[[nodiscard]] CorpusCase make_mountain_range(int copies, double cell_m, const std::filesystem::path& dir);

/// The old town's named features.
struct OldTownFeatures {
  double slope = 0.0;                     ///< grade of the coastal slope the grid lies on (fraction)
  std::vector<std::int64_t> oneway_ways;  ///< the grid's narrow one-way streets
  std::vector<std::int64_t> tunnel_ways;
  std::vector<Vec2> tunnel_portals;
  std::vector<std::int64_t> close_pair;  ///< two parallel streets 4 m apart, each 6 m wide
  std::vector<std::int64_t> path_ways;   ///< steps and a footway ramp (not built by default)
};

[[nodiscard]] const OldTownFeatures& old_town_features();

/// Writes the old town (30 m Int16 DEM with a void) into `dir`.
[[nodiscard]] CorpusCase make_old_town(const std::filesystem::path& dir);

}  // namespace relief::test

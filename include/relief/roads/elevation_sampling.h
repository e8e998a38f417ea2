#pragma once
// Elevation assignment (the seed paper's Algorithm 1): every road sampled every `spacing_m`
// along its centreline plus at every OSM node, each sample's height taken from the DEM.

#include <cstdint>
#include <vector>

#include "relief/core/diagnostics.h"
#include "relief/roads/road_network.h"
#include "relief/terrain/dem_sampler.h"

namespace relief {

/// What to do with samples where the DEM has no valid height (a void with no valid corner).
enum class NodataFill {
  interpolate,  ///< linear along the road between the nearest valid samples (ends: nearest valid,
                ///< or the height of the junction from the other roads there)
  error,        ///< refuse: throw InvalidInput naming the first road with a void
};
[[nodiscard]] std::optional<NodataFill> parse_nodata_fill(std::string_view text);
[[nodiscard]] std::string_view to_string(NodataFill fill);

struct SamplingOptions {
  double spacing_m = 1.0;  ///< finite, > 0
  NodataFill nodata_fill = NodataFill::interpolate;
  /// Accept roads partly or wholly outside every DEM (filled like voids; roads with no height
  /// at all are marked has_height = false). Without it, any uncovered sample is a CoverageError.
  bool allow_partial = false;
  /// Largest estimate_sample_count() a run may take (> 0): a whole build holds about 0.7 kB of
  /// working memory per sample (profiles, the profile fit, validation), so the default 1.5e7 is
  /// about 10 GB. Measured on the sf-ne set with /usr/bin/time -v, `--outputs report`: 132 k
  /// samples (1 m spacing) peak at 197 MB, 2.6 M samples (0.05 m) at 1.86 GB, i.e. 0.71 kB for
  /// each extra sample (0.68 kB between 0.25 m and 0.1 m with all outputs).
  double max_samples = 1.5e7;
};

/// Upper estimate of the samples sample_elevation takes: the sum over the roads of
/// length / spacing_m + their OSM node count (every spacing_m plus every vertex; a 100 m road
/// of 2 nodes at 1 m: 102 for its 101 samples). A double: 1e-6 m over a city is ~1e11.
/// Throws OptionError unless spacing_m is finite and > 0.
[[nodiscard]] double estimate_sample_count(const RoadNetwork& network, double spacing_m);

/// Refuses, before any sampling, options whose cost would exhaust the machine: throws
/// OptionError when estimate_sample_count exceeds options.max_samples, naming the estimate, the
/// road length, the memory, the limit and the smallest spacing that fits ("sample spacing
/// 1e-06 m would take 7.7e+09 elevation samples for 7.7 km of road and 1306 OSM nodes, about
/// 5.4 TB of memory (limit 1.5e+07 samples, 10 GB): use a spacing of at least 0.00052 m");
/// OptionError too for a spacing that is not finite and > 0 and a max_samples not > 0.
void check_sample_budget(const RoadNetwork& network, const SamplingOptions& options);

/// Heights along one road. All vectors have one entry per sample.
struct RoadProfile {
  std::vector<double> s;              ///< arc length from the road's start (m), s[0] = 0
  std::vector<Vec2> xy;               ///< local frame
  std::vector<double> z;              ///< metres
  std::vector<std::uint8_t> at_node;  ///< 1 where the sample is an OSM node of the road
  std::vector<std::uint8_t> filled;   ///< 1 where the DEM had no height and z was filled
  /// Arc length along the road as driven at each station (road_model_builder.h,
  /// driven_stations), when known; empty: s. The fit takes grades and curvatures along it.
  std::vector<double> driven_s;
  bool has_height = true;  ///< false: no height could be found for any sample

  [[nodiscard]] std::size_t size() const { return s.size(); }
};

struct ElevationSamples {
  std::vector<RoadProfile> profiles;  ///< parallel to RoadNetwork::roads
  std::size_t samples = 0;
  std::size_t void_samples = 0;       ///< inside the DEM extent but nodata (filled)
  std::size_t uncovered_samples = 0;  ///< outside every DEM (filled, only with allow_partial)
  std::size_t roads_without_height = 0;
};

/// Stations along a road: every spacing_m plus every vertex (a 100 m straight road at 1 m
/// spacing gives 101 samples). Stations closer than spacing_m / 4 are merged, a vertex winning
/// over a grid station, so no segment is shorter than that except between two vertices.
[[nodiscard]] RoadProfile make_stations(const Road& road, double spacing_m);

/// Height at arc length `s` along a profile, linear between stations (clamped to the ends).
[[nodiscard]] double height_at_station(const RoadProfile& profile, double s);

/// Samples every road. Throws OptionError first when check_sample_budget refuses the options;
/// CoverageError when samples fall outside every DEM and !allow_partial (the message gives the
/// uncovered share and a location); InvalidInput under NodataFill::error when a sample is a
/// void. Voids and fills are reported to `diagnostics`
/// ("elevation.void", "elevation.uncovered", "elevation.road_without_height").
[[nodiscard]] ElevationSamples sample_elevation(const RoadNetwork& network, const DemSampler& dem,
                                                const SamplingOptions& options, Diagnostics& diagnostics);

}  // namespace relief

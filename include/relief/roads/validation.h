#pragma once
// The seed paper's validation framework: height errors against the DEM that was used and an
// independent reference DEM, gradients and their compliance with per-class limits, junction
// elevation gaps, and network counts.

#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "relief/roads/elevation_sampling.h"
#include "relief/roads/road_network.h"
#include "relief/terrain/dem_sampler.h"

namespace relief {

/// Error statistics of heights against a reference (metres).
struct ErrorStats {
  double mae_m = 0.0;
  double rmse_m = 0.0;
  double max_m = 0.0;   ///< largest absolute error
  double bias_m = 0.0;  ///< mean signed error (road minus reference)
  std::size_t n = 0;
  std::size_t max_at = 0;  ///< index (into the values) of the largest absolute error
};

/// Statistics of `values[i] - reference[i]` over pairs where both are present.
[[nodiscard]] ErrorStats error_stats(std::span<const double> values,
                                     std::span<const std::optional<double>> reference);

/// Maximum grade in percent per road class. Defaults from the seed paper: 8 % motorway/trunk
/// (and links), 12 % primary/secondary/tertiary (and links), 15 % every other street.
struct GradeLimits {
  std::map<HighwayClass, double> percent;

  [[nodiscard]] static GradeLimits paper();
  [[nodiscard]] double limit_for(HighwayClass cls) const;
  /// Applies "motorway=8,primary=10,..." (classes or the groups "highway", "arterial",
  /// "local"); throws InvalidInput on an unknown class or a bad number.
  void apply_overrides(std::string_view text);
};

/// Grade statistics, weighted by segment length.
struct GradeClassStats {
  double length_km = 0.0;
  double limit_percent = 0.0;
  double compliance_percent = 100.0;  ///< share of length with |grade| <= limit
  double max_percent = 0.0;           ///< largest |grade|
  double p99_percent = 0.0;           ///< 99th percentile of |grade| by length
};

struct GradeStats {
  double compliance_percent = 100.0;
  double max_percent = 0.0;
  double p99_percent = 0.0;
  std::optional<int> steepest_road;
  std::map<std::string, GradeClassStats> by_class;  ///< keyed by highway class name
};

/// |grade| of each segment between consecutive samples (percent, dz over horizontal ds).
[[nodiscard]] std::vector<double> segment_grades_percent(const RoadProfile& profile);

[[nodiscard]] GradeStats grade_stats(const RoadNetwork& network, const std::vector<RoadProfile>& profiles,
                                     const GradeLimits& limits);

struct JunctionGapStats {
  double max_gap_m = 0.0;  ///< largest z spread among the road ends at one junction
  std::optional<int> worst_junction;
  std::size_t over_bound = 0;  ///< junctions whose gap exceeds bound_m
  double bound_m = 0.1;
  std::size_t checked = 0;  ///< junctions with two or more road ends
};

[[nodiscard]] JunctionGapStats junction_gaps(const RoadNetwork& network,
                                             const std::vector<RoadProfile>& profiles, double bound_m = 0.1);

struct NetworkStats {
  std::size_t roads = 0;
  std::size_t junctions = 0;  ///< intersections + attribute changes (not dead ends)
  std::size_t intersections = 0;
  std::size_t attribute_changes = 0;
  std::size_t dead_ends = 0;
  std::size_t roundabouts = 0;
  std::size_t traffic_signals = 0;  ///< junctions carrying a signal
  std::size_t bridges = 0;          ///< roads
  std::size_t tunnels = 0;          ///< roads
  double length_km = 0.0;
  double bridge_km = 0.0;
  double tunnel_km = 0.0;
  std::map<std::string, double> km_by_class;
};

[[nodiscard]] NetworkStats network_stats(const RoadNetwork& network);

/// Height errors of the road model.
struct HeightValidation {
  /// Road surface (piecewise linear between samples) against the DEM used, at the midpoints
  /// between samples: how far the road model departs from the DEM between its samples.
  ErrorStats vs_dem;
  /// Point-to-surface distance of those midpoints: |dz| / sqrt(1 + |grad z|^2).
  double error_3d_mean_m = 0.0;
  double error_3d_max_m = 0.0;
  /// Road samples against an independent reference DEM, when one is given.
  std::optional<ErrorStats> vs_reference;
  /// Where vs_dem's largest error lies: the road (index into the profiles; -1 when none), the
  /// midpoint, and the road minus the DEM there.
  int max_road = -1;
  Vec2 max_xy = Vec2::Zero();
  double max_error_m = 0.0;
  std::int64_t max_osm_way = 0;  ///< that road's first OSM way (set by the caller that knows it)
};

/// Validates profiles that share the stations of `stations` (every method of making the
/// profiles keeps the raw stations). The DEM heights and gradients at the midpoints and the
/// reference heights at the stations are read once, at construction.
class HeightValidator {
 public:
  HeightValidator(const std::vector<RoadProfile>& stations, const DemSampler& dem,
                  const DemSampler* reference);

  /// Figures of the roads selected by `road_mask` (one flag per road; empty = all roads).
  [[nodiscard]] HeightValidation validate(const std::vector<RoadProfile>& profiles,
                                          std::span<const std::uint8_t> road_mask = {}) const;

 private:
  std::vector<std::size_t> first_midpoint_;  // per road, index of its first midpoint
  std::vector<std::optional<double>> dem_mid_;
  std::vector<std::optional<Vec2>> gradient_mid_;
  std::vector<std::size_t> first_station_;  // per road, index of its first station
  std::vector<std::optional<double>> reference_;
  bool has_reference_ = false;
};

/// How far a profile departs from the terrain (the raw DEM drape) on roads on the ground:
/// fill where it runs above the terrain, cut where below.
struct CutFillStats {
  double max_fill_m = 0.0;
  double max_cut_m = 0.0;  ///< as a positive depth
  double mean_abs_m = 0.0;
  double km_over_0_5_m = 0.0;     ///< length departing by more than 0.5 m
  double km_over_2_m = 0.0;       ///< ... by more than 2 m
  std::optional<int> worst_road;  ///< where the largest departure is
  double worst_s_m = 0.0;
};

/// Compares `profiles` with `terrain` (same stations) on the roads where `road_mask` is set.
[[nodiscard]] CutFillStats cut_fill(const std::vector<RoadProfile>& profiles,
                                    const std::vector<RoadProfile>& terrain,
                                    std::span<const std::uint8_t> road_mask = {});

/// 1 for roads on the ground (neither bridge nor tunnel), 0 for structures; `structures`
/// inverts it.
[[nodiscard]] std::vector<std::uint8_t> ground_mask(const RoadNetwork& network, bool structures = false);

}  // namespace relief

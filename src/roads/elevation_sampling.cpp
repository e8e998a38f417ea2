#include "relief/roads/elevation_sampling.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "relief/core/diagnostic_codes.h"
#include "relief/core/errors.h"
#include "relief/geometry/polyline.h"

namespace relief {
namespace {

std::string describe_road(const Road& road) {
  std::ostringstream out;
  out << "road " << road.id;
  if (!road.osm_way_ids.empty()) out << " (OSM way " << road.osm_way_ids.front() << ")";
  if (!road.attributes.name.empty()) out << " '" << road.attributes.name << "'";
  return out.str();
}

// Reports that `count` of a road's `total` samples had no DEM height (`where`) and were filled.
void report_filled(Diagnostics& diagnostics, const DiagnosticCode& code, const Road& road, std::size_t count,
                   std::size_t total, const char* where) {
  Diagnostic d;
  d.code = code;
  d.road_id = road.id;
  if (!road.osm_way_ids.empty()) d.osm_way_id = road.osm_way_ids.front();
  d.message = describe_road(road) + ": " + std::to_string(count) + " of " + std::to_string(total) +
              " samples " + where + ", filled along the road";
  diagnostics.report(std::move(d));
}

// Fills the missing heights of one profile: ends from the junction heights when known, then
// linear interpolation in s between valid samples, then the nearest valid sample at the ends.
// Returns false when no height at all could be found.
bool fill_profile(RoadProfile& p, const std::vector<std::uint8_t>& valid, std::optional<double> start_height,
                  std::optional<double> end_height) {
  std::vector<std::uint8_t> known = valid;
  const std::size_t n = p.size();
  if (!known.front() && start_height) {
    p.z.front() = *start_height;
    known.front() = 1;
  }
  if (!known.back() && end_height) {
    p.z.back() = *end_height;
    known.back() = 1;
  }
  std::optional<std::size_t> prev;
  for (std::size_t i = 0; i < n; ++i) {
    if (!known[i]) continue;
    if (prev && i > *prev + 1) {
      const double s0 = p.s[*prev], s1 = p.s[i], z0 = p.z[*prev], z1 = p.z[i];
      for (std::size_t k = *prev + 1; k < i; ++k) p.z[k] = z0 + (z1 - z0) * (p.s[k] - s0) / (s1 - s0);
    }
    prev = i;
  }
  if (!prev) return false;
  const auto first = static_cast<std::size_t>(std::find(known.begin(), known.end(), 1) - known.begin());
  for (std::size_t k = 0; k < first; ++k) p.z[k] = p.z[first];
  for (std::size_t k = *prev + 1; k < n; ++k) p.z[k] = p.z[*prev];
  return true;
}

// Working memory of a build per elevation sample (see SamplingOptions::max_samples).
constexpr double kBytesPerSample = 700.0;

void require_spacing(double spacing_m) {
  if (!(std::isfinite(spacing_m) && spacing_m > 0.0)) {
    std::ostringstream msg;
    msg << "the sample spacing must be a finite number of metres > 0 (got " << spacing_m << ")";
    throw OptionError(msg.str());
  }
}

// `value` rounded up to 2 significant digits (for a bound the user must stay above).
double round_up_2(double value) {
  const double unit = std::pow(10.0, std::floor(std::log10(value)) - 1.0);
  return std::ceil(value / unit - 1e-9) * unit;
}

// "91 TB": 2 significant digits in the largest unit not above the value.
std::string format_bytes(double bytes) {
  const char* units[] = {"kB", "MB", "GB", "TB", "PB", "EB"};
  std::size_t u = 0;
  double value = bytes / 1e3;
  while (value >= 1e3 && u + 1 < std::size(units)) {
    value /= 1e3;
    ++u;
  }
  std::ostringstream out;
  out << std::setprecision(2) << value << " " << units[u];
  return out.str();
}

}  // namespace

double estimate_sample_count(const RoadNetwork& network, double spacing_m) {
  require_spacing(spacing_m);
  double samples = 0.0;
  for (const Road& road : network.roads) {
    samples += length_m(road.points) / spacing_m + static_cast<double>(road.points.size());
  }
  return samples;
}

void check_sample_budget(const RoadNetwork& network, const SamplingOptions& options) {
  require_spacing(options.spacing_m);
  if (!(options.max_samples > 0.0)) {
    std::ostringstream msg;
    msg << "the sample limit must be > 0 (got " << options.max_samples << ")";
    throw OptionError(msg.str());
  }
  const double samples = estimate_sample_count(network, options.spacing_m);
  if (samples <= options.max_samples) return;
  double length = 0.0;
  double nodes = 0.0;
  for (const Road& road : network.roads) {
    length += length_m(road.points);
    nodes += static_cast<double>(road.points.size());
  }
  std::ostringstream msg;
  msg << std::setprecision(2) << "sample spacing " << options.spacing_m << " m would take " << samples
      << " elevation samples for " << std::fixed << std::setprecision(1) << length / 1000.0
      << " km of road and " << std::setprecision(0) << nodes << " OSM nodes, about "
      << format_bytes(samples * kBytesPerSample) << " of memory (limit " << std::defaultfloat
      << std::setprecision(2) << options.max_samples << " samples, "
      << format_bytes(options.max_samples * kBytesPerSample) << "): ";
  if (nodes < options.max_samples) {
    msg << "use a spacing of at least " << round_up_2(length / (options.max_samples - nodes)) << " m";
  } else {
    msg << "the roads' nodes alone exceed it: build a smaller area (--bbox)";
  }
  throw OptionError(msg.str());
}

std::optional<NodataFill> parse_nodata_fill(std::string_view text) {
  if (text == "interpolate") return NodataFill::interpolate;
  if (text == "error") return NodataFill::error;
  return std::nullopt;
}

std::string_view to_string(NodataFill fill) {
  return fill == NodataFill::interpolate ? "interpolate" : "error";
}

double height_at_station(const RoadProfile& p, double s) {
  if (p.s.empty()) throw InvalidInput("height_at_station: empty profile");
  if (s <= p.s.front()) return p.z.front();
  if (s >= p.s.back()) return p.z.back();
  const auto it = std::upper_bound(p.s.begin(), p.s.end(), s);
  const auto i = static_cast<std::size_t>(it - p.s.begin());
  const double t = (s - p.s[i - 1]) / (p.s[i] - p.s[i - 1]);
  return p.z[i - 1] + t * (p.z[i] - p.z[i - 1]);
}

RoadProfile make_stations(const Road& road, double spacing_m) {
  const std::vector<double> cumulative = cumulative_length(road.points);
  RoadProfile p;
  // Stations closer than a quarter spacing share one (an OSM node wins over a grid station):
  // slivers of road a few millimetres long would carry meaningless grades.
  p.s = sample_stations(cumulative.back(), spacing_m, cumulative, 0.25 * spacing_m);
  p.xy.reserve(p.s.size());
  p.at_node.assign(p.s.size(), 0);
  // Stations and vertices are both sorted: mark the stations that are vertices in one sweep.
  std::size_t v = 0;
  for (std::size_t i = 0; i < p.s.size(); ++i) {
    p.xy.push_back(point_at(road.points, cumulative, p.s[i]));
    while (v < cumulative.size() && cumulative[v] < p.s[i] - 1e-9) ++v;
    if (v < cumulative.size() && std::abs(cumulative[v] - p.s[i]) <= 1e-9) p.at_node[i] = 1;
  }
  p.z.assign(p.s.size(), 0.0);
  p.filled.assign(p.s.size(), 0);
  return p;
}

ElevationSamples sample_elevation(const RoadNetwork& network, const DemSampler& dem,
                                  const SamplingOptions& options, Diagnostics& diagnostics) {
  check_sample_budget(network, options);
  ElevationSamples result;
  result.profiles.reserve(network.roads.size());
  std::vector<std::size_t> offset(network.roads.size() + 1, 0);
  for (const Road& road : network.roads) {
    result.profiles.push_back(make_stations(road, options.spacing_m));
    offset[result.profiles.size()] = offset[result.profiles.size() - 1] + result.profiles.back().size();
  }
  result.samples = offset.back();

  // One batched DEM query for every sample of every road.
  std::vector<Vec2> points;
  points.reserve(result.samples);
  for (const auto& p : result.profiles) points.insert(points.end(), p.xy.begin(), p.xy.end());
  // A sample whose interpolation weighs a void cell counts as in the void and is filled along
  // the road: the renormalised weights jump at a void's centre, from one neighbour's height to
  // the other's (149 m on a steep path through an SRTM void). Only a road with no sample clear
  // of voids takes the renormalised heights, rather than none.
  std::vector<std::optional<double>> heights(points.size());
  dem.heights_at(points, heights, NearVoid::no_height);
  for (std::size_t r = 0; r < network.roads.size(); ++r) {
    const auto first = heights.begin() + static_cast<std::ptrdiff_t>(offset[r]);
    const auto last = heights.begin() + static_cast<std::ptrdiff_t>(offset[r + 1]);
    if (std::any_of(first, last, [](const std::optional<double>& h) { return h.has_value(); })) continue;
    const std::span<const Vec2> road_points(points.data() + offset[r], offset[r + 1] - offset[r]);
    dem.heights_at(road_points, std::span<std::optional<double>>(&*first, road_points.size()));
  }

  const Aabb2 coverage = dem.coverage_bounds();
  std::vector<std::vector<std::uint8_t>> valid(network.roads.size());
  std::optional<std::size_t> first_uncovered;
  for (std::size_t r = 0; r < network.roads.size(); ++r) {
    RoadProfile& p = result.profiles[r];
    valid[r].assign(p.size(), 0);
    std::size_t voids = 0, uncovered = 0;
    for (std::size_t i = 0; i < p.size(); ++i) {
      const auto& h = heights[offset[r] + i];
      if (h) {
        p.z[i] = *h;
        valid[r][i] = 1;
      } else {
        p.filled[i] = 1;
        if (coverage.contains(p.xy[i])) {
          ++voids;
        } else {
          ++uncovered;
          if (!first_uncovered) first_uncovered = offset[r] + i;
        }
      }
    }
    result.void_samples += voids;
    result.uncovered_samples += uncovered;
    const Road& road = network.roads[r];
    if (voids > 0) {
      if (options.nodata_fill == NodataFill::error) {
        throw InvalidInput("the DEM has no height (a void) under " + describe_road(road) + ": " +
                           std::to_string(voids) + " of " + std::to_string(p.size()) +
                           " samples; use --nodata-fill interpolate to fill along the road");
      }
      report_filled(diagnostics, codes::kElevationVoid, road, voids, p.size(), "in a DEM void");
    }
    if (uncovered > 0 && options.allow_partial) {
      report_filled(diagnostics, codes::kElevationUncovered, road, uncovered, p.size(), "outside every DEM");
    }
  }

  if (result.uncovered_samples > 0 && !options.allow_partial) {
    const double percent =
        100.0 * static_cast<double>(result.uncovered_samples) / static_cast<double>(result.samples);
    std::ostringstream msg;
    msg.precision(3);
    msg << "the DEM does not cover the roads: " << result.uncovered_samples << " of " << result.samples
        << " road samples (" << percent << " %) lie outside every DEM";
    if (first_uncovered) {
      const Vec2 at = points[*first_uncovered];
      msg << ", e.g. at local (" << at.x() << ", " << at.y() << ") m";
    }
    msg << "; give a DEM that covers them, clip with --bbox, or accept it with --allow-partial";
    throw CoverageError(msg.str(), percent);
  }

  // Junction heights from the valid road ends, for filling ends that have none.
  std::vector<double> junction_sum(network.junctions.size(), 0.0);
  std::vector<int> junction_n(network.junctions.size(), 0);
  for (std::size_t r = 0; r < network.roads.size(); ++r) {
    const RoadProfile& p = result.profiles[r];
    const Road& road = network.roads[r];
    if (valid[r].front()) {
      junction_sum[road.start_junction] += p.z.front();
      ++junction_n[road.start_junction];
    }
    if (valid[r].back()) {
      junction_sum[road.end_junction] += p.z.back();
      ++junction_n[road.end_junction];
    }
  }
  const auto junction_height = [&](int j) -> std::optional<double> {
    if (j < 0 || junction_n[j] == 0) return std::nullopt;
    return junction_sum[j] / junction_n[j];
  };
  for (std::size_t r = 0; r < network.roads.size(); ++r) {
    RoadProfile& p = result.profiles[r];
    if (std::all_of(valid[r].begin(), valid[r].end(), [](auto v) { return v != 0; })) continue;
    const Road& road = network.roads[r];
    if (!fill_profile(p, valid[r], junction_height(road.start_junction),
                      junction_height(road.end_junction))) {
      p.has_height = false;
      ++result.roads_without_height;
      Diagnostic d;
      d.severity = Severity::error;
      d.code = codes::kElevationRoadWithoutHeight;
      d.road_id = road.id;
      if (!road.osm_way_ids.empty()) d.osm_way_id = road.osm_way_ids.front();
      d.message = describe_road(road) + " has no height anywhere; it is left out of the outputs";
      diagnostics.report(std::move(d));
    }
  }
  return result;
}

}  // namespace relief

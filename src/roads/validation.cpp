#include "relief/roads/validation.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "relief/core/errors.h"
#include "relief/geometry/polyline.h"

namespace relief {
namespace {

// Grades are compared with their limits to a thousandth of a percent (1 mm per 100 m): a fitted
// profile sits on its limit up to the solver's rounding.
constexpr double kGradeTolerancePercent = 1e-3;

// Length-weighted percentile of |grade|: the smallest grade g such that segments with grade <= g
// make up `fraction` of the length. `items` is (grade, length); sorted in place.
double weighted_percentile(std::vector<std::pair<double, double>>& items, double fraction) {
  if (items.empty()) return 0.0;
  std::sort(items.begin(), items.end());
  double total = 0.0;
  for (const auto& [g, len] : items) total += len;
  double acc = 0.0;
  for (const auto& [g, len] : items) {
    acc += len;
    if (acc >= fraction * total) return g;
  }
  return items.back().first;
}

const std::map<std::string_view, std::vector<HighwayClass>>& class_groups() {
  using H = HighwayClass;
  static const std::map<std::string_view, std::vector<HighwayClass>> groups = {
      {"highway", {H::motorway, H::motorway_link, H::trunk, H::trunk_link}},
      {"arterial",
       {H::primary, H::primary_link, H::secondary, H::secondary_link, H::tertiary, H::tertiary_link}},
      {"local",
       {H::unclassified, H::residential, H::service, H::living_street, H::pedestrian, H::track, H::footway,
        H::path, H::cycleway, H::steps, H::bridleway}},
  };
  return groups;
}

}  // namespace

ErrorStats error_stats(std::span<const double> values, std::span<const std::optional<double>> reference) {
  ErrorStats s;
  double sum_abs = 0.0, sum_sq = 0.0, sum = 0.0;
  for (std::size_t i = 0; i < values.size() && i < reference.size(); ++i) {
    if (!reference[i]) continue;
    const double e = values[i] - *reference[i];
    sum += e;
    sum_abs += std::abs(e);
    sum_sq += e * e;
    if (s.n == 0 || std::abs(e) > s.max_m) {
      s.max_m = std::abs(e);
      s.max_at = i;
    }
    ++s.n;
  }
  if (s.n > 0) {
    const auto n = static_cast<double>(s.n);
    s.mae_m = sum_abs / n;
    s.rmse_m = std::sqrt(sum_sq / n);
    s.bias_m = sum / n;
  }
  return s;
}

GradeLimits GradeLimits::paper() {
  GradeLimits limits;
  for (const auto& [group, classes] : class_groups()) {
    const double value = group == "highway" ? 8.0 : group == "arterial" ? 12.0 : 15.0;
    for (HighwayClass cls : classes) limits.percent[cls] = value;
  }
  return limits;
}

double GradeLimits::limit_for(HighwayClass cls) const {
  const auto it = percent.find(cls);
  return it == percent.end() ? 15.0 : it->second;
}

void GradeLimits::apply_overrides(std::string_view text) {
  std::string item;
  std::istringstream in{std::string(text)};
  while (std::getline(in, item, ',')) {
    const auto eq = item.find('=');
    if (eq == std::string::npos) throw InvalidInput("grade limit '" + item + "' is not CLASS=PERCENT");
    const std::string key = item.substr(0, eq);
    double value = 0.0;
    try {
      std::size_t used = 0;
      value = std::stod(item.substr(eq + 1), &used);
      if (used != item.size() - eq - 1 || !(value > 0.0)) throw std::invalid_argument("bad");
    } catch (const std::exception&) {
      throw InvalidInput("grade limit '" + item + "' needs a positive percentage");
    }
    if (const auto group = class_groups().find(key); group != class_groups().end()) {
      for (HighwayClass cls : group->second) percent[cls] = value;
    } else if (const auto cls = parse_highway_class(key)) {
      percent[*cls] = value;
    } else {
      throw InvalidInput("grade limit '" + item + "': unknown road class '" + key +
                         "' (a highway value, or highway/arterial/local)");
    }
  }
}

std::vector<double> segment_grades_percent(const RoadProfile& profile) {
  std::vector<double> grades;
  if (profile.size() < 2) return grades;
  grades.reserve(profile.size() - 1);
  for (std::size_t i = 0; i + 1 < profile.size(); ++i) {
    const double ds = profile.s[i + 1] - profile.s[i];
    grades.push_back(ds > 0.0 ? 100.0 * std::abs(profile.z[i + 1] - profile.z[i]) / ds : 0.0);
  }
  return grades;
}

GradeStats grade_stats(const RoadNetwork& network, const std::vector<RoadProfile>& profiles,
                       const GradeLimits& limits) {
  GradeStats stats;
  std::vector<std::pair<double, double>> all;
  std::map<std::string, std::vector<std::pair<double, double>>> per_class;
  double total_len = 0.0, compliant_len = 0.0;
  std::map<std::string, std::pair<double, double>> class_len;  // total, compliant
  for (std::size_t r = 0; r < network.roads.size(); ++r) {
    const RoadProfile& p = profiles[r];
    if (!p.has_height) continue;
    const HighwayClass cls = network.roads[r].attributes.highway;
    const std::string name(to_string(cls));
    const double limit = limits.limit_for(cls);
    auto& cls_stats = stats.by_class[name];
    cls_stats.limit_percent = limit;
    const std::vector<double> grades = segment_grades_percent(p);
    for (std::size_t i = 0; i < grades.size(); ++i) {
      const double len = p.s[i + 1] - p.s[i];
      const double g = grades[i];
      all.emplace_back(g, len);
      per_class[name].emplace_back(g, len);
      total_len += len;
      class_len[name].first += len;
      if (g <= limit + kGradeTolerancePercent) {
        compliant_len += len;
        class_len[name].second += len;
      }
      cls_stats.max_percent = std::max(cls_stats.max_percent, g);
      if (g > stats.max_percent) {
        stats.max_percent = g;
        stats.steepest_road = network.roads[r].id;
      }
    }
  }
  stats.compliance_percent = total_len > 0.0 ? 100.0 * compliant_len / total_len : 100.0;
  stats.p99_percent = weighted_percentile(all, 0.99);
  for (auto& [name, cls_stats] : stats.by_class) {
    const auto [len, ok] = class_len[name];
    cls_stats.length_km = len / 1000.0;
    cls_stats.compliance_percent = len > 0.0 ? 100.0 * ok / len : 100.0;
    cls_stats.p99_percent = weighted_percentile(per_class[name], 0.99);
  }
  return stats;
}

JunctionGapStats junction_gaps(const RoadNetwork& network, const std::vector<RoadProfile>& profiles,
                               double bound_m) {
  JunctionGapStats stats;
  stats.bound_m = bound_m;
  for (const Junction& j : network.junctions) {
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    int n = 0;
    for (const RoadEnd& end : j.ends) {
      const RoadProfile& p = profiles[end.road];
      if (!p.has_height) continue;
      const double z = end.at_start ? p.z.front() : p.z.back();
      lo = std::min(lo, z);
      hi = std::max(hi, z);
      ++n;
    }
    if (n < 2) continue;
    ++stats.checked;
    const double gap = hi - lo;
    if (gap > bound_m) ++stats.over_bound;
    if (!stats.worst_junction || gap > stats.max_gap_m) {
      stats.max_gap_m = gap;
      stats.worst_junction = j.id;
    }
  }
  return stats;
}

NetworkStats network_stats(const RoadNetwork& network) {
  NetworkStats s;
  s.roads = network.roads.size();
  for (const Junction& j : network.junctions) {
    switch (j.kind) {
      case JunctionKind::intersection:
        ++s.intersections;
        break;
      case JunctionKind::attribute_change:
        ++s.attribute_changes;
        break;
      case JunctionKind::dead_end:
        ++s.dead_ends;
        break;
    }
    if (j.traffic_signal) ++s.traffic_signals;
  }
  s.junctions = s.intersections + s.attribute_changes;
  s.roundabouts = network.roundabouts;
  for (const Road& road : network.roads) {
    const double km = length_m(road.points) / 1000.0;
    s.length_km += km;
    s.km_by_class[std::string(to_string(road.attributes.highway))] += km;
    if (road.attributes.bridge) {
      ++s.bridges;
      s.bridge_km += km;
    }
    if (road.attributes.tunnel) {
      ++s.tunnels;
      s.tunnel_km += km;
    }
  }
  return s;
}

std::vector<std::uint8_t> ground_mask(const RoadNetwork& network, bool structures) {
  std::vector<std::uint8_t> mask;
  mask.reserve(network.roads.size());
  for (const Road& road : network.roads) {
    const bool structure = road.attributes.bridge || road.attributes.tunnel;
    mask.push_back(structure == structures ? 1 : 0);
  }
  return mask;
}

CutFillStats cut_fill(const std::vector<RoadProfile>& profiles, const std::vector<RoadProfile>& terrain,
                      std::span<const std::uint8_t> road_mask) {
  CutFillStats c;
  double sum = 0.0, len = 0.0, worst = -1.0;
  for (std::size_t r = 0; r < profiles.size(); ++r) {
    if (!road_mask.empty() && !road_mask[r]) continue;
    const RoadProfile& p = profiles[r];
    const RoadProfile& t = terrain[r];
    if (!p.has_height || !t.has_height) continue;
    for (std::size_t i = 0; i < p.size(); ++i) {
      const double d = p.z[i] - t.z[i];
      const double w =
          0.5 * ((i > 0 ? p.s[i] - p.s[i - 1] : 0.0) + (i + 1 < p.size() ? p.s[i + 1] - p.s[i] : 0.0));
      c.max_fill_m = std::max(c.max_fill_m, d);
      c.max_cut_m = std::max(c.max_cut_m, -d);
      sum += std::abs(d) * w;
      len += w;
      if (std::abs(d) > 0.5) c.km_over_0_5_m += w / 1000.0;
      if (std::abs(d) > 2.0) c.km_over_2_m += w / 1000.0;
      if (std::abs(d) > worst) {
        worst = std::abs(d);
        c.worst_road = static_cast<int>(r);
        c.worst_s_m = p.s[i];
      }
    }
  }
  c.mean_abs_m = len > 0.0 ? sum / len : 0.0;
  return c;
}

HeightValidator::HeightValidator(const std::vector<RoadProfile>& stations, const DemSampler& dem,
                                 const DemSampler* reference)
    : has_reference_(reference != nullptr) {
  // Midpoints of every segment, and four probes around each for the DEM gradient.
  constexpr double step = 0.5;
  std::vector<Vec2> mids;
  first_midpoint_.reserve(stations.size() + 1);
  first_station_.reserve(stations.size() + 1);
  std::size_t n_stations = 0;
  for (const RoadProfile& p : stations) {
    first_midpoint_.push_back(mids.size());
    first_station_.push_back(n_stations);
    n_stations += p.size();
    for (std::size_t i = 0; i + 1 < p.size(); ++i) mids.emplace_back(0.5 * (p.xy[i] + p.xy[i + 1]));
  }
  first_midpoint_.push_back(mids.size());
  first_station_.push_back(n_stations);

  const std::size_t n = mids.size();
  std::vector<Vec2> probes;
  probes.reserve(n * 5);
  probes.insert(probes.end(), mids.begin(), mids.end());
  for (const Vec2& offset : {Vec2(step, 0), Vec2(-step, 0), Vec2(0, step), Vec2(0, -step)}) {
    for (const Vec2& m : mids) probes.emplace_back(m + offset);
  }
  // As the road samples: the DEM has no height where its interpolation weighs a void.
  std::vector<std::optional<double>> heights(probes.size());
  dem.heights_at(probes, heights, NearVoid::no_height);
  dem_mid_.assign(heights.begin(), heights.begin() + static_cast<std::ptrdiff_t>(n));
  gradient_mid_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const auto &xp = heights[n + i], &xm = heights[2 * n + i], &yp = heights[3 * n + i],
               &ym = heights[4 * n + i];
    if (xp && xm && yp && ym) gradient_mid_[i] = Vec2((*xp - *xm) / (2 * step), (*yp - *ym) / (2 * step));
  }

  if (reference) {
    std::vector<Vec2> pts;
    pts.reserve(n_stations);
    for (const RoadProfile& p : stations) pts.insert(pts.end(), p.xy.begin(), p.xy.end());
    reference_.resize(pts.size());
    reference->heights_at(pts, reference_);
  }
}

HeightValidation HeightValidator::validate(const std::vector<RoadProfile>& profiles,
                                           std::span<const std::uint8_t> road_mask) const {
  HeightValidation v;
  std::vector<double> mid_z, ref_z;
  std::vector<std::optional<double>> mid_dem, ref;
  std::vector<std::pair<int, Vec2>> mid_at;  // road and plan position of each midpoint
  double sum3d = 0.0;
  std::size_t n3d = 0;
  for (std::size_t r = 0; r < profiles.size(); ++r) {
    const RoadProfile& p = profiles[r];
    if (!p.has_height || (!road_mask.empty() && !road_mask[r])) continue;
    for (std::size_t i = 0; i + 1 < p.size(); ++i) {
      const std::size_t m = first_midpoint_[r] + i;
      const double z = 0.5 * (p.z[i] + p.z[i + 1]);
      mid_z.push_back(z);
      mid_dem.push_back(dem_mid_[m]);
      mid_at.emplace_back(static_cast<int>(r), 0.5 * (p.xy[i] + p.xy[i + 1]));
      if (dem_mid_[m] && gradient_mid_[m]) {
        const double d = std::abs(z - *dem_mid_[m]) / std::sqrt(1.0 + gradient_mid_[m]->squaredNorm());
        sum3d += d;
        ++n3d;
        v.error_3d_max_m = std::max(v.error_3d_max_m, d);
      }
    }
    if (has_reference_) {
      ref_z.insert(ref_z.end(), p.z.begin(), p.z.end());
      ref.insert(ref.end(), reference_.begin() + static_cast<std::ptrdiff_t>(first_station_[r]),
                 reference_.begin() + static_cast<std::ptrdiff_t>(first_station_[r + 1]));
    }
  }
  v.vs_dem = error_stats(mid_z, mid_dem);
  if (v.vs_dem.n > 0) {
    const std::size_t k = v.vs_dem.max_at;
    v.max_road = mid_at[k].first;
    v.max_xy = mid_at[k].second;
    v.max_error_m = mid_z[k] - *mid_dem[k];
  }
  v.error_3d_mean_m = n3d > 0 ? sum3d / static_cast<double>(n3d) : 0.0;
  if (has_reference_) v.vs_reference = error_stats(ref_z, ref);
  return v;
}

}  // namespace relief

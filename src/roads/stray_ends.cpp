#include "roads/stray_ends.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <utility>

#include "relief/geometry/plane.h"
#include "relief/geometry/polyline.h"

namespace relief::detail {
namespace {

constexpr double kCell = 25.0;  // m, grid cell of the segment index

// Distance from p to segment ab, and the parameter (0..1) of the nearest point.
std::pair<double, double> point_segment(const Vec2& p, const Vec2& a, const Vec2& b) {
  const double u = segment_parameter(p, a, b);
  return {(p - (a + u * (b - a))).norm(), u};
}

// Distance between segments pq and ab, and the parameter on ab of the nearest point.
std::pair<double, double> segment_segment(const Vec2& p, const Vec2& q, const Vec2& a, const Vec2& b) {
  const double d1 = cross(q - p, a - p), d2 = cross(q - p, b - p);
  const double d3 = cross(b - a, p - a), d4 = cross(b - a, q - a);
  if (((d1 > 0.0 && d2 < 0.0) || (d1 < 0.0 && d2 > 0.0)) &&
      ((d3 > 0.0 && d4 < 0.0) || (d3 < 0.0 && d4 > 0.0))) {
    return {0.0, d1 / (d1 - d2)};  // they cross: at this parameter of ab
  }
  std::pair<double, double> best = point_segment(p, a, b);
  const auto consider = [&](std::pair<double, double> c) {
    if (c.first < best.first) best = c;
  };
  consider(point_segment(q, a, b));
  consider({point_segment(a, p, q).first, 0.0});
  consider({point_segment(b, p, q).first, 1.0});
  return best;
}

std::int64_t cell_key(long cx, long cy) {
  return (static_cast<std::int64_t>(cx) << 32) ^ (cy & 0xffffffffL);
}

// Point and unit direction of a polyline at arc length s.
std::pair<Vec2, Vec2> pose_at(const Polyline2& points, const std::vector<double>& along, double s) {
  const auto it = std::upper_bound(along.begin(), along.end(), s);
  std::size_t i = it == along.begin() ? 0 : static_cast<std::size_t>(it - along.begin()) - 1;
  i = std::min(i, points.size() - 2);
  const double len = along[i + 1] - along[i];
  const double u = len > 0.0 ? std::clamp((s - along[i]) / len, 0.0, 1.0) : 0.0;
  const Vec2 d = points[i + 1] - points[i];
  return {points[i] + u * d, d / std::max(d.norm(), 1e-12)};
}

}  // namespace

std::vector<StrayEnd> clear_stray_ends(const RoadNetwork& network, const std::vector<RoadProfile>& profiles,
                                       const std::vector<double>& half_width,
                                       std::vector<std::array<double, 2>>& trim,
                                       const StrayEndOptions& options) {
  std::vector<StrayEnd> out;
  std::vector<std::vector<double>> along(network.roads.size());
  std::unordered_map<std::int64_t, std::vector<std::pair<int, std::uint32_t>>> grid;
  double widest = 0.0;
  for (const Road& road : network.roads) {
    if (!profiles[road.id].has_height) continue;
    along[road.id] = cumulative_length(road.points);
    const double w = half_width[road.id];
    widest = std::max(widest, w);
    for (std::uint32_t k = 0; k + 1 < road.points.size(); ++k) {
      const Vec2 lo = road.points[k].cwiseMin(road.points[k + 1]) - Vec2::Constant(w);
      const Vec2 hi = road.points[k].cwiseMax(road.points[k + 1]) + Vec2::Constant(w);
      for (long cx = std::lround(std::floor(lo.x() / kCell)); cx <= std::lround(std::floor(hi.x() / kCell));
           ++cx)
        for (long cy = std::lround(std::floor(lo.y() / kCell)); cy <= std::lround(std::floor(hi.y() / kCell));
             ++cy)
          grid[cell_key(cx, cy)].emplace_back(road.id, k);
    }
  }
  // The first other road whose pavement the cross-section ab at height z comes within gap_m of.
  const auto blocking = [&](int self, const Vec2& a, const Vec2& b, double z) {
    const Vec2 lo = a.cwiseMin(b) - Vec2::Constant(widest + options.gap_m);
    const Vec2 hi = a.cwiseMax(b) + Vec2::Constant(widest + options.gap_m);
    for (long cx = std::lround(std::floor(lo.x() / kCell)); cx <= std::lround(std::floor(hi.x() / kCell));
         ++cx) {
      for (long cy = std::lround(std::floor(lo.y() / kCell)); cy <= std::lround(std::floor(hi.y() / kCell));
           ++cy) {
        const auto it = grid.find(cell_key(cx, cy));
        if (it == grid.end()) continue;
        for (const auto& [other, k] : it->second) {
          if (other == self) continue;
          const Road& o = network.roads[static_cast<std::size_t>(other)];
          const auto [d, u] = segment_segment(a, b, o.points[k], o.points[k + 1]);
          if (d - half_width[static_cast<std::size_t>(other)] >= options.gap_m) continue;
          const std::vector<double>& s = along[static_cast<std::size_t>(other)];
          const double z_other =
              height_at_station(profiles[static_cast<std::size_t>(other)], s[k] + u * (s[k + 1] - s[k]));
          if (std::abs(z_other - z) <= options.max_height_difference_m) return other;
        }
      }
    }
    return -1;
  };
  for (const Junction& j : network.junctions) {
    if (j.kind != JunctionKind::dead_end || j.ends.size() != 1) continue;
    const RoadEnd& e = j.ends.front();
    const Road& road = network.roads[static_cast<std::size_t>(e.road)];
    if (!profiles[road.id].has_height || road.start_junction == road.end_junction) continue;
    const std::vector<double>& s_of = along[road.id];
    const double length = s_of.back();
    double& t = trim[road.id][e.at_start ? 0 : 1];
    const double cap = length - trim[road.id][e.at_start ? 1 : 0] - options.min_kept_length_m;
    const double t0 = t;
    StrayEnd found{road.id, e.at_start, -1, 0.0, false};
    for (;;) {
      const double s = e.at_start ? t : length - t;
      const auto [p, dir] = pose_at(road.points, s_of, s);
      const Vec2 n(-dir.y(), dir.x());
      const double w = half_width[road.id];
      const int other = blocking(road.id, p - w * n, p + w * n, height_at_station(profiles[road.id], s));
      if (other < 0) {
        found.cleared = true;
        break;
      }
      if (found.other_road < 0) found.other_road = other;
      const double next = std::min(t + options.step_m, cap);
      if (!(next > t + 1e-9)) break;
      t = next;
    }
    found.trimmed_m = t - t0;
    if (found.other_road >= 0) out.push_back(found);
  }
  return out;
}

}  // namespace relief::detail

#include "roads/close_road_pairs.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <utility>

#include "roads/lane_layout.h"

namespace relief::detail {

std::vector<RoadSample> sample_roads(const RoadNetwork& network, double step_m) {
  std::vector<RoadSample> samples;
  for (const Road& road : network.roads) {
    double s = 0.0;
    for (std::size_t i = 0; i + 1 < road.points.size(); ++i) {
      const Vec2 a = road.points[i], b = road.points[i + 1];
      const double length = (b - a).norm();
      if (!(length > 0.0)) continue;
      const int n = std::max(1, static_cast<int>(std::ceil(length / step_m)));
      for (int k = 0; k < n; ++k) {
        const double t = k / static_cast<double>(n);
        samples.push_back({road.id, s + t * length, a + (b - a) * t, (b - a) / length});
      }
      s += length;
    }
  }
  return samples;
}

void for_each_near_pair(const std::vector<RoadSample>& samples, double reach_m,
                        const std::function<void(const RoadSample&, const RoadSample&)>& visit) {
  const double cell = reach_m;
  const auto cell_of = [&](const Vec2& p) {
    return std::pair(static_cast<std::int64_t>(std::floor(p.x() / cell)),
                     static_cast<std::int64_t>(std::floor(p.y() / cell)));
  };
  const auto key = [](std::int64_t cx, std::int64_t cy) {
    return (static_cast<std::uint64_t>(cx) << 32) ^ static_cast<std::uint64_t>(cy & 0xffffffff);
  };
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> cells;
  for (std::uint32_t i = 0; i < samples.size(); ++i) {
    const auto [cx, cy] = cell_of(samples[i].p);
    cells[key(cx, cy)].push_back(i);
  }
  for (const RoadSample& s : samples) {
    const auto [cx, cy] = cell_of(s.p);
    for (std::int64_t dx = -1; dx <= 1; ++dx) {
      for (std::int64_t dy = -1; dy <= 1; ++dy) {
        const auto it = cells.find(key(cx + dx, cy + dy));
        if (it == cells.end()) continue;
        for (const std::uint32_t j : it->second) {
          const RoadSample& t = samples[j];
          if (t.road != s.road) visit(s, t);
        }
      }
    }
  }
}

double widest_half_width(const RoadNetwork& network) {
  double widest = 0.0;
  for (const Road& road : network.roads) widest = std::max(widest, half_width(road));
  return widest;
}

bool near_shared_junction(const RoadNetwork& network, const RoadSample& a, const RoadSample& b,
                          double reach_m) {
  const Road& ra = network.roads[static_cast<std::size_t>(a.road)];
  const Road& rb = network.roads[static_cast<std::size_t>(b.road)];
  for (const int j : {ra.start_junction, ra.end_junction}) {
    if (j < 0 || (j != rb.start_junction && j != rb.end_junction)) continue;
    const Vec2& at = network.junctions[static_cast<std::size_t>(j)].position;
    if ((a.p - at).norm() < reach_m || (b.p - at).norm() < reach_m) return true;
  }
  return false;
}

bool beside(const RoadSample& a, const RoadSample& b, double step_m, double& across) {
  const Vec2 d = b.p - a.p;
  if (std::abs(a.dir.dot(d)) > 0.5 * step_m) return false;
  across = a.dir.x() * d.y() - a.dir.y() * d.x();
  return true;
}

}  // namespace relief::detail

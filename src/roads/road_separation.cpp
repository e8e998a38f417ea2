#include "roads/road_separation.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <sstream>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "relief/core/diagnostic_codes.h"
#include "roads/close_road_pairs.h"
#include "roads/lane_layout.h"

namespace relief::detail {
namespace {

constexpr double kMaxAngle = 30.0 * std::numbers::pi / 180.0;    // from parallel, either way
constexpr double kMergeAngle = 10.0 * std::numbers::pi / 180.0;  // a Y this sharp is still a junction's
constexpr double kDuplicateShare = 0.25;  // of the half widths' sum: one road drawn twice

// At station s of a road, its neighbour needs it `by` metres farther; the neighbour lies on the
// road's left (side +1) or right (-1).
struct Push {
  double s = 0.0;
  double by = 0.0;
  int side = 0;
};

// What one road sees of one neighbour.
struct Approach {
  std::vector<Push> pushes;
  int overlapping = 0;                                       // samples whose pavements overlap
  double closest = std::numeric_limits<double>::infinity();  // between the centre lines
  double needed = 0.0;                                       // half widths' sum
};

bool one_level(const WayAttributes& a, const WayAttributes& b) {
  return a.layer == b.layer && a.tunnel == b.tunnel;
}

// Whether road a gives way to b: the lower highway class, then the narrower, then the later id.
bool gives_way(const Road& a, const Road& b) {
  if (a.attributes.highway != b.attributes.highway) return a.attributes.highway > b.attributes.highway;
  const double wa = half_width(a), wb = half_width(b);
  if (wa != wb) return wa < wb;
  return a.id > b.id;
}

double cosine_rise(double t) {
  return t >= 1.0 ? 1.0 : t <= 0.0 ? 0.0 : 0.5 * (1.0 - std::cos(std::numbers::pi * t));
}

// The shift of a road of `length` metres at station s: the largest push tapered to s, held to
// zero at the ends.
double shift_at(const std::vector<Push>& pushes, double s, double length, const SeparationOptions& o) {
  double d = 0.0;
  for (const Push& p : pushes) {
    const double taper = std::max(o.min_taper_m, o.taper_per_shift * p.by);
    d = std::max(d, p.by * (1.0 - cosine_rise(std::abs(s - p.s) / taper)));
  }
  return d * cosine_rise(std::min(s, length - s) / o.min_taper_m);
}

Vec2 left_normal(const Vec2& dir) {
  return {-dir.y(), dir.x()};
}

// Moves the road's centre line `side` * -shift along its left normal, with new points every step
// where it moves.
void move_road(Road& road, const std::vector<Push>& pushes, int side, const SeparationOptions& o) {
  const Polyline2& pts = road.points;
  std::vector<double> station(pts.size(), 0.0);
  for (std::size_t i = 1; i < pts.size(); ++i) station[i] = station[i - 1] + (pts[i] - pts[i - 1]).norm();
  const double length = station.back();
  double lo = length, hi = 0.0;
  for (const Push& p : pushes) {
    const double taper = std::max(o.min_taper_m, o.taper_per_shift * p.by);
    lo = std::min(lo, p.s - taper);
    hi = std::max(hi, p.s + taper);
  }
  const auto direction = [&](std::size_t i) { return (pts[i + 1] - pts[i]) / (station[i + 1] - station[i]); };
  Polyline2 moved;
  std::vector<std::int64_t> ids;
  const auto add = [&](const Vec2& p, const Vec2& normal, double s, std::int64_t id) {
    moved.push_back(p - static_cast<double>(side) * shift_at(pushes, s, length, o) * normal);
    ids.push_back(id);
  };
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const bool has_next = i + 1 < pts.size() && station[i + 1] > station[i];
    const bool has_prev = i > 0 && station[i] > station[i - 1];
    Vec2 normal = Vec2::Zero();
    if (has_prev) normal += left_normal(direction(i - 1));
    if (has_next) normal += left_normal(direction(i));
    if (normal.norm() > 1e-9) normal.normalize();
    add(pts[i], normal, station[i], road.osm_node_ids[i]);
    if (!has_next) continue;
    const double a = std::max(station[i], lo), b = std::min(station[i + 1], hi);
    if (!(b > a)) continue;
    const Vec2 dir = direction(i);
    for (double s = a - std::fmod(a, o.sample_step_m) + o.sample_step_m; s < b; s += o.sample_step_m) {
      if (s - station[i] < 0.5 * o.sample_step_m || station[i + 1] - s < 0.5 * o.sample_step_m) continue;
      add(pts[i] + dir * (s - station[i]), left_normal(dir), s, 0);
    }
  }
  road.points = std::move(moved);
  road.osm_node_ids = std::move(ids);
}

std::string way_text(const Road& road) {
  return "road " + std::to_string(road.id) + " (OSM way " + std::to_string(road.osm_way_ids.front()) +
         (road.attributes.name.empty() ? "" : ", " + road.attributes.name) + ")";
}

}  // namespace

std::size_t separate_close_roads(RoadNetwork& network, Diagnostics& diagnostics,
                                 const SeparationOptions& options) {
  const std::vector<RoadSample> samples = sample_roads(network, options.sample_step_m);
  if (samples.empty()) return 0;
  const double widest = widest_half_width(network);

  std::vector<std::unordered_map<int, Approach>> approaches(network.roads.size());
  for_each_near_pair(
      samples, std::max(2.0 * widest + options.margin_m, options.sample_step_m),
      [&](const RoadSample& s, const RoadSample& t) {
        if (std::abs(s.dir.dot(t.dir)) < std::cos(kMaxAngle)) return;
        double across = 0.0;
        if (!beside(s, t, options.sample_step_m, across)) return;
        const Road& a = network.roads[static_cast<std::size_t>(s.road)];
        const Road& b = network.roads[static_cast<std::size_t>(t.road)];
        const double needed = half_width(a) + half_width(b);
        const double distance = std::abs(across);
        if (!(distance < needed + options.margin_m) || distance < kDuplicateShare * needed) return;
        if (!one_level(a.attributes, b.attributes)) return;
        if (near_shared_junction(network, s, t, needed / std::sin(kMergeAngle))) return;
        Approach& ap = approaches[static_cast<std::size_t>(s.road)][t.road];
        ap.pushes.push_back({s.s, needed + options.margin_m - distance, across > 0.0 ? 1 : -1});
        if (distance < needed) ++ap.overlapping;
        ap.closest = std::min(ap.closest, distance);
        ap.needed = needed;
      });

  const int min_samples =
      std::max(1, static_cast<int>(std::ceil(options.min_overlap_m / options.sample_step_m)));
  // Per road to move: its pushes, the side they come from (0: both, left alone) and the
  // neighbour that pushes it farthest.
  struct Move {
    std::vector<Push> pushes;
    int side = 0;
    bool conflict = false;
    int neighbour = -1;
    double by = 0.0, closest = 0.0, needed = 0.0;
  };
  std::unordered_map<int, Move> moves;
  for (std::size_t r = 0; r < network.roads.size(); ++r) {
    for (const auto& [other, ap] : approaches[r]) {
      const Road& road = network.roads[r];
      const Road& neighbour = network.roads[static_cast<std::size_t>(other)];
      if (!gives_way(road, neighbour)) continue;
      const auto back = approaches[static_cast<std::size_t>(other)].find(road.id);
      if (ap.overlapping < min_samples || back == approaches[static_cast<std::size_t>(other)].end() ||
          back->second.overlapping < min_samples)
        continue;
      double by = 0.0;
      int left = 0;
      for (const Push& p : ap.pushes) {
        by = std::max(by, p.by);
        left += p.side;
      }
      if (by > options.max_shift_m) continue;  // one road drawn over the other: the mesh checks'
      Move& m = moves[road.id];
      const int side = left >= 0 ? 1 : -1;
      if (m.side != 0 && m.side != side) m.conflict = true;
      m.side = side;
      m.pushes.insert(m.pushes.end(), ap.pushes.begin(), ap.pushes.end());
      if (by > m.by) {
        m.by = by;
        m.neighbour = other;
        m.closest = ap.closest;
        m.needed = ap.needed;
      }
    }
  }
  std::size_t moved = 0;
  for (Road& road : network.roads) {
    const auto it = moves.find(road.id);
    if (it == moves.end() || it->second.conflict) continue;
    const Move& m = it->second;
    move_road(road, m.pushes, m.side, options);
    ++moved;
    std::ostringstream text;
    text.precision(3);
    text << way_text(road) << " is drawn " << m.closest << " m from "
         << way_text(network.roads[static_cast<std::size_t>(m.neighbour)])
         << ", closer than their pavements reach (" << m.needed << " m): it is moved up to " << m.by
         << " m away from it";
    diagnostics.report({Severity::warning, std::string(codes::kNetworkRoadsMoved), text.str(),
                        road.osm_way_ids.front(), std::nullopt, road.id});
  }
  return moved;
}

}  // namespace relief::detail

#include "relief/roads/grade_separation.h"

#include <cmath>
#include <unordered_map>

#include "relief/geometry/polyline.h"

namespace relief {
namespace {

constexpr double kCell = 25.0;  // m, grid cell for the segment index

struct Segment {
  int road;
  std::size_t index;  // segment [index, index + 1] of the road's polyline
};

std::int64_t cell_key(long cx, long cy) {
  return (static_cast<std::int64_t>(cx) << 32) ^ (cy & 0xffffffff);
}

// Intersection parameters (t on p0-p1, u on q0-q1) of two segments, if they cross.
std::optional<std::pair<double, double>> intersect(const Vec2& p0, const Vec2& p1, const Vec2& q0,
                                                   const Vec2& q1) {
  const Vec2 r = p1 - p0, s = q1 - q0;
  const double denom = r.x() * s.y() - r.y() * s.x();
  if (std::abs(denom) < 1e-12) return std::nullopt;  // parallel
  const Vec2 d = q0 - p0;
  const double t = (d.x() * s.y() - d.y() * s.x()) / denom;
  const double u = (d.x() * r.y() - d.y() * r.x()) / denom;
  if (t < 0.0 || t > 1.0 || u < 0.0 || u > 1.0) return std::nullopt;
  return std::make_pair(t, u);
}

}  // namespace

int effective_layer(const WayAttributes& a) {
  if (a.layer != 0) return a.layer;
  if (a.bridge) return 1;
  if (a.tunnel) return -1;
  return 0;
}

std::vector<GradeSeparation> find_grade_separations(const RoadNetwork& network,
                                                    const std::vector<RoadProfile>& profiles) {
  // Index every segment in the grid cells its bounding box touches.
  std::unordered_map<std::int64_t, std::vector<Segment>> grid;
  std::vector<std::vector<double>> cumulative(network.roads.size());
  for (const Road& road : network.roads) {
    cumulative[road.id] = cumulative_length(road.points);
    for (std::size_t i = 0; i + 1 < road.points.size(); ++i) {
      const Vec2 lo = road.points[i].cwiseMin(road.points[i + 1]);
      const Vec2 hi = road.points[i].cwiseMax(road.points[i + 1]);
      for (long cx = std::lround(std::floor(lo.x() / kCell)); cx <= std::lround(std::floor(hi.x() / kCell));
           ++cx)
        for (long cy = std::lround(std::floor(lo.y() / kCell)); cy <= std::lround(std::floor(hi.y() / kCell));
             ++cy)
          grid[cell_key(cx, cy)].push_back({road.id, i});
    }
  }

  std::vector<GradeSeparation> found;
  std::unordered_map<std::int64_t, std::vector<std::size_t>> by_pair;  // road pair -> found indices
  for (const auto& [key, segments] : grid) {
    for (std::size_t a = 0; a < segments.size(); ++a) {
      for (std::size_t b = a + 1; b < segments.size(); ++b) {
        const Road& ra = network.roads[segments[a].road];
        const Road& rb = network.roads[segments[b].road];
        const int la = effective_layer(ra.attributes), lb = effective_layer(rb.attributes);
        if (la == lb) continue;
        const std::size_t ia = segments[a].index, ib = segments[b].index;
        const auto hit = intersect(ra.points[ia], ra.points[ia + 1], rb.points[ib], rb.points[ib + 1]);
        if (!hit) continue;
        const Vec2 xy = ra.points[ia] + hit->first * (ra.points[ia + 1] - ra.points[ia]);
        // Roads that meet at a junction there are connected, not separated.
        const auto near_junction = [&](const Road& r) {
          return (xy - network.junctions[r.start_junction].position).norm() < 0.5 ||
                 (xy - network.junctions[r.end_junction].position).norm() < 0.5;
        };
        if (near_junction(ra) && near_junction(rb)) continue;
        const bool a_up = la > lb;
        const Road& up = a_up ? ra : rb;
        const Road& down = a_up ? rb : ra;
        const auto s_on = [&](const Road& r, std::size_t i, double t) {
          const auto& c = cumulative[r.id];
          return c[i] + t * (c[i + 1] - c[i]);
        };
        GradeSeparation sep;
        sep.upper_road = up.id;
        sep.lower_road = down.id;
        sep.s_upper = a_up ? s_on(ra, ia, hit->first) : s_on(rb, ib, hit->second);
        sep.s_lower = a_up ? s_on(rb, ib, hit->second) : s_on(ra, ia, hit->first);
        sep.xy = xy;
        // The same crossing is seen from every cell both segments touch: keep it once.
        const std::int64_t pair =
            (static_cast<std::int64_t>(up.id) << 32) | static_cast<std::uint32_t>(down.id);
        bool duplicate = false;
        for (std::size_t k : by_pair[pair]) duplicate |= (found[k].xy - xy).norm() < 1.0;
        if (duplicate) continue;
        by_pair[pair].push_back(found.size());
        found.push_back(sep);
      }
    }
  }
  // Deterministic order whatever the hash map did.
  std::sort(found.begin(), found.end(), [](const GradeSeparation& x, const GradeSeparation& y) {
    return std::tie(x.upper_road, x.lower_road, x.s_upper) < std::tie(y.upper_road, y.lower_road, y.s_upper);
  });
  update_clearances(found, profiles);
  for (GradeSeparation& sep : found) sep.raw_clearance_m = sep.clearance_m;
  return found;
}

void update_clearances(std::vector<GradeSeparation>& separations, const std::vector<RoadProfile>& profiles) {
  for (GradeSeparation& sep : separations) {
    sep.clearance_m = height_at_station(profiles[sep.upper_road], sep.s_upper) -
                      height_at_station(profiles[sep.lower_road], sep.s_lower);
  }
}

}  // namespace relief

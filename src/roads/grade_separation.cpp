#include "relief/roads/grade_separation.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <unordered_map>

#include "relief/geometry/polyline.h"

namespace relief {
namespace {

constexpr double kCell = 25.0;  // m, grid cell for the segment index
// Alongside separations: checked every 5 m along the upper road, the full clearance at least
// 20 m from every end of the two roads.
constexpr double kAlongsideSpacing = 5.0;
constexpr double kAlongsideEndClearance = 20.0;
// Two roads leaving one junction overlap near it as they fan out; no order is asked there.
const double kFanSine = std::sin(10.0 * std::numbers::pi / 180.0);

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

// Half the paved width of a road (its lanes; shoulders and sidewalks not counted).
double half_width(const Road& road) {
  const WayAttributes& a = road.attributes;
  return 0.5 * a.lane_width_m * static_cast<double>(std::max(1, a.lanes_forward + a.lanes_backward));
}

// The height at parameter t of segment i of a road's straight span between its two ends (its
// profile's first and last heights, by arc length): where a deck would lie without its data.
double span_height(const RoadProfile& profile, const std::vector<double>& cumulative, std::size_t i,
                   double t) {
  const double s = cumulative[i] + t * (cumulative[i + 1] - cumulative[i]);
  const double length = cumulative.back();
  if (profile.z.empty()) return 0.0;
  const double f = length > 0.0 ? std::clamp(s / length, 0.0, 1.0) : 0.0;
  return profile.z.front() + f * (profile.z.back() - profile.z.front());
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
  // Index every segment in the grid cells its bounding box, grown by the road's half width,
  // touches: two segments whose pavements overlap then share a cell.
  std::unordered_map<std::int64_t, std::vector<Segment>> grid;
  std::vector<std::vector<double>> cumulative(network.roads.size());
  for (const Road& road : network.roads) {
    cumulative[road.id] = cumulative_length(road.points);
    const Vec2 grow = Vec2::Constant(half_width(road));
    for (std::size_t i = 0; i + 1 < road.points.size(); ++i) {
      const Vec2 lo = road.points[i].cwiseMin(road.points[i + 1]) - grow;
      const Vec2 hi = road.points[i].cwiseMax(road.points[i + 1]) + grow;
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
        const bool stacked = la == lb && ra.id != rb.id &&
                             ((ra.attributes.bridge && rb.attributes.bridge) ||
                              (ra.attributes.tunnel && rb.attributes.tunnel));
        if (la == lb && !stacked) continue;
        const std::size_t ia = segments[a].index, ib = segments[b].index;
        bool a_up = la > lb;
        if (stacked) {
          const auto hit = intersect(ra.points[ia], ra.points[ia + 1], rb.points[ib], rb.points[ib + 1]);
          if (!hit) continue;  // only where they cross: alongside, neither is known to be above
          const double za = span_height(profiles[ra.id], cumulative[ra.id], ia, hit->first);
          const double zb = span_height(profiles[rb.id], cumulative[rb.id], ib, hit->second);
          a_up = za > zb || (za == zb && ra.id < rb.id);
        }
        const Road& up = a_up ? ra : rb;
        const Road& down = a_up ? rb : ra;
        const std::size_t iu = a_up ? ia : ib, id = a_up ? ib : ia;
        const auto s_on = [&](const Road& r, std::size_t i, double t) {
          const auto& c = cumulative[r.id];
          return c[i] + t * (c[i + 1] - c[i]);
        };
        // The same place is seen from every cell both segments touch: keep it once.
        const std::int64_t pair =
            (static_cast<std::int64_t>(up.id) << 32) | static_cast<std::uint32_t>(down.id);
        const auto add = [&](double t_up, double t_down, const Vec2& xy, double spacing, bool alongside,
                             bool ordering_only) {
          for (std::size_t k : by_pair[pair]) {
            if (found[k].alongside == alongside && (found[k].xy - xy).norm() < spacing) return;
          }
          GradeSeparation sep;
          sep.upper_road = up.id;
          sep.lower_road = down.id;
          sep.s_upper = s_on(up, iu, t_up);
          sep.s_lower = s_on(down, id, t_down);
          sep.xy = xy;
          sep.alongside = alongside;
          sep.ordering_only = ordering_only;
          by_pair[pair].push_back(found.size());
          found.push_back(sep);
        };
        const Vec2& u0 = up.points[iu];
        const Vec2& u1 = up.points[iu + 1];
        const Vec2& d0 = down.points[id];
        const Vec2& d1 = down.points[id + 1];
        if (const auto hit = intersect(u0, u1, d0, d1)) {
          const Vec2 xy = u0 + hit->first * (u1 - u0);
          // Roads that meet at a junction there are connected, not separated.
          const auto near_junction = [&](const Road& r) {
            return (xy - network.junctions[r.start_junction].position).norm() < 0.5 ||
                   (xy - network.junctions[r.end_junction].position).norm() < 0.5;
          };
          if (!(near_junction(ra) && near_junction(rb))) add(hit->first, hit->second, xy, 1.0, false, false);
        }
        if (stacked) {
          for (const std::size_t k : by_pair[pair]) found[k].guessed_order = true;
          continue;
        }
        // Alongside: the upper road runs over the lower one, their paved widths overlapping (a
        // viaduct over the street below it, a street over a tunnel, a tunnel's bend under a street
        // beside its portal), with the full clearance away from the roads' ends (where a road
        // leaving a structure runs beside it) and from a junction they share; elsewhere the upper
        // one only stays above. Measured from points along the upper road to the nearest point
        // of the lower segment, so that a bend's corner counts too.
        const Vec2 du = u1 - u0, dd = d1 - d0;
        const double lu = du.norm(), ld = dd.norm();
        if (!(lu > 0.0 && ld > 0.0)) continue;
        const double reach = half_width(up) + half_width(down);
        std::vector<Vec2> shared;  // junctions both roads meet
        for (const int j : {up.start_junction, up.end_junction})
          if (j == down.start_junction || j == down.end_junction)
            shared.push_back(network.junctions[j].position);
        const double fan = reach / kFanSine;
        const auto steps = static_cast<int>(std::ceil(lu / kAlongsideSpacing));
        for (int k = 0; k < steps; ++k) {
          const double t_up = (k + 0.5) / steps;
          const Vec2 xy = u0 + t_up * du;
          const double t_down = std::clamp((xy - d0).dot(dd) / (ld * ld), 0.0, 1.0);
          if ((d0 + t_down * dd - xy).norm() >= reach) continue;
          if (std::any_of(shared.begin(), shared.end(), [&](const Vec2& j) { return (xy - j).norm() < fan; }))
            continue;
          bool near_end = false;
          for (const Road* r : {&up, &down}) {
            for (const int j : {r->start_junction, r->end_junction})
              near_end = near_end || (xy - network.junctions[j].position).norm() < kAlongsideEndClearance;
          }
          add(t_up, t_down, xy, 0.5 * kAlongsideSpacing, true, near_end || !shared.empty());
        }
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

#include "roads/close_roads.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>
#include <unordered_map>
#include <utility>
#include <vector>

#include "relief/core/diagnostic_codes.h"
#include "roads/close_road_pairs.h"
#include "roads/lane_layout.h"

namespace relief::detail {
namespace {

constexpr double kMaxAngle = 30.0 * std::numbers::pi / 180.0;    // from parallel
constexpr double kMergeAngle = 10.0 * std::numbers::pi / 180.0;  // a Y this sharp is still a junction's
constexpr double kDuplicateShare = 0.25;  // of the half widths' sum: one road drawn twice

// The two carriageways of one road: one-ways of the same name, on one level.
bool carriageways(const WayAttributes& a, const WayAttributes& b) {
  return a.oneway && b.oneway && !a.name.empty() && a.name == b.name && !a.bridge && !a.tunnel && !b.bridge &&
         !b.tunnel && a.layer == b.layer;
}

// The closest approach of a road to one neighbour: the smallest distance and how many samples
// of the road lie too close to it.
struct Approach {
  double distance = std::numeric_limits<double>::infinity();
  double needed = 0.0;  // the half widths' sum
  int samples = 0;
};

}  // namespace

std::size_t narrow_close_roads(RoadNetwork& network, Diagnostics& diagnostics,
                               const CloseRoadOptions& options) {
  const std::vector<RoadSample> samples = sample_roads(network, options.sample_step_m);
  if (samples.empty()) return 0;
  const double widest = widest_half_width(network);

  // Per road, its closest too-close neighbour.
  std::vector<std::unordered_map<int, Approach>> approaches(network.roads.size());
  // Cells as wide as the farthest two roads can reach: neighbours lie in adjacent cells.
  for_each_near_pair(samples, std::max(2.0 * widest, options.sample_step_m),
                     [&](const RoadSample& s, const RoadSample& t) {
                       // Carriageways run against each other; the neighbour's point lies beside this one and
                       // too close (cheap tests first).
                       if (s.dir.dot(t.dir) > -std::cos(kMaxAngle)) return;
                       double across = 0.0;
                       if (!beside(s, t, options.sample_step_m, across)) return;
                       across = std::abs(across);
                       const Road& a = network.roads[static_cast<std::size_t>(s.road)];
                       const Road& b = network.roads[static_cast<std::size_t>(t.road)];
                       const double needed = half_width(a) + half_width(b);
                       if (!(across < needed) || across < kDuplicateShare * needed) return;
                       if (!carriageways(a.attributes, b.attributes)) return;
                       if (near_shared_junction(network, s, t, needed / std::sin(kMergeAngle))) return;
                       Approach& ap = approaches[static_cast<std::size_t>(s.road)][t.road];
                       ap.distance = std::min(ap.distance, across);
                       ap.needed = needed;
                       ++ap.samples;
                     });
  const int min_samples =
      std::max(1, static_cast<int>(std::ceil(options.min_overlap_m / options.sample_step_m)));
  std::vector<double> factor(network.roads.size(), 1.0);
  std::vector<int> neighbour(network.roads.size(), -1);
  std::vector<double> distance(network.roads.size(), 0.0), needed(network.roads.size(), 0.0);
  for (std::size_t r = 0; r < network.roads.size(); ++r) {
    for (const auto& [other, ap] : approaches[r]) {
      // Both roads must be too close over the length, seen from each (a road's end beside the
      // other's middle is seen by one only).
      const auto back = approaches[static_cast<std::size_t>(other)].find(static_cast<int>(r));
      if (ap.samples < min_samples || back == approaches[static_cast<std::size_t>(other)].end() ||
          back->second.samples < min_samples)
        continue;
      const double f =
          std::max(0.0, std::min(ap.distance, back->second.distance) - options.margin_m) / ap.needed;
      // A pair that would need lanes under the minimum is left alone (and to the mesh checks);
      // both roads of every other pair take at least its narrowing, so their pavements meet.
      const double narrowest =
          std::min(network.roads[r].attributes.lane_width_m,
                   network.roads[static_cast<std::size_t>(other)].attributes.lane_width_m);
      if (narrowest * f < options.min_lane_width_m) continue;
      if (f < factor[r] || (f == factor[r] && neighbour[r] < 0)) {
        factor[r] = f;
        neighbour[r] = other;
        distance[r] = std::min(ap.distance, back->second.distance);
        needed[r] = ap.needed;
      }
    }
  }
  std::size_t narrowed = 0;
  for (Road& road : network.roads) {
    const auto r = static_cast<std::size_t>(road.id);
    if (!(factor[r] < 1.0)) continue;
    WayAttributes& a = road.attributes;
    const double before = a.lane_width_m;
    const double after = before * factor[r];
    a.lane_width_m = after;
    ++narrowed;
    const Road& other = network.roads[static_cast<std::size_t>(neighbour[r])];
    std::ostringstream text;
    text.precision(3);
    text << "road " << road.id << " (OSM way " << road.osm_way_ids.front()
         << (a.name.empty() ? "" : ", " + a.name) << ") is drawn " << distance[r] << " m from road "
         << other.id << " (OSM way " << other.osm_way_ids.front()
         << (other.attributes.name.empty() ? "" : ", " + other.attributes.name)
         << "), closer than their pavements reach (" << needed[r] << " m): its lanes are narrowed from "
         << before << " to " << after << " m";
    diagnostics.report({Severity::warning, std::string(codes::kNetworkRoadsNarrowed), text.str(),
                        road.osm_way_ids.front(), std::nullopt, road.id});
  }
  return narrowed;
}

}  // namespace relief::detail

#include "roads/end_trims.h"

#include <algorithm>
#include <array>
#include <optional>
#include <sstream>
#include <string>

#include "relief/core/diagnostic_codes.h"
#include "relief/geometry/plane.h"
#include "roads/junction_joining.h"
#include "roads/lane_layout.h"
#include "roads/stray_ends.h"
#include "roads/transition_roads.h"
#include "roads/turn_room.h"

namespace relief::detail {
namespace {

constexpr double kTrimStep = 0.5;    // m added to an overlapping road end's trim per pass
constexpr int kMaxTrimPasses = 400;  // bounds the trims' growth at one junction
constexpr int kMaxJoinRounds = 8;    // bounds the rounds of junctions joined by their trims

// The convex hull of two road ends' end lines: the ground the connecting roads between them
// cross (counter-clockwise; monotone chain over the four corners).
Polyline2 hull_of(const EndShape& a, const EndShape& b) {
  std::array<Vec2, 4> p{a.right, a.left, b.right, b.left};
  std::sort(p.begin(), p.end(),
            [](const Vec2& u, const Vec2& v) { return u.x() < v.x() || (u.x() == v.x() && u.y() < v.y()); });
  Polyline2 hull;
  for (int pass = 0; pass < 2; ++pass) {
    const std::size_t start = hull.size();
    for (int i = 0; i < 4; ++i) {
      const Vec2& q = p[pass == 0 ? i : 3 - i];
      while (hull.size() >= start + 2 && cross(hull.back() - hull[hull.size() - 2], q - hull.back()) <= 0.0)
        hull.pop_back();
      hull.push_back(q);
    }
    hull.pop_back();
  }
  return hull;
}

// Whether the end line of `c` enters the ground between two other ends of its junction, where
// their connecting roads run: its lanes would lie under them at its own heights.
bool in_path(const EndShape& c, const EndShape& a, const EndShape& b) {
  const Polyline2 hull = hull_of(a, b);
  return hull.size() >= 3 && segment_polygon_distance(c.right, c.left, hull) <= 0.0;
}

// Grows the trims of the usable road ends at junction j in steps until no two overlap, none
// lies between two others (in_path) and, at an intersection, every turn between two of them is
// at least min_turn_radius_m round (turn_room). Overlapping ends that reach their cap mark their roads
// `stuck`; where ends still overlap, the junction goes into `overlaps` and is made level in
// `planes`. Returns the ends whose trims grew.
std::size_t grow_apart(JunctionEnds& state, const Junction& j, std::vector<std::uint8_t>& stuck,
                       EndTrimResult& out, std::vector<Vec2>& planes) {
  const RoadNetwork& network = state.network;
  const RoadModelOptions& options = state.options;
  std::vector<const RoadEnd*> ends;
  for (const RoadEnd* e : state.ends_of(j)) {
    if (state.usable(network.roads[e->road])) ends.push_back(e);
  }
  if (ends.size() < 2) return 0;
  std::vector<std::optional<EndShape>> shape(ends.size());
  const auto shape_of = [&](std::size_t k) -> const EndShape& {
    if (!shape[k]) shape[k] = state.end_shape_at(*ends[k]);
    return *shape[k];
  };
  std::vector<EndLanes> lanes;
  lanes.reserve(ends.size());
  for (const RoadEnd* e : ends) lanes.push_back(end_lanes(network.roads[e->road], e->at_start));
  const bool turns_need_room =
      options.min_turn_radius_m > 0.0 && (ends.size() >= 3 || j.kind == JunctionKind::intersection);
  std::vector<std::uint8_t> grown(ends.size(), 0), capped(ends.size(), 0);
  bool clear = false;
  for (int pass = 0; pass < kMaxTrimPasses; ++pass) {
    // Ends that overlap another; ends lying between two others (grown too, but they do not
    // make the junction level: only connecting roads pass over them, no road end).
    std::vector<std::uint8_t> grow(ends.size(), 0), between(ends.size(), 0);
    for (std::size_t a = 0; a < ends.size(); ++a) {
      for (std::size_t b = a + 1; b < ends.size(); ++b) {
        if (!state.ends_overlap(shape_of(a), shape_of(b))) continue;
        grow[a] = grow[b] = 1;
      }
    }
    clear = std::find(grow.begin(), grow.end(), 1) == grow.end();
    if (ends.size() >= 3) {
      for (std::size_t c = 0; c < ends.size(); ++c) {
        for (std::size_t a = 0; a < ends.size() && !between[c]; ++a) {
          for (std::size_t b = a + 1; b < ends.size() && !between[c]; ++b) {
            if (a != c && b != c && in_path(shape_of(c), shape_of(a), shape_of(b))) between[c] = 1;
          }
        }
      }
    }
    // Ends too close to a turn's crossing for its connecting road to be round enough: the end
    // with the shorter tangent grows (at intersections; a transition road's bend has its own
    // reach, transition_reach).
    std::vector<std::uint8_t> tight(ends.size(), 0);
    if (turns_need_room) {
      for (std::size_t a = 0; a < ends.size(); ++a) {
        for (std::size_t b = 0; b < ends.size(); ++b) {
          if (ends[a]->road == ends[b]->road) continue;
          const TurnRoom room = turn_room(shape_of(a), lanes[a], shape_of(b), lanes[b]);
          if (room.radius < options.min_turn_radius_m) tight[room.shorter == 0 ? a : b] = 1;
        }
      }
    }
    bool any = false;
    for (std::size_t k = 0; k < ends.size(); ++k) {
      if (!grow[k] && !between[k] && !tight[k]) continue;
      const Road& road = network.roads[ends[k]->road];
      const double length = state.cumulative[road.id].back();
      double& t = state.trim[road.id][ends[k]->at_start ? 0 : 1];
      // Both ends of a road draw on its length, leaving it min_kept_length_m; a loop's two
      // ends overlap each other whatever is cut, so it keeps the per-end share. An end grown
      // only for a turn's room keeps that share too, and leaves its road at least as long as it
      // is wide: a rounder turn never makes a road a stub between two junctions, whose lanes
      // would turn from one junction's roll to the other's within a few metres.
      const double other = state.trim[road.id][ends[k]->at_start ? 1 : 0];
      double cap = length - other - options.min_kept_length_m;
      if (state.loop(road)) cap = options.max_trim_fraction * length;
      if (!grow[k] && !between[k])
        cap =
            std::max(t, std::min({cap, options.max_trim_fraction * length, length - other - lanes[k].width}));
      const double next = std::min(t + kTrimStep, cap);
      if (next - t < 1e-9) {
        if (grow[k]) capped[k] = state.loop(road) ? 0 : 1;
        continue;
      }
      t = next;
      shape[k].reset();
      grown[k] = 1;
      any = true;
    }
    if (!any) break;
  }
  std::size_t ends_trimmed = 0;
  for (const std::uint8_t g : grown) ends_trimmed += g;
  if (!clear) {
    for (std::size_t k = 0; k < ends.size(); ++k) {
      if (capped[k]) stuck[ends[k]->road] = 1;
    }
    std::vector<int> roads;
    roads.reserve(ends.size());
    for (const RoadEnd* e : ends) roads.push_back(e->road);
    out.overlaps.emplace_back(static_cast<int>(j.id), roads);
    // Road ends that still overlap would cross each other once tilted differently: the
    // junction stays level.
    for (const int m : state.clusters.members[j.id]) planes[m] = Vec2::Zero();
    planes[j.id] = Vec2::Zero();
  }
  return ends_trimmed;
}

}  // namespace

std::vector<double> junction_radii(const RoadNetwork& network, const std::vector<RoadProfile>& profiles,
                                   const RoadModelOptions& options,
                                   const std::vector<std::uint8_t>& transition) {
  std::vector<double> radius(network.junctions.size(), 0.0);
  for (const Junction& j : network.junctions) {
    // Two one-ways without passage between them end apart, clear of each other as at a fork.
    const bool apart =
        j.kind == JunctionKind::attribute_change && j.ends.size() == 2 && !has_passage(network, j);
    if (j.kind != JunctionKind::intersection && !transition[j.id] && !apart) continue;
    double widest = 0.0;
    for (const RoadEnd& e : j.ends) widest = std::max(widest, half_width(network.roads[e.road]));
    radius[j.id] = widest + options.junction_margin_m;
    if (transition[j.id]) radius[j.id] = transition_reach(network, profiles, j, radius[j.id], options);
  }
  return radius;
}

EndTrimResult grow_end_trims(JunctionEnds& ends, std::vector<Vec2>& planes) {
  // A road whose trims leave it only min_kept_length_m while its ends still overlap others is
  // used up: its two junctions are joined and the trims run again from the radii (a stub
  // between two junctions cannot hold both).
  const RoadNetwork& network = ends.network;
  EndTrimResult out;
  const std::vector<std::array<double, 2>> radius_trim = ends.trim;
  const std::vector<Vec2> given_planes = planes;
  std::vector<std::uint8_t> used_up(network.roads.size(), 0);
  for (int round = 0;; ++round) {
    ends.trim = radius_trim;
    planes = given_planes;
    out.overlaps.clear();
    std::size_t ends_trimmed = 0;
    std::vector<std::uint8_t> stuck(network.roads.size(), 0);
    for (const Junction& j : network.junctions) {
      if (!(ends.radius[j.id] > 0.0) || ends.clusters.members[j.id].empty()) continue;
      ends_trimmed += grow_apart(ends, j, stuck, out, planes);
    }
    out.ends_trimmed = ends_trimmed;
    if (!mark_used_up_roads(ends, radius_trim, stuck, used_up) || round + 1 == kMaxJoinRounds) break;
    ends.clusters = join_junctions(network, ends.radius, ends.road_length, ends.has_height,
                                   ends.options.min_kept_length_m, used_up);
  }
  return out;
}

void trim_stray_ends(JunctionEnds& ends, bool report, Diagnostics& diagnostics, RoadModelStats& stats) {
  const RoadNetwork& network = ends.network;
  std::vector<double> widths(network.roads.size());
  for (const Road& road : network.roads) widths[road.id] = half_width(road);
  StrayEndOptions stray;
  stray.gap_m = ends.options.junction_end_gap_m;
  stray.min_kept_length_m = ends.options.min_kept_length_m;
  const std::vector<StrayEnd> strays = clear_stray_ends(network, ends.profiles, widths, ends.trim, stray);
  if (!report) return;
  for (const StrayEnd& e : strays) {
    const Road& road = network.roads[static_cast<std::size_t>(e.road)];
    const Road& other = network.roads[static_cast<std::size_t>(e.other_road)];
    const auto way = [](const Road& r) {
      return r.osm_way_ids.empty() ? std::string("?") : std::to_string(r.osm_way_ids.front());
    };
    std::ostringstream msg;
    msg.precision(1);
    msg << std::fixed << "the dead end of OSM way " << way(road) << " lies on OSM way " << way(other)
        << " (no shared node; ways closer than their widths): "
        << (e.cleared ? "trimmed back " : "still there after trimming back ") << e.trimmed_m << " m";
    Diagnostic d;
    d.severity = e.cleared ? Severity::info : Severity::warning;
    d.code = e.cleared ? codes::kModelStrayEndTrimmed : codes::kModelStrayEndOverlap;
    d.message = msg.str();
    if (!road.osm_way_ids.empty()) d.osm_way_id = road.osm_way_ids.front();
    diagnostics.report(std::move(d));
    ++(e.cleared ? stats.stray_ends_trimmed : stats.stray_ends_left);
  }
}

void report_end_overlaps(const RoadNetwork& network, const EndTrimResult& trims, const RoadModel& model,
                         const std::vector<int>& model_road_of, Diagnostics& diagnostics,
                         RoadModelStats& stats) {
  for (const auto& [junction, roads] : trims.overlaps) {
    std::string ids;
    for (const int r : roads) {
      if (model_road_of[r] < 0) continue;
      ids += (ids.empty() ? "" : ", ") + std::to_string(model.roads[model_road_of[r]].id);
    }
    Diagnostic d;
    d.code = codes::kModelJunctionEndsOverlap;
    d.message = "the ends of roads " + ids + " at the junction of OSM node " +
                std::to_string(network.junctions[junction].osm_node_id) +
                " still overlap after trimming them by the largest share allowed";
    d.osm_node_id = network.junctions[junction].osm_node_id;
    diagnostics.report(std::move(d));
    ++stats.junction_ends_overlap;
  }
}

}  // namespace relief::detail

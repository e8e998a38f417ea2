#include "relief/roads/road_model_builder.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <sstream>

#include "relief/core/diagnostic_codes.h"
#include "relief/core/errors.h"
#include "relief/geometry/plane.h"
#include "relief/geometry/polygon.h"
#include "relief/geometry/polyline.h"
#include "relief/geometry/reference_line_fit.h"
#include "relief/roads/road_surface.h"
#include "roads/connecting_roads.h"
#include "roads/junction_clusters.h"
#include "roads/junction_planes.h"
#include "roads/lane_layout.h"
#include "roads/stray_ends.h"
#include "roads/transition_roads.h"

namespace relief {
namespace {

using namespace detail;  // the builder's steps (src/roads/*.h)

constexpr double kMinRoadLength = 0.05;  // m left after trimming, else the road is skipped
constexpr double kTrimStep = 0.5;        // m added to an overlapping road end's trim per pass
constexpr int kMaxTrimPasses = 400;      // bounds the trims' growth at one junction
constexpr int kMaxJoinRounds = 8;        // bounds the rounds of junctions joined by their trims
constexpr double kMaxJoinGap = 10.0;     // m beyond two radii a used-up road joins (netconvert's join-dist)

// Slope dz/ds of a profile at s, by central differences over +-h (one-sided at the ends).
double slope_at(const RoadProfile& p, double s, double h = 1.0) {
  const double lo = std::max(p.s.front(), s - h), hi = std::min(p.s.back(), s + h);
  if (hi - lo < 1e-9) return 0.0;
  return (height_at_station(p, hi) - height_at_station(p, lo)) / (hi - lo);
}

// The part [s0, s1] of a polyline; `kept_s` receives the polyline s of each returned point.
Polyline2 cut(const Polyline2& line, const std::vector<double>& cumulative, double s0, double s1,
              std::vector<double>& kept_s) {
  Polyline2 out{point_at(line, cumulative, s0)};
  kept_s = {s0};
  for (std::size_t i = 0; i < line.size(); ++i) {
    if (cumulative[i] > s0 + 1e-6 && cumulative[i] < s1 - 1e-6) {
      out.push_back(line[i]);
      kept_s.push_back(cumulative[i]);
    }
  }
  out.push_back(point_at(line, cumulative, s1));
  kept_s.push_back(s1);
  return out;
}

// Piecewise-linear map from polyline s to reference-line s through matching vertices.
double map_station(const std::vector<double>& from, const std::vector<double>& to, double s) {
  if (s <= from.front()) return to.front();
  if (s >= from.back()) return to.back();
  const auto it = std::upper_bound(from.begin(), from.end(), s);
  const auto i = static_cast<std::size_t>(it - from.begin());
  const double t = (s - from[i - 1]) / (from[i] - from[i - 1]);
  return to[i - 1] + t * (to[i] - to[i - 1]);
}

std::string road_type(HighwayClass c) {
  switch (c) {
    case HighwayClass::motorway:
    case HighwayClass::motorway_link:
      return "motorway";
    case HighwayClass::trunk:
    case HighwayClass::trunk_link:
      return "rural";
    case HighwayClass::footway:
    case HighwayClass::path:
    case HighwayClass::steps:
    case HighwayClass::pedestrian:
      return "pedestrian";
    case HighwayClass::cycleway:
      return "bicycle";
    default:
      return "town";
  }
}

// Distance between two segments, 0 when they cross or touch.
double segment_distance(const Vec2& a0, const Vec2& a1, const Vec2& b0, const Vec2& b1) {
  const double d1 = cross(a1 - a0, b0 - a0), d2 = cross(a1 - a0, b1 - a0);
  const double d3 = cross(b1 - b0, a0 - b0), d4 = cross(b1 - b0, a1 - b0);
  if (((d1 > 0.0) != (d2 > 0.0)) && ((d3 > 0.0) != (d4 > 0.0))) return 0.0;
  return std::min({point_segment_distance(a0, b0, b1), point_segment_distance(a1, b0, b1),
                   point_segment_distance(b0, a0, a1), point_segment_distance(b1, a0, a1)});
}

// A road end at a junction in plan: its end cross-section (outermost right to outermost left
// lane border) and the outline of its lanes over the first metres from that end (at most
// `max_reach` of them).
struct EndShape {
  Vec2 left = Vec2::Zero(), right = Vec2::Zero();
  Polyline2 strip;  ///< closed implicitly
};

constexpr double kStripLength = 50.0;  // m of lanes next to a junction that other ends must clear
constexpr double kStripStep = 1.0;     // m between outline samples

EndShape end_shape(const PlanView& plan, double outer_t, bool at_start, double max_reach) {
  const double length = plan.length();
  const double reach = std::min({length, kStripLength, max_reach});
  const int steps = std::max(1, static_cast<int>(std::ceil(reach / kStripStep)));
  Polyline2 left, right;
  for (int k = 0; k <= steps; ++k) {
    const double d = reach * k / steps;
    const Pose2 pose = plan.at(at_start ? d : length - d);
    const Vec2 n(-std::sin(pose.heading), std::cos(pose.heading));
    left.push_back(pose.position + outer_t * n);
    right.push_back(pose.position - outer_t * n);
  }
  EndShape e;
  e.left = left.front();
  e.right = right.front();
  e.strip = right;
  e.strip.insert(e.strip.end(), left.rbegin(), left.rend());
  return e;
}

// Distance from a segment to a polygon's area (0 when it enters it).
double segment_polygon_distance(const Vec2& a, const Vec2& b, const Polyline2& polygon) {
  bool inside = false;
  for (std::size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++) {
    const Vec2& p = polygon[i];
    const Vec2& q = polygon[j];
    if ((p.y() > a.y()) != (q.y() > a.y()) &&
        a.x() < p.x() + (a.y() - p.y()) / (q.y() - p.y()) * (q.x() - p.x())) {
      inside = !inside;
    }
  }
  if (inside) return 0.0;
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++) {
    best = std::min(best, segment_distance(a, b, polygon[j], polygon[i]));
  }
  return best;
}

}  // namespace

std::vector<double> driven_stations(const Road& road, const RoadProfile& profile,
                                    const RoadModelOptions& options) {
  std::vector<double> ref_s;
  (void)fit_reference_line(road.points, {options.plan_tolerance_m, 1e-3, minimum_radius(road, options)},
                           &ref_s, nullptr);
  const std::vector<double> cumulative = cumulative_length(road.points);
  std::vector<double> out(profile.size());
  for (std::size_t i = 0; i < profile.size(); ++i) out[i] = map_station(cumulative, ref_s, profile.s[i]);
  return out;
}

namespace {

// build_road_model; with `trims_only` it returns once the road ends are trimmed for their
// junctions (end_trims), before any road, lane or connecting road is built.
RoadModelBuild build_model(const RoadNetwork& network, const std::vector<RoadProfile>& profiles,
                           const RoadModelOptions& options, Diagnostics& diagnostics,
                           const std::vector<Vec2>& junction_gradient, bool trims_only) {
  if (profiles.size() != network.roads.size())
    throw InvalidInput("build_road_model: one profile per road is required");
  if (!junction_gradient.empty() && junction_gradient.size() != network.junctions.size())
    throw InvalidInput("build_road_model: one junction gradient per junction is required");
  std::vector<Vec2> planes = junction_planes(network, junction_gradient);
  const auto gradient_of = [&](int junction) -> Vec2 { return planes[junction]; };

  RoadModelBuild out;
  RoadModel& model = out.model;
  model.frame = network.frame;
  out.model_road_of.assign(network.roads.size(), -1);

  // Junction radii: room for the junction at every intersection, and for a transition road
  // where two roads meet at an angle or with lanes that do not line up.
  const std::vector<std::uint8_t> transition = transition_junctions(network);
  std::vector<double> radius(network.junctions.size(), 0.0);
  for (const Junction& j : network.junctions) {
    // Two one-ways without passage between them end apart, clear of each other as at a fork.
    const bool apart =
        j.kind == JunctionKind::attribute_change && j.ends.size() == 2 && !has_passage(network, j);
    if (j.kind != JunctionKind::intersection && !transition[j.id] && !apart) continue;
    double widest = 0.0;
    for (const RoadEnd& e : j.ends) widest = std::max(widest, half_width(network.roads[e.road]));
    radius[j.id] = widest + options.junction_margin_m;
  }

  // Slopes at the road ends, "leaving the junction" (downhill away from it is negative). Where
  // two roads meet head to tail (an attribute change), both take the mean so that the elevation
  // is C1 across the link: leaving slopes of a smooth pass-through are opposite.
  std::vector<std::array<double, 2>> leaving(network.roads.size(), {0.0, 0.0});
  for (const Road& road : network.roads) {
    const RoadProfile& p = profiles[road.id];
    if (!p.has_height) continue;
    leaving[road.id] = {slope_at(p, 0.0), -slope_at(p, p.s.back())};
  }
  for (const Junction& j : network.junctions) {
    if (j.kind != JunctionKind::attribute_change || j.ends.size() != 2) continue;
    const RoadEnd& e0 = j.ends[0];
    const RoadEnd& e1 = j.ends[1];
    if (!profiles[e0.road].has_height || !profiles[e1.road].has_height) continue;
    double& l0 = leaving[e0.road][e0.at_start ? 0 : 1];
    double& l1 = leaving[e1.road][e1.at_start ? 0 : 1];
    const double mean = 0.5 * (l0 - l1);
    l0 = mean;
    l1 = -mean;
  }

  // Trims at both ends of every road: the junction radius, then grown where road ends at a
  // junction overlap.
  std::vector<std::array<double, 2>> trim(network.roads.size(), {0.0, 0.0});
  std::vector<std::vector<double>> cumulative_of(network.roads.size());
  std::vector<double> road_length(network.roads.size());
  std::vector<std::uint8_t> has_height(network.roads.size());
  for (const Road& road : network.roads) {
    cumulative_of[road.id] = cumulative_length(road.points);
    road_length[road.id] = cumulative_of[road.id].back();
    has_height[road.id] = profiles[road.id].has_height ? 1 : 0;
    const double cap = options.max_trim_fraction * cumulative_of[road.id].back();
    trim[road.id] = {std::min(radius[road.start_junction], cap), std::min(radius[road.end_junction], cap)};
  }
  const auto min_radius = [&](const Road& road) { return minimum_radius(road, options); };
  const auto fit_part = [&](const Road& road, std::vector<double>& kept_s, std::vector<double>& ref_s,
                            ReferenceLineReport* report, std::array<bool, 2> untrimmed = {false, false}) {
    const std::vector<double>& cumulative = cumulative_of[road.id];
    const double s0 = untrimmed[0] ? 0.0 : trim[road.id][0];
    const double s1 = cumulative.back() - (untrimmed[1] ? 0.0 : trim[road.id][1]);
    const Polyline2 part = cut(road.points, cumulative, s0, s1, kept_s);
    return fit_reference_line(part, {options.plan_tolerance_m, 1e-3, min_radius(road)}, &ref_s, report);
  };
  const auto usable = [&](const Road& road) {
    return profiles[road.id].has_height &&
           cumulative_of[road.id].back() - trim[road.id][0] - trim[road.id][1] >= kMinRoadLength;
  };
  // Intersections too close for the road between them to hold both become one junction (more
  // are joined below where the trims use a road up).
  detail::JunctionClusters clusters =
      detail::join_junctions(network, radius, road_length, has_height, options.min_kept_length_m, {});
  // The road ends at a junction; for a joined one, at any of its members but the absorbed roads'.
  const auto ends_of = [&](const Junction& j) {
    std::vector<const RoadEnd*> ends;
    for (const int m : clusters.members[j.id]) {
      for (const RoadEnd& e : network.junctions[m].ends) {
        if (!clusters.absorbed[e.road]) ends.push_back(&e);
      }
    }
    return ends;
  };
  // Trims grown where road ends at a junction overlap. A road whose trims leave it only
  // min_kept_length_m while its ends still overlap others is used up: its two junctions are
  // joined and the trims run again from the radii (a stub between two junctions cannot hold both).
  std::vector<std::pair<int, std::vector<int>>> overlaps;  // junction, network roads
  const std::vector<std::array<double, 2>> radius_trim = trim;
  const std::vector<Vec2> given_planes = planes;
  std::vector<std::uint8_t> used_up(network.roads.size(), 0);
  // Both ends at one junction, or at two joined into one.
  const auto loop = [&](const Road& road) {
    return road.start_junction == road.end_junction ||
           (road.start_junction >= 0 && road.end_junction >= 0 &&
            clusters.representative[road.start_junction] == clusters.representative[road.end_junction]);
  };
  // The outline of a road end's first metres (its kerb lines and the line across its end) with
  // the current trims.
  const auto end_shape_at = [&](const RoadEnd& end) {
    const Road& road = network.roads[end.road];
    std::vector<double> kept_s, ref_s;
    // Where the street only carries on at the far end (a lane or tag change, a bend), the
    // road's area runs on to that node: its trimmed-off part is a transition road's or
    // the next road's, which this junction's ends must clear as well.
    const int far = end.at_start ? road.end_junction : road.start_junction;
    const bool carries_on = far >= 0 && !loop(road) &&
                            network.junctions[far].kind != JunctionKind::intersection &&
                            clusters.members[far].size() == 1;
    std::array<bool, 2> untrimmed{false, false};
    untrimmed[end.at_start ? 1 : 0] = carries_on;
    const PlanView plan = fit_part(road, kept_s, ref_s, nullptr, untrimmed);
    // A loop's strip stops at its middle: the far half holds its other end, which would
    // otherwise always overlap this one however far both are trimmed.
    const double max_reach = loop(road) ? 0.5 * plan.length() : kStripLength;
    return end_shape(plan, outer_border_t(road.attributes), end.at_start, max_reach);
  };
  // Whether two road ends come closer than the junction gap (either's end line on the other's
  // outline).
  const auto ends_overlap = [&](const EndShape& a, const EndShape& b) {
    return std::min(segment_polygon_distance(a.right, a.left, b.strip),
                    segment_polygon_distance(b.right, b.left, a.strip)) < options.junction_end_gap_m;
  };
  for (int round = 0;; ++round) {
    trim = radius_trim;
    planes = given_planes;
    overlaps.clear();
    std::size_t ends_trimmed = 0;
    std::vector<std::uint8_t> stuck(network.roads.size(), 0);
    for (const Junction& j : network.junctions) {
      if (!(radius[j.id] > 0.0) || clusters.members[j.id].empty()) continue;
      std::vector<const RoadEnd*> ends;
      for (const RoadEnd* e : ends_of(j)) {
        if (usable(network.roads[e->road])) ends.push_back(e);
      }
      if (ends.size() < 2) continue;
      std::vector<std::optional<EndShape>> shape(ends.size());
      const auto shape_of = [&](std::size_t k) -> const EndShape& {
        if (!shape[k]) shape[k] = end_shape_at(*ends[k]);
        return *shape[k];
      };
      std::vector<std::uint8_t> grown(ends.size(), 0), capped(ends.size(), 0);
      bool clear = false;
      for (int pass = 0; pass < kMaxTrimPasses && !clear; ++pass) {
        std::vector<std::uint8_t> grow(ends.size(), 0);
        for (std::size_t a = 0; a < ends.size(); ++a) {
          for (std::size_t b = a + 1; b < ends.size(); ++b) {
            if (!ends_overlap(shape_of(a), shape_of(b))) continue;
            grow[a] = grow[b] = 1;
          }
        }
        clear = std::find(grow.begin(), grow.end(), 1) == grow.end();
        bool any = false;
        for (std::size_t k = 0; k < ends.size(); ++k) {
          if (!grow[k]) continue;
          const Road& road = network.roads[ends[k]->road];
          const double length = cumulative_of[road.id].back();
          double& t = trim[road.id][ends[k]->at_start ? 0 : 1];
          // Both ends of a road draw on its length, leaving it min_kept_length_m; a loop's two
          // ends overlap each other whatever is cut, so it keeps the per-end share.
          const double cap =
              loop(road) ? options.max_trim_fraction * length
                         : length - trim[road.id][ends[k]->at_start ? 1 : 0] - options.min_kept_length_m;
          const double next = std::min(t + kTrimStep, cap);
          if (next - t < 1e-9) {
            capped[k] = loop(road) ? 0 : 1;
            continue;
          }
          t = next;
          shape[k].reset();
          grown[k] = 1;
          any = true;
        }
        if (!any) break;
      }
      for (const std::uint8_t g : grown) ends_trimmed += g;
      if (!clear) {
        for (std::size_t k = 0; k < ends.size(); ++k) {
          if (capped[k]) stuck[ends[k]->road] = 1;
        }
        std::vector<int> roads;
        for (const RoadEnd* e : ends) roads.push_back(e->road);
        overlaps.emplace_back(static_cast<int>(j.id), roads);
        // Road ends that still overlap would cross each other once tilted differently: the
        // junction stays level.
        for (const int m : clusters.members[j.id]) planes[m] = Vec2::Zero();
        planes[j.id] = Vec2::Zero();
      }
    }
    out.stats.junction_ends_trimmed = ends_trimmed;
    // Whether the roads at one junction of a road reach into its other junction's area (the
    // hull of its road ends' end lines, this road's own end there included), or the two areas
    // overlap: the trims at the first pushed them past the road between (roads meeting at a
    // small angle), and the two junctions' surfaces would overlap. A far end that only carries
    // the street on is covered by the end strips reaching to it.
    const auto junctions_meet = [&](const Road& road) {
      const int ja = road.start_junction, jb = road.end_junction;
      if (ja < 0 || jb < 0 || network.junctions[ja].kind != JunctionKind::intersection ||
          network.junctions[jb].kind != JunctionKind::intersection)
        return false;
      struct Side {
        std::vector<EndShape> others;
        Polyline2 area;
      };
      const auto side = [&](int junction) {
        Side out;
        Polyline2 corners;
        for (const RoadEnd* e : ends_of(network.junctions[clusters.representative[junction]])) {
          if (!usable(network.roads[e->road])) continue;
          EndShape shape = end_shape_at(*e);
          corners.push_back(shape.right);
          corners.push_back(shape.left);
          if (e->road != road.id) out.others.push_back(std::move(shape));
        }
        out.area = convex_hull(std::move(corners));
        return out;
      };
      const auto reaches = [&](const Side& from, const Side& into) {
        for (std::size_t i = 0; i < into.area.size(); ++i) {
          const Vec2& p = into.area[i];
          const Vec2& q = into.area[(i + 1) % into.area.size()];
          for (const EndShape& e : from.others) {
            if (segment_polygon_distance(p, q, e.strip) < options.junction_end_gap_m) return true;
          }
        }
        return false;
      };
      // The two areas overlapping (each junction's surface would lie through the other's).
      const auto areas_overlap = [&](const Side& x, const Side& y) {
        if (x.area.size() < 3 || y.area.size() < 3) return false;
        for (std::size_t i = 0; i < x.area.size(); ++i) {
          if (segment_polygon_distance(x.area[i], x.area[(i + 1) % x.area.size()], y.area) < 1e-9)
            return true;
        }
        return false;
      };
      const Side a = side(ja), b = side(jb);
      return reaches(a, b) || reaches(b, a) || areas_overlap(a, b) || areas_overlap(b, a);
    };
    // A road the trims left no more than min_kept_length_m: the two junctions' areas meet
    // across it (their kerb lines, their other roads' ends) and become one.
    bool joined_more = false;
    for (const Road& road : network.roads) {
      if (loop(road) || used_up[road.id] || clusters.absorbed[road.id] || !has_height[road.id]) continue;
      if (road_length[road.id] - trim[road.id][0] - trim[road.id][1] > options.min_kept_length_m + 1e-6)
        continue;
      if (!stuck[road.id] &&
          road_length[road.id] - radius_trim[road.id][0] - radius_trim[road.id][1] > kMaxJoinGap &&
          !(junctions_meet(road) && !detail::join_leaves_loop(network, clusters, radius, road_length,
                                                              has_height, options.min_kept_length_m, road)))
        continue;
      used_up[road.id] = 1;
      joined_more = true;
    }
    if (!joined_more || round + 1 == kMaxJoinRounds) break;
    clusters =
        detail::join_junctions(network, radius, road_length, has_height, options.min_kept_length_m, used_up);
  }
  for (const Junction& j : network.junctions) {
    const std::vector<int>& members = clusters.members[j.id];
    if (members.size() < 2) continue;
    std::string nodes, roads;
    for (const int m : members)
      nodes += (nodes.empty() ? "" : ", ") + std::to_string(network.junctions[m].osm_node_id);
    for (const int m : members) {
      for (const RoadEnd& e : network.junctions[m].ends) {
        if (!clusters.absorbed[e.road] || !e.at_start) continue;
        std::ostringstream len;
        len.precision(1);
        len << std::fixed << road_length[e.road];
        const Road& road = network.roads[e.road];
        const std::string way = road.osm_way_ids.empty() ? "?" : std::to_string(road.osm_way_ids.front());
        roads += (roads.empty() ? "" : ", ") + way + " (" + len.str() + " m)";
      }
    }
    Diagnostic d;
    d.severity = Severity::info;
    d.code = codes::kModelJunctionsJoined;
    d.message = "the junctions of OSM nodes " + nodes + " are one junction: the OSM way(s) " + roads +
                " between them are too short to hold both";
    d.osm_node_id = j.osm_node_id;
    diagnostics.report(std::move(d));
    for (const int m : members) {
      if (m != j.id && network.junctions[m].kind == JunctionKind::intersection) ++out.stats.junctions_joined;
    }
  }
  for (const std::uint8_t a : clusters.absorbed) out.stats.roads_absorbed += a;

  // Dead ends that stop on another road (ways closer than their widths, "almost junctions").
  {
    std::vector<double> widths(network.roads.size());
    for (const Road& road : network.roads) widths[road.id] = half_width(road);
    detail::StrayEndOptions stray;
    stray.gap_m = options.junction_end_gap_m;
    stray.min_kept_length_m = options.min_kept_length_m;
    const std::vector<detail::StrayEnd> strays =
        detail::clear_stray_ends(network, profiles, widths, trim, stray);
    for (const detail::StrayEnd& e : trims_only ? std::vector<detail::StrayEnd>{} : strays) {
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
      ++(e.cleared ? out.stats.stray_ends_trimmed : out.stats.stray_ends_left);
    }
  }

  out.end_trims = trim;
  if (trims_only) return out;

  // Roads: trimmed, fitted reference line, elevation records, lanes.
  for (const Road& road : network.roads) {
    const RoadProfile& p = profiles[road.id];
    if (!p.has_height) {
      ++out.stats.roads_skipped;
      continue;
    }
    if (clusters.absorbed[road.id]) continue;  // inside a joined junction
    const std::vector<double>& cumulative = cumulative_of[road.id];
    const double length = cumulative.back();
    const double s0 = trim[road.id][0];
    const double s1 = length - trim[road.id][1];
    if (s1 - s0 < kMinRoadLength) {
      ++out.stats.roads_skipped;
      diagnostics.report(Severity::warning, codes::kOpendriveRoadTooShort,
                         "road " + std::to_string(road.id) + " (" + std::to_string(length) +
                             " m) has no length left between its junctions; left out of the OpenDRIVE");
      continue;
    }
    std::vector<double> kept_s, ref_s;
    ReferenceLineReport fit_report;
    ModelRoad m;
    m.plan = fit_part(road, kept_s, ref_s, &fit_report);
    m.id = static_cast<int>(model.roads.size()) + 1;
    if (fit_report.corners_widened > 0 || fit_report.vertices_merged > 0) {
      ++out.stats.corners_rounded;
      out.stats.max_corner_departure_m =
          std::max(out.stats.max_corner_departure_m, fit_report.max_departure_m);
      if (fit_report.max_departure_m > options.plan_tolerance_m) {
        std::ostringstream msg;
        msg.precision(2);
        msg << std::fixed << "road " << m.id << ": "
            << fit_report.corners_widened + fit_report.vertices_merged
            << " sharp corner(s) rounded to the minimum radius " << min_radius(road)
            << " m; the reference line departs from the OSM way by up to " << fit_report.max_departure_m
            << " m";
        Diagnostic d;
        d.severity = Severity::info;
        d.code = codes::kModelCornerRounded;
        d.message = msg.str();
        d.road_id = m.id;
        if (!road.osm_way_ids.empty()) d.osm_way_id = road.osm_way_ids.front();
        diagnostics.report(std::move(d));
      }
    }
    m.name = road.attributes.name;
    m.source_road = road.id;
    m.osm_way_ids = road.osm_way_ids;
    m.type = road_type(road.attributes.highway);
    m.speed_mps = road.attributes.maxspeed_mps ? *road.attributes.maxspeed_mps
                                               : default_speed_mps(road.attributes.highway);

    // Elevation: the fitted profile's stations inside the trimmed part, on the reference line.
    std::vector<double> es{0.0}, ez{height_at_station(p, s0)};
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (p.s[i] <= s0 + 1e-6 || p.s[i] >= s1 - 1e-6) continue;
      const double rs = map_station(kept_s, ref_s, p.s[i]);
      if (rs - es.back() < 1e-6) continue;
      es.push_back(rs);
      ez.push_back(p.z[i]);
    }
    const double end_s = m.plan.length();
    if (end_s - es.back() < 1e-6) {
      es.pop_back();
      ez.pop_back();
    }
    es.push_back(end_s);
    ez.push_back(height_at_station(p, s1));
    // End slopes along the reference line; untrimmed ends take the junction's shared slope.
    const double g0 = s0 > 0.0 ? slope_at(p, s0) : leaving[road.id][0];
    const double g1 = s1 < length ? slope_at(p, s1) : -leaving[road.id][1];
    m.elevation = fit_cubic_profile(es, ez, options.elevation_tolerance_m, std::make_pair(g0, g1));
    for (std::size_t i = 0; i < es.size(); ++i) {
      out.stats.max_elevation_deviation_m =
          std::max(out.stats.max_elevation_deviation_m, std::abs(m.elevation.value(es[i]) - ez[i]));
    }
    m.superelevation =
        end_rolls(m.plan.length(), plane_roll(gradient_of(road.start_junction), m.plan.at(0.0).heading),
                  plane_roll(gradient_of(road.end_junction), m.plan.at(m.plan.length()).heading));
    add_lanes(m, road.attributes);
    out.model_road_of[road.id] = static_cast<int>(model.roads.size());
    model.roads.push_back(std::move(m));
    ++out.stats.roads;
  }

  for (const auto& [junction, roads] : overlaps) {
    std::string ids;
    for (const int r : roads) {
      if (out.model_road_of[r] < 0) continue;
      ids += (ids.empty() ? "" : ", ") + std::to_string(model.roads[out.model_road_of[r]].id);
    }
    Diagnostic d;
    d.code = codes::kModelJunctionEndsOverlap;
    d.message = "the ends of roads " + ids + " at the junction of OSM node " +
                std::to_string(network.junctions[junction].osm_node_id) +
                " still overlap after trimming them by the largest share allowed";
    d.osm_node_id = network.junctions[junction].osm_node_id;
    diagnostics.report(std::move(d));
    ++out.stats.junction_ends_overlap;
  }

  // Junctions.
  for (const Junction& j : network.junctions) {
    if (clusters.members[j.id].empty()) continue;  // joined into another
    std::vector<EndRef> ends;
    for (const RoadEnd* e : ends_of(j)) {
      if (out.model_road_of[e->road] >= 0) ends.push_back({e->road, e->at_start});
    }
    const auto model_of = [&](const EndRef& e) -> ModelRoad& {
      return model.roads[out.model_road_of[e.network_road]];
    };

    if (j.kind == JunctionKind::attribute_change && ends.size() == 2 && !has_passage(network, j)) {
      report_no_passage(j, model_of(ends[0]), model_of(ends[1]), diagnostics);
      ++out.stats.ends_without_passage;
      continue;
    }
    if (transition[j.id] && ends.size() == 2) {
      add_transition_road(model, model_of(ends[0]), ends[0].at_start, model_of(ends[1]).id, ends[1].at_start,
                          gradient_of(j.id));
      ++out.stats.transition_roads;
      continue;
    }
    if (j.kind == JunctionKind::attribute_change && ends.size() == 2) {
      link_directly(model_of(ends[0]), ends[0].at_start, model_of(ends[1]), ends[1].at_start);
      ++out.stats.direct_links;
      continue;
    }
    if (j.kind != JunctionKind::intersection || ends.size() < 2) continue;
    add_junction(network, clusters, j, ends, planes, options, out, diagnostics);
  }
  return out;
}

}  // namespace

RoadModelBuild build_road_model(const RoadNetwork& network, const std::vector<RoadProfile>& profiles,
                                const RoadModelOptions& options, Diagnostics& diagnostics,
                                const std::vector<Vec2>& junction_gradient) {
  return build_model(network, profiles, options, diagnostics, junction_gradient, false);
}

std::vector<std::array<double, 2>> junction_end_trims(const RoadNetwork& network,
                                                      const std::vector<RoadProfile>& profiles,
                                                      const RoadModelOptions& options) {
  Diagnostics ignored;  // build_road_model reports the same findings
  return build_model(network, profiles, options, ignored, {}, true).end_trims;
}

}  // namespace relief

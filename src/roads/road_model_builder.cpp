#include "relief/roads/road_model_builder.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "relief/core/diagnostic_codes.h"
#include "relief/geometry/cubic_profile.h"
#include "relief/roads/highway_class.h"

#include "relief/core/errors.h"
#include "relief/geometry/polyline.h"
#include "relief/geometry/reference_line_fit.h"
#include "roads/connecting_roads.h"
#include "roads/end_trims.h"
#include "roads/junction_ends.h"
#include "roads/junction_joining.h"
#include "roads/junction_planes.h"
#include "roads/lane_layout.h"
#include "roads/transition_roads.h"

namespace relief {
namespace {

// Slope dz/ds of a profile at s, by central differences over +-h (one-sided at the ends).
double slope_at(const RoadProfile& p, double s, double h = 1.0) {
  const double lo = std::max(p.s.front(), s - h), hi = std::min(p.s.back(), s + h);
  if (hi - lo < 1e-9) return 0.0;
  return (height_at_station(p, hi) - height_at_station(p, lo)) / (hi - lo);
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

// Links the model roads at every junction: two roads meeting end to end without passage end
// there, with a transition road or directly; an intersection gets its junction and connecting
// roads.
void link_junctions(const RoadNetwork& network, const detail::JunctionEnds& trimmed,
                    const std::vector<std::uint8_t>& transition, const std::vector<Vec2>& planes,
                    const RoadModelOptions& options, RoadModelBuild& out, Diagnostics& diagnostics) {
  RoadModel& model = out.model;
  for (const Junction& j : network.junctions) {
    if (trimmed.clusters.members[j.id].empty()) continue;  // joined into another
    std::vector<detail::EndRef> ends;
    for (const RoadEnd* e : trimmed.ends_of(j)) {
      if (out.model_road_of[e->road] >= 0) ends.push_back({e->road, e->at_start});
    }
    const auto model_of = [&](const detail::EndRef& e) -> ModelRoad& {
      return model.roads[out.model_road_of[e.network_road]];
    };
    const bool end_to_end = j.kind == JunctionKind::attribute_change && ends.size() == 2;
    if (end_to_end && !detail::has_passage(network, j)) {
      detail::report_no_passage(j, model_of(ends[0]), model_of(ends[1]), diagnostics);
      ++out.stats.ends_without_passage;
    } else if (transition[j.id] && ends.size() == 2) {
      detail::add_transition_road(model, model_of(ends[0]), ends[0].at_start, model_of(ends[1]).id,
                                  ends[1].at_start, planes[j.id]);
      ++out.stats.transition_roads;
    } else if (end_to_end) {
      detail::link_directly(model_of(ends[0]), ends[0].at_start, model_of(ends[1]), ends[1].at_start);
      ++out.stats.direct_links;
    } else if (j.kind == JunctionKind::intersection && ends.size() >= 2) {
      detail::add_junction(network, trimmed.clusters, j, ends, planes, options, out, diagnostics);
    }
  }
}

// build_road_model; with `trims_only` it returns once the road ends are trimmed for their
// junctions (end_trims), before any road, lane or connecting road is built.
RoadModelBuild build_model(const RoadNetwork& network, const std::vector<RoadProfile>& profiles,
                           const RoadModelOptions& options, Diagnostics& diagnostics,
                           const std::vector<Vec2>& junction_gradient, bool trims_only) {
  if (profiles.size() != network.roads.size())
    throw InvalidInput("build_road_model: one profile per road is required");
  if (!junction_gradient.empty() && junction_gradient.size() != network.junctions.size())
    throw InvalidInput("build_road_model: one junction gradient per junction is required");
  RoadModelBuild out;
  out.model.frame = network.frame;
  out.model_road_of.assign(network.roads.size(), -1);
  std::vector<Vec2> planes = detail::junction_planes(network, junction_gradient);

  // Road ends trimmed back from their junctions: by each junction's radius, further where ends
  // overlap, joining junctions across the roads that leaves too short; dead ends off other roads.
  const std::vector<std::uint8_t> transition = detail::transition_junctions(network);
  detail::JunctionEnds trimmed(network, profiles, options,
                               detail::junction_radii(network, options, transition));
  const detail::EndTrimResult trims = detail::grow_end_trims(trimmed, planes);
  out.stats.junction_ends_trimmed = trims.ends_trimmed;
  detail::report_joined_junctions(trimmed, diagnostics, out.stats);
  detail::trim_stray_ends(trimmed, /*report=*/!trims_only, diagnostics, out.stats);
  out.end_trims = trimmed.trim;
  if (trims_only) return out;

  RoadModel& model = out.model;
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

  // Roads: trimmed, fitted reference line, elevation records, lanes.
  for (const Road& road : network.roads) {
    const RoadProfile& p = profiles[road.id];
    if (!p.has_height) {
      ++out.stats.roads_skipped;
      continue;
    }
    if (trimmed.clusters.absorbed[road.id]) continue;  // inside a joined junction
    const std::vector<double>& cumulative = trimmed.cumulative[road.id];
    const double length = cumulative.back();
    const double s0 = trimmed.trim[road.id][0];
    const double s1 = length - trimmed.trim[road.id][1];
    if (s1 - s0 < detail::kMinRoadLength) {
      ++out.stats.roads_skipped;
      diagnostics.report(Severity::warning, codes::kOpendriveRoadTooShort,
                         "road " + std::to_string(road.id) + " (" + std::to_string(length) +
                             " m) has no length left between its junctions; left out of the OpenDRIVE");
      continue;
    }
    std::vector<double> kept_s, ref_s;
    ReferenceLineReport fit_report;
    ModelRoad m;
    m.plan = trimmed.fit_part(road, kept_s, ref_s, &fit_report);
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
            << " sharp corner(s) rounded to the minimum radius " << detail::minimum_radius(road, options)
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
    m.superelevation = detail::end_rolls(
        m.plan.length(), detail::plane_roll(planes[road.start_junction], m.plan.at(0.0).heading),
        detail::plane_roll(planes[road.end_junction], m.plan.at(m.plan.length()).heading));
    detail::add_lanes(m, road.attributes);
    out.model_road_of[road.id] = static_cast<int>(model.roads.size());
    model.roads.push_back(std::move(m));
    ++out.stats.roads;
  }
  detail::report_end_overlaps(network, trims, out.model, out.model_road_of, diagnostics, out.stats);
  link_junctions(network, trimmed, transition, planes, options, out, diagnostics);
  return out;
}

}  // namespace

std::vector<double> driven_stations(const Road& road, const RoadProfile& profile,
                                    const RoadModelOptions& options) {
  std::vector<double> ref_s;
  (void)fit_reference_line(
      road.points, {options.plan_tolerance_m, 1e-3, detail::minimum_radius(road, options)}, &ref_s, nullptr);
  const std::vector<double> cumulative = cumulative_length(road.points);
  std::vector<double> out(profile.size());
  for (std::size_t i = 0; i < profile.size(); ++i) out[i] = map_station(cumulative, ref_s, profile.s[i]);
  return out;
}

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

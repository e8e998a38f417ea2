#include "relief/roads/road_model_builder.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "relief/core/errors.h"
#include "relief/geometry/polyline.h"
#include "relief/geometry/reference_line_fit.h"
#include "roads/connecting_roads.h"
#include "roads/end_trims.h"
#include "roads/junction_ends.h"
#include "roads/junction_joining.h"
#include "roads/junction_planes.h"
#include "roads/lane_layout.h"
#include "roads/road_records.h"
#include "roads/transition_roads.h"

namespace relief {
namespace {

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
      // Its lanes within the cap a connecting road there would keep (connecting_roads.cpp).
      const double max_lane_grade =
          options.grade_caps.empty()
              ? std::numeric_limits<double>::infinity()
              : std::max(options.grade_caps[ends[0].network_road], options.grade_caps[ends[1].network_road]) +
                    detail::kConnectionGradeAllowance;
      const detail::TransitionOutcome outcome = detail::add_transition_road(
          model, model_of(ends[0]), ends[0].at_start, model_of(ends[1]).id, ends[1].at_start, planes[j.id],
          options.min_radius_margin_m, max_lane_grade);
      if (outcome == detail::TransitionOutcome::added) {
        ++out.stats.transition_roads;
      } else {
        detail::report_transition_as_junction(j, model_of(ends[0]), model_of(ends[1]), outcome,
                                              options.min_radius_margin_m, max_lane_grade, diagnostics);
        ++out.stats.transitions_as_junctions;
        detail::add_junction(network, trimmed.clusters, j, ends, options, out, diagnostics);
      }
    } else if (end_to_end) {
      detail::link_directly(model_of(ends[0]), ends[0].at_start, model_of(ends[1]), ends[1].at_start);
      ++out.stats.direct_links;
    } else if (j.kind == JunctionKind::intersection && ends.size() >= 2) {
      detail::add_junction(network, trimmed.clusters, j, ends, options, out, diagnostics);
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
                               detail::junction_radii(network, profiles, options, transition));
  const detail::EndTrimResult trims = detail::grow_end_trims(trimmed, planes);
  out.stats.junction_ends_trimmed = trims.ends_trimmed;
  detail::report_joined_junctions(trimmed, diagnostics, out.stats);
  detail::trim_stray_ends(trimmed, /*report=*/!trims_only, diagnostics, out.stats);
  out.end_trims = trimmed.trim;
  out.joined_into = trimmed.clusters.representative;
  out.absorbed = trimmed.clusters.absorbed;
  if (trims_only) return out;

  // Roads between their trims, then the links and junctions between them.
  detail::add_model_roads(trimmed, detail::leaving_slopes(network, profiles), planes, out, diagnostics);
  detail::report_end_overlaps(network, trims, out.model, out.model_road_of, diagnostics, out.stats);
  link_junctions(network, trimmed, transition, planes, options, out, diagnostics);
  return out;
}

}  // namespace

std::vector<double> driven_stations(const Road& road, const RoadProfile& profile,
                                    const RoadModelOptions& options) {
  std::vector<double> ref_s;
  const PlanView plan = fit_reference_line(
      road.points, {options.plan_tolerance_m, 1e-3, detail::minimum_radius(road, options)}, &ref_s, nullptr);
  const std::vector<double> cumulative = cumulative_length(road.points);
  // The outermost lane's centre on the inside of each bend: d(driven) = (1 - |curvature| t) ds,
  // each step between stations at its tightest curvature, so that a grade limit on the step
  // holds where the lane is shortest (the elevation records climb no steeper than the step).
  // The minimum radius (outer border plus margin) keeps the factor above zero.
  const double t =
      std::max(0.0, detail::outer_border_t(road.attributes) - 0.5 * road.attributes.lane_width_m);
  const std::vector<PlanGeometry>& records = plan.records();
  std::vector<double> out(profile.size());
  double previous = 0.0;
  for (std::size_t i = 0; i < profile.size(); ++i) {
    const double s = detail::map_station(cumulative, ref_s, profile.s[i]);
    double tightest = 0.0;  // |curvature| (the reference line has lines and arcs only)
    if (i > 0) {
      for (std::size_t k = plan.record_at(previous); k < records.size() && records[k].s < s; ++k) {
        if (records[k].s + records[k].length > previous)
          tightest = std::max(tightest, std::abs(records[k].curvature));
      }
    }
    out[i] = i == 0 ? s : out[i - 1] + (s - previous) * (1.0 - t * tightest);
    previous = s;
  }
  return out;
}

RoadModelBuild build_road_model(const RoadNetwork& network, const std::vector<RoadProfile>& profiles,
                                const RoadModelOptions& options, Diagnostics& diagnostics,
                                const std::vector<Vec2>& junction_gradient) {
  return build_model(network, profiles, options, diagnostics, junction_gradient, false);
}

JunctionCuts junction_cuts(const RoadNetwork& network, const std::vector<RoadProfile>& profiles,
                           const RoadModelOptions& options) {
  Diagnostics ignored;  // build_road_model reports the same findings
  RoadModelBuild trims = build_model(network, profiles, options, ignored, {}, true);
  return JunctionCuts{std::move(trims.end_trims), std::move(trims.joined_into), std::move(trims.absorbed)};
}

}  // namespace relief

#include "sight/lane_path.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>

#include "relief/roads/road_surface.h"

namespace relief::detail {
namespace {

constexpr int kMaxLanesAhead = 64;

/// The lane's id in the section at s, or the outermost one on its side where that section has
/// fewer; 0 when it has none.
int lane_in_section(const ModelRoad& road, double s, int lane) {
  const LaneSection& section = section_at(road, s);
  const auto count = static_cast<int>((lane > 0 ? section.left : section.right).size());
  if (count == 0) return 0;
  return lane > 0 ? std::min(lane, count) : std::max(lane, -count);
}

/// Heading of travel on `lane` at its start (at_end = false) or its end.
double travel_heading(const ModelRoad& road, const LaneRef& lane, bool at_end) {
  const bool at_s_end = lane.forward() == at_end;
  const double h = heading_at(road, at_s_end ? road.length() : 0.0);
  return lane.forward() ? h : h + std::numbers::pi;
}

double turn_between(double from, double to) {
  return std::abs(std::remainder(to - from, 2.0 * std::numbers::pi));
}

}  // namespace

LanePoints lane_points(const RoadModel& model, const LaneRef& lane, double step) {
  LanePoints out;
  const ModelRoad& road = model.roads[static_cast<std::size_t>(lane.road)];
  const double length = road.length();
  if (!(length > 0.0) || road.sections.empty()) return out;
  const auto n = static_cast<std::size_t>(std::ceil(length / step - 1e-9));
  for (std::size_t i = 0; i <= n; ++i) {
    const double along = std::min(static_cast<double>(i) * step, length);
    const double s = lane.forward() ? along : length - along;
    const int id = lane_in_section(road, s, lane.lane);
    if (id == 0) return {};
    const Vec3 p = surface_point(road, s, lane_centre_t(road, s, id));
    out.distance.push_back(
        out.points.empty() ? 0.0 : out.distance.back() + (p - out.points.back()).head<2>().norm());
    out.points.push_back(p);
    out.s.push_back(s);
  }
  return out;
}

std::optional<LaneRef> next_lane(const RoadModel& model, const LaneRef& lane) {
  const ModelRoad& road = model.roads[static_cast<std::size_t>(lane.road)];
  const std::optional<RoadLink>& link = lane.forward() ? road.successor : road.predecessor;
  if (!link) return std::nullopt;
  if (link->element == RoadLink::Element::road) {
    const int next = model.road_index(link->id);
    if (next < 0) return std::nullopt;
    // Entering at its start we travel along it (a right lane), at its end against it.
    const int side = link->contact == RoadLink::Contact::start ? -1 : 1;
    const LaneSection& at_end = lane.forward() ? road.sections.back() : road.sections.front();
    std::optional<int> mapped;
    for (const LaneModel& l : lane.lane > 0 ? at_end.left : at_end.right)
      if (l.id == lane.lane) mapped = lane.forward() ? l.successor : l.predecessor;
    const int id = mapped && (*mapped > 0) == (side > 0) ? *mapped : side;
    return LaneRef{next, id};
  }
  const auto junction = std::find_if(model.junctions.begin(), model.junctions.end(),
                                     [&](const JunctionModel& j) { return j.id == link->id; });
  if (junction == model.junctions.end()) return std::nullopt;
  const double heading = travel_heading(road, lane, true);
  std::optional<LaneRef> best;
  double best_turn = std::numeric_limits<double>::infinity();
  for (const JunctionConnection& c : junction->connections) {
    if (c.incoming_road != road.id) continue;
    const int connecting = model.road_index(c.connecting_road);
    if (connecting < 0) continue;
    for (const auto& [from, to] : c.lane_links) {
      if (from != lane.lane) continue;
      const LaneRef candidate{connecting, to};
      const double turn = turn_between(
          heading, travel_heading(model.roads[static_cast<std::size_t>(connecting)], candidate, true));
      if (turn < best_turn) {
        best_turn = turn;
        best = candidate;
      }
    }
  }
  return best;
}

LanePoints lane_ahead(const RoadModel& model, const LaneRef& lane, double step, double length, bool& ended) {
  LanePoints out = lane_points(model, lane, step);
  ended = false;
  LaneRef at = lane;
  for (int k = 0; k < kMaxLanesAhead && !out.points.empty() && out.distance.back() < length; ++k) {
    const std::optional<LaneRef> next = next_lane(model, at);
    if (!next) {
      ended = true;
      return out;
    }
    const LanePoints more = lane_points(model, *next, step);
    if (more.points.empty()) {
      ended = true;
      return out;
    }
    // Its first point is where this lane ended (to the join's rounding): not repeated.
    for (std::size_t i = 1; i < more.size(); ++i) {
      out.distance.push_back(out.distance.back() + (more.points[i] - out.points.back()).head<2>().norm());
      out.points.push_back(more.points[i]);
      out.s.push_back(std::numeric_limits<double>::quiet_NaN());
    }
    at = *next;
  }
  return out;
}

}  // namespace relief::detail

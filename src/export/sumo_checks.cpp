#include "relief/export/sumo_checks.h"

#include <pugixml.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <sstream>
#include <tuple>
#include <unordered_map>
#include <unordered_set>
#include <utility>

#include "export/sumo_lane_locator.h"
#include "relief/core/errors.h"
#include "relief/roads/road_model_checks.h"
#include "relief/roads/road_surface.h"

namespace relief {
namespace {

using detail::LaneLocator;
using detail::load_net;
using detail::parse_shape;

constexpr double kStepRiseM = 0.1;        // a height step: more than this rise...
constexpr double kStepWindowM = 0.5;      // ...within this plan distance...
constexpr double kStepMinGrade = 0.5;     // ...and steeper than this there,
constexpr double kStepOverCap = 0.15;     // and than its road's cap by this
constexpr double kStreetGradeCap = 0.35;  // the cap without SumoOptions::grade_caps

// The first step along a 3D polyline (two points within kStepWindowM of plan distance along it
// that differ by more than kStepRiseM in height, at more than `min_grade`), or nullopt.
std::optional<Vec3> first_step(const Polyline3& line, double min_grade) {
  std::size_t j = 0;
  double run = 0.0;  // plan distance along the line from point i to point j
  for (std::size_t i = 0; i + 1 < line.size(); ++i) {
    if (j < i) {
      j = i;
      run = 0.0;
    }
    while (j + 1 < line.size() && run + (line[j + 1] - line[j]).head<2>().norm() <= kStepWindowM) {
      run += (line[j + 1] - line[j]).head<2>().norm();
      ++j;
    }
    double along = 0.0;  // plan distance from point i to point k
    for (std::size_t k = i + 1; k <= j; ++k) {
      along += (line[k] - line[k - 1]).head<2>().norm();
      const double dz = std::abs(line[k].z() - line[i].z());
      if (dz > kStepRiseM && dz > min_grade * along) return line[i];
    }
    if (j > i) run -= (line[i + 1] - line[i]).head<2>().norm();
  }
  return std::nullopt;
}

// Largest value and 99th percentile (the value at rank floor(0.99 (n - 1))); sorts `values`.
std::pair<double, double> max_and_p99(std::vector<double>& values) {
  if (values.empty()) return {0.0, 0.0};
  std::sort(values.begin(), values.end());
  return {values.back(), values[static_cast<std::size_t>(0.99 * static_cast<double>(values.size() - 1))]};
}

}  // namespace

SumoNetCheck check_sumo_net(std::string_view net_xml, const RoadModel& model, const std::string& file,
                            const std::vector<double>& grade_caps) {
  pugi::xml_document doc;
  const pugi::xml_node net = load_net(doc, net_xml, file);

  SumoNetCheck check;
  LaneLocator locator(net, model);
  // The least grade of a step on each road: kStepOverCap over its cap, at least kStepMinGrade
  // (a connecting road: the larger cap of the roads it joins).
  std::vector<double> step_grade(model.roads.size(), kStepMinGrade);
  for (std::size_t i = 0; i < model.roads.size(); ++i) {
    const double cap = grade_caps.empty() ? kStreetGradeCap : linked_grade_cap(model, grade_caps, i);
    step_grade[i] = std::max(kStepMinGrade, std::max(cap, kStreetGradeCap) + kStepOverCap);
  }
  std::unordered_map<std::string, double> lane_step_grade;  // lane id -> its road's
  std::vector<double> errors;
  double worst_error = 0.0;
  std::unordered_map<std::string, Polyline3> lane_shapes;
  for (const pugi::xml_node& edge : net.children("edge")) {
    const bool internal = std::string_view(edge.attribute("function").as_string()) == "internal";
    if (!internal) ++check.edges;
    for (const pugi::xml_node& lane : edge.children("lane")) {
      const std::string id = lane.attribute("id").as_string();
      bool missing_z = false;
      const Polyline3 shape = parse_shape(lane.attribute("shape").as_string(), &missing_z);
      if (missing_z) ++check.lanes_without_z;
      lane_shapes[id] = shape;
      double min_grade = kStepMinGrade;
      if (!shape.empty()) {
        if (const auto at = locator.locate(id, Vec2(shape.front().x(), shape.front().y()), std::nullopt))
          if (const int k = model.road_index(at->road->id); k >= 0)
            min_grade = step_grade[static_cast<std::size_t>(k)];
      }
      lane_step_grade[id] = min_grade;
      if (const auto step = first_step(shape, min_grade)) {
        if (check.height_steps++ == 0) {
          check.first_step_lane = id;
          check.first_step_point = *step;
        }
      }
      if (!lane.attribute("disallow").empty()) ++check.disallowed_lanes;
      internal ? ++check.internal_lanes : ++check.lanes;
      for (std::size_t i = 1; i < shape.size(); ++i) {
        const double run = (shape[i] - shape[i - 1]).head<2>().norm();
        if (run >= 1.0) {
          double& worst = internal ? check.max_internal_lane_grade_percent : check.max_lane_grade_percent;
          worst = std::max(worst, 100.0 * std::abs(shape[i].z() - shape[i - 1].z()) / run);
        }
      }
      std::optional<std::pair<int, double>> last_at;  // along the road from the point before
      for (const Vec3& p : shape) {
        const auto at = locator.locate(id, Vec2(p.x(), p.y()), last_at);
        if (!at) {
          ++check.points_unmapped;
          last_at.reset();
          continue;
        }
        last_at = std::make_pair(at->road->id, at->s);
        const double error = std::abs(p.z() - surface_z(*at->road, at->s, at->t));
        if (!at->lane.odr_shape) {
          // netconvert's own curve where the OpenDRIVE lane folds: measured apart.
          ++check.points_netconvert_shape;
          check.netconvert_shape_z_max_m = std::max(check.netconvert_shape_z_max_m, error);
          continue;
        }
        errors.push_back(error);
        if (check.z_max_lane.empty() || errors.back() > worst_error) {
          worst_error = errors.back();
          check.z_max_lane = id;
          check.z_max_point = p;
        }
        if (at->lane.lane) {
          // Lane centre points lie on the OpenDRIVE lane centre.
          const double off = std::abs(at->t - lane_centre_t(*at->road, at->s, *at->lane.lane));
          if (off > check.xy_max_m) {
            check.xy_max_m = off;
            check.xy_max_lane = id;
          }
        }
      }
    }
  }
  check.points = errors.size();
  std::tie(check.z_max_m, check.z_p99_m) = max_and_p99(errors);

  // Height steps where a lane hands over to its internal lane and the internal lane to the next.
  for (const pugi::xml_node& c : net.children("connection")) {
    const std::string from = c.attribute("from").as_string();
    const std::string via = c.attribute("via").as_string();
    const std::string to = c.attribute("to").as_string();
    const auto a = lane_shapes.find(from + "_" + c.attribute("fromLane").as_string());
    const auto b = lane_shapes.find(via.empty() ? to + "_" + c.attribute("toLane").as_string() : via);
    if (a == lane_shapes.end() || b == lane_shapes.end() || a->second.empty() || b->second.empty()) continue;
    const double step = std::abs(a->second.back().z() - b->second.front().z());
    check.max_handover_step_m = std::max(check.max_handover_step_m, step);
    ++check.handovers;
    const double gap = (a->second.back() - b->second.front()).head<2>().norm();
    if (gap > check.max_handover_gap_m) {
      check.max_handover_gap_m = gap;
      check.handover_gap_lanes = a->first + " -> " + b->first;
      check.handover_gap_point = a->second.back();
    }
    const double min_grade = std::max(lane_step_grade[a->first], lane_step_grade[b->first]);
    if (step > kStepRiseM && step > min_grade * gap && check.height_steps++ == 0) {
      check.first_step_lane = a->first;
      check.first_step_point = a->second.back();
    }
  }
  for (const pugi::xml_node& j : net.children("junction")) {
    if (std::string_view(j.attribute("type").as_string()) != "internal") ++check.junctions;
  }
  for ([[maybe_unused]] const pugi::xml_node& t : net.children("tlLogic")) ++check.traffic_lights;
  return check;
}

FcdCheck check_sumo_fcd(std::string_view fcd_xml, std::string_view net_xml, const RoadModel& model,
                        const std::string& file) {
  pugi::xml_document net_doc;
  const pugi::xml_node net = load_net(net_doc, net_xml, "network of " + file);
  pugi::xml_document doc;
  const pugi::xml_parse_result parsed = doc.load_buffer(fcd_xml.data(), fcd_xml.size());
  if (!parsed) throw InvalidInput("'" + file + "' is not XML: " + parsed.description());
  const pugi::xml_node fcd = doc.child("fcd-export");
  if (!fcd) throw InvalidInput("'" + file + "' is not SUMO FCD output (no <fcd-export> element)");

  FcdCheck check;
  LaneLocator locator(net, model);
  std::unordered_set<std::string> vehicles;
  std::vector<double> z_errors, slope_errors;
  constexpr double kDegrees = 180.0 / std::numbers::pi;
  constexpr double kHalfStep = 0.05;  // m, central difference of the surface grade
  for (const pugi::xml_node& step : fcd.children("timestep")) {
    ++check.timesteps;
    for (const pugi::xml_node& v : step.children("vehicle")) {
      vehicles.insert(v.attribute("id").as_string());
      const pugi::xml_attribute x = v.attribute("x"), y = v.attribute("y");
      const auto at =
          x && y ? locator.locate(v.attribute("lane").as_string(), Vec2(x.as_double(), y.as_double()))
                 : std::nullopt;
      if (!at) {
        ++check.samples_unmapped;
        continue;
      }
      if (!at->lane.odr_shape) {
        ++check.samples_netconvert_shape;
        continue;
      }
      const ModelRoad& road = *at->road;
      if (const pugi::xml_attribute z = v.attribute("z")) {
        z_errors.push_back(std::abs(z.as_double() - surface_z(road, at->s, at->t)));
      }
      if (const pugi::xml_attribute slope = v.attribute("slope")) {
        // Grade along the line at the sample's t: dz/ds of the profile scaled by the offset
        // line's length (and the superelevation's share, if any).
        const double s0 = std::max(0.0, at->s - kHalfStep), s1 = std::min(road.length(), at->s + kHalfStep);
        const Vec3 a = surface_point(road, s0, at->t), b = surface_point(road, s1, at->t);
        const double run = (b - a).head<2>().norm();
        if (run <= 0.0) continue;
        // Right lanes drive along s; without a lane id, the vehicle's heading tells
        // (SUMO's angle: degrees clockwise from north).
        double along = 1.0;
        if (at->lane.lane) {
          along = *at->lane.lane < 0 ? 1.0 : -1.0;
        } else {
          const double heading = (90.0 - v.attribute("angle").as_double()) / kDegrees;
          along = (b - a).head<2>().dot(Vec2(std::cos(heading), std::sin(heading))) >= 0.0 ? 1.0 : -1.0;
        }
        const double expected_deg = along * std::atan((b.z() - a.z()) / run) * kDegrees;
        slope_errors.push_back(std::abs(slope.as_double() - expected_deg));
      }
    }
  }
  check.vehicles = vehicles.size();
  check.samples = z_errors.size();
  check.slope_samples = slope_errors.size();
  std::tie(check.z_max_m, check.z_p99_m) = max_and_p99(z_errors);
  std::tie(check.slope_max_deg, check.slope_p99_deg) = max_and_p99(slope_errors);
  return check;
}

}  // namespace relief

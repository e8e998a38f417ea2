#include "relief/export/sumo_checks.h"

#include <pugixml.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <unordered_map>

#include "relief/core/errors.h"
#include "relief/roads/road_surface.h"

namespace relief {
namespace {

Polyline3 parse_shape(const char* text) {
  Polyline3 out;
  std::istringstream in(text);
  for (std::string token; in >> token;) {
    Vec3 p = Vec3::Zero();
    std::replace(token.begin(), token.end(), ',', ' ');
    std::istringstream xyz(token);
    xyz >> p.x() >> p.y();
    if (!(xyz >> p.z())) p.z() = 0.0;
    out.push_back(p);
  }
  return out;
}

std::optional<int> param_int(const pugi::xml_node& node, const char* key) {
  for (const pugi::xml_node& p : node.children("param")) {
    if (std::string_view(p.attribute("key").as_string()) == key) return p.attribute("value").as_int();
  }
  return std::nullopt;
}

// (s, t) of the point of `road`'s reference line nearest to p: a 1 m scan, then Newton steps.
class RoadProjector {
 public:
  explicit RoadProjector(const ModelRoad& road) : road_(road) {
    const double length = road.length();
    const int n = std::max(1, static_cast<int>(std::ceil(length)));
    for (int i = 0; i <= n; ++i) {
      const double s = length * i / n;
      stations_.push_back(s);
      const Vec3 p = surface_point(road, s, 0.0);
      points_.emplace_back(p.x(), p.y());
    }
  }

  [[nodiscard]] std::pair<double, double> project(const Vec2& p) const {
    std::size_t best = 0;
    double best_d = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < points_.size(); ++i) {
      const double d = (points_[i] - p).squaredNorm();
      if (d < best_d) {
        best_d = d;
        best = i;
      }
    }
    double s = stations_[best];
    for (int it = 0; it < 6; ++it) {
      const Vec3 o = surface_point(road_, s, 0.0);
      const double h = heading_at(road_, s);
      const double ds = (p - Vec2(o.x(), o.y())).dot(Vec2(std::cos(h), std::sin(h)));
      s = std::clamp(s + ds, 0.0, road_.length());
      if (std::abs(ds) < 1e-6) break;
    }
    const Vec3 o = surface_point(road_, s, 0.0);
    const double h = heading_at(road_, s);
    const double t = (p - Vec2(o.x(), o.y())).dot(Vec2(-std::sin(h), std::cos(h)));
    return {s, t};
  }

 private:
  const ModelRoad& road_;
  std::vector<double> stations_;
  std::vector<Vec2> points_;
};

}  // namespace

SumoNetCheck check_sumo_net(std::string_view net_xml, const RoadModel& model, const std::string& file) {
  pugi::xml_document doc;
  const pugi::xml_parse_result parsed = doc.load_buffer(net_xml.data(), net_xml.size());
  if (!parsed) throw InvalidInput("'" + file + "' is not XML: " + parsed.description());
  const pugi::xml_node net = doc.child("net");
  if (!net) throw InvalidInput("'" + file + "' is not a SUMO network (no <net> element)");

  SumoNetCheck check;
  std::unordered_map<int, RoadProjector> projectors;
  const auto projector = [&](int road_id) -> const RoadProjector* {
    const int index = model.road_index(road_id);
    if (index < 0) return nullptr;
    auto it = projectors.find(road_id);
    if (it == projectors.end()) {
      it = projectors.emplace(road_id, RoadProjector(model.roads[static_cast<std::size_t>(index)])).first;
    }
    return &it->second;
  };

  // Internal lanes take the OpenDRIVE road of the connection that runs through them.
  std::unordered_map<std::string, std::pair<int, int>> internal_road;  // lane id -> (road, lane)
  for (const pugi::xml_node& c : net.children("connection")) {
    const std::string via = c.attribute("via").as_string();
    if (via.empty()) continue;
    const auto road = param_int(c, "odr.road");
    const auto lane = param_int(c, "odr.lane");
    if (road && lane) internal_road[via] = {*road, *lane};
  }
  // A connection's internal lane may be split (":J_0_0" -> ":J_1_0"): follow the chain.
  for (bool changed = true; changed;) {
    changed = false;
    for (const pugi::xml_node& c : net.children("connection")) {
      const std::string from = c.attribute("from").as_string();
      const std::string via = c.attribute("via").as_string();
      if (from.empty() || from[0] != ':' || via.empty() || internal_road.count(via)) continue;
      const auto it = internal_road.find(from + "_" + c.attribute("fromLane").as_string());
      if (it == internal_road.end()) continue;
      internal_road[via] = it->second;
      changed = true;
    }
  }

  std::vector<double> errors;
  std::unordered_map<std::string, Polyline3> lane_shapes;
  for (const pugi::xml_node& edge : net.children("edge")) {
    const bool internal = std::string_view(edge.attribute("function").as_string()) == "internal";
    const auto edge_road = param_int(edge, "odr.road");
    if (!internal) ++check.edges;
    for (const pugi::xml_node& lane : edge.children("lane")) {
      const std::string id = lane.attribute("id").as_string();
      const Polyline3 shape = parse_shape(lane.attribute("shape").as_string());
      lane_shapes[id] = shape;
      if (!lane.attribute("disallow").empty()) ++check.disallowed_lanes;
      internal ? ++check.internal_lanes : ++check.lanes;
      for (std::size_t i = 1; i < shape.size(); ++i) {
        const double run = (shape[i] - shape[i - 1]).head<2>().norm();
        if (run >= 1.0) {
          double& worst = internal ? check.max_internal_lane_grade_percent : check.max_lane_grade_percent;
          worst = std::max(worst, 100.0 * std::abs(shape[i].z() - shape[i - 1].z()) / run);
        }
      }
      std::optional<int> road;
      std::optional<int> odr_lane;
      if (internal) {
        if (const auto it = internal_road.find(id); it != internal_road.end()) {
          road = it->second.first;
          odr_lane = it->second.second;
        }
      } else {
        road = edge_road;
        odr_lane = param_int(lane, "odr.lane");
      }
      const RoadProjector* proj = road ? projector(*road) : nullptr;
      if (!proj) {
        check.points_unmapped += shape.size();
        continue;
      }
      const ModelRoad& model_road = model.roads[static_cast<std::size_t>(model.road_index(*road))];
      for (const Vec3& p : shape) {
        const auto [s, t] = proj->project(Vec2(p.x(), p.y()));
        const Vec3 q = surface_point(model_road, s, t);
        errors.push_back(std::abs(p.z() - q.z()));
        if (odr_lane) {
          // Lane centre points lie on the OpenDRIVE lane centre (away from the lane's ends,
          // where netconvert may cut the shape).
          check.xy_max_m = std::max(check.xy_max_m, std::abs(t - lane_centre_t(model_road, s, *odr_lane)));
        }
      }
    }
  }
  check.points = errors.size();
  if (!errors.empty()) {
    std::sort(errors.begin(), errors.end());
    check.z_max_m = errors.back();
    check.z_p99_m = errors[static_cast<std::size_t>(0.99 * static_cast<double>(errors.size() - 1))];
  }

  // Height steps where a lane hands over to its internal lane and the internal lane to the next.
  for (const pugi::xml_node& c : net.children("connection")) {
    const std::string from = c.attribute("from").as_string();
    const std::string via = c.attribute("via").as_string();
    const std::string to = c.attribute("to").as_string();
    const auto a = lane_shapes.find(from + "_" + c.attribute("fromLane").as_string());
    const auto b = lane_shapes.find(via.empty() ? to + "_" + c.attribute("toLane").as_string() : via);
    if (a == lane_shapes.end() || b == lane_shapes.end() || a->second.empty() || b->second.empty()) continue;
    check.max_handover_step_m =
        std::max(check.max_handover_step_m, std::abs(a->second.back().z() - b->second.front().z()));
    ++check.handovers;
  }
  for (const pugi::xml_node& j : net.children("junction")) {
    if (std::string_view(j.attribute("type").as_string()) != "internal") ++check.junctions;
  }
  for ([[maybe_unused]] const pugi::xml_node& t : net.children("tlLogic")) ++check.traffic_lights;
  return check;
}

}  // namespace relief

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

#include "relief/core/errors.h"
#include "relief/roads/road_surface.h"

namespace relief {
namespace {

// A lane shape; `missing_z` is set when a point comes without z (taken as 0).
Polyline3 parse_shape(const char* text, bool* missing_z = nullptr) {
  Polyline3 out;
  std::istringstream in(text);
  for (std::string token; in >> token;) {
    Vec3 p = Vec3::Zero();
    std::replace(token.begin(), token.end(), ',', ' ');
    std::istringstream xyz(token);
    xyz >> p.x() >> p.y();
    if (!(xyz >> p.z())) {
      p.z() = 0.0;
      if (missing_z) *missing_z = true;
    }
    out.push_back(p);
  }
  return out;
}

constexpr double kStepRiseM = 0.1;     // a height step: more than this rise...
constexpr double kStepWindowM = 0.5;   // ...within this plan distance...
constexpr double kStepMinGrade = 0.5;  // ...and steeper than this there

// The first step along a 3D polyline (two points within kStepWindowM of plan distance along it
// that differ by more than kStepRiseM in height, at more than kStepMinGrade), or nullopt.
std::optional<Vec3> first_step(const Polyline3& line) {
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
      if (dz > kStepRiseM && dz > kStepMinGrade * along) return line[i];
    }
    if (j > i) run -= (line[i + 1] - line[i]).head<2>().norm();
  }
  return std::nullopt;
}

std::optional<int> param_int(const pugi::xml_node& node, const char* key) {
  for (const pugi::xml_node& p : node.children("param")) {
    if (std::string_view(p.attribute("key").as_string()) == key) return p.attribute("value").as_int();
  }
  return std::nullopt;
}

// Where a point lies on a road: station and offset, and how far it lies past the road's start
// (negative) or end (positive) along the reference line (0 when it projects inside).
struct Projection {
  double s = 0.0, t = 0.0, beyond = 0.0;
};

// (s, t) of the point of `road`'s reference line nearest to p: a 1 m scan, then Newton steps.
class RoadProjector {
 public:
  explicit RoadProjector(const ModelRoad& road) : road_(road) {
    const double length = road.length();
    const int n = std::max(1, static_cast<int>(std::ceil(length)));
    for (int i = 0; i <= n; ++i) {
      const double s = length * i / n;
      stations_.push_back(s);
      points_.push_back(road.plan.at(s).position);
    }
  }

  [[nodiscard]] Projection project(const Vec2& p) const {
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
    for (int it = 0; it < 20; ++it) {
      // Newton on (p - o(s)) . T(s) = 0, whose derivative is -(1 - curvature t): on a tight
      // bend the plain tangent step (the derivative taken as -1) overshoots on the outside and
      // never settles.
      const Pose2 pose = road_.plan.at(s);
      const Vec2 d = p - pose.position;
      const double along = d.dot(Vec2(std::cos(pose.heading), std::sin(pose.heading)));
      const double across = d.dot(Vec2(-std::sin(pose.heading), std::cos(pose.heading)));
      const double scale = 1.0 - pose.curvature * across;
      const double ds = along / std::max(scale, 0.25);
      s = std::clamp(s + ds, 0.0, road_.length());
      if (std::abs(ds) < 1e-6) break;
    }
    const Pose2 pose = road_.plan.at(s);
    const Vec2 d = p - pose.position;
    const double along = d.dot(Vec2(std::cos(pose.heading), std::sin(pose.heading)));
    const bool at_end = s <= 0.0 || s >= road_.length();
    return {s, d.dot(Vec2(-std::sin(pose.heading), std::cos(pose.heading))), at_end ? along : 0.0};
  }

 private:
  const ModelRoad& road_;
  std::vector<double> stations_;
  std::vector<Vec2> points_;
};

// OpenDRIVE road and lane of a SUMO lane.
struct LaneRoad {
  int road = -1;
  std::optional<int> lane;
  bool odr_shape = true;  ///< false: netconvert drew the lane itself (not on the OpenDRIVE lane centre)
};

// Where a point of a SUMO lane lies on its OpenDRIVE road.
struct LanePoint {
  const ModelRoad* road = nullptr;
  double s = 0.0, t = 0.0;
  LaneRoad lane;
};

// The internal lane of a connection without params: the model's connecting road that joins the
// connection's lanes (from_road/from_lane -> to_road/to_lane); a direct road-to-road link (or
// the two halves of a split road) stays on the road it leaves.
std::optional<LaneRoad> connecting_lane(const RoadModel& model, const LaneRoad& from, const LaneRoad& to) {
  if (!from.lane || !to.lane) return std::nullopt;
  for (const JunctionModel& junction : model.junctions) {
    for (const JunctionConnection& c : junction.connections) {
      if (c.incoming_road != from.road) continue;
      const int ci = model.road_index(c.connecting_road);
      if (ci < 0) continue;
      const ModelRoad& conn = model.roads[static_cast<std::size_t>(ci)];
      const bool along_s = c.contact == RoadLink::Contact::start;
      const std::optional<RoadLink>& exit = along_s ? conn.successor : conn.predecessor;
      if (!exit || exit->element != RoadLink::Element::road || exit->id != to.road) continue;
      for (const auto& [in_lane, conn_lane] : c.lane_links) {
        if (in_lane != *from.lane || conn.sections.empty()) continue;
        const LaneSection& sec = conn.sections.front();
        for (const LaneModel& l : conn_lane < 0 ? sec.right : sec.left) {
          if (l.id != conn_lane) continue;
          if ((along_s ? l.successor : l.predecessor) == *to.lane) return LaneRoad{conn.id, conn_lane, true};
        }
      }
    }
  }
  const int fi = model.road_index(from.road);
  if (fi < 0) return std::nullopt;
  const ModelRoad& road = model.roads[static_cast<std::size_t>(fi)];
  const auto links_to = [&](const std::optional<RoadLink>& link) {
    return link && link->element == RoadLink::Element::road && link->id == to.road;
  };
  if (from.road == to.road || links_to(road.predecessor) || links_to(road.successor)) return from;
  return std::nullopt;
}

// Every lane of a .net.xml mapped to its OpenDRIVE road and lane, and points of a lane
// projected onto that road (one projector per road, made on first use).
class LaneLocator {
 public:
  LaneLocator(const pugi::xml_node& net, const RoadModel& model) : model_(model) {
    for (const pugi::xml_node& edge : net.children("edge")) {
      if (std::string_view(edge.attribute("function").as_string()) == "internal") continue;
      const auto road = param_int(edge, "odr.road");
      if (!road) continue;
      for (const pugi::xml_node& lane : edge.children("lane")) {
        lanes_[lane.attribute("id").as_string()] = {*road, param_int(lane, "odr.lane"), true};
      }
    }
    // Internal lanes take the OpenDRIVE road of the connection that runs through them.
    for (const pugi::xml_node& c : net.children("connection")) {
      const std::string via = c.attribute("via").as_string();
      const std::string from = c.attribute("from").as_string();
      if (via.empty() || from.empty() || from[0] == ':') continue;
      const bool odr_shape = !c.attribute("shape").empty();
      const auto road = param_int(c, "odr.road");
      const auto lane = param_int(c, "odr.lane");
      if (road && lane) {
        lanes_[via] = {*road, *lane, odr_shape};
        continue;
      }
      const auto a = lanes_.find(from + "_" + c.attribute("fromLane").as_string());
      const auto b =
          lanes_.find(std::string(c.attribute("to").as_string()) + "_" + c.attribute("toLane").as_string());
      if (a == lanes_.end() || b == lanes_.end()) continue;
      if (const auto mapped = connecting_lane(model, a->second, b->second)) {
        lanes_[via] = *mapped;
        if (mapped->road == a->second.road) {
          lanes_[via].lane.reset();  // a link between road ends: short, beside no lane centre
        } else {
          lanes_[via].odr_shape = odr_shape;
        }
      }
    }
    // A connection's internal lane may be split (":J_0_0" -> ":J_1_0"): follow the chain.
    for (bool changed = true; changed;) {
      changed = false;
      for (const pugi::xml_node& c : net.children("connection")) {
        const std::string from = c.attribute("from").as_string();
        const std::string via = c.attribute("via").as_string();
        if (from.empty() || from[0] != ':' || via.empty() || lanes_.count(via)) continue;
        const auto it = lanes_.find(from + "_" + c.attribute("fromLane").as_string());
        if (it == lanes_.end()) continue;
        lanes_[via] = it->second;
        changed = true;
      }
    }
  }

  /// The OpenDRIVE road, lane and (s, t) of point p of SUMO lane `lane_id`; nullopt when the
  /// lane has no road in the model. A point past an end of its road (netconvert stretches an
  /// internal lane to where it cut the next lane) lies on the road linked there, if any: the
  /// surface at that (x, y) is that road's.
  [[nodiscard]] std::optional<LanePoint> locate(const std::string& lane_id, const Vec2& p) {
    const auto it = lanes_.find(lane_id);
    if (it == lanes_.end()) return std::nullopt;
    const ModelRoad* road = road_of(it->second.road);
    if (road == nullptr) return std::nullopt;
    const Projection at = projector(*road).project(p);
    if (std::abs(at.beyond) > kPastEnd_m) {
      const std::optional<RoadLink>& link = at.beyond < 0.0 ? road->predecessor : road->successor;
      const ModelRoad* next = link && link->element == RoadLink::Element::road ? road_of(link->id) : nullptr;
      if (next != nullptr) {
        const Projection on = projector(*next).project(p);
        if (std::abs(on.beyond) <= kPastEnd_m) {
          LaneRoad lane = it->second;
          lane.lane.reset();  // not on this road's lane centre: height only
          return LanePoint{next, on.s, on.t, lane};
        }
      }
    }
    return LanePoint{road, at.s, at.t, it->second};
  }

 private:
  static constexpr double kPastEnd_m = 0.01;

  [[nodiscard]] const ModelRoad* road_of(int id) const {
    const int index = model_.road_index(id);
    return index < 0 ? nullptr : &model_.roads[static_cast<std::size_t>(index)];
  }

  RoadProjector& projector(const ModelRoad& road) {
    auto it = projectors_.find(road.id);
    if (it == projectors_.end()) it = projectors_.emplace(road.id, RoadProjector(road)).first;
    return it->second;
  }

  const RoadModel& model_;
  std::unordered_map<std::string, LaneRoad> lanes_;
  std::unordered_map<int, RoadProjector> projectors_;
};

pugi::xml_node load_net(pugi::xml_document& doc, std::string_view net_xml, const std::string& file) {
  const pugi::xml_parse_result parsed = doc.load_buffer(net_xml.data(), net_xml.size());
  if (!parsed) throw InvalidInput("'" + file + "' is not XML: " + parsed.description());
  const pugi::xml_node net = doc.child("net");
  if (!net) throw InvalidInput("'" + file + "' is not a SUMO network (no <net> element)");
  return net;
}

// Largest value and 99th percentile (the value at rank floor(0.99 (n - 1))); sorts `values`.
std::pair<double, double> max_and_p99(std::vector<double>& values) {
  if (values.empty()) return {0.0, 0.0};
  std::sort(values.begin(), values.end());
  return {values.back(), values[static_cast<std::size_t>(0.99 * static_cast<double>(values.size() - 1))]};
}

}  // namespace

SumoNetCheck check_sumo_net(std::string_view net_xml, const RoadModel& model, const std::string& file) {
  pugi::xml_document doc;
  const pugi::xml_node net = load_net(doc, net_xml, file);

  SumoNetCheck check;
  LaneLocator locator(net, model);
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
      if (const auto step = first_step(shape)) {
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
      for (const Vec3& p : shape) {
        const auto at = locator.locate(id, Vec2(p.x(), p.y()));
        if (!at) {
          ++check.points_unmapped;
          continue;
        }
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
    if (step > kStepRiseM && step > kStepMinGrade * gap && check.height_steps++ == 0) {
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

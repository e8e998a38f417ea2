#pragma once
// Private to the export module: reading a .net.xml written by netconvert from relief's plain
// network. Lane shapes, params, and the LaneLocator that maps every lane (internal ones through
// their connections) to its OpenDRIVE road and lane and projects lane points onto that road.
// Shared by the checks of a net (sumo_checks.cpp) and the draping of its lanes onto the
// OpenDRIVE surface (sumo_drape.cpp).

#include <pugixml.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

#include "relief/geometry/types.h"
#include "relief/roads/road_model.h"

namespace relief::detail {

/// The points of a lane shape ("x,y[,z] ..."); `missing_z` is set when a point comes without z
/// (taken as 0).
[[nodiscard]] Polyline3 parse_shape(const char* text, bool* missing_z = nullptr);

/// The integer value of <param key="key"> under `node`, if any.
[[nodiscard]] std::optional<int> param_int(const pugi::xml_node& node, const char* key);

/// Parses `net_xml` into `doc` and returns its <net> element. Throws InvalidInput (naming
/// `file`) when it is not XML or not a SUMO network.
pugi::xml_node load_net(pugi::xml_document& doc, std::string_view net_xml, const std::string& file);

// Where a point lies on a road: station and offset, and how far it lies past the road's start
// (negative) or end (positive) along the reference line (0 when it projects inside).
struct Projection {
  double s = 0.0, t = 0.0, beyond = 0.0;
};

// (s, t) of the point of `road`'s reference line nearest to p: the nearest of its points sampled
// every metre or less, then Newton steps within one sample spacing of it. With a station `hint`
// near the answer (a point a few metres from one projected before) only the samples within
// 2 d + one spacing along the road from the hint are searched, d the distance from p to the
// hint's point: the answer lies within d of p, so within 2 d of that point in plan (and along
// the road unless it curls back on itself; the search of the whole road is O(length) per
// point). Newton alone from the hint ran off on a hairpin of 3.75 m arcs and short lines
// (Liechtenstein's Bergstrasse: to the hairpin's other leg, 12 m away and 3 m lower) and stopped
// at the wrong end of a connecting road turning 150 degrees on a 1.7 m radius (a wheel past the
// turn's centre), and the cosim measures took those heights.
class RoadProjector {
 public:
  explicit RoadProjector(const ModelRoad& road) : road_(road) {
    const double length = road.length();
    const int n = std::max(1, static_cast<int>(std::ceil(length)));
    spacing_ = length / n;
    for (int i = 0; i <= n; ++i) {
      const double s = length * i / n;
      stations_.push_back(s);
      points_.push_back(road.plan.at(s).position);
    }
  }

  [[nodiscard]] Projection project(const Vec2& p, std::optional<double> hint = std::nullopt) const {
    std::size_t first = 0, last = points_.size() - 1;
    if (hint && spacing_ > 0.0) {
      const double h = std::clamp(*hint, 0.0, road_.length());
      const double reach = 2.0 * (p - road_.plan.at(h).position).norm() + spacing_;
      const auto index = [&](double s) {
        return static_cast<std::size_t>(std::clamp(s / spacing_, 0.0, static_cast<double>(last)));
      };
      first = index(h - reach);
      last = std::min(last, index(h + reach) + 1);
    }
    std::size_t best = first;
    double best_d = std::numeric_limits<double>::infinity();
    for (std::size_t i = first; i <= last; ++i) {
      const double d = (points_[i] - p).squaredNorm();
      if (d < best_d) {
        best_d = d;
        best = i;
      }
    }
    const double lo = std::max(0.0, stations_[best] - spacing_);
    const double hi = std::min(road_.length(), stations_[best] + spacing_);
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
      s = std::clamp(s + ds, lo, hi);
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
  double spacing_ = 0.0;
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
  double beyond = 0.0;  ///< how far the point lies past that road's ends (Projection::beyond)
};

/// The internal lane of a connection without params: the model's connecting road that joins the
/// connection's lanes (from_road/from_lane -> to_road/to_lane); a direct road-to-road link (or
/// the two halves of a split road) stays on the road it leaves.
[[nodiscard]] std::optional<LaneRoad> connecting_lane(const RoadModel& model, const LaneRoad& from,
                                                      const LaneRoad& to);

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
    // The internal lanes each lane leads into and comes out of (its point past its road's end
    // into a junction lies on one of their roads).
    for (const pugi::xml_node& c : net.children("connection")) {
      const std::string via = c.attribute("via").as_string();
      const std::string from = c.attribute("from").as_string();
      if (via.empty() || from.empty() || from[0] == ':') continue;
      leads_into_[from + "_" + c.attribute("fromLane").as_string()].push_back(via);
      const std::string to = c.attribute("to").as_string();
      if (!to.empty() && to[0] != ':')
        comes_out_of_[to + "_" + c.attribute("toLane").as_string()].push_back(via);
    }
    // A connection's internal lane may be split (":J_0_0" -> ":J_1_0"): follow the chain.
    for (bool changed = true; changed;) {
      changed = false;
      for (const pugi::xml_node& c : net.children("connection")) {
        const std::string from = c.attribute("from").as_string();
        const std::string via = c.attribute("via").as_string();
        if (from.empty() || from[0] != ':' || via.empty() || lanes_.contains(via)) continue;
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
  /// surface at that (x, y) is that road's; past a road's end into a junction (netconvert
  /// drawing a lane on into the junction's outline), on the connecting road of an internal lane
  /// it leads into or comes out of, not on its own road's last cross-section drawn on. `near`: (OpenDRIVE
  /// road id, station) of a point a few metres from p, used as the projection's start on that road
  /// (RoadProjector::project).
  [[nodiscard]] std::optional<LanePoint> locate(const std::string& lane_id, const Vec2& p,
                                                std::optional<std::pair<int, double>> near = std::nullopt) {
    const auto hint = [&](const ModelRoad& r) {
      return near && near->first == r.id ? std::optional<double>(near->second) : std::nullopt;
    };
    const auto it = lanes_.find(lane_id);
    if (it == lanes_.end()) return std::nullopt;
    const ModelRoad* road = road_of(it->second.road);
    if (road == nullptr) return std::nullopt;
    const Projection at = projector(*road).project(p, hint(*road));
    if (std::abs(at.beyond) > kPastEnd_m) {
      const std::optional<RoadLink>& link = at.beyond < 0.0 ? road->predecessor : road->successor;
      std::vector<const ModelRoad*> next;
      bool in_junction = false;
      if (link && link->element == RoadLink::Element::road) {
        // On along the road links while p lies past each road's far end: a road trimmed to 1 m
        // between a junction and a transition road leaves p on the road after it (Fuzz seed 29:
        // an internal lane stretched 4.3 m past its connecting road, held at that road's end
        // height, 0.51 m under the lane it hands over to).
        const ModelRoad* n = road_of(link->id);
        for (int hop = 0; n != nullptr && hop < kMaxLinkHops; ++hop) {
          next.push_back(n);
          const Projection on = projector(*n).project(p, hint(*n));
          if (std::abs(on.beyond) <= kPastEnd_m) break;
          const std::optional<RoadLink>& on_link = on.beyond < 0.0 ? n->predecessor : n->successor;
          if (!on_link || on_link->element != RoadLink::Element::road || on_link->id == road->id) break;
          n = road_of(on_link->id);
        }
      } else if (link && link->element == RoadLink::Element::junction &&
                 std::abs(at.beyond) > kIntoJunction_m) {
        in_junction = true;
        const auto& vias = at.beyond < 0.0 ? comes_out_of_ : leads_into_;
        if (const auto v = vias.find(lane_id); v != vias.end()) {
          for (const std::string& via : v->second) {
            const auto mapped = lanes_.find(via);
            if (mapped != lanes_.end() && mapped->second.road != road->id)
              next.push_back(road_of(mapped->second.road));
          }
        }
      }
      // Of the roads that reach p, the one whose centre it lies nearest; in a junction only a
      // connecting road whose lane p lies on (its reference line is the lane's centre).
      std::optional<LanePoint> best;
      for (const ModelRoad* n : next) {
        if (n == nullptr) continue;
        const Projection on = projector(*n).project(p, hint(*n));
        if (std::abs(on.beyond) > kPastEnd_m || (best && std::abs(on.t) >= std::abs(best->t))) continue;
        if (in_junction && std::abs(on.t) > kOnConnectingLane_m) continue;
        LaneRoad lane = it->second;
        lane.lane.reset();  // not on this road's lane centre: height only
        best = LanePoint{n, on.s, on.t, lane, on.beyond};
      }
      if (best) return best;
    }
    return LanePoint{road, at.s, at.t, it->second, at.beyond};
  }

 private:
  static constexpr double kPastEnd_m = 0.01;
  // A lane end past its road's end by more than this lies in the junction (netconvert drawing
  // it on to the junction's outline: 7.7 m at NE's J216); less is netconvert's rounding and
  // offsetting, on the road's own end.
  static constexpr double kIntoJunction_m = 0.5;
  static constexpr double kOnConnectingLane_m = 2.0;  // half the widest lane (4 m), off its centre
  static constexpr int kMaxLinkHops = 4;              // roads followed past their ends

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
  std::unordered_map<std::string, std::vector<std::string>> leads_into_, comes_out_of_;  ///< lane -> vias
  std::unordered_map<int, RoadProjector> projectors_;
};

}  // namespace relief::detail

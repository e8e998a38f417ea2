#include "export/sumo_seams.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string_view>
#include <unordered_map>

#include "export/sumo_shapes.h"
#include "relief/roads/road_surface.h"

namespace relief::detail {
namespace {

// Points of `lane` (an OpenDRIVE lane centre of `road`) from station s0 to s1 (either order),
// every metre, simplified within 1 cm; both ends included.
Polyline3 lane_centre_between(const ModelRoad& road, int lane, double s0, double s1) {
  const int n = std::max(1, static_cast<int>(std::ceil(std::abs(s1 - s0))));
  Polyline3 line;
  for (int i = 0; i <= n; ++i) {
    const double s = s0 + (s1 - s0) * i / n;
    line.push_back(surface_point(road, s, lane_centre_t(road, s, lane)));
  }
  return simplify_3d(line, 0.01);
}

std::string shape_text(const Polyline3& shape) {
  std::string text;
  char point[96];
  for (const Vec3& p : shape) {
    std::snprintf(point, sizeof point, "%.2f,%.2f,%.2f", p.x(), p.y(), p.z());
    if (!text.empty()) text += ' ';
    text += point;
  }
  return text;
}

double plan_length(const Polyline3& line) {
  double length = 0.0;
  for (std::size_t i = 1; i < line.size(); ++i) length += (line[i] - line[i - 1]).head<2>().norm();
  return length;
}

struct Lane {
  pugi::xml_node node;
  Polyline3 shape;
};

class Seams {
 public:
  Seams(pugi::xml_node net, LaneLocator& locator, double tolerance_m)
      : locator_(locator), tolerance_m_(tolerance_m) {
    for (pugi::xml_node edge : net.children("edge")) {
      for (pugi::xml_node lane : edge.children("lane")) {
        lanes_[lane.attribute("id").as_string()] = {lane, parse_shape(lane.attribute("shape").as_string())};
      }
    }
  }

  // Closes the hand-over from lane `from` to lane `to`, one of them internal.
  void close(const std::string& from, const std::string& to) {
    const auto a = lanes_.find(from), b = lanes_.find(to);
    if (a == lanes_.end() || b == lanes_.end() || a->second.shape.size() < 2 || b->second.shape.size() < 2)
      return;
    const Polyline3& out = a->second.shape;
    const Polyline3& in = b->second.shape;
    if ((out.back() - in.front()).head<2>().norm() <= tolerance_m_) return;
    const bool into_junction = !from.starts_with(':');
    Lane& internal = into_junction ? b->second : a->second;
    const double old_length = plan_length(internal.shape);
    if (!extend(from, to, into_junction, internal)) snap(into_junction, out, in, internal);
    internal.node.attribute("shape").set_value(shape_text(internal.shape).c_str());
    char length[32];
    std::snprintf(length, sizeof length, "%.2f",
                  std::max(0.01, internal.node.attribute("length").as_double() + plan_length(internal.shape) -
                                     old_length));
    internal.node.attribute("length").set_value(length);
  }

  SumoSeams result;

 private:
  // Extends the internal lane along the other lane's OpenDRIVE lane when that lane stops short of
  // it; false when it does not (the two ends side by side, or the lane reaching past).
  bool extend(const std::string& from, const std::string& to, bool into_junction, Lane& internal) {
    const Polyline3& out = lanes_.at(from).shape;
    const Polyline3& in = lanes_.at(to).shape;
    const std::string& lane_id = into_junction ? from : to;
    const Vec2 lane_end = (into_junction ? out.back() : in.front()).head<2>();
    const Vec2 internal_end = (into_junction ? in.front() : out.back()).head<2>();
    const auto at_lane = locator_.locate(lane_id, lane_end);
    const auto at_internal = locator_.locate(lane_id, internal_end);
    if (!at_lane || !at_internal || !at_lane->lane.lane || at_lane->road != at_internal->road) return false;
    const int lane = *at_lane->lane.lane;
    // Right lanes (negative ids) run along s. Into the junction the internal lane must start
    // further along the lane than the cut end; out of it, end before the lane's start.
    const double ahead =
        (at_internal->s - at_lane->s) * (lane < 0 ? 1.0 : -1.0) * (into_junction ? 1.0 : -1.0);
    if (!(ahead > tolerance_m_)) return false;
    Polyline3 cut = into_junction ? lane_centre_between(*at_lane->road, lane, at_lane->s, at_internal->s)
                                  : lane_centre_between(*at_lane->road, lane, at_internal->s, at_lane->s);
    cut.front() = out.back();  // exactly the two lanes' points
    cut.back() = in.front();
    if (into_junction) {
      internal.shape.insert(internal.shape.begin(), cut.begin(), cut.end() - 1);
    } else {
      internal.shape.insert(internal.shape.end(), cut.begin() + 1, cut.end());
    }
    ++result.extended;
    const double added = plan_length(cut);
    if (added > result.max_extension_m) {
      result.max_extension_m = added;
      result.max_extension_lane = internal.node.attribute("id").as_string();
    }
    return true;
  }

  // Moves the internal lane's end onto the other lane's: the internal lane is cut at its point
  // nearest to that lane end (netconvert drew the lane past it, or beside it) and ends there.
  void snap(bool into_junction, const Polyline3& out, const Polyline3& in, Lane& internal) {
    const Vec3 target = into_junction ? out.back() : in.front();
    Polyline3 line = internal.shape;
    if (!into_junction) std::reverse(line.begin(), line.end());
    // Searched over the lane's first half only: a U-turn's other end may pass near the target.
    const double half = 0.5 * plan_length(line);
    std::size_t best = 0;
    double best_d = std::numeric_limits<double>::infinity();
    double along = 0.0;
    for (std::size_t i = 0; i + 1 < line.size() && (i == 0 || along < half); ++i) {
      along += (line[i + 1] - line[i]).head<2>().norm();
      const Vec2 p = line[i].head<2>(), q = line[i + 1].head<2>(), d = q - p;
      const double u =
          d.squaredNorm() > 0.0 ? std::clamp((target.head<2>() - p).dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
      const double dist = (p + u * d - target.head<2>()).norm();
      if (dist < best_d) {
        best_d = dist;
        best = i;
      }
    }
    const double moved = (line.front() - target).head<2>().norm();
    line.erase(line.begin(), line.begin() + static_cast<std::ptrdiff_t>(best + 1));
    line.insert(line.begin(), target);
    if (!into_junction) std::reverse(line.begin(), line.end());
    internal.shape = std::move(line);
    ++result.snapped;
    if (moved > result.max_snap_m) {
      result.max_snap_m = moved;
      result.max_snap_lane = internal.node.attribute("id").as_string();
    }
  }

  LaneLocator& locator_;
  double tolerance_m_;
  std::unordered_map<std::string, Lane> lanes_;
};

}  // namespace

SumoSeams close_handover_gaps(pugi::xml_node net, LaneLocator& locator, double tolerance_m) {
  Seams seams(net, locator, tolerance_m);
  for (const pugi::xml_node& c : net.children("connection")) {
    const std::string from =
        std::string(c.attribute("from").as_string()) + "_" + c.attribute("fromLane").as_string();
    const std::string via = c.attribute("via").as_string();
    const std::string to =
        std::string(c.attribute("to").as_string()) + "_" + c.attribute("toLane").as_string();
    if (!from.starts_with(':') && !via.empty()) seams.close(from, via);  // into the junction
    if (from.starts_with(':') && via.empty() && !to.starts_with(':')) seams.close(from, to);  // out of it
  }
  return seams.result;
}

}  // namespace relief::detail

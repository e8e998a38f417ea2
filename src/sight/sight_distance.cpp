#include "relief/sight/sight_distance.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <thread>

#include "relief/core/errors.h"
#include "sight/lane_path.h"
#include "sight/ray_scene.h"

namespace relief {
namespace {

using detail::LanePoints;
using detail::LaneRef;
using detail::RayScene;

constexpr double kGravity = 9.80665;
constexpr double kDefaultSpeed = 13.4112;  // 30 mph
constexpr double kRefine = 0.05;           // the first hidden step is bisected to this (m)

void check(const SightOptions& o) {
  const auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
  if (!positive(o.eye_height_m) || !positive(o.object_height_m) || !positive(o.step_m) ||
      !positive(o.reaction_s) || !positive(o.deceleration_mps2) || !positive(o.search_m))
    throw InvalidInput(
        "sight: heights, step, reaction time, deceleration and search distance must be finite and > 0");
}

/// The steepest downgrade the stopping distance is taken on: where g G would eat half the
/// deceleration (-17 % at 3.4 m/s2; SF's -31 % streets would otherwise need 9 times the distance
/// of the level, a figure AASHTO's formula was never meant for).
double steep_grade(const SightOptions& o) {
  return -0.5 * o.deceleration_mps2 / kGravity;
}

/// The point `d` m of plan distance after the suffix's start at index i, interpolated.
Vec3 point_at(const LanePoints& path, std::size_t i, double d) {
  const double target = path.distance[i] + d;
  const auto it =
      std::lower_bound(path.distance.begin() + static_cast<std::ptrdiff_t>(i), path.distance.end(), target);
  if (it == path.distance.end()) return path.points.back();
  const auto k = static_cast<std::size_t>(it - path.distance.begin());
  if (k == 0 || path.distance[k] <= path.distance[k - 1]) return path.points[k];
  const double f = (target - path.distance[k - 1]) / (path.distance[k] - path.distance[k - 1]);
  return path.points[k - 1] + f * (path.points[k] - path.points[k - 1]);
}

struct LaneJob {
  LaneRef lane;
  std::string road_class;
};

struct LaneOutcome {
  std::vector<SightStation> stations;
  std::size_t rays = 0;
};

LaneOutcome measure_lane(const RoadModel& model, const RayScene& rays, const LaneRef& lane,
                         const SightOptions& o) {
  LaneOutcome out;
  const ModelRoad& road = model.roads[static_cast<std::size_t>(lane.road)];
  const double speed = road.speed_mps.value_or(kDefaultSpeed);
  const double own = road.length();
  // Far enough for the steepest downgrade's stopping distance (steep_grade), or the whole search.
  const double needed =
      o.measure_beyond_required
          ? o.search_m
          : std::min(o.search_m, stopping_sight_distance(speed, steep_grade(o), o) + o.step_m);
  bool ended = false;
  const LanePoints path = detail::lane_ahead(model, lane, o.step_m, own + needed, ended);
  const Vec3 eye_up(0.0, 0.0, o.eye_height_m), object_up(0.0, 0.0, o.object_height_m);
  for (std::size_t i = 0; i < path.size() && !std::isnan(path.s[i]); ++i) {
    SightStation st;
    st.road = lane.road;
    st.lane = lane.lane;
    st.s = path.s[i];
    st.point = path.points[i];
    st.speed_mps = speed;
    const double left = path.distance.back() - path.distance[i];
    // The grade over the stopping distance, twice (it changes the distance).
    double required = stopping_sight_distance(speed, 0.0, o);
    double grade = 0.0;
    for (int pass = 0; pass < 2; ++pass) {
      const double over = std::min(required, left);
      grade = over > 1.0 ? (point_at(path, i, over).z() - st.point.z()) / over : 0.0;
      required = stopping_sight_distance(speed, std::max(grade, steep_grade(o)), o);
    }
    st.grade = grade;
    st.required_m = required;
    const double limit = std::min(o.measure_beyond_required ? o.search_m : required, left);
    const Vec3 eye = st.point + eye_up;
    const auto visible = [&](double d) {
      ++out.rays;
      return !rays.blocked(eye, point_at(path, i, d) + object_up);
    };
    double seen = limit;
    bool hidden = false;
    for (double d = std::min(o.step_m, limit), last = 0.0; d > 0.0;
         last = d, d = std::min(d + o.step_m, limit)) {
      if (!visible(d)) {
        double lo = last, hi = d;
        while (hi - lo > kRefine) {
          const double mid = 0.5 * (lo + hi);
          (visible(mid) ? lo : hi) = mid;
        }
        seen = lo;
        hidden = true;
        if (const auto hit = rays.first_hit(eye, point_at(path, i, hi) + object_up)) {
          st.obstacle = hit->kind == SurfaceKind::terrain ? SightObstacle::terrain : SightObstacle::road;
          st.obstacle_point = hit->point;
        }
        break;
      }
      if (d >= limit) break;
    }
    st.available_m = seen;
    st.measured = hidden || o.measure_beyond_required || !(seen >= required);
    st.path_ended = !hidden && ended && left < (o.measure_beyond_required ? o.search_m : required);
    out.stations.push_back(st);
  }
  return out;
}

}  // namespace

double stopping_sight_distance(double speed_mps, double grade, const SightOptions& o) {
  if (!std::isfinite(speed_mps) || speed_mps < 0.0 || !std::isfinite(grade))
    throw InvalidInput("stopping sight distance: speed must be finite and >= 0, grade finite");
  const double braking = o.deceleration_mps2 + kGravity * grade;
  if (!(braking > 0.0))
    throw InvalidInput("stopping sight distance: a downgrade of " + std::to_string(grade * 100.0) +
                       " % outweighs the deceleration");
  return speed_mps * o.reaction_s + speed_mps * speed_mps / (2.0 * braking);
}

const char* to_string(SightObstacle obstacle) {
  switch (obstacle) {
    case SightObstacle::road:
      return "road";
    case SightObstacle::terrain:
      return "terrain";
    case SightObstacle::none:
      break;
  }
  return "none";
}

SightResult sight_distances(const RoadModel& model, const MeshScene& obstacles, const SightOptions& options,
                            const std::vector<std::string>& road_class) {
  check(options);
  if (!road_class.empty() && road_class.size() != model.roads.size())
    throw InvalidInput("sight: " + std::to_string(road_class.size()) + " road classes for " +
                       std::to_string(model.roads.size()) + " roads");
  const RayScene rays(obstacles, [](SurfaceKind k) { return k != SurfaceKind::marking; });
  SightResult result;
  result.obstacle_triangles = rays.triangles();
  std::vector<LaneJob> jobs;
  for (std::size_t r = 0; r < model.roads.size(); ++r) {
    const ModelRoad& road = model.roads[r];
    if ((road.junction >= 0 && !options.junction_roads) || road.sections.empty()) continue;
    const std::string cls = road_class.empty() ? road.type : road_class[r];
    const LaneSection& first = road.sections.front();
    for (const std::vector<LaneModel>* side : {&first.right, &first.left})
      for (const LaneModel& lane : *side)
        if (lane.type == "driving") jobs.push_back({LaneRef{static_cast<int>(r), lane.id}, cls});
  }
  std::vector<LaneOutcome> outcomes(jobs.size());
  const unsigned threads = std::max(1U, std::min(std::thread::hardware_concurrency(), 8U));
  std::vector<std::thread> pool;
  for (unsigned t = 0; t < threads; ++t)
    pool.emplace_back([&, t] {
      for (std::size_t j = t; j < jobs.size(); j += threads)
        outcomes[j] = measure_lane(model, rays, jobs[j].lane, options);
    });
  for (std::thread& th : pool) th.join();

  const auto is_short_at = [](const SightStation& st) { return st.short_of_required() && !st.path_ended; };
  for (std::size_t j = 0; j < jobs.size(); ++j) {
    LaneOutcome& lane = outcomes[j];
    result.rays += lane.rays;
    SightClassFigures& cls = result.by_class[jobs[j].road_class];
    // Each station stands for the lane up to the next one.
    for (std::size_t i = 0; i < lane.stations.size(); ++i) {
      const SightStation& st = lane.stations[i];
      const double km = i + 1 < lane.stations.size() ? std::abs(lane.stations[i + 1].s - st.s) / 1000.0 : 0.0;
      cls.km_checked += km;
      result.km_checked += km;
      if (!is_short_at(st)) continue;
      cls.km_short += km;
      result.km_short += km;
      if (i == 0 || !is_short_at(lane.stations[i - 1])) {
        SightStretch s;
        s.road = st.road;
        s.lane = st.lane;
        s.s_from = s.s_to = st.s;
        s.road_class = jobs[j].road_class;
        // A lane's last station alone: its line starts at the station before.
        if (i > 0 && i + 1 == lane.stations.size()) {
          s.points.push_back(lane.stations[i - 1].point);
          s.s_from = std::min(s.s_from, lane.stations[i - 1].s);
          s.s_to = std::max(s.s_to, lane.stations[i - 1].s);
        }
        result.stretches.push_back(std::move(s));
      }
      SightStretch& s = result.stretches.back();
      const double next_s = i + 1 < lane.stations.size() ? lane.stations[i + 1].s : st.s;
      s.s_from = std::min({s.s_from, st.s, next_s});
      s.s_to = std::max({s.s_to, st.s, next_s});
      s.points.push_back(st.point);
      // The last short station's line runs on to the next station.
      if (i + 1 < lane.stations.size() && !is_short_at(lane.stations[i + 1]))
        s.points.push_back(lane.stations[i + 1].point);
      if (s.required_m == 0.0 || st.available_m / st.required_m < s.available_m / s.required_m) {
        s.available_m = st.available_m;
        s.required_m = st.required_m;
        s.speed_mps = st.speed_mps;
        s.grade = st.grade;
        s.obstacle = st.obstacle;
        s.obstacle_point = st.obstacle_point;
      }
    }
    result.station_count += lane.stations.size();
    if (options.keep_stations)
      result.stations.insert(result.stations.end(), lane.stations.begin(), lane.stations.end());
    lane.stations = {};
  }
  std::stable_sort(result.stretches.begin(), result.stretches.end(),
                   [](const SightStretch& a, const SightStretch& b) {
                     return a.available_m / a.required_m < b.available_m / b.required_m;
                   });
  return result;
}

}  // namespace relief

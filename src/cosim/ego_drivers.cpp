#include "cosim/ego_drivers.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

#include "cosim/placement_measures.h"
#include "relief/core/diagnostic_codes.h"
#include "relief/geometry/polyline.h"

namespace relief::detail {
namespace {

constexpr double kDegree = 180.0 / std::numbers::pi;
constexpr std::size_t kResyncLogSize = 100;
constexpr double kPathAhead_m = 50.0;  // of lane centre handed to the driver
// An ego this close to the end of its route is handed back to SUMO, which lets it arrive
// (a vehicle SUMO is told where to be every step never reaches its arrival).
constexpr double kReleaseBeforeEnd_m = 10.0;
// SUMO maps a moved vehicle in plan onto an edge of its whole route (by distance and angle): where
// another part of the route passes less than this much farther from the ego than its own edge
// (over or under it, a hairpin, the way back), or the ego is farther than kOffRoute_m from its
// own, SUMO could take it there (in Liechtenstein 1.5 km along the route, which SUMO 1.15 then
// aborts on): SUMO drives the ego that step instead, and the resync brings the physics back.
constexpr double kAmbiguityMargin_m = 1.0;
constexpr double kOffRoute_m = 1.5;
// SUMO also drives an ego while any of it is in a junction (SumoSession::spans_junction):
// libsumo 1.15 (built with assertions in Debian) aborted on a remote-controlled vehicle whose
// back spanned a junction's internal lanes ("Request backPos ... for invalid lane", Liechtenstein).
constexpr double kGapGain_per_s = 3.0;  // speed added per metre SUMO is ahead

Vec2 direction(double heading) {
  return {std::cos(heading), std::sin(heading)};
}

// SUMO's angle (0 north, clockwise, degrees) of a heading in relief's frame.
double sumo_angle(double heading) {
  const double a = 90.0 - heading * kDegree;
  return a - 360.0 * std::floor(a / 360.0);
}

std::string place_text(const std::string& id, double t, double error, const SumoVehicleState& v) {
  char text[200];
  std::snprintf(text, sizeof text, "%s at t = %.2f s: %.2f m apart, SUMO on %s at (%.1f, %.1f)", id.c_str(),
                t, error, v.lane.c_str(), v.front.x(), v.front.y());
  return text;
}

double distance_to_segment(const Vec2& p, const Vec2& a, const Vec2& b) {
  const PolylineFoot foot = nearest_on_polyline({a, b}, p);
  return ((foot.found ? foot.point : a) - p).norm();
}

// The point of the polyline nearest `at` (`at` itself without a segment).
Vec2 nearest_on(const std::vector<Vec2>& line, const Vec2& at) {
  const PolylineFoot foot = nearest_on_polyline(line, at);
  return foot.found ? foot.point : at;
}

// The direction of the polyline's segment nearest `at` (`fallback` without one).
double heading_at(const std::vector<Vec2>& line, const Vec2& at, double fallback) {
  const PolylineFoot foot = nearest_on_polyline(line, at);
  return foot.found ? std::atan2(foot.direction.y(), foot.direction.x()) : fallback;
}

}  // namespace

EgoDrivers::EgoDrivers(const MeshScene& scene, const SurfaceQuery& query, SumoSession& sumo,
                       const CosimOptions& options)
    : scene_(scene),
      query_(query),
      sumo_(sumo),
      options_(options),
      named_(options.egos.begin(), options.egos.end()) {}

void EgoDrivers::pick(const SumoVehicleState& v) {
  if (!seen_.insert(v.id).second) return;
  if (named_.contains(v.id)) {
    driven_.insert(v.id);
  } else if (picked_ < options_.ego_count && (options_.ego_type.empty() || v.type == options_.ego_type)) {
    driven_.insert(v.id);
    ++picked_;
  }
}

void EgoDrivers::spawn(const SumoVehicleState& v, double heading) {
  if (!world_) world_ = std::make_unique<EgoWorld>(scene_);
  auto [it, added] = vclass_.try_emplace(v.type);
  if (added) it->second = sumo_.vehicle_class(v.type);
  const EgoSpec spec = ego_spec_for(it->second, v.length_m, v.width_m, v.height_m);
  const double slope = v.slope_deg / kDegree;
  const Vec2 centre = Vec2(v.front.x(), v.front.y()) - 0.5 * v.length_m * direction(heading);
  const std::optional<SurfacePose> pose =
      place_on_surface(query_, centre, heading, WheelBase{spec.wheelbase_m, spec.track_m},
                       v.front.z() - std::tan(slope) * 0.5 * v.length_m, slope, options_.max_contact_gap_m);
  if (!route_.contains(v.id)) route_[v.id] = sumo_.route_shapes(v.id);
  if (pose) {
    world_->place(v.id, spec, centre, heading, pose->z_m, v.speed_mps, pose->pitch_rad, pose->roll_rad);
  } else {
    world_->place(v.id, spec, centre, heading, v.front.z() - std::tan(slope) * 0.5 * v.length_m, v.speed_mps,
                  slope);
  }
}

void EgoDrivers::after_sumo_step(std::vector<SumoVehicleState>& vehicles, double t, CosimResult& result) {
  std::unordered_set<std::string> present;
  for (SumoVehicleState& v : vehicles) {
    pick(v);
    if (!driven_.contains(v.id) || released_.contains(v.id)) continue;
    present.insert(v.id);
    lane_[v.id] = v.lane;
    if (!world_ || !world_->has(v.id)) {
      spawn(v, v.heading());
      if (spawned_.insert(v.id).second) ++result.egos;  // distinct egos, not spawns
    } else {
      const EgoState s = world_->state(v.id);
      const Vec2 front = s.centre + 0.5 * v.length_m * direction(s.heading_rad);
      const Vec2 sumo_front(v.front.x(), v.front.y());
      // SUMO changes lanes in one step (without its sublane model): while the ego changes
      // lanes, anywhere between SUMO's position and its counterpart on the lane the ego is
      // taking agrees with SUMO.
      const std::vector<Vec2> lane = sumo_.lane_path_ahead(v.id, sumo_front, 1.0);
      const Vec2 counterpart = nearest_on(lane, sumo_front);
      const double error = distance_to_segment(front, sumo_front, counterpart);
      gap_[v.id] = (sumo_front - front).dot(direction(s.heading_rad));  // > 0: SUMO is ahead
      sync_errors_.push_back(static_cast<float>(error));
      speed_gaps_.push_back(static_cast<float>(std::abs(v.speed_mps - s.speed_mps)));
      ++result.ego_steps;
      // A body with no wheel on anything and off the surface under it fell through a gap in the
      // physics' mesh: a desync too.
      const std::optional<SurfaceHit> under = query_.nearest(s.centre.x(), s.centre.y(), v.front.z());
      const bool fell = s.wheels_on_ground == 0 && (!under || std::abs(s.ground_z_m - under->z_m) > 1.0);
      if (error > options_.resync_m || fell) {  // the physics yields: SUMO's place, lane direction and speed
        ++result.resyncs;
        if (result.resync_log.size() < kResyncLogSize)
          result.resync_log.push_back(place_text(v.id, t, error, v) +
                                      (fell ? ", fell through the mesh" : ""));
        const std::vector<Vec2> own = sumo_.lane_path_ahead(v.id, sumo_front, 1.0, v.lane);
        spawn(v, heading_at(own, sumo_front, v.heading()));  // at SUMO's speed too
      }
    }
    const EgoState s = world_->state(v.id);
    const Vec2 front = s.centre + 0.5 * v.length_m * direction(s.heading_rad);
    v.front = Vec3(front.x(), front.y(), v.front.z());
    v.angle_deg = sumo_angle(s.heading_rad);
    v.speed_mps = s.speed_mps;
  }
  if (!world_) return;
  for (const std::string& id : driven_)
    if (world_->has(id) && !present.contains(id)) world_->remove(id);  // arrived
}

SurfacePose EgoDrivers::pose(const std::string& id) const {
  const EgoState s = world_->state(id);
  SurfacePose p;
  p.z_m = s.ground_z_m;
  p.pitch_rad = s.pitch_rad;
  p.roll_rad = s.roll_rad;
  p.wheels_in_air = 4 - s.wheels_on_ground;
  for (std::size_t i = 0; i < 4; ++i) {
    const Vec3& c = s.contacts[i];
    const std::optional<SurfaceHit> hit = query_.nearest(c.x(), c.y(), c.z());
    if (!hit || std::abs(hit->z_m - c.z()) > options_.max_contact_gap_m) {
      ++p.contacts_missing;
      p.wheel_z_m[i] = c.z();
      continue;
    }
    p.wheel_z_m[i] = hit->z_m;
    p.wheel_kind[i] = hit->kind;
    p.wheel_under_m[i] = hit->z_m - c.z();  // > 0: the wheel's bottom under the surface
  }
  return p;
}

void EgoDrivers::drive(double dt_s) {
  if (!world_) return;
  for (const std::string& id : driven_) {
    if (world_->has(id) && sumo_.distance_to_route_end(id) < kReleaseBeforeEnd_m) {
      world_->remove(id);
      released_.insert(id);
    }
  }
  for (const std::string& id : driven_) {
    if (!world_->has(id)) continue;
    const EgoSpec& spec = world_->spec(id);
    const EgoState s = world_->state(id);
    const std::vector<Vec2> path = sumo_.lane_path_ahead(id, s.centre, kPathAhead_m);
    // Toward SUMO's desired speed, closing a gap to where SUMO has the vehicle (it has one after a
    // step SUMO drove).
    const double target = std::max(0.0, sumo_.desired_speed(id) + kGapGain_per_s * gap_[id]);
    world_->set_controls(id, drive_along(spec, s, path, target, options_.driver));
  }
  world_->step(dt_s);
  for (const std::string& id : driven_) {
    if (!world_->has(id)) continue;
    const EgoState s = world_->state(id);
    const Vec2 front = s.centre + 0.5 * world_->spec(id).length_m * direction(s.heading_rad);
    if (route_ambiguous_at(id, front) || sumo_.spans_junction(id)) {
      ++held_steps_;
      continue;
    }
    sumo_.move_to(id, lane_[id], front, sumo_angle(s.heading_rad));
  }
}

bool EgoDrivers::route_ambiguous_at(const std::string& id, const Vec2& front) const {
  const auto it = route_.find(id);
  if (it == route_.end()) return false;
  const auto& route = it->second;
  const std::string current = sumo_.route_edge(id);
  std::size_t here = route.size();
  for (std::size_t i = 0; i < route.size() && here == route.size(); ++i)
    if (route[i].first == current) here = i;
  if (here == route.size()) return true;  // off its route: SUMO drives
  double own = std::numeric_limits<double>::infinity(), other = own;
  for (std::size_t i = 0; i < route.size(); ++i) {
    const bool near_here = i + 1 >= here && i <= here + 1;  // where it is and its neighbours
    for (const std::vector<Vec2>& lane : route[i].second) {
      const PolylineFoot foot = nearest_on_polyline(lane, front);
      if (!foot.found) continue;
      const double d = (foot.point - front).norm();
      (near_here ? own : other) = std::min(near_here ? own : other, d);
    }
  }
  return own > kOffRoute_m || other < own + kAmbiguityMargin_m;
}

void EgoDrivers::finish(CosimResult& result, Diagnostics& diagnostics) {
  result.ego_steps_held = held_steps_;
  result.sync_error_m = spread_of(sync_errors_);
  result.ego_speed_gap_mps = spread_of(speed_gaps_);
  for (const std::string& id : options_.egos) {
    if (!seen_.contains(id))
      diagnostics.report(Severity::warning, codes::kCosimEgoMissing,
                         "vehicle '" + id + "' was named as an ego but never ran in SUMO");
  }
  if (result.resyncs > 0) {
    diagnostics.report(Severity::warning, codes::kCosimEgoResync,
                       std::to_string(result.resyncs) + " resynchronisation(s) of ego vehicles past " +
                           std::to_string(options_.resync_m) + " m; the first: " + result.resync_log.front());
  }
}

}  // namespace relief::detail

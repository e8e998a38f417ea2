#include "cosim/placement_measures.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <sstream>

#include "relief/core/diagnostic_codes.h"

namespace relief::detail {
namespace {

constexpr double kDegree = 180.0 / std::numbers::pi;
// A wheel contact this far outside a road's outermost lane borders is off that road: its
// OpenDRIVE height there would be the road's roll carried past its edge (Liechtenstein's road
// 3046, a wheel 2.5 m outside it: 1 m over the junction it stood on).
constexpr double kOffRoad_m = 0.25;

}  // namespace

Spread spread_of(std::vector<float>& values) {
  Spread s;
  s.count = values.size();
  if (values.empty()) return s;
  const auto at = [&](double q) {
    const auto k = static_cast<std::size_t>(q * static_cast<double>(values.size() - 1));
    std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(k), values.end());
    return static_cast<double>(values[k]);
  };
  s.p50 = at(0.5);
  s.p99 = at(0.99);
  s.max = static_cast<double>(*std::max_element(values.begin(), values.end()));
  return s;
}

void PlacementMeasures::track_lane(const SumoVehicleState& v) {
  std::array<std::string, 3>& lanes = recent_[v.id];
  if (lanes[0] != v.lane) {
    std::rotate(lanes.rbegin(), lanes.rbegin() + 1, lanes.rend());
    lanes[0] = v.lane;
  }
}

void PlacementMeasures::unplaced(const SumoVehicleState& v, double t, CosimResult& result) {
  if (result.unplaced++ > 0) return;
  const Vec2 centre = v.centre();
  std::ostringstream where;
  where << "vehicle '" << v.id << "' on lane '" << v.lane << "' at t = " << t << " s (" << centre.x() << ", "
        << centre.y() << ")";
  first_unplaced_ = where.str();
}

std::optional<double> PlacementMeasures::odr_body_z(const SumoVehicleState& v, const std::string& lane,
                                                    const LaneSurfacePoint& near) {
  const WheelBase wheels = wheel_base_of(v.length_m, v.width_m);
  const Vec2 centre = v.centre();
  const double heading = v.heading();
  const Vec2 forward(std::cos(heading), std::sin(heading));
  const Vec2 left(-forward.y(), forward.x());
  double sum = 0.0;
  for (const double along : {0.5 * wheels.wheelbase_m, -0.5 * wheels.wheelbase_m}) {
    for (const double across : {0.5 * wheels.track_m, -0.5 * wheels.track_m}) {
      const Vec2 contact = centre + along * forward + across * left;
      const auto on = [](const std::optional<LaneSurfacePoint>& p) {
        return p && p->on_road() && p->outside_m <= kOffRoad_m;
      };
      std::optional<LaneSurfacePoint> at = odr_.at(lane, contact, &near);
      // A contact past the centre's road (the vehicle spans a road's end) or beside it (it
      // turns across a road's edge): on the road of another of its last lanes.
      for (const std::string& other : recent_[v.id]) {
        if (on(at) || other.empty()) break;
        if (other != lane) at = odr_.at(other, contact);
      }
      if (!on(at)) return std::nullopt;
      sum += at->z_m;
    }
  }
  return 0.25 * sum;
}

void PlacementMeasures::add(const SumoVehicleState& v, const SurfacePose& pose, double t, CosimResult& result,
                            bool sumo_placed) {
  ++result.vehicle_steps;
  result.contacts_missing += static_cast<std::size_t>(pose.contacts_missing);
  const double under = std::max(0.0, *std::max_element(pose.wheel_under_m.begin(), pose.wheel_under_m.end()));
  wheel_under_.push_back(static_cast<float>(under));
  if (under > worst_under_) {
    worst_under_ = under;
    const Vec2 centre = v.centre();
    std::ostringstream where;
    where << "vehicle '" << v.id << "' at t = " << t << " s on lane '" << v.lane << "' at (" << centre.x()
          << ", " << centre.y() << "), heading " << v.heading() << " rad: wheels at " << pose.wheel_z_m[0]
          << ", " << pose.wheel_z_m[1] << ", " << pose.wheel_z_m[2] << ", " << pose.wheel_z_m[3]
          << " m (front left, front right, rear left, rear right), " << under << " m";
    result.worst_wheel_under_place = where.str();
  }
  for (const double wheel : pose.wheel_under_m)
    if (wheel > options_.wheel_under_limit_m) ++result.wheels_under_road;
  for (const SurfaceKind kind : pose.wheel_kind)
    if (kind != SurfaceKind::road && kind != SurfaceKind::junction) ++result.off_pavement;

  // SUMO's own height at the bumper, on the lane it reports.
  const std::optional<LaneSurfacePoint> at_front =
      sumo_placed ? odr_.at(v.lane, Vec2(v.front.x(), v.front.y())) : std::nullopt;
  if (at_front && at_front->on_road())
    sumo_z_errors_.push_back(static_cast<float>(std::abs(v.front.z() - at_front->z_m)));

  // The placement at the centre, on the newest of its last lanes whose road the centre is on.
  const Vec2 centre = v.centre();
  const double heading = v.heading();
  std::optional<LaneSurfacePoint> at_centre;
  const std::string* centre_lane = nullptr;
  for (const std::string& lane : recent_[v.id]) {
    if (lane.empty()) break;
    at_centre = odr_.at(lane, centre);
    if (at_centre && at_centre->on_road()) {
      centre_lane = &lane;
      break;
    }
    at_centre.reset();
  }
  // The nearby points start their projections at the centre's station (no search along the road).
  // Within half a metre of its road's end the centre has no slope there: its height is still
  // measured, its pitch not.
  const std::optional<double> slope =
      centre_lane ? odr_.slope(*centre_lane, centre, heading, 0.5, &*at_centre) : std::nullopt;
  if (!at_centre) {
    if (result.unmapped++ == 0) {
      std::ostringstream where;
      where << "lane '" << v.lane << "' at t = " << t << " s";
      first_unmapped_ = where.str();
    }
    return;
  }
  const double z_error = std::abs(pose.z_m - at_centre->z_m);
  // The vehicle, time, lane and place of an error (the worst of its kind so far).
  const auto place = [&](double error) {
    std::ostringstream where;
    where << "vehicle '" << v.id << "' at t = " << t << " s on lane '" << v.lane << "' (OpenDRIVE road "
          << at_centre->odr_road << ", s = " << at_centre->s << ") at (" << centre.x() << ", " << centre.y()
          << "): " << error << " m";
    return where.str();
  };
  if (!sumo_placed) {
    // An ego: the physics' body on its suspension, not a placement. With a wheel off the ground
    // (a crest taken fast lifts it) counted apart.
    if (pose.wheels_in_air > 0) {
      ++result.ego_steps_wheels_in_air;
      if (z_error > result.wheels_in_air_z_max_m) {
        result.wheels_in_air_z_max_m = z_error;
        result.worst_in_air_place = place(z_error);
      }
    } else {
      ego_z_errors_.push_back(static_cast<float>(z_error));
      if (z_error > worst_ego_z_) {
        worst_ego_z_ = z_error;
        result.worst_ego_z_place = place(z_error);
      }
    }
    return;
  }
  z_errors_.push_back(static_cast<float>(z_error));
  (centre_lane->starts_with(':') ? z_errors_junction_ : z_errors_road_)
      .push_back(static_cast<float>(z_error));
  if (slope)
    pitch_errors_.push_back(static_cast<float>(std::abs(pose.pitch_rad - std::atan(*slope)) * kDegree));
  // The same vehicle set on the OpenDRIVE surface: its wheel contacts' mean height there.
  if (const std::optional<double> body = odr_body_z(v, *centre_lane, *at_centre)) {
    const auto e = static_cast<float>(std::abs(pose.z_m - *body));
    body_errors_.push_back(e);
    (centre_lane->starts_with(':') ? body_errors_junction_ : body_errors_road_).push_back(e);
    if (e > worst_body_) {
      worst_body_ = e;
      result.worst_body_place = place(e);
    }
  }
  if (z_error > worst_z_) {
    worst_z_ = z_error;
    result.worst_z_place = place(z_error);
  }
}

void PlacementMeasures::finish(CosimResult& result, Diagnostics& diagnostics) {
  result.vehicles = recent_.size();
  result.z_error_m = spread_of(z_errors_);
  result.z_error_on_roads_m = spread_of(z_errors_road_);
  result.z_error_in_junctions_m = spread_of(z_errors_junction_);
  result.z_error_body_m = spread_of(body_errors_);
  result.z_error_body_on_roads_m = spread_of(body_errors_road_);
  result.z_error_body_in_junctions_m = spread_of(body_errors_junction_);
  result.sumo_z_error_m = spread_of(sumo_z_errors_);
  result.pitch_error_deg = spread_of(pitch_errors_);
  result.wheel_under_m = spread_of(wheel_under_);
  result.ego_z_error_m = spread_of(ego_z_errors_);
  if (result.unplaced > 0) {
    diagnostics.report(Severity::warning, codes::kCosimVehicleOffSurface,
                       std::to_string(result.unplaced) +
                           " vehicle step(s) with two or more wheels on no surface near where SUMO has the "
                           "vehicle, not placed; the first: " +
                           first_unplaced_);
  }
  if (result.unmapped > 0) {
    diagnostics.report(Severity::warning, codes::kCosimLaneUnmapped,
                       std::to_string(result.unmapped) +
                           " vehicle step(s) whose centre lies on no OpenDRIVE road of its last lanes, not "
                           "measured; the first on " +
                           first_unmapped_);
  }
}

}  // namespace relief::detail

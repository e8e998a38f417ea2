#include "relief/cosim/ego_controller.h"

#include "relief/geometry/polyline.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace relief {
namespace {

constexpr double kGravity = 9.81;
constexpr double kAirDensity = 1.2;

// The speed the path allows now: every point ahead taken no faster than its curvature lets
// the lateral acceleration stay at `lateral`, reached by braking at `decel`. Curvature is the
// heading change over 4 m of the path resampled at 1 m.
double curve_speed(std::span<const Vec2> path, const Vec2& from, double lateral, double decel) {
  std::vector<Vec2> samples;
  double carry = 0.0;
  for (std::size_t i = 0; i + 1 < path.size(); ++i) {
    const Vec2& a = path[i];
    const Vec2 ab = path[i + 1] - a;
    const double length = ab.norm();
    for (double s = carry; s < length; s += 1.0) samples.emplace_back(a + (s / length) * ab);
    carry = length > 0.0 ? std::fmod(carry - length, 1.0) : carry;
    if (carry < 0.0) carry += 1.0;
  }
  double allowed = std::numeric_limits<double>::infinity();
  std::size_t start = 0;
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const double d = (samples[i] - from).squaredNorm();
    if (d < best) {
      best = d;
      start = i;
    }
  }
  for (std::size_t i = std::max<std::size_t>(start, 2); i + 2 < samples.size(); ++i) {
    const Vec2 in = samples[i] - samples[i - 2], out = samples[i + 2] - samples[i];
    const double turn = std::abs(std::atan2(in.x() * out.y() - in.y() * out.x(), in.dot(out)));
    const double curvature = turn / (in.norm() + out.norm());
    if (curvature < 1e-4) continue;
    const auto ahead = static_cast<double>(i - std::min(i, start));
    allowed = std::min(allowed, std::sqrt(lateral / curvature + 2.0 * decel * ahead));
  }
  return allowed;
}

}  // namespace

EgoControls drive_along(const EgoSpec& spec, const EgoState& state, std::span<const Vec2> path,
                        double target_mps, const EgoDriverOptions& options) {
  EgoControls c;
  const Vec2 heading(std::cos(state.heading_rad), std::sin(state.heading_rad));
  const double v = state.speed_mps;
  // Steering: Stanley's law (Hoffmann et al. 2007) at the front bumper: the heading error plus
  // the angle that closes the cross-track error within gain^-1 (v + softening) metres.
  const Vec2 bumper = state.centre + 0.5 * spec.length_m * heading;
  PolylineFoot near = nearest_on_polyline(Polyline2(path.begin(), path.end()), bumper, true);
  if (!near.found) near = {true, 0, bumper, heading};  // no path: straight on
  const Vec2 tangent = near.direction;
  const double heading_error =
      std::atan2(heading.x() * tangent.y() - heading.y() * tangent.x(), heading.dot(tangent));
  const Vec2 off = bumper - near.point;
  const double cross_track = tangent.x() * off.y() - tangent.y() * off.x();  // > 0: left of the path
  const double correction =
      std::atan(options.cross_track_gain * cross_track / (options.softening_mps + std::max(0.0, v)));
  c.steer_rad = std::clamp(heading_error - correction, -spec.max_steer_rad, spec.max_steer_rad);
  // Pedals: the resistances now plus a pull toward the target.
  const double weight = spec.mass_kg * kGravity;
  const double resistance =
      weight * (std::sin(state.pitch_rad) + spec.rolling_resistance * std::cos(state.pitch_rad)) +
      0.5 * kAirDensity * spec.drag_area_m2 * v * std::abs(v);
  target_mps =
      std::min(target_mps, curve_speed(path, bumper, options.max_lateral_mps2, options.curve_decel_mps2));
  const double pull = std::clamp(options.speed_gain_per_s * (target_mps - v), -options.max_decel_mps2,
                                 options.max_accel_mps2);
  const double force = spec.mass_kg * pull + resistance;
  if (target_mps < 0.1 && v < 0.5) {  // stopped or stopping: hold on the brakes
    c.brake_force_n = spec.max_brake_force_n;
  } else if (force >= 0.0) {
    c.drive_force_n = std::min({force, spec.max_drive_force_n, spec.engine_power_w / std::max(v, 1.0)});
  } else {
    c.brake_force_n = std::min(-force, spec.max_brake_force_n);
  }
  return c;
}

double power_limited_speed(const EgoSpec& spec, double grade) {
  const double a = std::atan(grade);
  const double climb = spec.mass_kg * kGravity * (std::sin(a) + spec.rolling_resistance * std::cos(a));
  const double drag = 0.5 * kAirDensity * spec.drag_area_m2;
  // f(v) = climb v + drag v^3 - P is increasing for climb > 0: bisection.
  double lo = 0.0, hi = 200.0;
  for (int i = 0; i < 100; ++i) {
    const double mid = 0.5 * (lo + hi);
    (climb * mid + drag * mid * mid * mid < spec.engine_power_w ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace relief

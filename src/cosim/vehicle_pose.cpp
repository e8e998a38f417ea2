#include "relief/cosim/vehicle_pose.h"

#include <cmath>

#include "relief/core/errors.h"

namespace relief {

WheelBase wheel_base_of(double length_m, double width_m) {
  if (!(std::isfinite(length_m) && length_m > 0.0) || !(std::isfinite(width_m) && width_m > 0.0))
    throw InvalidInput("a vehicle needs a finite length and width > 0");
  return {0.6 * length_m, std::max(width_m - 0.4, 0.6 * width_m)};
}

std::optional<SurfacePose> place_on_surface(const SurfaceQuery& query, const Vec2& centre, double heading,
                                            const WheelBase& wheels, double z_hint_m, double pitch_hint_rad,
                                            double max_gap_m) {
  const Vec2 forward(std::cos(heading), std::sin(heading));
  const Vec2 left(-forward.y(), forward.x());
  const double a = 0.5 * wheels.wheelbase_m, b = 0.5 * wheels.track_m;
  // Front left, front right, rear left, rear right.
  const std::array<double, 4> sx = {a, a, -a, -a}, sy = {b, -b, b, -b};
  SurfacePose pose;
  int missing = -1;
  for (std::size_t k = 0; k < 4; ++k) {
    const Vec2 contact = centre + sx[k] * forward + sy[k] * left;
    const double expected = z_hint_m + std::tan(pitch_hint_rad) * sx[k];
    const std::optional<SurfaceHit> hit = query.nearest(contact.x(), contact.y(), expected);
    if (!hit || std::abs(hit->z_m - expected) > max_gap_m) {
      if (missing >= 0) return std::nullopt;
      missing = static_cast<int>(k);
      continue;
    }
    pose.wheel_z_m[k] = hit->z_m;
    pose.wheel_kind[k] = hit->kind;
  }
  if (missing >= 0) {
    // The corners of a rectangle: each is the sum of its two neighbours less the opposite one.
    const auto m = static_cast<std::size_t>(missing);
    const std::size_t opposite = 3 - m, along = m ^ 2U, across = m ^ 1U;
    pose.wheel_z_m[m] = pose.wheel_z_m[along] + pose.wheel_z_m[across] - pose.wheel_z_m[opposite];
    pose.contacts_missing = 1;
  }
  const auto& z = pose.wheel_z_m;
  const double front = 0.5 * (z[0] + z[1]), rear = 0.5 * (z[2] + z[3]);
  const double left_z = 0.5 * (z[0] + z[2]), right_z = 0.5 * (z[1] + z[3]);
  pose.z_m = 0.25 * (z[0] + z[1] + z[2] + z[3]);
  const double along = (front - rear) / wheels.wheelbase_m;
  const double across = (left_z - right_z) / wheels.track_m;
  pose.pitch_rad = std::atan(along);
  pose.roll_rad = std::atan(across);
  for (std::size_t k = 0; k < 4; ++k)
    pose.wheel_under_m[k] = z[k] - (pose.z_m + along * sx[k] + across * sy[k]);
  return pose;
}

}  // namespace relief

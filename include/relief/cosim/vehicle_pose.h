#pragma once
// A vehicle set down on the 3D surface: z, pitch and roll from the surface under its four wheel
// contact points, not from the point under its centre (a car straddling a crest or a cross-fall
// sits on its wheels). The body is the least-squares plane through the four contacts: with the
// contacts at (+-wheelbase/2, +-track/2) in the body frame, its slope along the body is the
// mean front height minus the mean rear height over the wheelbase, across it the mean left
// minus the mean right over the track, and its height at the centre the mean of the four.

#include <array>
#include <optional>

#include "relief/geometry/types.h"
#include "relief/scene/surface_query.h"

namespace relief {

/// Where a vehicle's wheels touch, in its body frame.
struct WheelBase {
  double wheelbase_m = 2.7;  ///< front axle to rear axle
  double track_m = 1.6;      ///< left wheel to right wheel
};

/// Wheel base of a vehicle of a given outer length and width (a SUMO vehicle type's): the axles
/// 60 % of the length apart (cars 0.55-0.65, buses and trucks 0.55-0.6), the wheels 0.2 m in
/// from each side (at least 60 % of the width apart). Throws InvalidInput for a length or width
/// that is not finite and > 0.
[[nodiscard]] WheelBase wheel_base_of(double length_m, double width_m);

struct SurfacePose {
  double z_m = 0.0;        ///< the body plane's height under the centre
  double pitch_rad = 0.0;  ///< nose up positive
  double roll_rad = 0.0;   ///< right side down positive (the body tilts to the right)
  /// Surface height under each contact: front left, front right, rear left, rear right.
  std::array<double, 4> wheel_z_m{};
  /// How far each contact's surface lies above the body plane (> 0: that wheel would sink
  /// into the road if the body were rigid on the plane); at most 0 on a plane.
  std::array<double, 4> wheel_under_m{};
  std::array<SurfaceKind, 4> wheel_kind{};  ///< what each contact stands on (missing: as given)
  /// Contacts with no surface within max_gap_m of their expected height: each took the height
  /// of the plane through the other three (its wheel_under_m is 0).
  int contacts_missing = 0;
  /// An ego's wheels off the ground (hanging at full extension: over a crest taken fast, a kerb);
  /// its z is then the physics' and not a placement on the surface. 0 for a placement.
  int wheels_in_air = 0;
};

/// Sets a vehicle with its centre at `centre`, heading `heading` (radians, counter-clockwise
/// from +x) on the surface of `query`. Each contact's expected height is the plane through
/// `z_hint_m` (at the centre) rising at `pitch_hint_rad` along the heading (where the traffic
/// simulation has the vehicle); the contact takes the surface nearest that height (on a bridge
/// the deck, under it the road), if one lies within `max_gap_m` of it. A contact without one (a
/// wheel past the pavement's edge in a tunnel, where only the hill above has a surface) takes
/// the height of the plane through the other three. Nothing when two or more contacts have
/// none.
[[nodiscard]] std::optional<SurfacePose> place_on_surface(const SurfaceQuery& query, const Vec2& centre,
                                                          double heading, const WheelBase& wheels,
                                                          double z_hint_m, double pitch_hint_rad = 0.0,
                                                          double max_gap_m = 1.0);

}  // namespace relief

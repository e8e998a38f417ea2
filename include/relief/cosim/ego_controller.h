#pragma once
// The ego vehicles' driver (issue 16): Stanley's steering law on the lane centre (heading
// error plus a cross-track term; it follows curves without cutting them, as pure pursuit
// does), taken at the front bumper, the point SUMO keeps on the lane centre (at the front axle
// a car's bumper swings 0.5 m out of a 6 m turn, which SUMO reads as a 0.5 m sync error); and
// for the pedals
// the force that holds the target speed: the resistances the vehicle feels now (grade from its
// pitch, rolling, drag) plus a proportional pull toward the target, limited by the engine's
// power and the gearbox's force, or by the brakes.

#include <span>

#include "relief/cosim/ego_world.h"
#include "relief/geometry/types.h"

namespace relief {

struct EgoDriverOptions {
  double cross_track_gain = 2.0;  ///< Stanley's k, 1/s
  double softening_mps = 1.0;     ///< keeps the cross-track term finite at standstill
  double speed_gain_per_s = 1.5;  ///< acceleration per m/s short of the target
  double max_accel_mps2 = 2.5;    ///< comfort limits of that pull
  double max_decel_mps2 = 6.0;
  /// Curves ahead: taken at no more lateral acceleration than this, slowed for at this rate.
  double max_lateral_mps2 = 2.5;
  double curve_decel_mps2 = 2.5;
};

/// Controls that take an ego in `state` along `path` (the lane centre ahead in plan, starting
/// near the vehicle; beyond its end the last segment continues) toward `target_mps`, slower
/// where a curve ahead asks for it.
[[nodiscard]] EgoControls drive_along(const EgoSpec& spec, const EgoState& state, std::span<const Vec2> path,
                                      double target_mps, const EgoDriverOptions& options = {});

/// The speed at which the engine's power just carries the resistances on a steady climb of
/// `grade` (rise over run): P = m g v (sin a + c_rr cos a) + rho/2 c_d A v^3, solved for v.
[[nodiscard]] double power_limited_speed(const EgoSpec& spec, double grade);

}  // namespace relief

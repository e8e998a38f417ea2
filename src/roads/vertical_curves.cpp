#include "relief/roads/vertical_curves.h"

#include <string>

#include "relief/core/errors.h"

namespace relief {

double stopping_sight_distance_m(double speed_kmh) {
  constexpr double kReactionS = 2.5;
  constexpr double kDecelerationMps2 = 3.4;
  return 0.278 * speed_kmh * kReactionS + 0.039 * speed_kmh * speed_kmh / kDecelerationMps2;
}

double VerticalCurveBounds::crest_curvature_per_m() const {
  return 1.0 / (100.0 * crest_k);
}
double VerticalCurveBounds::sag_curvature_per_m() const {
  return 1.0 / (100.0 * sag_k);
}

VerticalCurveBounds vertical_curve_bounds(double design_speed_kmh) {
  if (!(design_speed_kmh > 0.0)) {
    throw InvalidInput("vertical curves: the design speed must be positive, got " +
                       std::to_string(design_speed_kmh));
  }
  const double s = stopping_sight_distance_m(design_speed_kmh);
  return {s * s / 658.0, s * s / (120.0 + 3.5 * s)};
}

}  // namespace relief

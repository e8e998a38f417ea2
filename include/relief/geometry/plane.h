#pragma once
// Small helpers for angles and vectors in the plane (metres and radians, local frame), shared by
// the modules that would otherwise each keep a copy: angle wrapping, the 2-D cross product, the
// distance from a point to a segment (which works in space as well).

#include <algorithm>
#include <cmath>
#include <numbers>

#include "relief/geometry/types.h"

namespace relief {

/// The angle a (radians) wrapped into (-pi, pi]. Exact: std::remainder subtracts the nearest
/// multiple of 2 pi without rounding, so headings that are many turns away wrap as accurately as
/// near ones. NaN for a non-finite a.
[[nodiscard]] inline double wrap_angle(double a) {
  a = std::remainder(a, 2.0 * std::numbers::pi);
  if (a <= -std::numbers::pi) a += 2.0 * std::numbers::pi;
  return a;
}

/// The z component of the cross product of a and b (a.x b.y - a.y b.x): positive when b turns
/// left (counter-clockwise) from a, |a| |b| times the sine of the angle between them.
[[nodiscard]] inline double cross(const Vec2& a, const Vec2& b) {
  return a.x() * b.y() - a.y() * b.x();
}

/// The parameter t in [0, 1] of the point a + t (b - a) of segment ab nearest to q (0 when the
/// segment is a point). In the plane (Vec2) or in space (Vec3).
template <int N>
[[nodiscard]] double segment_parameter(const Eigen::Matrix<double, N, 1>& q,
                                       const Eigen::Matrix<double, N, 1>& a,
                                       const Eigen::Matrix<double, N, 1>& b) {
  const Eigen::Matrix<double, N, 1> d = b - a;
  const double len2 = d.squaredNorm();
  return len2 > 0.0 ? std::clamp((q - a).dot(d) / len2, 0.0, 1.0) : 0.0;
}

/// Distance from q to segment ab (to the nearer end beyond its ends; to a when a = b). In the
/// plane (Vec2) or in space (Vec3).
template <int N>
[[nodiscard]] double point_segment_distance(const Eigen::Matrix<double, N, 1>& q,
                                            const Eigen::Matrix<double, N, 1>& a,
                                            const Eigen::Matrix<double, N, 1>& b) {
  return (q - (a + segment_parameter(q, a, b) * (b - a))).norm();
}

}  // namespace relief

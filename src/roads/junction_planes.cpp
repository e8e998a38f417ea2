#include "roads/junction_planes.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>

#include <Eigen/Eigenvalues>

namespace relief::detail {
namespace {

// A road's roll eases from its junction's to level over this length: a lane t metres from the
// reference line climbs at most 1.5 t tan(roll) / kRollEase_m more than the road (0.45 % for a
// 1.5 m lane centre at a 10 % cross-slope).
constexpr double kRollEase_m = 50.0;
constexpr double kRollStep_m = 0.5;  // roll samples along a road inside a junction
// A direction of a junction's plane counts as determined by its roads when lambda, the sum of
// the squared cosines of the roads' directions with it, is at least kPlaneDetermined (a T
// junction: 2 along the through road, 1 across; a fork at 45 degrees: 0.5 across), and not at
// all under kPlaneUndetermined (a road straight through: 0; a fork at 13 degrees: 0.05), a
// smoothstep between.
constexpr double kPlaneDetermined = 0.5;
constexpr double kPlaneUndetermined = 0.05;
constexpr double kRollTolerance_rad = 1e-5;  // 0.02 mm at 2 m from the reference line

}  // namespace

// The part of a junction's plane gradient its roads determine. The fit's plane is pinned only
// along the roads' directions: across a road that runs straight through, or across the two
// roads of a fork at a shallow angle, it is set by a few centimetres of height over a lateral
// offset of a metre or by nothing at all, and tilting the lanes by it would twist a wide road
// for no reason. With M = sum of u u^T over the roads' unit directions u leaving the junction,
// each eigen-direction e of M (eigenvalue lambda) keeps the share of G . e that lambda says.
Eigen::Matrix2d determined_share(const RoadNetwork& network, const Junction& j) {
  Eigen::Matrix2d m = Eigen::Matrix2d::Zero();
  for (const RoadEnd& e : j.ends) {
    const Polyline2& pts = network.roads[e.road].points;
    if (pts.size() < 2) continue;
    const Vec2 d = e.at_start ? Vec2(pts[1] - pts[0]) : Vec2(pts[pts.size() - 2] - pts.back());
    if (!(d.norm() > 0.0)) continue;
    const Vec2 u = d.normalized();
    m += u * u.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(m);
  Eigen::Matrix2d out = Eigen::Matrix2d::Zero();
  for (int k = 0; k < 2; ++k) {
    const double x = std::clamp(
        (eig.eigenvalues()[k] - kPlaneUndetermined) / (kPlaneDetermined - kPlaneUndetermined), 0.0, 1.0);
    const Vec2 e = eig.eigenvectors().col(k);
    out += x * x * (3.0 - 2.0 * x) * e * e.transpose();
  }
  return out;
}

std::vector<Vec2> junction_planes(const RoadNetwork& network, const std::vector<Vec2>& junction_gradient) {
  std::vector<Vec2> planes(network.junctions.size(), Vec2::Zero());
  if (!junction_gradient.empty()) {
    for (const Junction& j : network.junctions)
      planes[j.id] = determined_share(network, j) * junction_gradient[j.id];
  }
  return planes;
}

double plane_roll(const Vec2& g, double heading) {
  return std::atan(g.dot(Vec2(-std::sin(heading), std::cos(heading))));
}

CubicProfile end_rolls(double length, std::optional<double> r0, std::optional<double> r1) {
  if (!r0 || !r1) {
    // A dead end has no plane to meet: it keeps what the other end's ease has left there (a
    // stub shorter than the ease no longer twists to level within its own length).
    const double r = r0 ? *r0 : r1.value_or(0.0);  // 0 with both ends free
    if (r == 0.0 || length >= kRollEase_m) return end_rolls(length, r0.value_or(0.0), r1.value_or(0.0));
    const double v = length / kRollEase_m;
    const double value = r * (1.0 - 3.0 * v * v + 2.0 * v * v * v);
    const double slope = r * 6.0 * v * (v - 1.0) / kRollEase_m;  // d roll / d distance from the pinned end
    return r0 ? hermite_profile(length, r, 0.0, value, slope)
              : hermite_profile(length, value, -slope, r, 0.0);
  }
  if (*r0 == 0.0 && *r1 == 0.0) return CubicProfile::constant(0.0);
  if (length < 2.0 * kRollEase_m) return hermite_profile(length, *r0, 0.0, *r1, 0.0);
  const double e = kRollEase_m;
  const double e2 = e * e, e3 = e2 * e;
  std::vector<CubicPiece> pieces{{0.0, Poly3{*r0, 0.0, -3.0 * *r0 / e2, 2.0 * *r0 / e3}}};
  if (length > 2.0 * e) pieces.push_back({e, Poly3{0.0, 0.0, 0.0, 0.0}});
  pieces.push_back({length - e, Poly3{0.0, 0.0, 3.0 * *r1 / e2, -2.0 * *r1 / e3}});
  return CubicProfile(std::move(pieces));
}

CubicProfile plane_rolls(const PlanView& plan, const Vec2& g0, const Vec2& g1) {
  if (g0.isZero(0.0) && g1.isZero(0.0)) return CubicProfile::constant(0.0);
  const double len = plan.length();
  const auto n = static_cast<std::size_t>(std::max(8.0, std::ceil(len / kRollStep_m)));
  std::vector<double> s(n + 1), r(n + 1);
  for (std::size_t i = 0; i <= n; ++i) {
    s[i] = len * static_cast<double>(i) / static_cast<double>(n);
    const double u = s[i] / len;
    r[i] = plane_roll((1.0 - u) * g0 + u * g1, plan.at(s[i]).heading);
  }
  return fit_cubic_profile(s, r, kRollTolerance_rad);
}

}  // namespace relief::detail

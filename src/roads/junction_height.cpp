#include "relief/roads/junction_height.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>

#include "relief/core/errors.h"
#include "relief/geometry/grade_limit.h"
#include "relief/roads/road_surface.h"
#include "roads/junction_planes.h"

namespace relief {
namespace {

constexpr double kOnSegment_m = 1e-9;  // closer than this, a point is on the end's segment
constexpr double kFade_m = 5.0;        // a road end's departure of grade from the trend fades over
constexpr double kSampleStep_m = 0.5;  // along a road inside the junction
constexpr double kHeightTolerance_m = 1e-3;
constexpr double kRollTolerance_rad = 1e-4;
constexpr double kGradeBlend_m = 5.0;      // half-width of the mean that rounds a grade-limited stretch
constexpr double kDepartureReach_m = 4.0;  // a departure point's reach (with_departures)
constexpr double kEndFade_m = 1.0;         // departures fade to none at an end's cross-section

// Nearest point of segment ab to p.
Vec2 nearest_on_segment(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 d = b - a;
  const double len2 = d.squaredNorm();
  if (len2 <= 0.0) return a;
  return a + std::clamp((p - a).dot(d) / len2, 0.0, 1.0) * d;
}

// Outermost lane ids of a section's sides (0 where a side has none: the centre lane).
std::pair<int, int> outer_lanes(const LaneSection& section) {
  int right = 0, left = 0;
  for (const LaneModel& l : section.right) right = std::min(right, l.id);
  for (const LaneModel& l : section.left) left = std::max(left, l.id);
  return {right, left};
}

}  // namespace

EndPlane end_plane(const ModelRoad& road, bool at_start) {
  const double s = at_start ? 0.0 : road.length();
  const Pose2 pose = road.plan.at(s);
  const Vec2 along(std::cos(pose.heading), std::sin(pose.heading));
  const Vec2 left_normal(-along.y(), along.x());
  EndPlane e;
  e.point = pose.position;
  e.z = road.elevation.value(s);
  e.gradient = road.elevation.derivative(s) * along + std::tan(road.superelevation.value(s)) * left_normal;
  const auto [right, left] = outer_lanes(section_at(road, s));
  e.right = surface_point(road, pose, s, lane_border_t(road, s, right)).head<2>();
  e.left = surface_point(road, pose, s, lane_border_t(road, s, left)).head<2>();
  return e;
}

JunctionHeight::JunctionHeight(std::vector<EndPlane> ends) : ends_(std::move(ends)) {
  if (ends_.empty()) throw InvalidInput("junction height: a junction without road ends");
  // The trend: the least-squares plane through every end's corners and reference point, at
  // their heights on their own planes (the least-norm gradient where the points are collinear).
  Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();
  Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
  centre_ = Vec2::Zero();
  for (const EndPlane& e : ends_) centre_ += e.point;
  centre_ /= static_cast<double>(ends_.size());
  for (const EndPlane& e : ends_) {
    for (const Vec2& p : {e.right, e.point, e.left}) {
      const Eigen::Vector3d row(1.0, p.x() - centre_.x(), p.y() - centre_.y());
      normal += row * row.transpose();
      rhs += row * (e.z + e.gradient.dot(p - e.point));
    }
  }
  const Eigen::Vector3d plane = normal.completeOrthogonalDecomposition().solve(rhs);
  trend_z_ = plane[0];
  trend_gradient_ = Vec2(plane[1], plane[2]);
}

JunctionHeight JunctionHeight::with_departures(std::vector<std::vector<Vec3>> departures) const {
  JunctionHeight out = *this;
  out.departures_ = std::move(departures);
  std::erase_if(out.departures_, [](const std::vector<Vec3>& line) { return line.empty(); });
  return out;
}

std::pair<double, Vec2> JunctionHeight::at(const Vec2& p) const {
  auto out = base_at(p);
  if (departures_.empty()) return out;
  const auto [dz, grad] = departure_at(p);
  out.first += dz;
  out.second += grad;
  return out;
}

std::pair<double, Vec2> JunctionHeight::departure_at(const Vec2& p) const {
  // K: smoothstep of the distance to the nearest end's segment (zero value and gradient on it).
  double d_end = kEndFade_m;
  Vec2 grad_d_end = Vec2::Zero();
  for (const EndPlane& e : ends_) {
    const Vec2 q = nearest_on_segment(p, e.right, e.left);
    const double d = (p - q).norm();
    if (d < d_end) {
      d_end = d;
      grad_d_end = d > 0.0 ? Vec2((p - q) / d) : Vec2::Zero();
    }
  }
  if (!(d_end > 0.0)) return {0.0, Vec2::Zero()};
  const double t = d_end / kEndFade_m;
  const double k = t >= 1.0 ? 1.0 : t * t * (3.0 - 2.0 * t);
  const Vec2 grad_k = t >= 1.0 ? Vec2::Zero() : Vec2(6.0 * t * (1.0 - t) / kEndFade_m * grad_d_end);
  // F = N / D: per line, its departure at its point nearest p (linear between its points),
  // blended with the surface's own weight 1 / R^2.
  constexpr double kR = kDepartureReach_m;
  double num = 0.0, den = 1.0 / (kR * kR);
  Vec2 grad_num = Vec2::Zero(), grad_den = Vec2::Zero();
  for (const std::vector<Vec3>& line : departures_) {
    // The nearest point: its distance, departure and the departure's gradient in p.
    double best = std::numeric_limits<double>::infinity(), value = 0.0;
    Vec2 q_best = Vec2::Zero(), grad_value = Vec2::Zero();
    for (std::size_t i = 0; i < line.size(); ++i) {
      const Vec2 a = line[i].head<2>();
      const Vec2 b = line[std::min(i + 1, line.size() - 1)].head<2>();
      const Vec2 ab = b - a;
      const double len2 = ab.squaredNorm();
      const double u = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
      const Vec2 q = a + u * ab;
      const double d2 = (p - q).squaredNorm();
      if (d2 >= best) continue;
      best = d2;
      q_best = q;
      const double za = line[i].z(), zb = line[std::min(i + 1, line.size() - 1)].z();
      value = za + u * (zb - za);
      grad_value = (u > 0.0 && u < 1.0) ? Vec2((zb - za) * ab / len2) : Vec2::Zero();
    }
    if (best >= kR * kR) continue;
    if (best < kOnSegment_m * kOnSegment_m) return {k * value, k * grad_value + value * grad_k};
    const Vec2 v = p - q_best;
    const double d = std::sqrt(best);
    const double fade = 1.0 - d / kR;
    const double w = fade * fade / best;
    // dw/dd = -2 fade / (R d^2) - 2 fade^2 / d^3; grad d = v / d.
    const Vec2 grad_w = (-2.0 * fade / (kR * best) - 2.0 * fade * fade / (best * d)) * v / d;
    num += w * value;
    den += w;
    grad_num += grad_w * value + w * grad_value;
    grad_den += grad_w;
  }
  const double f = num / den;
  const Vec2 grad_f = (grad_num - f * grad_den) / den;
  return {k * f, k * grad_f + f * grad_k};
}

std::pair<double, Vec2> JunctionHeight::base_at(const Vec2& p) const {
  // S = T + R, T the trend plane, R = N / D the blend of each end's departure from it:
  // N = sum w r_e, D = sum w, w = 1 / d^2 (d the distance to the end's segment, q its nearest
  // point there, grad w = -2 (p - q) / d^4); r_e = c + h . (p - P) tau(d), c the end's height
  // over T, h its gradient's departure from T's, tau = 1 / (1 + d^2 / l^2) (tau(0) = 1 and
  // tau'(0) = 0: S leaves the end with its plane's gradient, and a departure of grade fades
  // within a few metres instead of carrying across the junction; blending the ends' planes
  // themselves climbed 36 % between roads at 5 and 12 % on Potrero's De Haro Street).
  // grad R = (sum (grad w r_e + w grad r_e) - R sum grad w) / D.
  const double trend = trend_z_ + trend_gradient_.dot(p - centre_);
  double num = 0.0, den = 0.0;
  Vec2 grad_num = Vec2::Zero(), grad_den = Vec2::Zero();
  for (const EndPlane& e : ends_) {
    const Vec2 q = nearest_on_segment(p, e.right, e.left);
    const double d2 = (p - q).squaredNorm();
    if (d2 < kOnSegment_m * kOnSegment_m) return {e.z + e.gradient.dot(p - e.point), e.gradient};
    const double c = e.z - (trend_z_ + trend_gradient_.dot(e.point - centre_));
    const Vec2 h = e.gradient - trend_gradient_;
    const double lin = h.dot(p - e.point);
    const double u = 1.0 + d2 / (kFade_m * kFade_m);
    const double tau = 1.0 / u;
    const Vec2 grad_tau = -2.0 * (p - q) / (kFade_m * kFade_m * u * u);  // d tau / dd * grad d
    const double r = c + lin * tau;
    const Vec2 grad_r = h * tau + lin * grad_tau;
    const double w = 1.0 / d2;
    const Vec2 grad_w = -2.0 * (p - q) / (d2 * d2);
    num += w * r;
    den += w;
    grad_num += grad_w * r + w * grad_r;
    grad_den += grad_w;
  }
  const double residual = num / den;
  return {trend + residual, trend_gradient_ + (grad_num - residual * grad_den) / den};
}

SurfaceProfiles surface_profiles(const PlanView& plan, const JunctionHeight& surface, double grade_limit) {
  const double len = plan.length();
  const int n = std::max(2, static_cast<int>(std::ceil(len / kSampleStep_m)));
  std::vector<double> s(n + 1), z(n + 1), roll(n + 1);
  double slope0 = 0.0, slope1 = 0.0;
  std::vector<Vec2> xy(n + 1);
  SurfaceProfiles out;
  for (int i = 0; i <= n; ++i) {
    s[i] = len * i / n;
    const Pose2 pose = plan.at(s[i]);
    xy[i] = pose.position;
    const auto [height, gradient] = surface.at(pose.position);
    z[i] = height;
    roll[i] = detail::plane_roll(gradient, pose.heading);
    const double slope = gradient.dot(Vec2(std::cos(pose.heading), std::sin(pose.heading)));
    if (i == 0) slope0 = slope;
    if (i == n) slope1 = slope;
    if (i > 0) out.max_grade = std::max(out.max_grade, std::abs(z[i] - z[i - 1]) / (s[i] - s[i - 1]));
  }
  const auto end_slopes = std::make_pair(slope0, slope1);
  const auto departures = [&](const std::vector<double>& heights) {
    if (&heights == &z && !surface.has_departures()) return;  // on the surface: none
    for (int i = 0; i <= n; ++i) {
      const double dz = heights[i] - surface.base_at(xy[i]).first;
      out.max_departure_m = std::max(out.max_departure_m, std::abs(dz));
      if (&heights != &z) out.left.emplace_back(xy[i].x(), xy[i].y(), dz);
    }
  };
  if (out.max_grade <= grade_limit) {
    out.elevation = fit_cubic_profile(s, z, kHeightTolerance_m, end_slopes);
    departures(z);
  } else {
    // The limit is never under the grade between the ends themselves (a short road whose ends'
    // cross-sections meet the surface a little apart).
    const double ends_grade = std::abs(z[n] - z[0]) / len * (1.0 + 1e-9);
    const std::vector<double> limited = grade_limited(s, z, std::max(grade_limit, ends_grade), kGradeBlend_m);
    departures(limited);
    out.elevation = fit_grade_bounded_profile(s, limited, kHeightTolerance_m, end_slopes);
  }
  // Where the roads that left the surface left it in different directions, its departures rise
  // and fall within a metre between them, and the surface tilts up to 80 degrees across a road
  // crossing there (Fuzz seed 31: tan(roll) 5.6; Liechtenstein 0.79). Across, a road lies no
  // steeper than it may climb (its ends keep the rolls of the roads they join): the lane centre
  // stays on the surface, its borders within the cap of it.
  if (std::isfinite(grade_limit)) {
    const double bound =
        std::atan(std::max({grade_limit, std::abs(std::tan(roll.front())), std::abs(std::tan(roll.back()))}));
    for (double& r : roll) r = std::clamp(r, -bound, bound);
  }
  out.superelevation = fit_cubic_profile(s, roll, kRollTolerance_rad);
  return out;
}

}  // namespace relief

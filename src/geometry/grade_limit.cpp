#include "relief/geometry/grade_limit.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <string>

#include <Eigen/SparseCore>

#include "relief/core/errors.h"
#include "relief/geometry/soft_qp.h"

namespace relief {
namespace {

constexpr double kLimitPrice = 1e6;  // per unit of grade over the limit (a departure costs d^2)
constexpr double kEndPrice = 1e3;    // per unit of an end chord's grade off z's
constexpr double kMoved_m = 1e-9;    // a height that moved less than this did not move

void validate(const std::vector<double>& s, const std::vector<double>& z, double limit, double round_m) {
  if (s.size() != z.size()) throw InvalidInput("grade limit: stations and heights differ in number");
  if (s.size() < 2) throw InvalidInput("grade limit: fewer than two stations");
  if (!std::isfinite(limit) || limit < 0.0)
    throw InvalidInput("grade limit: the limit must be finite and >= 0");
  if (!std::isfinite(round_m) || round_m < 0.0)
    throw InvalidInput("grade limit: the rounding length must be finite and >= 0");
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (!std::isfinite(s[i]) || !std::isfinite(z[i]))
      throw InvalidInput("grade limit: a value is not finite");
    if (i > 0 && !(s[i] > s[i - 1])) throw InvalidInput("grade limit: stations not strictly increasing");
  }
  const double span = s.back() - s.front();
  if (std::abs(z.back() - z.front()) > limit * span * (1.0 + 1e-12))
    throw InvalidInput("grade limit: the ends lie further apart in height than the limit allows");
}

// The heights z + d nearest z (least sum d^2) with every chord within the limit (the dearest
// rows), d = 0 at both ends and every chord that starts within end_m of an end (at least the end
// chord) at z's grade (soft, given way only to the limit).
std::vector<double> nearest_within(const std::vector<double>& s, const std::vector<double>& z, double limit,
                                   double end_m) {
  const std::size_t n = s.size();
  const auto ni = static_cast<Eigen::Index>(n);
  const auto chord = [&](std::size_t i) { return (z[i + 1] - z[i]) / (s[i + 1] - s[i]); };
  SoftQp qp;
  qp.P.resize(ni, ni);
  qp.P.setIdentity();
  qp.P *= 2.0;
  qp.q = Eigen::VectorXd::Zero(ni);
  // Rows: every chord's grade of d within the limit less z's own; then the end chords at 0.
  std::vector<std::size_t> end_chords;
  for (std::size_t i = 0; i + 1 < n; ++i)
    if (i == 0 || i + 2 == n || s[i] - s.front() < end_m || s.back() - s[i + 1] < end_m)
      end_chords.push_back(i);
  const auto m = static_cast<Eigen::Index>(n - 1 + end_chords.size());
  std::vector<Eigen::Triplet<double>> a;
  qp.lower.resize(m);
  qp.upper.resize(m);
  qp.price.resize(m);
  const auto add_chord = [&](Eigen::Index r, std::size_t i, double lo, double hi, double price) {
    const double inv = 1.0 / (s[i + 1] - s[i]);
    a.emplace_back(r, static_cast<Eigen::Index>(i), -inv);
    a.emplace_back(r, static_cast<Eigen::Index>(i) + 1, inv);
    qp.lower[r] = lo;
    qp.upper[r] = hi;
    qp.price[r] = price;
  };
  for (std::size_t i = 0; i + 1 < n; ++i)
    add_chord(static_cast<Eigen::Index>(i), i, -limit - chord(i), limit - chord(i), kLimitPrice);
  for (std::size_t k = 0; k < end_chords.size(); ++k)
    add_chord(static_cast<Eigen::Index>(n - 1 + k), end_chords[k], 0.0, 0.0, kEndPrice);
  qp.A.resize(m, ni);
  qp.A.setFromTriplets(a.begin(), a.end());
  qp.fixed.assign(n, std::numeric_limits<double>::quiet_NaN());
  qp.fixed.front() = 0.0;
  qp.fixed.back() = 0.0;
  SoftQpOptions options;
  options.tolerance = 1e-12;
  const SoftQpResult result = solve_soft_qp(qp, options);
  if (!result.converged) throw Error("grade limit: the solver did not converge (" + result.status + ")");
  std::vector<double> out(n);
  for (std::size_t i = 0; i < n; ++i) out[i] = z[i] + result.x[static_cast<Eigen::Index>(i)];
  out.front() = z.front();
  out.back() = z.back();
  return out;
}

// The heights nearest p in the largest departure whose chords keep the limit, with p's ends:
// the mean of the upper envelope min_j p_j + limit |s - s_j| and the lower one, clamped to the
// cone the two ends allow. It moves p only by what p's chords exceed the limit by (the solver's
// rounding, 1e-8 of a grade), so that the limit holds to the last bit.
std::vector<double> exactly_within(const std::vector<double>& s, std::vector<double> p, double limit) {
  const std::size_t n = s.size();
  std::vector<double> upper = p, lower = p;
  for (std::size_t i = 1; i < n; ++i) {
    const double rise = limit * (s[i] - s[i - 1]);
    upper[i] = std::min(upper[i], upper[i - 1] + rise);
    lower[i] = std::max(lower[i], lower[i - 1] - rise);
  }
  for (std::size_t i = n - 1; i-- > 0;) {
    const double rise = limit * (s[i + 1] - s[i]);
    upper[i] = std::min(upper[i], upper[i + 1] + rise);
    lower[i] = std::max(lower[i], lower[i + 1] - rise);
  }
  for (std::size_t i = 1; i + 1 < n; ++i) {
    const double from_start = limit * (s[i] - s.front()), to_end = limit * (s.back() - s[i]);
    const double lo = std::max(p.front() - from_start, p.back() - to_end);
    const double hi = std::min(p.front() + from_start, p.back() + to_end);
    p[i] = std::clamp(0.5 * (upper[i] + lower[i]), std::min(lo, hi), std::max(lo, hi));
  }
  return p;
}

// Integral of the polyline (s, z) from s_0 to x, `cumulative` its integral up to each station.
double integral_to(const std::vector<double>& s, const std::vector<double>& z,
                   const std::vector<double>& cumulative, double x) {
  const auto it = std::upper_bound(s.begin(), s.end(), x);
  const std::size_t k =
      std::min<std::size_t>(it == s.begin() ? 0 : static_cast<std::size_t>(it - s.begin()) - 1, s.size() - 2);
  const double f = (x - s[k]) / (s[k + 1] - s[k]);
  const double zx = z[k] + f * (z[k + 1] - z[k]);
  return cumulative[k] + 0.5 * (x - s[k]) * (z[k] + zx);
}

}  // namespace

std::vector<double> grade_limited(const std::vector<double>& s, const std::vector<double>& z, double limit,
                                  double round_m) {
  validate(s, z, limit, round_m);
  const std::size_t n = s.size();
  bool within = true;
  for (std::size_t i = 0; i + 1 < n && within; ++i)
    within = std::abs(z[i + 1] - z[i]) <= limit * (s[i + 1] - s[i]);
  if (within) return z;
  std::vector<double> p =
      exactly_within(s, nearest_within(s, z, limit, std::min(round_m, 0.25 * (s.back() - s.front()))), limit);
  if (round_m == 0.0) return p;

  // Distance to the nearest moved station, both ways.
  std::vector<double> distance(n, std::numeric_limits<double>::infinity());
  for (std::size_t i = 0; i < n; ++i) {
    if (std::abs(p[i] - z[i]) > kMoved_m)
      distance[i] = 0.0;
    else if (i > 0)
      distance[i] = distance[i - 1] + (s[i] - s[i - 1]);
  }
  for (std::size_t i = n - 1; i-- > 0;)
    distance[i] = std::min(distance[i], distance[i + 1] + (s[i + 1] - s[i]));
  // The moving mean of p's polyline over [s - h, s + h]. Its slope is a blend of the chords of p
  // from the window's middle to its two ends, with weights (1 + h') / 2 and (1 - h') / 2: within
  // the limit wherever |h'| <= 1, which every term of h keeps.
  std::vector<double> cumulative(n, 0.0);
  for (std::size_t i = 1; i < n; ++i)
    cumulative[i] = cumulative[i - 1] + 0.5 * (s[i] - s[i - 1]) * (p[i] + p[i - 1]);
  std::vector<double> out = p;
  for (std::size_t i = 1; i + 1 < n; ++i) {
    const double h =
        std::min({round_m, s[i] - s.front(), s.back() - s[i], std::max(0.0, 2.0 * round_m - distance[i])});
    if (h > 0.0)
      out[i] =
          (integral_to(s, p, cumulative, s[i] + h) - integral_to(s, p, cumulative, s[i] - h)) / (2.0 * h);
  }
  return out;
}

}  // namespace relief

#include "relief/geometry/cubic_profile.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "relief/core/errors.h"

namespace relief {

namespace {

// Cubic Hermite on [0, h] with values z0, z1 and slopes m0, m1 at its ends.
Poly3 hermite(double h, double z0, double m0, double z1, double m1) {
  const double secant = (z1 - z0) / h;
  Poly3 p;
  p.a = z0;
  p.b = m0;
  p.c = (3.0 * secant - 2.0 * m0 - m1) / h;
  p.d = (m0 + m1 - 2.0 * secant) / (h * h);
  return p;
}

// Knot slopes: three-point derivative of the non-uniform samples (exact for quadratics),
// one-sided at the ends; two samples give the secant.
std::vector<double> sample_slopes(const std::vector<double>& s, const std::vector<double>& z) {
  const std::size_t n = s.size();
  std::vector<double> m(n, 0.0);
  if (n < 2) return m;
  if (n == 2) {
    m[0] = m[1] = (z[1] - z[0]) / (s[1] - s[0]);
    return m;
  }
  for (std::size_t i = 1; i + 1 < n; ++i) {
    const double h1 = s[i] - s[i - 1];
    const double h2 = s[i + 1] - s[i];
    m[i] = (-h2 / (h1 * (h1 + h2))) * z[i - 1] + ((h2 - h1) / (h1 * h2)) * z[i] +
           (h1 / (h2 * (h1 + h2))) * z[i + 1];
  }
  {
    const double h1 = s[1] - s[0];
    const double h2 = s[2] - s[1];
    m[0] = (-(2.0 * h1 + h2) / (h1 * (h1 + h2))) * z[0] + ((h1 + h2) / (h1 * h2)) * z[1] -
           (h1 / (h2 * (h1 + h2))) * z[2];
  }
  {
    const double h1 = s[n - 2] - s[n - 3];
    const double h2 = s[n - 1] - s[n - 2];
    m[n - 1] = (h2 / (h1 * (h1 + h2))) * z[n - 3] - ((h1 + h2) / (h1 * h2)) * z[n - 2] +
               ((2.0 * h2 + h1) / (h2 * (h1 + h2))) * z[n - 1];
  }
  return m;
}

// Knots 0 = k_0 < k_1 < ... = n - 1 among n candidates, each piece the longest from its start
// that `fits` (two consecutive candidates always must): from knot k, first the whole rest (a
// check stops at its first miss, so this is cheap), then exponential search for a failing end
// and binary search for the furthest end that fits; O(n log n) checks overall.
template <typename Fits>
std::vector<std::size_t> greedy_knots(std::size_t n, const Fits& fits) {
  std::vector<std::size_t> knots{0};
  std::size_t k = 0;
  while (k + 1 < n) {
    std::size_t good = k + 1;  // two consecutive candidates always fit
    std::size_t bad = n;       // first end known not to fit (n: none)
    std::size_t step = 2;
    if (fits(k, n - 1)) good = n - 1;
    while (good + 1 < n) {
      const std::size_t j = std::min(k + step, n - 1);
      if (fits(k, j)) {
        good = j;
        step *= 2;
      } else {
        bad = j;
        break;
      }
    }
    while (bad < n && bad - good > 1) {
      const std::size_t mid = good + (bad - good) / 2;
      if (fits(k, mid))
        good = mid;
      else
        bad = mid;
    }
    knots.push_back(good);
    k = good;
  }
  return knots;
}

// Largest |slope| of a cubic on [0, h]: at an end or at the vertex of its derivative.
double steepest_slope(const Poly3& p, double h) {
  double steepest = std::max(std::abs(p.derivative(0.0)), std::abs(p.derivative(h)));
  if (p.d != 0.0) {
    const double vertex = -p.c / (3.0 * p.d);
    if (vertex > 0.0 && vertex < h) steepest = std::max(steepest, std::abs(p.derivative(vertex)));
  }
  return steepest;
}

void check_samples(const std::vector<double>& s, const std::vector<double>& z, double tolerance,
                   const std::optional<std::pair<double, double>>& end_slopes) {
  const std::size_t n = s.size();
  if (n == 0) throw InvalidInput("cubic profile fit: no samples");
  if (z.size() != n) {
    throw InvalidInput("cubic profile fit: " + std::to_string(n) + " stations but " +
                       std::to_string(z.size()) + " values");
  }
  if (!(tolerance >= 0.0) || !std::isfinite(tolerance)) {
    throw InvalidInput("cubic profile fit: tolerance must be finite and non-negative");
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(s[i]) || !std::isfinite(z[i])) {
      throw InvalidInput("cubic profile fit: sample " + std::to_string(i) + " is not finite");
    }
    if (i > 0 && !(s[i] > s[i - 1])) {
      throw InvalidInput("cubic profile fit: stations are not strictly increasing at sample " +
                         std::to_string(i));
    }
  }
  if (end_slopes && (!std::isfinite(end_slopes->first) || !std::isfinite(end_slopes->second))) {
    throw InvalidInput("cubic profile fit: end slopes are not finite");
  }
}

}  // namespace

CubicProfile::CubicProfile(std::vector<CubicPiece> pieces) : pieces_(std::move(pieces)) {
  for (std::size_t i = 0; i < pieces_.size(); ++i) {
    if (!std::isfinite(pieces_[i].s)) {
      throw InvalidInput("cubic profile: piece " + std::to_string(i) + " has a non-finite start");
    }
    if (i > 0 && !(pieces_[i].s > pieces_[i - 1].s)) {
      throw InvalidInput("cubic profile: pieces are not sorted by s (piece " + std::to_string(i) +
                         " at s=" + std::to_string(pieces_[i].s) + ")");
    }
  }
}

CubicProfile CubicProfile::constant(double value) {
  CubicPiece piece;
  piece.poly.a = value;
  return CubicProfile({piece});
}

std::size_t CubicProfile::piece_at(double s) const {
  const auto it = std::upper_bound(pieces_.begin(), pieces_.end(), s,
                                   [](double value, const CubicPiece& p) { return value < p.s; });
  if (it == pieces_.begin()) return 0;
  return static_cast<std::size_t>(it - pieces_.begin()) - 1;
}

double CubicProfile::value(double s) const {
  if (pieces_.empty()) return 0.0;
  const CubicPiece& p = pieces_[piece_at(s)];
  return p.poly.value(s - p.s);
}

double CubicProfile::derivative(double s) const {
  if (pieces_.empty()) return 0.0;
  const CubicPiece& p = pieces_[piece_at(s)];
  return p.poly.derivative(s - p.s);
}

CubicProfile fit_cubic_profile(const std::vector<double>& s, const std::vector<double>& z, double tolerance,
                               const std::optional<std::pair<double, double>>& end_slopes) {
  check_samples(s, z, tolerance, end_slopes);
  const std::size_t n = s.size();
  if (n == 1) {
    CubicPiece piece{s[0], {}};
    piece.poly.a = z[0];
    if (end_slopes) piece.poly.b = end_slopes->first;
    return CubicProfile({piece});
  }

  std::vector<double> m = sample_slopes(s, z);
  if (end_slopes) {
    m.front() = end_slopes->first;
    m.back() = end_slopes->second;
  }

  // The Hermite piece from knot k to knot j, if it reproduces every sample between.
  const auto fits = [&](std::size_t k, std::size_t j) {
    const Poly3 p = hermite(s[j] - s[k], z[k], m[k], z[j], m[j]);
    for (std::size_t i = k + 1; i < j; ++i) {
      if (!(std::abs(p.value(s[i] - s[k]) - z[i]) <= tolerance)) return false;
    }
    return true;
  };

  std::vector<CubicPiece> pieces;
  const std::vector<std::size_t> knots = greedy_knots(n, fits);
  for (std::size_t i = 0; i + 1 < knots.size(); ++i) {
    const std::size_t k = knots[i], j = knots[i + 1];
    pieces.push_back({s[k], hermite(s[j] - s[k], z[k], m[k], z[j], m[j])});
  }
  return CubicProfile(std::move(pieces));
}

CubicProfile fit_grade_bounded_profile(const std::vector<double>& s, const std::vector<double>& z,
                                       double tolerance,
                                       const std::optional<std::pair<double, double>>& end_slopes) {
  check_samples(s, z, tolerance, end_slopes);
  const std::size_t n = s.size();
  if (n == 1 || tolerance == 0.0) return fit_cubic_profile(s, z, tolerance, end_slopes);

  // The samples' polyline with each kink rounded: a grade G(s) piecewise linear, constant at
  // the chord grade q_i along interval i and ramping linearly across [s_i - a_i, s_i + a_i]
  // (a parabolic vertical curve, which passes |q_i - q_(i-1)| a_i / 4 from the sample: at most
  // half the tolerance). At the ends G ramps from the end slope over L to the end interval's
  // grade, raised so that the interval still rises by exactly its chord.
  const double half = 0.5 * tolerance;
  std::vector<double> h(n - 1), q(n - 1);
  for (std::size_t i = 0; i + 1 < n; ++i) {
    h[i] = s[i + 1] - s[i];
    q[i] = (z[i + 1] - z[i]) / h[i];
  }
  const std::vector<double> m = sample_slopes(s, z);
  const double e0 = end_slopes ? end_slopes->first : m.front();
  const double e1 = end_slopes ? end_slopes->second : m.back();
  // A ramp's length: at most half its room; a corner's within the half tolerance, an end's short
  // enough that raising its interval's grade costs at most a quarter of it over the interval.
  const auto ramp = [](double room, double step, double reach) {
    return step == 0.0 ? 0.0 : std::min(0.5 * room, reach / std::abs(step));
  };
  const double l0 = ramp(h.front(), q.front() - e0, 0.5 * half);
  const double l1 = ramp(h.back(), e1 - q.back(), 0.5 * half);
  if (n == 2) {
    q[0] = (h[0] * q[0] - 0.5 * (l0 * e0 + l1 * e1)) / (h[0] - 0.5 * (l0 + l1));
  } else {
    q.front() = (h.front() * q.front() - 0.5 * l0 * e0) / (h.front() - 0.5 * l0);
    q.back() = (h.back() * q.back() - 0.5 * l1 * e1) / (h.back() - 0.5 * l1);
  }

  // Breakpoints of G (station, grade); z follows by integrating G exactly (trapezoids).
  struct Break {
    double s, g, z;
  };
  std::vector<Break> b{{s[0], e0, z[0]}};
  const auto add = [&](double at, double g) {
    if (at - b.back().s <= 1e-9 * std::max(1.0, std::abs(at))) {
      b.back().g = g;  // a ramp of no length: G steps here (only where a ramp is 0)
      return;
    }
    b.push_back({at, g, b.back().z + 0.5 * (b.back().g + g) * (at - b.back().s)});
  };
  if (l0 > 0.0) add(s[0] + l0, q.front());
  for (std::size_t i = 1; i + 1 < n; ++i) {
    const double a = ramp(std::min(h[i - 1], h[i]), q[i] - q[i - 1], 4.0 * half);
    add(s[i] - a, q[i - 1]);
    add(s[i] + a, q[i]);
  }
  if (l1 > 0.0) add(s[n - 1] - l1, q.back());
  add(s[n - 1], e1);
  b.back().z = z[n - 1];

  // Merged into the longest Hermite pieces between breakpoints that keep every sample within
  // the tolerance and the slope within G's steepest over the span (plus a hundredth of a
  // percent): one breakpoint to the next is G's own quadratic, which always does.
  constexpr double kSlopeAllowance = 1e-4;
  const auto piece = [&](std::size_t k, std::size_t j) {
    return hermite(b[j].s - b[k].s, b[k].z, b[k].g, b[j].z, b[j].g);
  };
  const auto fits = [&](std::size_t k, std::size_t j) {
    if (j == k + 1) return true;
    const Poly3 p = piece(k, j);
    double steepest = 0.0;
    for (std::size_t i = k; i <= j; ++i) steepest = std::max(steepest, std::abs(b[i].g));
    if (steepest_slope(p, b[j].s - b[k].s) > steepest + kSlopeAllowance) return false;
    auto i = static_cast<std::size_t>(std::upper_bound(s.begin(), s.end(), b[k].s) - s.begin());
    for (; i < n && s[i] < b[j].s; ++i) {
      if (!(std::abs(p.value(s[i] - b[k].s) - z[i]) <= tolerance)) return false;
    }
    return true;
  };
  std::vector<CubicPiece> pieces;
  const std::vector<std::size_t> knots = greedy_knots(b.size(), fits);
  for (std::size_t i = 0; i + 1 < knots.size(); ++i)
    pieces.push_back({b[knots[i]].s, piece(knots[i], knots[i + 1])});
  return CubicProfile(std::move(pieces));
}

CubicProfile hermite_profile(double length, double z0, double g0, double z1, double g1) {
  if (!(length > 0.0) || !std::isfinite(length)) {
    throw InvalidInput("hermite profile: length must be positive and finite");
  }
  return CubicProfile({CubicPiece{0.0, hermite(length, z0, g0, z1, g1)}});
}

double slope_bound(double length, double z0, double g0, double z1, double g1, double allowance) {
  return std::max({std::abs(g0), std::abs(g1), std::abs(z1 - z0) / length + allowance});
}

CubicProfile slope_bounded_profile(double length, double z0, double g0, double z1, double g1,
                                   double allowance) {
  CubicProfile cubic = hermite_profile(length, z0, g0, z1, g1);
  if (!(allowance >= 0.0)) throw InvalidInput("slope-bounded profile: the allowance must be >= 0");
  const double rise = z1 - z0;
  const double bound = slope_bound(length, z0, g0, z1, g1, allowance);
  // The Hermite slope is a quadratic in s: its extreme lies at an end or at its vertex.
  const Poly3& h = cubic.pieces().front().poly;
  double steepest = std::max(std::abs(g0), std::abs(g1));
  if (h.d != 0.0) {
    const double vertex = -h.c / (3.0 * h.d);
    if (vertex > 0.0 && vertex < length) steepest = std::max(steepest, std::abs(cubic.derivative(vertex)));
  }
  if (steepest <= bound + allowance) return cubic;  // the smoothest, where it overshoots little
  // Slope ramps of length r from g0 to c and from c to g1, c constant between: the rise is
  // r (g0 + g1) / 2 + c (length - r). The longest ramps (r = length / 2) when their c is within
  // the bound, else c at the bound on the side of the overshoot and r from the rise.
  const double mean_end = 0.5 * (g0 + g1);
  double r = 0.5 * length;
  double c = 2.0 * rise / length - mean_end;
  if (std::abs(c) > bound) {
    c = std::copysign(bound, c);
    r = (rise - c * length) / (mean_end - c);
    if (!(r > 0.0 && r <= 0.5 * length)) return cubic;  // no such ramps: the rise itself is too steep
  }
  const double z_r = z0 + 0.5 * r * (g0 + c);
  std::vector<CubicPiece> pieces{{0.0, Poly3{z0, g0, 0.5 * (c - g0) / r, 0.0}}};
  const double straight = length - 2.0 * r;
  if (straight > 1e-9 * length) pieces.push_back({r, Poly3{z_r, c, 0.0, 0.0}});
  pieces.push_back({length - r, Poly3{z_r + c * std::max(straight, 0.0), c, 0.5 * (g1 - c) / r, 0.0}});
  return CubicProfile(std::move(pieces));
}

}  // namespace relief

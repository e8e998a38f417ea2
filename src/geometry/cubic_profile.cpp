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

  // Greedy: from knot k, first the whole rest (a check stops at its first miss, so this is
  // cheap), then exponential search for a failing end and binary search for the furthest end
  // that fits; O(n log n) evaluations overall.
  std::vector<CubicPiece> pieces;
  std::size_t k = 0;
  while (k + 1 < n) {
    std::size_t good = k + 1;  // two consecutive samples always fit
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
    pieces.push_back({s[k], hermite(s[good] - s[k], z[k], m[k], z[good], m[good])});
    k = good;
  }
  return CubicProfile(std::move(pieces));
}

CubicProfile hermite_profile(double length, double z0, double g0, double z1, double g1) {
  if (!(length > 0.0) || !std::isfinite(length)) {
    throw InvalidInput("hermite profile: length must be positive and finite");
  }
  return CubicProfile({CubicPiece{0.0, hermite(length, z0, g0, z1, g1)}});
}

CubicProfile slope_bounded_profile(double length, double z0, double g0, double z1, double g1,
                                   double allowance) {
  const CubicProfile cubic = hermite_profile(length, z0, g0, z1, g1);
  if (!(allowance >= 0.0)) throw InvalidInput("slope-bounded profile: the allowance must be >= 0");
  const double rise = z1 - z0;
  const double bound = std::max({std::abs(g0), std::abs(g1), std::abs(rise) / length + allowance});
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

#include "relief/geometry/plan_view.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <string>
#include <type_traits>

#include "relief/core/errors.h"

namespace relief {

namespace {

constexpr int kGaussPoints = 16;

struct GaussLegendre {
  std::array<double, kGaussPoints> node{};  // on [-1, 1]
  std::array<double, kGaussPoints> weight{};
};

// 16-point Gauss-Legendre rule: roots of P_16 by Newton from Chebyshev guesses
// (Press et al., Numerical Recipes 3rd ed., 4.6.1), computed once.
const GaussLegendre& gauss_legendre() {
  static const GaussLegendre rule = [] {
    GaussLegendre r;
    const int n = kGaussPoints;
    for (int i = 0; i < (n + 1) / 2; ++i) {
      double x = std::cos(std::numbers::pi * (i + 0.75) / (n + 0.5));
      double dp = 0.0;
      for (int iter = 0; iter < 100; ++iter) {
        double p0 = 1.0;
        double p1 = 0.0;
        for (int j = 0; j < n; ++j) {
          const double p2 = p1;
          p1 = p0;
          p0 = ((2.0 * j + 1.0) * x * p1 - j * p2) / (j + 1.0);
        }
        dp = n * (x * p0 - p1) / (x * x - 1.0);
        const double dx = p0 / dp;
        x -= dx;
        if (std::abs(dx) < 1e-16) break;
      }
      const double w = 2.0 / ((1.0 - x * x) * dp * dp);
      r.node[static_cast<std::size_t>(i)] = -x;
      r.node[static_cast<std::size_t>(n - 1 - i)] = x;
      r.weight[static_cast<std::size_t>(i)] = w;
      r.weight[static_cast<std::size_t>(n - 1 - i)] = w;
    }
    return r;
  }();
  return rule;
}

// Integral of f over [a, b] with one 16-point Gauss-Legendre rule.
template <typename F>
auto gauss16(const F& f, double a, double b) {
  using Value = std::decay_t<decltype(f(a))>;
  const auto& rule = gauss_legendre();
  const double half = 0.5 * (b - a);
  const double mid = 0.5 * (a + b);
  Value sum = f(mid + half * rule.node[0]) * rule.weight[0];
  for (std::size_t i = 1; i < rule.node.size(); ++i) sum += f(mid + half * rule.node[i]) * rule.weight[i];
  return Value(sum * half);
}

// sin(x) / x, accurate near 0.
double sinc(double x) {
  if (std::abs(x) < 1e-4) return 1.0 - x * x / 6.0;
  return std::sin(x) / x;
}

Vec2 direction(double heading) {
  return {std::cos(heading), std::sin(heading)};
}

double speed(const Poly3& u, const Poly3& v, double p) {
  return std::hypot(u.derivative(p), v.derivative(p));
}

// Adaptive Gauss-Legendre: accept [a, b] when one rule agrees with the two halves.
double adaptive_length(const Poly3& u, const Poly3& v, double a, double b, double whole, double tol,
                       int depth) {
  const auto f = [&](double p) { return speed(u, v, p); };
  const double mid = 0.5 * (a + b);
  const double left = gauss16(f, a, mid);
  const double right = gauss16(f, mid, b);
  if (depth >= 40 || std::abs(left + right - whole) <= tol) return left + right;
  return adaptive_length(u, v, a, mid, left, 0.5 * tol, depth + 1) +
         adaptive_length(u, v, mid, b, right, 0.5 * tol, depth + 1);
}

Pose2 evaluate_line(const PlanGeometry& g, double ds) {
  return {g.start + ds * direction(g.heading), g.heading, 0.0};
}

// Exact arc: chord of length ds * sinc(k ds / 2) at the mean heading.
Pose2 evaluate_arc(const PlanGeometry& g, double ds) {
  const double k = g.curvature;
  if (k == 0.0) return evaluate_line(g, ds);
  const double sweep = k * ds;
  const double chord = ds * sinc(0.5 * sweep);
  return {g.start + chord * direction(g.heading + 0.5 * sweep), g.heading + sweep, k};
}

// Clothoid: heading(σ) = h + k0 σ + c σ²/2; position by Gauss-Legendre on sub-intervals that
// each turn by at most ~0.5 rad, where 16 points are exact to rounding.
Pose2 evaluate_spiral(const PlanGeometry& g, double ds) {
  const double k0 = g.curvature_start;
  const double c = g.length > 0.0 ? (g.curvature_end - g.curvature_start) / g.length : 0.0;
  const auto heading = [&](double sigma) { return g.heading + sigma * (k0 + 0.5 * c * sigma); };
  const double k_end = k0 + c * ds;
  const double max_turn = std::max(std::abs(k0), std::abs(k_end)) * ds;
  const int pieces = static_cast<int>(std::clamp(std::ceil(max_turn / 0.5), 1.0, 100000.0));
  const auto f = [&](double sigma) -> Vec2 { return direction(heading(sigma)); };
  Vec2 offset = Vec2::Zero();
  const double step = ds / pieces;
  for (int i = 0; i < pieces; ++i) offset += gauss16(f, i * step, (i + 1) * step);
  return {g.start + offset, heading(ds), k_end};
}

constexpr int kArcIntervals = 32;

}  // namespace

std::vector<double> param_poly3_arc_table(const PlanGeometry& record) {
  const double p_end = record.normalized ? 1.0 : record.length;
  const auto f = [&](double p) { return speed(record.u, record.v, p); };
  std::vector<double> cumulative(kArcIntervals + 1, 0.0);
  for (int i = 0; i < kArcIntervals; ++i) {
    const double a = p_end * i / kArcIntervals;
    const double b = p_end * (i + 1) / kArcIntervals;
    cumulative[static_cast<std::size_t>(i) + 1] = cumulative[static_cast<std::size_t>(i)] + gauss16(f, a, b);
  }
  return cumulative;
}

namespace {

// paramPoly3: arc length ds (scaled so that `length` maps to the full range) -> p by the
// cumulative table of Gauss-Legendre lengths, then safeguarded Newton inside one interval.
Pose2 evaluate_param_poly3(const PlanGeometry& g, double ds, const std::vector<double>& cumulative) {
  constexpr int kIntervals = kArcIntervals;
  const double p_end = g.normalized ? 1.0 : g.length;
  const auto f = [&](double p) { return speed(g.u, g.v, p); };
  const double total = cumulative.back();
  double p = p_end;
  if (ds <= 0.0) {
    p = 0.0;
  } else if (ds < g.length && total > 0.0) {
    const double target = ds * total / g.length;
    const auto it = std::upper_bound(cumulative.begin(), cumulative.end(), target);
    const auto i =
        static_cast<int>(std::clamp<std::ptrdiff_t>(it - cumulative.begin() - 1, 0, kIntervals - 1));
    double lo = p_end * i / kIntervals;
    double hi = p_end * (i + 1) / kIntervals;
    const double base = cumulative[static_cast<std::size_t>(i)];
    const double p0 = lo;
    p = lo + (hi - lo) *
                 std::clamp((target - base) / (cumulative[static_cast<std::size_t>(i) + 1] - base), 0.0, 1.0);
    for (int iter = 0; iter < 60; ++iter) {
      const double err = base + gauss16(f, p0, p) - target;
      if (std::abs(err) < 1e-12 * std::max(1.0, total)) break;
      if (err > 0.0)
        hi = p;
      else
        lo = p;
      const double v = f(p);
      double next = v > 0.0 ? p - err / v : 0.5 * (lo + hi);
      if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
      p = next;
    }
  }
  const double du = g.u.derivative(p);
  const double dv = g.v.derivative(p);
  const Vec2 local(g.u.value(p), g.v.value(p));
  const double ch = std::cos(g.heading);
  const double sh = std::sin(g.heading);
  const Vec2 position = g.start + Vec2(ch * local.x() - sh * local.y(), sh * local.x() + ch * local.y());
  const double v2 = du * du + dv * dv;
  const double curvature =
      v2 > 0.0 ? (du * g.v.second_derivative(p) - dv * g.u.second_derivative(p)) / (v2 * std::sqrt(v2)) : 0.0;
  return {position, g.heading + std::atan2(dv, du), curvature};
}

}  // namespace

PlanView::PlanView(std::vector<PlanGeometry> records) : records_(std::move(records)) {
  arc_tables_.resize(records_.size());
  for (std::size_t i = 0; i < records_.size(); ++i) {
    const PlanGeometry& g = records_[i];
    if (g.kind == PlanGeometry::Kind::param_poly3) arc_tables_[i] = param_poly3_arc_table(g);
    if (!(std::isfinite(g.length) && g.length > 0.0)) {
      throw InvalidInput("plan view: geometry record " + std::to_string(i) + " has length " +
                         std::to_string(g.length) + " (must be positive and finite)");
    }
    if (!std::isfinite(g.s) || !std::isfinite(g.heading) || !g.start.allFinite()) {
      throw InvalidInput("plan view: geometry record " + std::to_string(i) + " has a non-finite start");
    }
    if (i > 0 && !(g.s > records_[i - 1].s)) {
      throw InvalidInput("plan view: geometry records are not sorted by s (record " + std::to_string(i) +
                         " at s=" + std::to_string(g.s) + ")");
    }
  }
}

double PlanView::length() const {
  if (records_.empty()) return 0.0;
  return records_.back().s + records_.back().length;
}

std::size_t PlanView::record_at(double s) const {
  if (records_.empty()) throw InvalidInput("plan view: no geometry records");
  const auto it = std::upper_bound(records_.begin(), records_.end(), s,
                                   [](double value, const PlanGeometry& g) { return value < g.s; });
  if (it == records_.begin()) return 0;
  return static_cast<std::size_t>(it - records_.begin()) - 1;
}

double PlanView::total_turn(double s0, double s1) const {
  double turn = 0.0;
  for (std::size_t i = records_.empty() ? 0 : record_at(s0); i < records_.size(); ++i) {
    const PlanGeometry& g = records_[i];
    const double a = std::max(s0, g.s) - g.s, b = std::min(s1, g.s + g.length) - g.s;  // in the record
    if (g.s >= s1) break;
    if (!(b > a)) continue;
    switch (g.kind) {
      case PlanGeometry::Kind::line:
        break;
      case PlanGeometry::Kind::arc:
        turn += std::abs(g.curvature) * (b - a);
        break;
      case PlanGeometry::Kind::spiral: {
        // Curvature linear in s: |k| integrates to a trapezoid, or two triangles where k
        // changes sign.
        const double rate = (g.curvature_end - g.curvature_start) / g.length;
        const double ka = g.curvature_start + rate * a, kb = g.curvature_start + rate * b;
        if ((ka >= 0.0) == (kb >= 0.0)) {
          turn += 0.5 * std::abs(ka + kb) * (b - a);
        } else {
          turn += 0.5 * (ka * ka + kb * kb) / std::abs(rate);
        }
        break;
      }
      case PlanGeometry::Kind::param_poly3: {
        const int steps = std::max(1, static_cast<int>(std::ceil((b - a) / 0.25)));
        const double step = (b - a) / steps;
        for (int k = 0; k < steps; ++k) {
          turn += std::abs(evaluate_param_poly3(g, a + (k + 0.5) * step, arc_tables_[i]).curvature) * step;
        }
        break;
      }
    }
  }
  return turn;
}

Pose2 PlanView::at(double s) const {
  if (records_.empty()) throw InvalidInput("plan view: no geometry records");
  const double clamped = std::clamp(s, records_.front().s, length());
  const std::size_t i = record_at(clamped);
  const PlanGeometry& g = records_[i];
  if (g.kind == PlanGeometry::Kind::param_poly3) {
    return evaluate_param_poly3(g, std::clamp(clamped - g.s, 0.0, g.length), arc_tables_[i]);
  }
  return evaluate(g, clamped - g.s);
}

Pose2 evaluate(const PlanGeometry& record, double ds) {
  const double d = std::clamp(ds, 0.0, std::max(0.0, record.length));
  switch (record.kind) {
    case PlanGeometry::Kind::line:
      return evaluate_line(record, d);
    case PlanGeometry::Kind::arc:
      return evaluate_arc(record, d);
    case PlanGeometry::Kind::spiral:
      return evaluate_spiral(record, d);
    case PlanGeometry::Kind::param_poly3:
      return evaluate_param_poly3(record, d, param_poly3_arc_table(record));
  }
  return evaluate_line(record, d);
}

double param_poly3_length(const Poly3& u, const Poly3& v, double p_end) {
  if (!(p_end > 0.0)) return 0.0;
  const auto f = [&](double p) { return speed(u, v, p); };
  // Start from 8 intervals so that a cusp-free cubic converges on the first check.
  double total = 0.0;
  constexpr int kStart = 8;
  for (int i = 0; i < kStart; ++i) {
    const double a = p_end * i / kStart;
    const double b = p_end * (i + 1) / kStart;
    total += adaptive_length(u, v, a, b, gauss16(f, a, b), 1e-11, 0);
  }
  return total;
}

}  // namespace relief

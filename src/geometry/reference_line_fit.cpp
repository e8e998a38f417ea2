#include "relief/geometry/reference_line_fit.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "relief/core/errors.h"
#include "relief/geometry/plane.h"

namespace relief {

namespace {

constexpr double kDuplicate_m = 1e-3;                               // vertices closer than this are merged
constexpr double kStraight_rad = 1e-9;                              // turning angles below this add no arc
constexpr double kVanish_m = 1e-9;                                  // lines this short vanish without notice
constexpr double kMaxHalfTurn_rad = 0.5 * std::numbers::pi - 1e-9;  // U-turn clamp

// Plan records laid end to end: each starts at the previous one's end pose (exact G1).
struct RecordChain {
  explicit RecordChain(const Pose2& start) : end(start) {}

  void append(PlanGeometry g) {
    g.s = length;
    g.start = end.position;
    g.heading = end.heading;
    end = evaluate(g, g.length);
    length += g.length;
    records.push_back(g);
  }

  std::vector<PlanGeometry> records;
  Pose2 end;
  double length = 0.0;
};

}  // namespace

PlanView fit_reference_line(const Polyline2& polyline, const ReferenceLineOptions& options,
                            std::vector<double>* station_map, ReferenceLineReport* report) {
  if (!(options.tolerance_m > 0.0) || !std::isfinite(options.tolerance_m)) {
    throw InvalidInput("reference line fit: tolerance must be positive and finite");
  }
  if (!(options.min_length_m >= 0.0) || !std::isfinite(options.min_length_m)) {
    throw InvalidInput("reference line fit: minimum record length must be finite and non-negative");
  }
  if (!(options.min_radius_m >= 0.0) || !std::isfinite(options.min_radius_m)) {
    throw InvalidInput("reference line fit: minimum radius must be finite and non-negative");
  }
  for (std::size_t i = 0; i < polyline.size(); ++i) {
    if (!polyline[i].allFinite()) {
      throw InvalidInput("reference line fit: polyline vertex " + std::to_string(i) + " is not finite");
    }
  }
  ReferenceLineReport local_report;
  ReferenceLineReport& rep = report != nullptr ? *report : local_report;
  rep = {};

  // 1. Merge near-duplicate vertices; the last kept vertex is the polyline's true end.
  std::vector<std::size_t> kept;
  std::vector<std::size_t> kept_of(polyline.size(), 0);
  for (std::size_t i = 0; i < polyline.size(); ++i) {
    if (kept.empty() || (polyline[i] - polyline[kept.back()]).norm() > kDuplicate_m) kept.push_back(i);
    kept_of[i] = kept.size() - 1;
  }
  if (kept.size() < 2) {
    throw InvalidInput("reference line fit: the polyline has fewer than two distinct vertices");
  }
  if (kept.back() != polyline.size() - 1) kept.back() = polyline.size() - 1;

  // The working vertices: the kept ones, each remembering which kept vertex it is (-1 once it
  // has been merged into a new position).
  std::vector<Vec2> p;
  std::vector<long> origin;
  for (std::size_t i = 0; i < kept.size(); ++i) {
    p.push_back(polyline[kept[i]]);
    origin.push_back(static_cast<long>(i));
  }

  std::size_t m = 0;
  std::vector<double> len, seg_heading, theta, radius, tangent;
  std::vector<Vec2> dir;
  std::vector<std::size_t> corners;  // start, arc vertices, end
  const double min_r = options.min_radius_m;
  // 2. Corner arcs: radius max(R_min, min(R_tol, R_fit)); d = tangent distance from the vertex.
  const auto layout = [&] {
    m = p.size();
    len.assign(m - 1, 0.0);
    dir.assign(m - 1, Vec2::Zero());
    seg_heading.assign(m - 1, 0.0);
    for (std::size_t j = 0; j + 1 < m; ++j) {
      const Vec2 d = p[j + 1] - p[j];
      len[j] = d.norm();
      dir[j] = d / len[j];
      seg_heading[j] = std::atan2(d.y(), d.x());
    }
    theta.assign(m, 0.0);
    radius.assign(m, 0.0);
    tangent.assign(m, 0.0);
    corners = {0};
    for (std::size_t i = 1; i + 1 < m; ++i) {
      theta[i] = std::atan2(cross(dir[i - 1], dir[i]), dir[i - 1].dot(dir[i]));
      if (std::abs(theta[i]) < kStraight_rad) continue;
      const double half = std::min(0.5 * std::abs(theta[i]), kMaxHalfTurn_rad);
      // R_tol = tol / (1/cos(half) - 1), with 1 - cos(x) = 2 sin^2(x/2) for small angles.
      const double sq = std::sin(0.5 * half);
      const double r_tol = options.tolerance_m * std::cos(half) / (2.0 * sq * sq);
      const double t = std::tan(half);
      const double r_fit = 0.5 * std::min(len[i - 1], len[i]) / t;
      radius[i] = std::max(min_r, std::min(r_tol, r_fit));
      tangent[i] = radius[i] * t;
      corners.push_back(i);
    }
    corners.push_back(m - 1);
  };

  // 2b. Arcs of the minimum radius may not fit on their segments: merge the two corners of an
  //     overfull segment (or drop the corner next to an end) until every arc fits.
  bool widened = false;
  for (;;) {
    layout();
    std::size_t worst = m;
    double worst_excess = 1e-9;
    for (std::size_t j = 0; j + 1 < m; ++j) {
      const double excess = tangent[j] + tangent[j + 1] - len[j];
      if (excess > worst_excess) {
        worst_excess = excess;
        worst = j;
      }
    }
    if (worst == m) break;
    widened = true;
    ++rep.vertices_merged;
    const std::size_t j = worst;
    if (j == 0 || j + 2 == m) {
      // The first or last segment: drop its inner vertex, the end stays.
      const std::size_t drop = j == 0 ? 1 : m - 2;
      p.erase(p.begin() + static_cast<long>(drop));
      origin.erase(origin.begin() + static_cast<long>(drop));
      continue;
    }
    // Two turns the same way: one corner where the outer segments' lines meet (ahead of both);
    // otherwise (an S-bend, a near U-turn) the midpoint of the two.
    Vec2 merged = 0.5 * (p[j] + p[j + 1]);
    const double turn = theta[j] + theta[j + 1];
    if (theta[j] * theta[j + 1] > 0.0 && std::abs(turn) < std::numbers::pi - 0.1) {
      const Vec2& a = dir[j - 1];
      const Vec2& b = dir[j + 1];
      const double denom = cross(a, b);
      if (std::abs(denom) > 1e-12) {
        const double u = cross(p[j + 1] - p[j], b) / denom;  // along a from p[j]
        const double v = cross(p[j + 1] - p[j], a) / denom;  // along b from p[j + 1]
        if (u >= 0.0 && v <= 0.0) merged = p[j] + u * a;
      }
    }
    p[j] = merged;
    origin[j] = -1;
    p.erase(p.begin() + static_cast<long>(j + 1));
    origin.erase(origin.begin() + static_cast<long>(j + 1));
    if ((p[j] - p[j - 1]).norm() <= kDuplicate_m || (p[j + 1] - p[j]).norm() <= kDuplicate_m) {
      p.erase(p.begin() + static_cast<long>(j));
      origin.erase(origin.begin() + static_cast<long>(j));
    }
  }
  for (const std::size_t i : corners) {
    if (i == 0 || i + 1 == m) continue;
    const double half = std::min(0.5 * std::abs(theta[i]), kMaxHalfTurn_rad);
    const double sq = std::sin(0.5 * half);
    if (radius[i] > options.tolerance_m * std::cos(half) / (2.0 * sq * sq) + 1e-12) {
      ++rep.corners_widened;
      widened = true;
    }
  }

  // Cumulative polyline length, for runs of straight lines through collinear vertices.
  std::vector<double> cum(m, 0.0);
  for (std::size_t j = 0; j + 1 < m; ++j) cum[j + 1] = cum[j] + len[j];
  const auto run_length = [&](std::size_t r) {
    const std::size_t a = corners[r];
    const std::size_t b = corners[r + 1];
    return cum[b] - cum[a] - tangent[a] - tangent[b];
  };

  // 3. A line shorter than min_length (but not vanishing) shrinks its neighbouring arcs until it
  //    is min_length long: smaller radii only bring the arcs closer to the polyline. Where that
  //    would take an arc below the minimum radius, the arcs grow instead until the line
  //    vanishes. A line on a polyline segment that is itself shorter than min_length stays:
  //    dropping it would shift the rest of the reference line off the polyline.
  const double min_len = options.min_length_m;
  const auto half_tan = [&](std::size_t i) {
    return std::tan(std::min(0.5 * std::abs(theta[i]), kMaxHalfTurn_rad));
  };
  for (std::size_t pass = 0; pass <= corners.size(); ++pass) {
    bool changed = false;
    for (std::size_t r = 0; r + 1 < corners.size(); ++r) {
      const double ell = run_length(r);
      if (ell <= kVanish_m || ell >= min_len) continue;
      const std::size_t a = corners[r];
      const std::size_t b = corners[r + 1];
      const double need = min_len - ell;
      const double avail = tangent[a] + tangent[b];
      if (!(avail > need)) continue;  // the segment itself is shorter than min_length: kept
      const double share_a = tangent[a] / avail;
      bool shrink = true;
      for (const auto& [i, share] : {std::pair{a, share_a}, std::pair{b, 1.0 - share_a}}) {
        if (tangent[i] > 0.0 && (tangent[i] - need * share) / half_tan(i) < min_r) shrink = false;
      }
      const double delta = shrink ? -need : ell;
      for (const auto& [i, share] : {std::pair{a, share_a}, std::pair{b, 1.0 - share_a}}) {
        if (tangent[i] == 0.0) continue;
        tangent[i] += delta * share;
        radius[i] = tangent[i] / half_tan(i);
      }
      changed = true;
    }
    if (!changed) break;
  }

  // 4. Records: lines along the runs, arcs at the corners. Each record starts at the previous
  //    record's end (exact G1); each arc's sweep absorbs the heading drift of merged lines.
  RecordChain chain(Pose2{p[0], seg_heading[0], 0.0});
  std::vector<double> station(m, 0.0);
  for (std::size_t r = 0; r + 1 < corners.size(); ++r) {
    const std::size_t a = corners[r];
    const std::size_t b = corners[r + 1];
    const double ell = run_length(r);
    const bool keep = ell > kVanish_m;
    for (std::size_t i = a + 1; i < b; ++i)
      station[i] = chain.length + (keep ? cum[i] - cum[a] - tangent[a] : 0.0);
    if (keep) {
      PlanGeometry line;
      line.kind = PlanGeometry::Kind::line;
      line.length = ell;
      chain.append(line);
    }
    if (b + 1 == m) break;
    const double sweep = theta[b] + wrap_angle(seg_heading[b] - (chain.end.heading + theta[b]));
    PlanGeometry arc;
    arc.kind = PlanGeometry::Kind::arc;
    arc.length = radius[b] * std::abs(sweep);
    arc.curvature = std::copysign(1.0 / radius[b], sweep);
    station[b] = chain.length + 0.5 * arc.length;
    chain.append(arc);
  }
  PlanView plan(std::move(chain.records));

  if (widened) {
    // Departure: each polyline vertex's distance to the reference line, sampled densely
    // (chord error of an arc of radius R over angle a: R (1 - cos(a / 2)) < 1 mm).
    Polyline2 curve;
    for (const PlanGeometry& g : plan.records()) {
      int steps = 1;
      if (g.kind == PlanGeometry::Kind::arc) {
        const double r = 1.0 / std::abs(g.curvature);
        const double step_rad = 2.0 * std::acos(std::max(0.0, 1.0 - 1e-3 / r));
        steps = std::max(1, static_cast<int>(std::ceil(g.length / r / step_rad)));
      }
      for (int k = 0; k < steps; ++k) curve.push_back(evaluate(g, g.length * k / steps).position);
    }
    curve.push_back(plan.at(plan.length()).position);
    for (const Vec2& q : polyline) {
      double best = std::numeric_limits<double>::infinity();
      for (std::size_t i = 0; i + 1 < curve.size(); ++i) {
        const Vec2 d = curve[i + 1] - curve[i];
        const double len2 = d.squaredNorm();
        const double t = len2 > 0.0 ? std::clamp((q - curve[i]).dot(d) / len2, 0.0, 1.0) : 0.0;
        best = std::min(best, (curve[i] + t * d - q).norm());
      }
      rep.max_departure_m = std::max(rep.max_departure_m, best);
    }
  }

  if (station_map != nullptr) {
    const double total = plan.length();
    station.front() = 0.0;
    station.back() = total;
    // Stations of the kept vertices: the working vertex that still is one, else interpolated
    // by polyline length between such anchors.
    const std::size_t n_kept = kept.size();
    std::vector<double> kept_station(n_kept, -1.0);
    for (std::size_t i = 0; i < m; ++i) {
      if (origin[i] >= 0) kept_station[static_cast<std::size_t>(origin[i])] = station[i];
    }
    kept_station.front() = 0.0;
    kept_station.back() = total;
    std::vector<double> kept_cum(n_kept, 0.0);
    for (std::size_t i = 1; i < n_kept; ++i) {
      kept_cum[i] = kept_cum[i - 1] + (polyline[kept[i]] - polyline[kept[i - 1]]).norm();
    }
    std::size_t prev = 0;
    for (std::size_t i = 1; i < n_kept; ++i) {
      if (kept_station[i] < 0.0) continue;
      for (std::size_t k = prev + 1; k < i; ++k) {
        const double span = kept_cum[i] - kept_cum[prev];
        const double f = span > 0.0 ? (kept_cum[k] - kept_cum[prev]) / span : 0.0;
        kept_station[k] = kept_station[prev] + f * (kept_station[i] - kept_station[prev]);
      }
      prev = i;
    }
    station_map->assign(polyline.size(), 0.0);
    for (std::size_t i = 0; i < polyline.size(); ++i) {
      (*station_map)[i] = std::clamp(kept_station[kept_of[i]], 0.0, total);
    }
  }
  return plan;
}

double arc_tangent_scale(double turn_rad) {
  const double turn = std::min(std::abs(wrap_angle(turn_rad)), 0.9 * std::numbers::pi);
  return turn < 1e-6 ? 1.0 : 2.0 * std::tan(0.25 * turn) / std::sin(0.5 * turn);
}

PlanGeometry hermite_connector(const Pose2& from, const Pose2& to, double tangent_scale) {
  if (!(tangent_scale > 0.0) || !std::isfinite(tangent_scale)) {
    throw InvalidInput("hermite connector: tangent scale must be positive and finite");
  }
  if (!from.position.allFinite() || !to.position.allFinite() || !std::isfinite(from.heading) ||
      !std::isfinite(to.heading)) {
    throw InvalidInput("hermite connector: poses are not finite");
  }
  const Vec2 d = to.position - from.position;
  const double chord = d.norm();
  if (!(chord > 0.0)) throw InvalidInput("hermite connector: the two poses coincide");

  // `to` in the local frame of `from` (u along its heading, v to its left).
  const double ch = std::cos(from.heading);
  const double sh = std::sin(from.heading);
  const double x1 = ch * d.x() + sh * d.y();
  const double y1 = -sh * d.x() + ch * d.y();
  const double delta = wrap_angle(to.heading - from.heading);

  PlanGeometry g;
  g.start = from.position;
  g.heading = from.heading;
  if (x1 > 0.0 && std::abs(y1) <= 1e-9 && std::abs(delta) <= 1e-9) {
    g.kind = PlanGeometry::Kind::line;
    g.length = x1;
    return g;
  }

  // Cubic Hermite with P0 = 0, P0' = L (1, 0), P1 = (x1, y1), P1' = L (cos Δ, sin Δ):
  // b = M0, c = 3 P1 - 2 M0 - M1, d = M0 + M1 - 2 P1.
  const double tl = tangent_scale * chord;
  const double m1u = tl * std::cos(delta);
  const double m1v = tl * std::sin(delta);
  g.kind = PlanGeometry::Kind::param_poly3;
  g.normalized = true;
  g.u = Poly3{0.0, tl, 3.0 * x1 - 2.0 * tl - m1u, tl + m1u - 2.0 * x1};
  g.v = Poly3{0.0, 0.0, 3.0 * y1 - m1v, m1v - 2.0 * y1};
  g.length = param_poly3_length(g.u, g.v, 1.0);
  return g;
}

std::vector<PlanGeometry> corner_connector(const Pose2& from, const Pose2& to) {
  const double turn = wrap_angle(to.heading - from.heading);
  const auto fallback = [&] {
    return std::vector<PlanGeometry>{hermite_connector(from, to, arc_tangent_scale(turn))};
  };
  if (std::abs(turn) < 1e-3 || std::abs(turn) > 0.9 * std::numbers::pi) return fallback();
  if (!from.position.allFinite() || !to.position.allFinite()) return fallback();  // throws
  const Vec2 d0(std::cos(from.heading), std::sin(from.heading));
  const Vec2 d1(std::cos(to.heading), std::sin(to.heading));
  const Vec2 delta = to.position - from.position;
  // from + a d0 = to - b d1.
  const double det = cross(d0, d1);
  const double a = cross(delta, d1) / det;
  const double b = cross(d0, delta) / det;
  // An S-bend: the cubic whose tangents are as long as the chord (a lane change's smoothstep).
  if (!(a > 1e-6) || !(b > 1e-6)) return std::vector<PlanGeometry>{hermite_connector(from, to, 1.0)};
  const double tangent = std::min(a, b);
  const double radius = tangent / std::tan(0.5 * std::abs(turn));
  RecordChain chain(from);
  constexpr double kMinLine_m = 1e-6;
  const auto line = [&](double length) {
    if (!(length > kMinLine_m)) return;
    PlanGeometry g;
    g.kind = PlanGeometry::Kind::line;
    g.length = length;
    chain.append(g);
  };
  line(a - tangent);
  PlanGeometry arc;
  arc.kind = PlanGeometry::Kind::arc;
  arc.curvature = (turn > 0.0 ? 1.0 : -1.0) / radius;
  arc.length = radius * std::abs(turn);
  chain.append(arc);
  line(b - tangent);
  return std::move(chain.records);
}

}  // namespace relief

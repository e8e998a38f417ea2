#include "relief/geometry/polyline.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "relief/core/errors.h"

namespace relief {

std::vector<double> cumulative_length(const Polyline2& line) {
  std::vector<double> s(line.size(), 0.0);
  for (std::size_t i = 1; i < line.size(); ++i) s[i] = s[i - 1] + (line[i] - line[i - 1]).norm();
  return s;
}

double length_m(const Polyline2& line) {
  double total = 0.0;
  for (std::size_t i = 1; i < line.size(); ++i) total += (line[i] - line[i - 1]).norm();
  return total;
}

Vec2 point_at(const Polyline2& line, const std::vector<double>& cumulative, double s) {
  if (line.empty()) throw InvalidInput("point_at: empty polyline");
  if (line.size() == 1 || s <= 0.0) return line.front();
  if (s >= cumulative.back()) return line.back();
  // First vertex with cumulative length > s; the segment before it contains s.
  const auto it = std::upper_bound(cumulative.begin(), cumulative.end(), s);
  const auto i = static_cast<std::size_t>(it - cumulative.begin());
  const double seg = cumulative[i] - cumulative[i - 1];
  const double t = seg > 0.0 ? (s - cumulative[i - 1]) / seg : 0.0;
  return line[i - 1] + t * (line[i] - line[i - 1]);
}

PolylineFoot nearest_on_polyline(const Polyline2& line, const Vec2& p, bool extend_end) {
  PolylineFoot foot;
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i + 1 < line.size(); ++i) {
    const Vec2 ab = line[i + 1] - line[i];
    const double length2 = ab.squaredNorm();
    if (length2 <= 0.0) continue;
    double t = (p - line[i]).dot(ab) / length2;
    t = extend_end && i + 2 == line.size() ? std::max(t, 0.0) : std::clamp(t, 0.0, 1.0);
    const Vec2 q = line[i] + t * ab;
    const double d = (q - p).squaredNorm();
    if (d < best) {
      best = d;
      foot = {true, i, q, ab / std::sqrt(length2)};
    }
  }
  return foot;
}

std::vector<double> sample_stations(double length, double spacing_m, const std::vector<double>& extra,
                                    double merge_tolerance_m) {
  if (!(spacing_m > 0.0)) throw InvalidInput("sample spacing must be positive");
  std::vector<double> extras = extra;
  extras.push_back(0.0);
  extras.push_back(length);
  std::sort(extras.begin(), extras.end());

  // Grid stations k * spacing, strictly inside (0, length).
  std::vector<double> grid;
  const auto n = static_cast<long>(std::floor(length / spacing_m));
  grid.reserve(static_cast<std::size_t>(std::max(0L, n)) + 1);
  for (long k = 1; k <= n; ++k) {
    const double s = static_cast<double>(k) * spacing_m;
    if (s < length) grid.push_back(s);
  }

  // Merge: extra stations win; a grid station within tolerance of an extra is dropped.
  std::vector<double> out;
  out.reserve(grid.size() + extras.size());
  std::size_t e = 0;
  for (double g : grid) {
    while (e < extras.size() && extras[e] <= g + merge_tolerance_m) {
      if (out.empty() || extras[e] - out.back() > merge_tolerance_m) out.push_back(extras[e]);
      ++e;
    }
    if (out.empty() || g - out.back() > merge_tolerance_m) out.push_back(g);
  }
  for (; e < extras.size(); ++e) {
    if (out.empty() || extras[e] - out.back() > merge_tolerance_m) {
      out.push_back(extras[e]);
    } else if (e + 1 == extras.size()) {
      // The road end is always exactly `length`; a road shorter than the tolerance keeps both
      // ends (one station would give its two junctions one height).
      if (out.size() == 1 && extras[e] > out.back()) {
        out.push_back(extras[e]);
      } else {
        out.back() = extras[e];
      }
    }
  }
  return out;
}

std::vector<std::size_t> dedupe_vertices(const Polyline2& line, double tolerance_m) {
  std::vector<std::size_t> kept;
  for (std::size_t i = 0; i < line.size(); ++i) {
    if (kept.empty() || (line[i] - line[kept.back()]).norm() > tolerance_m) kept.push_back(i);
  }
  return kept;
}

}  // namespace relief

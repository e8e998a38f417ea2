#pragma once
// Arc-length operations on polylines, and Douglas-Peucker simplification.

#include <cstdint>
#include <utility>
#include <vector>

#include "relief/geometry/types.h"

namespace relief {

/// Cumulative arc length at each vertex: result[0] = 0, result.back() = total length (metres).
[[nodiscard]] std::vector<double> cumulative_length(const Polyline2& line);

/// Total length in metres.
[[nodiscard]] double length_m(const Polyline2& line);

/// Position at arc length `s` along `line` (clamped to [0, length]); `cumulative` must be
/// cumulative_length(line).
[[nodiscard]] Vec2 point_at(const Polyline2& line, const std::vector<double>& cumulative, double s);

/// Where a polyline passes nearest a point.
struct PolylineFoot {
  bool found = false;       ///< false for a line without a segment of non-zero length
  std::size_t segment = 0;  ///< index of the segment's first vertex
  Vec2 point = Vec2::Zero();
  Vec2 direction = Vec2::UnitX();  ///< the segment's unit direction
};

/// The point of `line` nearest `p` (the first segment on a tie). With `extend_end` the last
/// segment continues past the line's end (a path that goes on straight). Linear in the vertices.
[[nodiscard]] PolylineFoot nearest_on_polyline(const Polyline2& line, const Vec2& p, bool extend_end = false);

/// Arc lengths at which to sample a polyline of total length `length`: every `spacing_m` from 0,
/// plus `length` itself, plus each value in `extra` (e.g. vertex positions), sorted, with values
/// closer than `merge_tolerance_m` merged (the earlier kept, but `extra` values win over grid
/// values); 0 and `length` are always the first and the last (a line shorter than the
/// tolerance keeps both). Precondition: spacing_m > 0. A straight 100 m road at 1 m gives 101
/// values.
[[nodiscard]] std::vector<double> sample_stations(double length, double spacing_m,
                                                  const std::vector<double>& extra,
                                                  double merge_tolerance_m = 1e-6);

/// Removes consecutive vertices closer than `tolerance_m`; returns the indices kept.
[[nodiscard]] std::vector<std::size_t> dedupe_vertices(const Polyline2& line, double tolerance_m);

/// Douglas-Peucker over a sequence of n points given only through `deviation(i, k, j)`: how far
/// point k (i < k < j) lies from the chord between points i and j, in whatever measure the
/// caller simplifies by (perpendicular distance in plan, 3D distance, height error over a
/// parameter, ...). A chord is split at its farthest point while that lies more than
/// `tolerance` away, and also while `must_split(i, j)` holds (at the farthest point, or the
/// middle one when none lies beyond tolerance). Returns one flag per point, the first and last
/// set. Iterative: no recursion depth limit on long sequences.
template <typename Deviation, typename MustSplit>
[[nodiscard]] std::vector<std::uint8_t> douglas_peucker(std::size_t n, double tolerance,
                                                        Deviation&& deviation, MustSplit&& must_split) {
  std::vector<std::uint8_t> keep(n, 0);
  if (n == 0) return keep;
  keep.front() = keep.back() = 1;
  std::vector<std::pair<std::size_t, std::size_t>> stack;
  if (n > 2) stack.emplace_back(0, n - 1);
  while (!stack.empty()) {
    const auto [i, j] = stack.back();
    stack.pop_back();
    if (j <= i + 1) continue;
    double worst = -1.0;
    std::size_t at = i;
    for (std::size_t k = i + 1; k < j; ++k) {
      const double d = deviation(i, k, j);
      if (d > worst) {
        worst = d;
        at = k;
      }
    }
    const bool split = must_split(i, j);
    if (!(worst > tolerance) && !split) continue;
    if (!(worst > tolerance)) at = (i + j) / 2;
    keep[at] = 1;
    stack.emplace_back(i, at);
    stack.emplace_back(at, j);
  }
  return keep;
}

/// douglas_peucker with the tolerance as the only reason to split.
template <typename Deviation>
[[nodiscard]] std::vector<std::uint8_t> douglas_peucker(std::size_t n, double tolerance,
                                                        Deviation&& deviation) {
  return douglas_peucker(n, tolerance, std::forward<Deviation>(deviation),
                         [](std::size_t, std::size_t) { return false; });
}

}  // namespace relief

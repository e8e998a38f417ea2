#pragma once
// Arc-length operations on polylines.

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

/// Arc lengths at which to sample a polyline of total length `length`: every `spacing_m` from 0,
/// plus `length` itself, plus each value in `extra` (e.g. vertex positions), sorted, with values
/// closer than `merge_tolerance_m` merged (the earlier kept, but `extra` values win over grid
/// values). Precondition: spacing_m > 0. A straight 100 m road at 1 m gives 101 values.
[[nodiscard]] std::vector<double> sample_stations(double length, double spacing_m,
                                                  const std::vector<double>& extra,
                                                  double merge_tolerance_m = 1e-6);

/// Removes consecutive vertices closer than `tolerance_m`; returns the indices kept.
[[nodiscard]] std::vector<std::size_t> dedupe_vertices(const Polyline2& line, double tolerance_m);

}  // namespace relief

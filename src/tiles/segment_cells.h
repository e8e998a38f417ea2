#pragma once
// Private to the tiles module: the grid cells a road segment passes through or near, for the
// plan (which tiles a road needs, which windows a long segment crosses without a node in them).

#include <cmath>

#include "relief/geometry/types.h"

namespace relief::detail {

/// Whether the segment a-b meets the closed box (Liang-Barsky clipping).
[[nodiscard]] bool segment_meets_box(const Vec2& a, const Vec2& b, const Aabb2& box);

/// Calls `visit(column, row)` for every cell [column, column + 1) x [row, row + 1) of side
/// `size` (from 0) whose box grown by `margin` the segment a-b meets.
template <typename Visit>
void cells_near_segment(const Vec2& a, const Vec2& b, double size, double margin, Visit&& visit) {
  const auto cell = [&](double v) { return static_cast<long long>(std::floor(v / size)); };
  const long long c0 = cell(std::min(a.x(), b.x()) - margin), c1 = cell(std::max(a.x(), b.x()) + margin);
  const long long r0 = cell(std::min(a.y(), b.y()) - margin), r1 = cell(std::max(a.y(), b.y()) + margin);
  for (long long r = r0; r <= r1; ++r) {
    for (long long c = c0; c <= c1; ++c) {
      const Vec2 lo = size * Vec2(static_cast<double>(c), static_cast<double>(r));
      const Aabb2 box{lo - Vec2::Constant(margin), lo + Vec2::Constant(size + margin)};
      if (segment_meets_box(a, b, box)) visit(c, r);
    }
  }
}

}  // namespace relief::detail

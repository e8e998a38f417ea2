#pragma once
// Plane polygons: the convex hull of a point set.

#include "relief/geometry/types.h"

namespace relief {

/// The convex hull of `points`, counter-clockwise from the lowest-leftmost point, without
/// collinear or repeated points (Andrew's monotone chain, O(n log n)). Fewer than three
/// distinct points give those points; all collinear, the two extremes.
[[nodiscard]] Polyline2 convex_hull(Polyline2 points);

}  // namespace relief

#pragma once
// Plan-view records built in code for the geometry, roads and export tests.

#include "relief/geometry/plan_view.h"

namespace relief::test {

/// A line record from `start` along `heading` (rad), starting at `s`.
[[nodiscard]] PlanGeometry line_record(double s, const Vec2& start, double heading, double length_m);

/// An arc record of constant `curvature` (1/m, positive: to the left).
[[nodiscard]] PlanGeometry arc_record(double s, const Vec2& start, double heading, double length_m,
                                      double curvature);

}  // namespace relief::test

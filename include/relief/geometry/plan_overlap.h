#pragma once
// Triangles that lie under others seen from above: where two pieces of a 2.5-D surface (roads on
// the ground) overlap in plan, e.g. a tunnel's approach running under the street above its portal,
// or two OSM ways closer than their widths. Exact predicates (CGAL); CGAL stays in src/geometry/.

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "relief/geometry/triangle_mesh.h"

namespace relief {

struct PlanOverlaps {
  /// One flag per triangle of the mesh: 1 when its interior overlaps in plan the interior of
  /// another candidate triangle that is higher there (of a pair at the same height, the later).
  std::vector<std::uint8_t> under;
  std::size_t pairs = 0;    ///< pairs of candidate triangles whose interiors overlap in plan
  std::vector<Vec3> sites;  ///< centroids of the first kMaxPlanOverlapSites triangles flagged `under`
  /// Every overlapping pair as (lower, upper) triangle indices.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> lower_upper;
};

inline constexpr std::size_t kMaxPlanOverlapSites = 20;

/// Height above (x, y) of the plane through triangle `t` of `mesh`, extended beyond the
/// triangle; nothing for a triangle vertical or degenerate in plan.
[[nodiscard]] std::optional<double> plane_height(const TriangleMesh& mesh,
                                                 const std::array<std::uint32_t, 3>& t, const Vec2& xy);

/// Pairs of `candidates` (one flag per triangle; all when empty) whose interiors overlap when
/// projected onto the xy plane; touching along an edge or at a vertex is no overlap, and a
/// triangle of zero area in plan overlaps nothing. Of each pair the lower one (heights compared
/// on the two triangles' planes at the midpoint of their centroids) is flagged `under`. Leaving
/// the flagged ones out leaves candidates no two of which overlap in plan. Linear in the
/// triangles plus the overlapping box pairs (CGAL box_intersection_d).
[[nodiscard]] PlanOverlaps plan_overlaps(const TriangleMesh& mesh,
                                         const std::vector<std::uint8_t>& candidates = {});

}  // namespace relief

#pragma once
// Openings in the 2.5-D ground (roads on the ground + terrain) where a road goes on below it:
// into a tunnel, or under another road that lies over it in plan (the approach to a tunnel
// under the street above its portal; a street in a cutting under a bridge's abutment). The
// terrain would otherwise meet the lower road's edge there and close the step up to the upper
// surface with a slope across the lower road's lanes. Instead it meets the opening's top edge:
// the lower road's edge raised by the mouth height into a tunnel, by the cover of the road above
// elsewhere. Each opening is then one boundary loop of the ground, counted apart from holes.

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "relief/geometry/plan_overlap.h"
#include "relief/geometry/triangle_mesh.h"

namespace relief {

struct GroundOpeningOptions {
  double mouth_height_m = 5.0;  ///< top edge of a tunnel's mouth above the road's end edge
  /// Under another road, an opening only where the road above clears the lower one by this
  /// much (a vehicle passes); a smaller step is closed by the terrain as a ramp.
  double min_underpass_clearance_m = 2.0;
};

/// The top edge of every opening, as (road vertex position, the terrain's position above it),
/// sorted by the first (exact positions). Road-mesh vertices on the ground (`ground`, one flag
/// per triangle of `road`) that are shared with a tunnel triangle (`tunnel`) or with a triangle
/// left under another road (`overlaps`, of the same mesh) that joins a tunnel through such
/// triangles are raised by max(mouth height, cover); those shared only with triangles under
/// another road by the cover, the height of the upper triangle's plane above them, when it is
/// at least min_underpass_clearance_m.
[[nodiscard]] std::vector<std::pair<Vec3, Vec3>> opening_tops(const TriangleMesh& road,
                                                              const std::vector<std::uint8_t>& ground,
                                                              const std::vector<std::uint8_t>& tunnel,
                                                              const PlanOverlaps& overlaps,
                                                              const GroundOpeningOptions& options = {});

/// The terrain's position for road vertex `p` (p itself when it is at no opening).
[[nodiscard]] Vec3 opening_top(const std::vector<std::pair<Vec3, Vec3>>& tops, const Vec3& p);

/// Boundary loops of `mesh` through a vertex at one of the tops' raised positions.
[[nodiscard]] std::size_t loops_through_tops(const TriangleMesh& mesh,
                                             const std::vector<std::pair<Vec3, Vec3>>& tops);

}  // namespace relief

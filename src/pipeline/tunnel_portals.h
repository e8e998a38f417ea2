#pragma once
// Tunnel portals in the 2.5-D ground. Where a road on the ground runs into a tunnel, the terrain
// over the tunnel would meet the road's end edge and seal the mouth with a slope a vehicle
// drives into. Instead the terrain takes the mouth's top edge: the end edge raised by the
// portal height. Roads on the ground + terrain then keep one opening per portal (the mouth,
// with the tunnel's road beyond it), counted apart from holes.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "relief/geometry/triangle_mesh.h"

namespace relief {

/// Positions (exact, sorted) of the road-mesh vertices at tunnel mouths: those shared by a
/// triangle on the ground and a tunnel triangle, or a triangle left out of the ground as lying
/// under another road (`under`) that joins a tunnel through such triangles (the approach that
/// runs on under the street over the portal). One flag per triangle of `road` in each vector.
[[nodiscard]] std::vector<Vec3> portal_vertices(const TriangleMesh& road,
                                                const std::vector<std::uint8_t>& ground,
                                                const std::vector<std::uint8_t>& tunnel,
                                                const std::vector<std::uint8_t>& under);

/// Whether `p` is one of `portals` (as returned above).
[[nodiscard]] bool is_portal(const std::vector<Vec3>& portals, const Vec3& p);

/// Boundary loops of `mesh` through a vertex at one of `points` (sorted as above).
[[nodiscard]] std::size_t loops_through(const TriangleMesh& mesh, const std::vector<Vec3>& points);

}  // namespace relief

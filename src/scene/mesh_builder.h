#pragma once
// Private to the roads module: a triangle mesh under construction together with the owner of
// each triangle (road id or -1 - junction id), shared by the lane loft and the junction surfaces.

#include <array>
#include <cstdint>
#include <vector>

#include "relief/geometry/triangle_mesh.h"

namespace relief::detail {

inline constexpr std::uint32_t kNoVertex = ~std::uint32_t{0};

struct MeshBuilder {
  TriangleMesh mesh;
  std::vector<int> owner;  ///< per triangle

  std::uint32_t add_vertex(const Vec3& position, const Vec2& uv) {
    mesh.vertices.push_back(position);
    mesh.uvs.push_back(uv);
    return static_cast<std::uint32_t>(mesh.vertices.size() - 1);
  }

  /// Adds a triangle (counter-clockwise from above) unless two of its indices coincide.
  void add_triangle(std::uint32_t a, std::uint32_t b, std::uint32_t c, int owner_id) {
    if (a == b || b == c || a == c) return;
    mesh.triangles.push_back({a, b, c});
    owner.push_back(owner_id);
  }
};

}  // namespace relief::detail

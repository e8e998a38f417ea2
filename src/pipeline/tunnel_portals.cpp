#include "pipeline/tunnel_portals.h"

#include <algorithm>
#include <tuple>

namespace relief {
namespace {

bool less(const Vec3& a, const Vec3& b) {
  return std::tie(a.x(), a.y(), a.z()) < std::tie(b.x(), b.y(), b.z());
}

}  // namespace

std::vector<Vec3> portal_vertices(const TriangleMesh& road, const std::vector<std::uint8_t>& ground,
                                  const std::vector<std::uint8_t>& tunnel,
                                  const std::vector<std::uint8_t>& under) {
  // Vertices of the tunnels, grown through the triangles under other roads that touch them
  // (few: a fixed point over that short list).
  std::vector<std::uint8_t> inside(road.vertices.size(), 0);
  std::vector<std::size_t> pending;
  for (std::size_t i = 0; i < road.triangles.size(); ++i) {
    if (tunnel[i]) {
      for (const std::uint32_t v : road.triangles[i]) inside[v] = 1;
    } else if (under[i]) {
      pending.push_back(i);
    }
  }
  for (bool grew = true; grew;) {
    grew = false;
    std::erase_if(pending, [&](std::size_t i) {
      const auto& t = road.triangles[i];
      if (!inside[t[0]] && !inside[t[1]] && !inside[t[2]]) return false;
      for (const std::uint32_t v : t) inside[v] = 1;
      grew = true;
      return true;
    });
  }
  std::vector<Vec3> out;
  for (std::size_t i = 0; i < road.triangles.size(); ++i) {
    if (!ground[i]) continue;
    for (const std::uint32_t v : road.triangles[i]) {
      if (inside[v]) out.push_back(road.vertices[v]);
    }
  }
  std::sort(out.begin(), out.end(), less);
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

bool is_portal(const std::vector<Vec3>& portals, const Vec3& p) {
  return std::binary_search(portals.begin(), portals.end(), p, less);
}

std::size_t loops_through(const TriangleMesh& mesh, const std::vector<Vec3>& points) {
  std::size_t n = 0;
  for (const auto& loop : boundary_loops(mesh)) {
    n += std::any_of(loop.begin(), loop.end(),
                     [&](std::uint32_t v) { return is_portal(points, mesh.vertices[v]); })
             ? 1
             : 0;
  }
  return n;
}

}  // namespace relief

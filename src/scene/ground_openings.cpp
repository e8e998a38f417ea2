#include "scene/ground_openings.h"

#include <algorithm>
#include <limits>
#include <optional>
#include <tuple>

namespace relief {
namespace {

bool less(const Vec3& a, const Vec3& b) {
  return std::tie(a.x(), a.y(), a.z()) < std::tie(b.x(), b.y(), b.z());
}

}  // namespace

std::vector<std::pair<Vec3, Vec3>> opening_tops(const TriangleMesh& road,
                                                const std::vector<std::uint8_t>& ground,
                                                const std::vector<std::uint8_t>& tunnel,
                                                const PlanOverlaps& overlaps,
                                                const GroundOpeningOptions& options) {
  // Vertices of the tunnels, grown through the triangles under other roads that touch them
  // (few: a fixed point over that short list).
  std::vector<std::uint8_t> into_tunnel(road.vertices.size(), 0);
  std::vector<std::size_t> pending;
  for (std::size_t i = 0; i < road.triangles.size(); ++i) {
    if (tunnel[i]) {
      for (const std::uint32_t v : road.triangles[i]) into_tunnel[v] = 1;
    } else if (overlaps.under[i]) {
      pending.push_back(i);
    }
  }
  for (bool grew = true; grew;) {
    grew = false;
    std::erase_if(pending, [&](std::size_t i) {
      const auto& t = road.triangles[i];
      if (!into_tunnel[t[0]] && !into_tunnel[t[1]] && !into_tunnel[t[2]]) return false;
      for (const std::uint32_t v : t) into_tunnel[v] = 1;
      grew = true;
      return true;
    });
  }
  // Cover: how far the plane of a road over an under-triangle lies above its vertices.
  constexpr double kNone = -std::numeric_limits<double>::infinity();
  std::vector<double> cover(road.vertices.size(), kNone);
  for (const auto& [lower, upper] : overlaps.lower_upper) {
    for (const std::uint32_t v : road.triangles[lower]) {
      const std::optional<double> z = plane_height(road, road.triangles[upper], road.vertices[v].head<2>());
      if (z) cover[v] = std::max(cover[v], *z - road.vertices[v].z());
    }
  }
  std::vector<std::pair<Vec3, Vec3>> tops;
  for (std::size_t i = 0; i < road.triangles.size(); ++i) {
    if (!ground[i]) continue;
    for (const std::uint32_t v : road.triangles[i]) {
      double raise = 0.0;
      if (into_tunnel[v]) {
        raise = std::max(options.mouth_height_m, cover[v]);
      } else if (cover[v] >= options.min_underpass_clearance_m) {
        raise = cover[v];
      }
      if (raise > 0.0) tops.emplace_back(road.vertices[v], road.vertices[v] + Vec3(0.0, 0.0, raise));
    }
  }
  std::sort(tops.begin(), tops.end(), [](const auto& a, const auto& b) { return less(a.first, b.first); });
  tops.erase(
      std::unique(tops.begin(), tops.end(), [](const auto& a, const auto& b) { return a.first == b.first; }),
      tops.end());
  return tops;
}

Vec3 opening_top(const std::vector<std::pair<Vec3, Vec3>>& tops, const Vec3& p) {
  const auto it =
      std::lower_bound(tops.begin(), tops.end(), p,
                       [](const std::pair<Vec3, Vec3>& t, const Vec3& q) { return less(t.first, q); });
  return it != tops.end() && it->first == p ? it->second : p;
}

std::size_t loops_through_tops(const TriangleMesh& mesh, const std::vector<std::pair<Vec3, Vec3>>& tops) {
  std::vector<Vec3> raised;
  raised.reserve(tops.size());
  for (const auto& t : tops) raised.push_back(t.second);
  std::sort(raised.begin(), raised.end(), less);
  std::size_t n = 0;
  for (const auto& loop : boundary_loops(mesh)) {
    n += std::any_of(loop.begin(), loop.end(),
                     [&](std::uint32_t v) {
                       return std::binary_search(raised.begin(), raised.end(), mesh.vertices[v], less);
                     })
             ? 1
             : 0;
  }
  return n;
}

}  // namespace relief

#pragma once
// Private to the sight module: segments against the triangles of a MeshScene, through Embree
// (Intel's ray-tracing kernels, Debian libembree-dev 3.13): a BVH built once over the chosen
// meshes, then occlusion and first-hit queries, safe from several threads. Vertices go to
// Embree in single precision relative to the scene's centre, so a region 20 km across keeps
// its triangles within 1 mm.

#include <cstddef>
#include <memory>
#include <optional>
#include <vector>

#include "relief/geometry/triangle_mesh.h"
#include "relief/geometry/types.h"

namespace relief::detail {

/// Where a segment first meets a triangle.
struct RayHit {
  double fraction = 0.0;  ///< along the segment, 0 at its start, 1 at its end
  Vec3 point = Vec3::Zero();
  std::size_t mesh = 0;      ///< index into MeshScene::meshes
  std::size_t triangle = 0;  ///< index into that mesh's triangles
  SurfaceKind kind = SurfaceKind::road;
};

class RayScene {
 public:
  /// The triangles of every mesh of `scene` whose kind `use` accepts (e.g. not the markings,
  /// which float millimetres over the road). Keeps no reference to `scene`. Throws
  /// InvalidInput for a non-finite vertex.
  RayScene(const MeshScene& scene, bool (*use)(SurfaceKind));
  ~RayScene();
  RayScene(RayScene&& other) noexcept;
  RayScene& operator=(RayScene&& other) noexcept;
  RayScene(const RayScene&) = delete;
  RayScene& operator=(const RayScene&) = delete;

  /// Whether the open segment from a to b (its two ends left out by 1e-6 of its length) passes
  /// through a triangle.
  [[nodiscard]] bool blocked(const Vec3& a, const Vec3& b) const;
  /// The first triangle the segment from a to b meets, if any.
  [[nodiscard]] std::optional<RayHit> first_hit(const Vec3& a, const Vec3& b) const;
  /// The first triangles `n` rays from one `origin` along unit `dirs` meet within `length`:
  /// hits[i] is its distance along the ray, or infinity; kinds[i] what it met. Cast 16 at a time
  /// (Embree's packets: rays from one point share the traversal).
  void first_hits(const Vec3& origin, const Vec3* dirs, std::size_t n, double length, double* hits,
                  SurfaceKind* kinds) const;
  [[nodiscard]] std::size_t triangles() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace relief::detail

#include "sight/ray_scene.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "relief/core/errors.h"

namespace relief::detail {
namespace {

constexpr float kEndGap = 1e-6F;  // the segment's ends left out (fraction of its length)

}  // namespace

struct RayScene::Impl {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  Vec3 origin = Vec3::Zero();
  struct Geometry {
    std::size_t mesh = 0;
    SurfaceKind kind = SurfaceKind::road;
  };
  std::vector<Geometry> geometries;  // by Embree geometry id
  std::size_t triangles = 0;

  ~Impl() {
    if (scene != nullptr) rtcReleaseScene(scene);
    if (device != nullptr) rtcReleaseDevice(device);
  }

  [[nodiscard]] RTCRay ray(const Vec3& a, const Vec3& b) const {
    RTCRay r{};
    const Vec3 o = a - origin, d = b - a;
    r.org_x = static_cast<float>(o.x());
    r.org_y = static_cast<float>(o.y());
    r.org_z = static_cast<float>(o.z());
    r.dir_x = static_cast<float>(d.x());
    r.dir_y = static_cast<float>(d.y());
    r.dir_z = static_cast<float>(d.z());
    r.tnear = kEndGap;
    r.tfar = 1.0F - kEndGap;
    r.mask = std::numeric_limits<unsigned>::max();
    return r;
  }
};

RayScene::RayScene(const MeshScene& scene, bool (*use)(SurfaceKind)) : impl_(std::make_unique<Impl>()) {
  std::vector<std::size_t> meshes;
  for (std::size_t m = 0; m < scene.meshes.size(); ++m)
    if (!scene.meshes[m].empty() && use(scene.meshes[m].kind)) meshes.push_back(m);
  Impl& s = *impl_;
  // The centre of the vertices' box: Embree's floats then lose at most 1 mm 8 km from it.
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const std::size_t m : meshes)
    for (const Vec3& v : scene.meshes[m].vertices) {
      if (!v.allFinite())
        throw InvalidInput("mesh '" + scene.meshes[m].name + "' has a vertex that is not finite");
      lo = lo.cwiseMin(v);
      hi = hi.cwiseMax(v);
    }
  if (!meshes.empty()) s.origin = 0.5 * (lo + hi);
  s.device = rtcNewDevice(nullptr);
  if (s.device == nullptr) throw std::runtime_error("Embree: could not create a device");
  s.scene = rtcNewScene(s.device);
  // Compact nodes: a city's million triangles in less memory, for a few per cent of speed.
  rtcSetSceneFlags(s.scene, RTC_SCENE_FLAG_COMPACT);
  for (const std::size_t m : meshes) {
    const TriangleMesh& mesh = scene.meshes[m];
    RTCGeometry g = rtcNewGeometry(s.device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vb = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                           3 * sizeof(float), mesh.vertices.size()));
    for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
      const Vec3 v = mesh.vertices[i] - s.origin;
      for (int k = 0; k < 3; ++k) vb[3 * i + static_cast<std::size_t>(k)] = static_cast<float>(v[k]);
    }
    auto* ib = static_cast<unsigned*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                              3 * sizeof(unsigned), mesh.triangles.size()));
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
      for (std::size_t k = 0; k < 3; ++k) ib[3 * t + k] = mesh.triangles[t][k];
    rtcCommitGeometry(g);
    const unsigned id = rtcAttachGeometry(s.scene, g);
    rtcReleaseGeometry(g);
    if (id >= s.geometries.size()) s.geometries.resize(id + 1);
    s.geometries[id] = {m, mesh.kind};
    s.triangles += mesh.triangles.size();
  }
  rtcCommitScene(s.scene);
  if (rtcGetDeviceError(s.device) != RTC_ERROR_NONE)
    throw std::runtime_error("Embree: building the scene of " + std::to_string(s.triangles) +
                             " triangles failed");
}

RayScene::~RayScene() = default;
RayScene::RayScene(RayScene&&) noexcept = default;
RayScene& RayScene::operator=(RayScene&&) noexcept = default;

std::size_t RayScene::triangles() const {
  return impl_->triangles;
}

bool RayScene::blocked(const Vec3& a, const Vec3& b) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay r = impl_->ray(a, b);
  rtcOccluded1(impl_->scene, &context, &r);
  return r.tfar < 0.0F;  // Embree sets tfar to -inf on a hit
}

std::optional<RayHit> RayScene::first_hit(const Vec3& a, const Vec3& b) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rh{};
  rh.ray = impl_->ray(a, b);
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(impl_->scene, &context, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;
  const Impl::Geometry& g = impl_->geometries[rh.hit.geomID];
  RayHit hit;
  hit.fraction = rh.ray.tfar;
  hit.point = a + hit.fraction * (b - a);
  hit.mesh = g.mesh;
  hit.triangle = rh.hit.primID;
  hit.kind = g.kind;
  return hit;
}

void RayScene::first_hits(const Vec3& origin, const Vec3* dirs, std::size_t n, double length, double* hits,
                          SurfaceKind* kinds) const {
  constexpr std::size_t kPacket = 16;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  const Vec3 o = origin - impl_->origin;
  for (std::size_t start = 0; start < n; start += kPacket) {
    alignas(64) RTCRayHit16 rh{};
    alignas(64) int valid[kPacket];
    const std::size_t count = std::min(kPacket, n - start);
    for (std::size_t i = 0; i < kPacket; ++i) {
      valid[i] = i < count ? -1 : 0;
      const Vec3& d = dirs[start + std::min(i, count - 1)];
      rh.ray.org_x[i] = static_cast<float>(o.x());
      rh.ray.org_y[i] = static_cast<float>(o.y());
      rh.ray.org_z[i] = static_cast<float>(o.z());
      rh.ray.dir_x[i] = static_cast<float>(d.x());
      rh.ray.dir_y[i] = static_cast<float>(d.y());
      rh.ray.dir_z[i] = static_cast<float>(d.z());
      rh.ray.tnear[i] = 0.0F;
      rh.ray.tfar[i] = static_cast<float>(length);
      rh.ray.mask[i] = std::numeric_limits<unsigned>::max();
      rh.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
      rh.hit.instID[0][i] = RTC_INVALID_GEOMETRY_ID;
    }
    rtcIntersect16(valid, impl_->scene, &context, &rh);
    for (std::size_t i = 0; i < count; ++i) {
      if (rh.hit.geomID[i] == RTC_INVALID_GEOMETRY_ID) {
        hits[start + i] = std::numeric_limits<double>::infinity();
        continue;
      }
      hits[start + i] = rh.ray.tfar[i];
      kinds[start + i] = impl_->geometries[rh.hit.geomID[i]].kind;
    }
  }
}

}  // namespace relief::detail

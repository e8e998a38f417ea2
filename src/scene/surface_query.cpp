#include "relief/scene/surface_query.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <utility>

#include "relief/core/errors.h"

namespace relief {
namespace {

constexpr double kInsideTolerance = 1e-9;  // barycentric slack: points on edges count as inside
constexpr double kSameHeightM = 1e-3;      // two hits of one mesh this close are one surface
constexpr std::size_t kMaxCells = std::size_t{1} << 24;

bool indexed(const TriangleMesh& mesh, const SurfaceQueryOptions& options) {
  return mesh.kind != SurfaceKind::marking || options.markings;
}

}  // namespace

SurfaceQuery::SurfaceQuery(const MeshScene& scene, const SurfaceQueryOptions& options) : scene_(scene) {
  if (!(options.cell_size_m > 0.0))
    throw InvalidInput("SurfaceQuery: cell_size_m must be > 0, got " + std::to_string(options.cell_size_m));
  for (const TriangleMesh& mesh : scene.meshes) {
    if (!indexed(mesh, options)) continue;
    for (const auto& t : mesh.triangles)
      for (const std::uint32_t v : t) bounds_.extend(Vec2(mesh.vertices[v].x(), mesh.vertices[v].y()));
  }
  if (bounds_.empty()) {
    cell_start_.assign(1, 0);
    return;
  }
  // Cells of the asked size, grown until the grid fits kMaxCells.
  cell_m_ = options.cell_size_m;
  const Vec2 extent = bounds_.max - bounds_.min;
  const auto cells = [&](double m) {
    return std::pair<double, double>(std::floor(extent.x() / m) + 1.0, std::floor(extent.y() / m) + 1.0);
  };
  while (cells(cell_m_).first * cells(cell_m_).second > static_cast<double>(kMaxCells)) cell_m_ *= 2.0;
  nx_ = static_cast<std::size_t>(cells(cell_m_).first);
  ny_ = static_cast<std::size_t>(cells(cell_m_).second);
  const auto cell_x = [&](double x) {
    return std::min(nx_ - 1, static_cast<std::size_t>(std::max(0.0, (x - bounds_.min.x()) / cell_m_)));
  };
  const auto cell_y = [&](double y) {
    return std::min(ny_ - 1, static_cast<std::size_t>(std::max(0.0, (y - bounds_.min.y()) / cell_m_)));
  };
  // Two passes (count, then fill) into one flat array: every triangle in each cell its plan
  // bounding box touches.
  cell_start_.assign(nx_ * ny_ + 1, 0);
  const auto for_each_cell = [&](const TriangleMesh& mesh, const std::array<std::uint32_t, 3>& t, auto&& f) {
    Aabb2 box;
    for (const std::uint32_t v : t) box.extend(Vec2(mesh.vertices[v].x(), mesh.vertices[v].y()));
    for (std::size_t j = cell_y(box.min.y()); j <= cell_y(box.max.y()); ++j)
      for (std::size_t i = cell_x(box.min.x()); i <= cell_x(box.max.x()); ++i) f(j * nx_ + i);
  };
  for (const TriangleMesh& mesh : scene.meshes) {
    if (!indexed(mesh, options)) continue;
    for (const auto& t : mesh.triangles) for_each_cell(mesh, t, [&](std::size_t c) { ++cell_start_[c + 1]; });
  }
  for (std::size_t c = 0; c + 1 < cell_start_.size(); ++c) cell_start_[c + 1] += cell_start_[c];
  entries_.resize(cell_start_.back());
  std::vector<std::uint32_t> fill(cell_start_.begin(), cell_start_.end() - 1);
  for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
    const TriangleMesh& mesh = scene.meshes[m];
    if (!indexed(mesh, options)) continue;
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
      for_each_cell(mesh, mesh.triangles[t], [&](std::size_t c) {
        entries_[fill[c]++] = Entry{static_cast<std::uint32_t>(m), static_cast<std::uint32_t>(t)};
      });
      ++indexed_;
    }
  }
}

// Barycentric coordinates of (x, y) in the triangle's plan; its plane's height there when inside.
std::optional<double> SurfaceQuery::height_in(const Entry& e, double x, double y) const {
  const TriangleMesh& mesh = scene_.meshes[e.mesh];
  const auto& t = mesh.triangles[e.triangle];
  const Vec3& a = mesh.vertices[t[0]];
  const Vec3& b = mesh.vertices[t[1]];
  const Vec3& c = mesh.vertices[t[2]];
  const double area = (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
  if (std::abs(area) < 1e-12) return std::nullopt;  // vertical in plan
  const double wb = ((x - a.x()) * (c.y() - a.y()) - (y - a.y()) * (c.x() - a.x())) / area;
  const double wc = ((b.x() - a.x()) * (y - a.y()) - (b.y() - a.y()) * (x - a.x())) / area;
  const double wa = 1.0 - wb - wc;
  if (wa < -kInsideTolerance || wb < -kInsideTolerance || wc < -kInsideTolerance) return std::nullopt;
  return a.z() + wb * (b.z() - a.z()) + wc * (c.z() - a.z());  // exact where the triangle is level
}

std::vector<SurfaceHit> SurfaceQuery::all(double x, double y) const {
  std::vector<SurfaceHit> hits;
  if (nx_ == 0) return hits;
  // Outside the bounds of every triangle: nothing.
  if (x < bounds_.min.x() || y < bounds_.min.y() || x > bounds_.max.x() || y > bounds_.max.y()) return hits;
  const std::size_t i = std::min(nx_ - 1, static_cast<std::size_t>((x - bounds_.min.x()) / cell_m_));
  const std::size_t j = std::min(ny_ - 1, static_cast<std::size_t>((y - bounds_.min.y()) / cell_m_));
  const std::size_t c = j * nx_ + i;
  for (std::uint32_t k = cell_start_[c]; k < cell_start_[c + 1]; ++k) {
    const Entry& e = entries_[k];
    if (const std::optional<double> z = height_in(e, x, y))
      hits.push_back(SurfaceHit{*z, e.mesh, e.triangle, scene_.meshes[e.mesh].kind});
  }
  // Highest first (ties by mesh and triangle: the order does not depend on the grid); one hit
  // per mesh and height.
  std::sort(hits.begin(), hits.end(), [](const SurfaceHit& a, const SurfaceHit& b) {
    if (a.z_m != b.z_m) return a.z_m > b.z_m;
    return a.mesh != b.mesh ? a.mesh < b.mesh : a.triangle < b.triangle;
  });
  std::vector<SurfaceHit> kept;
  for (const SurfaceHit& h : hits) {
    const bool seen = std::any_of(kept.begin(), kept.end(), [&](const SurfaceHit& k) {
      return k.mesh == h.mesh && std::abs(k.z_m - h.z_m) <= kSameHeightM;
    });
    if (!seen) kept.push_back(h);
  }
  return kept;
}

std::optional<SurfaceHit> SurfaceQuery::highest(double x, double y) const {
  const std::vector<SurfaceHit> hits = all(x, y);
  if (hits.empty()) return std::nullopt;
  return hits.front();
}

std::optional<SurfaceHit> SurfaceQuery::nearest(double x, double y, double z_m) const {
  const std::vector<SurfaceHit> hits = all(x, y);  // highest first: the first of equal distance is the higher
  std::optional<SurfaceHit> best;
  for (const SurfaceHit& h : hits) {
    if (!best || std::abs(h.z_m - z_m) < std::abs(best->z_m - z_m)) best = h;
  }
  return best;
}

}  // namespace relief

// Greedy insertion of DEM samples into the terrain TIN, and the final check of every sample.

#include "terrain/tin_refinement.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <queue>

namespace relief::terrain_detail {
namespace {

// Finite face containing p (either one for a point on an edge), or null when p is a vertex or
// outside the triangulation. `hint`: a face near p (null: none).
FaceHandle locate(const Tin& tin, const Point& p, FaceHandle hint) {
  Tin::Locate_type type{};
  int li = 0;
  FaceHandle f = tin.locate(p, type, li, hint);
  if (type == Tin::VERTEX || type == Tin::OUTSIDE_CONVEX_HULL || type == Tin::OUTSIDE_AFFINE_HULL) return {};
  if (tin.is_infinite(f)) f = f->neighbor(li);  // on a hull edge
  return tin.is_infinite(f) ? FaceHandle() : f;
}

// The plane of a finite face as z = z0 + gx (x - x0) + gy (y - y0).
struct FacePlane {
  double x0, y0, z0, gx, gy;

  explicit FacePlane(const FaceHandle& f) {
    const Point& a = f->vertex(0)->point();
    const Point& b = f->vertex(1)->point();
    const Point& c = f->vertex(2)->point();
    const double bx = b.x() - a.x(), by = b.y() - a.y(), bz = b.z() - a.z();
    const double cx = c.x() - a.x(), cy = c.y() - a.y(), cz = c.z() - a.z();
    const double det = bx * cy - cx * by;
    x0 = a.x();
    y0 = a.y();
    z0 = a.z();
    gx = (bz * cy - cz * by) / det;
    gy = (cz * bx - bz * cx) / det;
  }
  [[nodiscard]] double at(const Vec2& p) const { return z0 + gx * (p.x() - x0) + gy * (p.y() - y0); }
};

bool may_be_vertex(const GridSamples& grid, std::size_t k) {
  return grid.has(k, kValid) && !grid.has(k, kPaved) && !grid.has(k, kNear) && !grid.has(k, kInserted);
}

}  // namespace

std::size_t insert_greedy(Tin& tin, GridSamples& grid, double tolerance_m) {
  // A heap entry is current while stamp[point] has not moved on: the stamp changes whenever
  // the face that proposed the point is destroyed or re-evaluated.
  struct Entry {
    double error;
    std::uint32_t point;
    std::uint32_t stamp;
    FaceHandle face;
  };
  // Ties of error (common on a quantised DEM) go to the lower sample index: the order must not
  // depend on where the faces lie in memory, or the TIN differs from run to run.
  const auto lower = [](const Entry& a, const Entry& b) {
    return a.error < b.error || (a.error == b.error && a.point > b.point);
  };
  std::priority_queue<Entry, std::vector<Entry>, decltype(lower)> heap(lower);
  std::vector<std::uint32_t> stamp(grid.size(), 0);

  const auto evaluate = [&](const FaceHandle& f) {
    FaceData& d = f->info();
    if (d.best != kNoIndex) ++stamp[d.best];
    d.best = kNoIndex;
    if (d.points.empty()) return;
    const FacePlane plane(f);
    double worst = tolerance_m;
    for (const std::uint32_t k : d.points) {
      const double e = std::abs(grid.z_target[k] - plane.at(grid.xy(k)));
      if (e > worst) {
        worst = e;
        d.best = k;
      }
    }
    if (d.best == kNoIndex) return;
    d.best_error = worst;
    heap.push({worst, d.best, ++stamp[d.best], f});
  };

  // Every candidate into the face containing it (row order keeps the walks short).
  FaceHandle hint;
  for (std::size_t k = 0; k < grid.size(); ++k) {
    if (!may_be_vertex(grid, k) || grid.has(k, kBoundary)) continue;
    const FaceHandle f = locate(tin, grid.point(k), hint);
    if (f == FaceHandle()) continue;
    hint = f;
    f->info().points.push_back(static_cast<std::uint32_t>(k));
  }
  for (auto f = tin.finite_faces_begin(); f != tin.finite_faces_end(); ++f) evaluate(f);

  std::size_t inserted = 0;
  std::vector<FaceHandle> zone;
  std::vector<Tin::Edge> boundary;
  std::vector<std::uint32_t> pending;
  std::vector<FaceHandle> touched;
  struct Cone {  // the new face (v, a, b), counter-clockwise
    FaceHandle face;
    Point a;
    Point b;
  };
  std::vector<Cone> star;
  while (!heap.empty()) {
    const Entry top = heap.top();
    heap.pop();
    if (stamp[top.point] != top.stamp) continue;
    const Point p = grid.point(top.point);

    // The conflict zone (bounded by constrained edges) is emptied and starred from p.
    zone.clear();
    boundary.clear();
    tin.get_conflicts_and_boundary(p, std::back_inserter(zone), std::back_inserter(boundary), top.face);
    if (zone.empty()) {  // p is already a vertex: drop it
      auto& points = top.face->info().points;
      points.erase(std::remove(points.begin(), points.end(), top.point), points.end());
      evaluate(top.face);
      continue;
    }
    pending.clear();
    for (const FaceHandle& f : zone) {
      FaceData& d = f->info();
      if (d.best != kNoIndex) ++stamp[d.best];
      d.best = kNoIndex;
      for (const std::uint32_t k : d.points) {
        if (k != top.point) pending.push_back(k);
      }
      std::vector<std::uint32_t>().swap(d.points);  // star_hole reuses these faces
    }
    const VertexHandle v = tin.star_hole(p, boundary.begin(), boundary.end(), zone.begin(), zone.end());
    v->info().grid = top.point;
    grid.flags[top.point] |= kInserted;
    ++inserted;

    // The zone's points go to the new faces around v (found by the cone of v they lie in,
    // CGAL's walk where rounding leaves a point in none); those faces are re-evaluated.
    star.clear();
    bool finite_star = true;
    auto around = tin.incident_faces(v);
    const auto first_face = around;
    do {
      const int i = around->index(v);
      finite_star = finite_star && !tin.is_infinite(around);
      star.push_back(
          {FaceHandle(around), around->vertex(Tin::ccw(i))->point(), around->vertex(Tin::cw(i))->point()});
    } while (++around != first_face);
    touched.clear();
    std::size_t last = 0;
    FaceHandle near = v->face();
    for (const std::uint32_t k : pending) {
      const Vec2 q = grid.xy(k);
      FaceHandle f;
      for (std::size_t n = 0; finite_star && n < star.size() && f == FaceHandle(); ++n) {
        const Cone& c = star[(last + n) % star.size()];
        const double ax = c.a.x() - p.x(), ay = c.a.y() - p.y();
        const double bx = c.b.x() - p.x(), by = c.b.y() - p.y();
        const double qx = q.x() - p.x(), qy = q.y() - p.y();
        if (ax * qy - ay * qx >= 0.0 && qx * by - qy * bx >= 0.0) {
          f = c.face;
          last = (last + n) % star.size();
        }
      }
      if (f == FaceHandle()) f = locate(tin, grid.point(k), near);
      if (f == FaceHandle()) continue;
      near = f;
      f->info().points.push_back(k);
      if (touched.empty() || touched.back() != f) touched.push_back(f);
    }
    std::sort(touched.begin(), touched.end());
    touched.erase(std::unique(touched.begin(), touched.end()), touched.end());
    for (const FaceHandle& f : touched) evaluate(f);
  }
  for (auto f = tin.finite_faces_begin(); f != tin.finite_faces_end(); ++f) {
    std::vector<std::uint32_t>().swap(f->info().points);
    f->info().best = kNoIndex;
  }
  return inserted;
}

RepairResult repair_and_measure(Tin& tin, GridSamples& grid, double tolerance_m) {
  constexpr int kMaxPasses = 64;
  RepairResult result;
  std::vector<FaceHandle> worst_faces;
  std::vector<std::uint32_t> insert;
  for (int pass = 0;; ++pass) {
    result.max_error_m = 0.0;
    result.max_error_outside_band_m = 0.0;
    worst_faces.clear();
    FaceHandle hint;
    for (std::size_t k = 0; k < grid.size(); ++k) {
      if (!grid.has(k, kValid) || grid.has(k, kPaved) || grid.has(k, kInserted)) continue;
      const FaceHandle f = locate(tin, grid.point(k), hint);
      if (f == FaceHandle()) continue;
      hint = f;
      const Vec2 xy = grid.xy(k);
      const double z = interpolate(f, xy.x(), xy.y());
      if (!grid.has(k, kBand)) {
        result.max_error_outside_band_m =
            std::max(result.max_error_outside_band_m, std::abs(grid.z_dem[k] - z));
      }
      if (grid.has(k, kNear)) continue;
      const double e = std::abs(grid.z_target[k] - z);
      result.max_error_m = std::max(result.max_error_m, e);
      FaceData& d = f->info();
      if (e <= tolerance_m) continue;
      if (d.best == kNoIndex) {
        worst_faces.push_back(f);
      } else if (e <= d.best_error) {
        continue;
      }
      d.best = static_cast<std::uint32_t>(k);
      d.best_error = e;
    }
    if (worst_faces.empty() || pass == kMaxPasses) return result;
    // Insert after the scan: insertions destroy faces of the list.
    insert.clear();
    for (const FaceHandle& f : worst_faces) {
      insert.push_back(f->info().best);
      f->info().best = kNoIndex;
    }
    for (const std::uint32_t k : insert) {
      const VertexHandle v = tin.insert(grid.point(k));
      v->info().grid = k;
      grid.flags[k] |= kInserted;
      ++result.inserted;
    }
  }
}

}  // namespace relief::terrain_detail

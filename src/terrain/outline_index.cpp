#include "terrain/outline_index.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace relief::terrain_detail {
namespace {

// Point of segment ab (in the plane) nearest to p, as a parameter in [0, 1].
double nearest_parameter(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double len2 = ab.squaredNorm();
  if (len2 <= 0.0) return 0.0;
  return std::clamp((p - a).dot(ab) / len2, 0.0, 1.0);
}

}  // namespace

OutlineIndex::OutlineIndex(const std::vector<Polyline3>& loops, double radius_m) : radius_m_(radius_m) {
  Aabb2 box;
  for (const Polyline3& loop : loops) {
    for (std::size_t i = 0; i < loop.size(); ++i) {
      segments_.push_back({loop[i], loop[(i + 1) % loop.size()]});
      box.extend(Vec2(loop[i].x(), loop[i].y()));
    }
  }
  if (segments_.empty()) return;
  box = box.inflated(radius_m_ + 1e-6);
  const Vec2 size = box.max - box.min;
  const double area = std::max(size.x() * size.y(), 1e-6);
  // Cells: about one segment each, at least a quarter of the search radius, at most ~4M cells.
  cell_m_ = std::max({radius_m_ / 4.0, std::sqrt(area / static_cast<double>(segments_.size())),
                      std::sqrt(area / 4.0e6), 1e-3});
  origin_ = box.min;
  nx_ = static_cast<long>(std::floor(size.x() / cell_m_)) + 1;
  ny_ = static_cast<long>(std::floor(size.y() / cell_m_)) + 1;

  // Cells whose centre is within half a cell diagonal of the segment (a superset of the cells
  // it crosses), counted then filled (compressed rows).
  const double reach = cell_m_ * std::sqrt(0.5) + 1e-9;
  const auto for_each_cell = [&](const Segment& s, const auto& visit) {
    const Vec2 a(s.a.x(), s.a.y());
    const Vec2 b(s.b.x(), s.b.y());
    const long x0 = std::clamp(
        static_cast<long>(std::floor((std::min(a.x(), b.x()) - origin_.x()) / cell_m_)), 0L, nx_ - 1);
    const long x1 = std::clamp(
        static_cast<long>(std::floor((std::max(a.x(), b.x()) - origin_.x()) / cell_m_)), 0L, nx_ - 1);
    const long y0 = std::clamp(
        static_cast<long>(std::floor((std::min(a.y(), b.y()) - origin_.y()) / cell_m_)), 0L, ny_ - 1);
    const long y1 = std::clamp(
        static_cast<long>(std::floor((std::max(a.y(), b.y()) - origin_.y()) / cell_m_)), 0L, ny_ - 1);
    for (long cy = y0; cy <= y1; ++cy) {
      for (long cx = x0; cx <= x1; ++cx) {
        const Vec2 centre =
            origin_ + cell_m_ * Vec2(static_cast<double>(cx) + 0.5, static_cast<double>(cy) + 0.5);
        const double t = nearest_parameter(centre, a, b);
        if ((a + t * (b - a) - centre).norm() <= reach) visit(cell_index(cx, cy));
      }
    }
  };
  cell_start_.assign(static_cast<std::size_t>(nx_ * ny_) + 1, 0);
  for (const Segment& s : segments_)
    for_each_cell(s, [&](long c) { ++cell_start_[static_cast<std::size_t>(c) + 1]; });
  for (std::size_t c = 1; c < cell_start_.size(); ++c) cell_start_[c] += cell_start_[c - 1];
  cell_segments_.resize(cell_start_.back());
  std::vector<std::uint32_t> fill(cell_start_.begin(), cell_start_.end() - 1);
  for (std::size_t i = 0; i < segments_.size(); ++i) {
    for_each_cell(segments_[i], [&](long c) {
      cell_segments_[fill[static_cast<std::size_t>(c)]++] = static_cast<std::uint32_t>(i);
    });
  }
}

std::optional<OutlineHit> OutlineIndex::nearest(const Vec2& p) const {
  if (segments_.empty()) return std::nullopt;
  const double fx = std::floor((p.x() - origin_.x()) / cell_m_);
  const double fy = std::floor((p.y() - origin_.y()) / cell_m_);
  // Outside the grid (which already holds the search radius around every segment): nothing.
  if (!(fx >= 0.0 && fy >= 0.0 && fx < static_cast<double>(nx_) && fy < static_cast<double>(ny_))) {
    return std::nullopt;
  }
  const auto cx = static_cast<long>(fx);
  const auto cy = static_cast<long>(fy);
  const long rings = static_cast<long>(std::ceil(radius_m_ / cell_m_)) + 1;

  double best = std::numeric_limits<double>::infinity();
  double best_z = 0.0;
  const auto visit = [&](long x, long y) {
    if (x < 0 || y < 0 || x >= nx_ || y >= ny_) return;
    const auto c = static_cast<std::size_t>(cell_index(x, y));
    for (std::uint32_t k = cell_start_[c]; k < cell_start_[c + 1]; ++k) {
      const Segment& s = segments_[cell_segments_[k]];
      const Vec2 a(s.a.x(), s.a.y());
      const Vec2 b(s.b.x(), s.b.y());
      const double t = nearest_parameter(p, a, b);
      const double d = (a + t * (b - a) - p).norm();
      if (d < best) {
        best = d;
        best_z = s.a.z() + t * (s.b.z() - s.a.z());
      }
    }
  };
  // Ring r holds cells at Chebyshev distance r; none of them is closer than (r - 1) cells.
  for (long r = 0; r <= rings; ++r) {
    if (r >= 1 && static_cast<double>(r - 1) * cell_m_ > std::min(best, radius_m_)) break;
    if (r == 0) {
      visit(cx, cy);
      continue;
    }
    for (long d = -r; d <= r; ++d) {
      visit(cx + d, cy - r);
      visit(cx + d, cy + r);
    }
    for (long d = -r + 1; d <= r - 1; ++d) {
      visit(cx - r, cy + d);
      visit(cx + r, cy + d);
    }
  }
  if (best > radius_m_) return std::nullopt;
  return OutlineHit{best, best_z};
}

}  // namespace relief::terrain_detail

#include "relief/geometry/polygon.h"

#include <algorithm>

namespace relief {
namespace {

double turn(const Vec2& o, const Vec2& a, const Vec2& b) {
  return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
}

}  // namespace

Polyline2 convex_hull(Polyline2 points) {
  const auto lower_left = [](const Vec2& a, const Vec2& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  };
  std::sort(points.begin(), points.end(), lower_left);
  points.erase(std::unique(points.begin(), points.end()), points.end());
  if (points.size() < 3) return points;
  Polyline2 hull(2 * points.size());
  std::size_t k = 0;
  for (const Vec2& p : points) {  // lower chain
    while (k >= 2 && turn(hull[k - 2], hull[k - 1], p) <= 0.0) --k;
    hull[k++] = p;
  }
  const std::size_t lower = k + 1;
  for (auto it = points.rbegin() + 1; it != points.rend(); ++it) {  // upper chain
    while (k >= lower && turn(hull[k - 2], hull[k - 1], *it) <= 0.0) --k;
    hull[k++] = *it;
  }
  hull.resize(k - 1);  // the last point is the first
  return hull;
}

}  // namespace relief

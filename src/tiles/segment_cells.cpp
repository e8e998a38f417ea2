#include "tiles/segment_cells.h"

namespace relief::detail {

bool segment_meets_box(const Vec2& a, const Vec2& b, const Aabb2& box) {
  double t0 = 0.0, t1 = 1.0;
  const Vec2 d = b - a;
  for (int axis = 0; axis < 2; ++axis) {
    const double lo = box.min[axis] - a[axis], hi = box.max[axis] - a[axis];
    if (d[axis] == 0.0) {
      if (lo > 0.0 || hi < 0.0) return false;
      continue;
    }
    double ta = lo / d[axis], tb = hi / d[axis];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
    if (t0 > t1) return false;
  }
  return true;
}

}  // namespace relief::detail

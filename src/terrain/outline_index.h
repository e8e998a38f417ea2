#pragma once
// Nearest road-edge queries for the terrain builder: the segments of the outline loops hashed
// into a uniform grid of cells, searched ring by ring outwards from the query point, so that a
// query costs the segments near it, not all of them.

#include <cstdint>
#include <optional>
#include <vector>

#include "relief/geometry/types.h"

namespace relief::terrain_detail {

/// The outline point nearest to a query, with its distance and interpolated height.
struct OutlineHit {
  double distance_m = 0.0;  ///< horizontal distance from the query point
  double z = 0.0;           ///< height of the outline at the nearest point (linear along the edge)
};

class OutlineIndex {
 public:
  /// `loops`: closed loops (first point not repeated). Queries look no farther than `radius_m`.
  OutlineIndex(const std::vector<Polyline3>& loops, double radius_m);

  /// Nearest outline point within the radius, nullopt when there is none.
  [[nodiscard]] std::optional<OutlineHit> nearest(const Vec2& p) const;

 private:
  struct Segment {
    Vec3 a;
    Vec3 b;
  };
  [[nodiscard]] long cell_index(long cx, long cy) const { return cy * nx_ + cx; }

  std::vector<Segment> segments_;
  double radius_m_ = 0.0;
  double cell_m_ = 1.0;
  Vec2 origin_ = Vec2::Zero();
  long nx_ = 0;
  long ny_ = 0;
  std::vector<std::uint32_t> cell_start_;  ///< CSR: segments of cell c are [start[c], start[c+1])
  std::vector<std::uint32_t> cell_segments_;
};

}  // namespace relief::terrain_detail

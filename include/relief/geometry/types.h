#pragma once
// The shared geometry vocabulary: Eigen vectors in double precision, polylines, boxes.
// World coordinates are metres in a local frame (see geo_frame.h), never floats.

#include <Eigen/Core>
#include <limits>
#include <vector>

namespace relief {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;

/// An open polyline in the plane (metres, local frame).
using Polyline2 = std::vector<Vec2>;
/// An open polyline in space (metres, local frame, z up).
using Polyline3 = std::vector<Vec3>;

/// Axis-aligned box in the plane. Empty until a point is added.
struct Aabb2 {
  Vec2 min{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  Vec2 max{-std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};

  [[nodiscard]] bool empty() const { return min.x() > max.x() || min.y() > max.y(); }
  void extend(const Vec2& p) {
    min = min.cwiseMin(p);
    max = max.cwiseMax(p);
  }
  void extend(const Aabb2& b) {
    if (b.empty()) return;
    extend(b.min);
    extend(b.max);
  }
  [[nodiscard]] bool contains(const Vec2& p) const {
    return p.x() >= min.x() && p.x() <= max.x() && p.y() >= min.y() && p.y() <= max.y();
  }
  [[nodiscard]] Aabb2 inflated(double margin) const {
    Aabb2 b = *this;
    b.min.array() -= margin;
    b.max.array() += margin;
    return b;
  }
  [[nodiscard]] Vec2 centre() const { return 0.5 * (min + max); }
};

/// Geographic position in degrees (WGS84 unless stated otherwise).
struct LonLat {
  double lon_deg = 0.0;
  double lat_deg = 0.0;
};

/// Geographic box in degrees.
struct LonLatBox {
  double min_lon = 0.0;
  double min_lat = 0.0;
  double max_lon = 0.0;
  double max_lat = 0.0;

  [[nodiscard]] bool contains(const LonLat& p) const {
    return p.lon_deg >= min_lon && p.lon_deg <= max_lon && p.lat_deg >= min_lat && p.lat_deg <= max_lat;
  }
  [[nodiscard]] LonLat centre() const { return {0.5 * (min_lon + max_lon), 0.5 * (min_lat + max_lat)}; }
};

}  // namespace relief

#pragma once
// The OpenDRIVE surface under a point of a SUMO lane: for a net that relief wrote from a
// RoadModel (its lanes carry odr.road / odr.lane params, internal lanes map through their
// connections), the road a lane belongs to and the height S(road, s, t) of that road's surface
// at a plan point, with its slope along a heading. What the co-simulation measures every
// vehicle against, and the same mapping the net's own checks use (sumo_checks.h).

#include <cmath>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "relief/geometry/types.h"
#include "relief/roads/road_model.h"

namespace relief {

/// The surface of one road at one plan point.
struct LaneSurfacePoint {
  int odr_road = -1;  ///< OpenDRIVE road id
  double s = 0.0;     ///< station on that road
  double t = 0.0;     ///< offset from its reference line (left positive)
  double z_m = 0.0;   ///< S(road, s, t).z
  /// How far p lies past the road's start (< 0) or end (> 0) along its reference line, 0 when
  /// it projects onto the road: then s is clamped to the end and z is the end's, not p's.
  double beyond_m = 0.0;
  /// How far p lies outside the road's outermost lane borders across it (0 between them): the
  /// surface there is the road's roll carried past its edge, not the road's.
  double outside_m = 0.0;
  [[nodiscard]] bool on_road(double tolerance_m = 0.01) const { return std::abs(beyond_m) <= tolerance_m; }
};

class SumoSurface {
 public:
  /// Reads `net_file` (a .net.xml). Keeps a reference to `model`, which must outlive this
  /// object. Throws IoError when the file cannot be read, InvalidInput when it is not a SUMO
  /// network.
  SumoSurface(const std::filesystem::path& net_file, const RoadModel& model);
  ~SumoSurface();
  SumoSurface(SumoSurface&& other) noexcept;
  SumoSurface& operator=(SumoSurface&& other) noexcept;

  /// Where plan point p of SUMO lane `lane_id` lies on the lane's OpenDRIVE road, and the
  /// surface height there; nullopt for a lane without a road in the model. Not thread-safe
  /// (road projectors are made on first use). `near`: the answer for a point a few metres from
  /// p, whose station starts the projection on the same road (sparing the search along it).
  [[nodiscard]] std::optional<LaneSurfacePoint> at(const std::string& lane_id, const Vec2& p,
                                                   const LaneSurfacePoint* near = nullptr);

  /// Slope dz/dl of that surface along `heading` (radians, counter-clockwise from +x) at p:
  /// central difference over +-half_step_m on the same road; nullopt as for at(), and when
  /// either end of the difference lies past the road.
  [[nodiscard]] std::optional<double> slope(const std::string& lane_id, const Vec2& p, double heading,
                                            double half_step_m = 0.5, const LaneSurfacePoint* near = nullptr);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace relief

#pragma once
// The local metric frame every relief output is expressed in: a metric CRS (UTM by default)
// plus an origin subtracted from its coordinates so that world coordinates stay small.
// local = crs_xy - origin. Every output records crs() and origin() so that any point can be
// mapped back to lon/lat.

#include <string>

#include "relief/geometry/types.h"

namespace relief {

class GeoFrame {
 public:
  GeoFrame() = default;
  /// `crs` must be a metric projected CRS PROJ knows ("EPSG:32610"); origin in its metres.
  GeoFrame(std::string crs, Vec2 origin) : crs_(std::move(crs)), origin_(std::move(origin)) {}

  /// The WGS84 UTM zone of `centre`, origin at the centre rounded to whole metres.
  [[nodiscard]] static GeoFrame utm_at(const LonLat& centre);
  /// Frame in the given CRS, origin at `centre` projected and rounded to whole metres.
  [[nodiscard]] static GeoFrame in_crs(std::string crs, const LonLat& centre);

  [[nodiscard]] const std::string& crs() const { return crs_; }
  [[nodiscard]] const Vec2& origin() const { return origin_; }

  /// PROJ string of the frame's CRS with the origin folded into false easting/northing where
  /// the CRS allows, so that local coordinates map straight to lon/lat (OpenDRIVE geoReference).
  [[nodiscard]] std::string proj_string() const;

  [[nodiscard]] Vec2 to_local(const Vec2& crs_xy) const { return crs_xy - origin_; }
  [[nodiscard]] Vec2 to_crs(const Vec2& local) const { return local + origin_; }

 private:
  std::string crs_ = "EPSG:32610";
  Vec2 origin_ = Vec2::Zero();
};

/// EPSG code of the WGS84 UTM zone containing `p` (326zz north, 327zz south).
[[nodiscard]] int utm_epsg_for(const LonLat& p);

}  // namespace relief

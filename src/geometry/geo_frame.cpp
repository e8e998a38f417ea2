#include "relief/geometry/geo_frame.h"

#include <algorithm>
#include <cmath>
#include <regex>
#include <sstream>

#include "relief/core/errors.h"
#include "relief/geometry/crs_transform.h"

namespace relief {

int utm_epsg_for(const LonLat& p) {
  int zone = static_cast<int>(std::floor((p.lon_deg + 180.0) / 6.0)) + 1;
  zone = std::clamp(zone, 1, 60);
  return (p.lat_deg >= 0.0 ? 32600 : 32700) + zone;
}

GeoFrame GeoFrame::utm_at(const LonLat& centre) {
  return in_crs("EPSG:" + std::to_string(utm_epsg_for(centre)), centre);
}

GeoFrame GeoFrame::in_crs(std::string crs, const LonLat& centre) {
  const CrsTransform to_crs("EPSG:4326", crs);
  const Vec2 c = to_crs.apply(Vec2(centre.lon_deg, centre.lat_deg));
  return GeoFrame(std::move(crs), Vec2(std::round(c.x()), std::round(c.y())));
}

std::string GeoFrame::proj_string() const {
  std::string text = crs_proj_string(crs_);
  // PROJ's utm fixes its own false easting, so UTM is written as the transverse Mercator it is
  // (datum and units kept) and the origin folded into its x_0 / y_0.
  std::smatch m;
  const std::regex utm(R"(\+proj=utm \+zone=(\d+)( \+south)?)");
  if (std::regex_search(text, m, utm)) {
    const int zone = std::stoi(m[1]);
    const bool south = m[2].matched;
    std::ostringstream tmerc;
    tmerc << "+proj=tmerc +lat_0=0 +lon_0=" << (zone * 6 - 183) << " +k=0.9996 +x_0=500000 +y_0="
          << (south ? 10000000 : 0);
    text = m.prefix().str() + tmerc.str() + m.suffix().str();
  }
  // Shift the false easting / northing by the origin.
  const auto shift = [&](const std::string& key, double delta) {
    const std::regex param(" \\+" + key + "=([-0-9.eE+]+)");
    std::smatch pm;
    std::ostringstream value;
    value.precision(17);
    if (std::regex_search(text, pm, param)) {
      value << (std::stod(pm[1]) - delta);
      text = pm.prefix().str() + " +" + key + "=" + value.str() + pm.suffix().str();
    } else {
      value << -delta;
      text += " +" + key + "=" + value.str();
    }
  };
  shift("x_0", origin_.x());
  shift("y_0", origin_.y());
  return text;
}

}  // namespace relief

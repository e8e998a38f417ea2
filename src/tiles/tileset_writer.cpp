#include "tiles/tileset_writer.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "relief/geometry/crs_transform.h"

namespace relief::detail {
namespace {

// WGS84 geodetic (degrees, metres) to Earth-centred Earth-fixed (EPSG:4978).
Vec3 ecef(double lon_deg, double lat_deg, double h) {
  constexpr double a = 6378137.0;
  constexpr double f = 1.0 / 298.257223563;
  constexpr double e2 = f * (2.0 - f);
  const double lon = lon_deg * M_PI / 180.0, lat = lat_deg * M_PI / 180.0;
  const double n = a / std::sqrt(1.0 - e2 * std::sin(lat) * std::sin(lat));
  return {(n + h) * std::cos(lat) * std::cos(lon), (n + h) * std::cos(lat) * std::sin(lon),
          (n * (1.0 - e2) + h) * std::sin(lat)};
}

// Column-major 4 x 4 matrix taking local frame metres (x, y, z up) to ECEF: the frame's axes at
// its origin, measured through the projection (so the grid's convergence is in it).
std::vector<double> frame_to_ecef(const GeoFrame& frame) {
  const CrsTransform to_wgs84(frame.crs(), "EPSG:4326");
  const auto at = [&](const Vec2& local) {
    const Vec2 ll = to_wgs84.apply(frame.to_crs(local));
    return ecef(ll.x(), ll.y(), 0.0);
  };
  constexpr double kStep = 100.0;
  const Vec3 o = at(Vec2::Zero());
  const Vec3 ex = (at(Vec2(kStep, 0.0)) - o).normalized();
  Vec3 ey = at(Vec2(0.0, kStep)) - o;
  ey = (ey - ey.dot(ex) * ex).normalized();
  const Vec3 ez = ex.cross(ey);
  return {ex.x(), ex.y(), ex.z(), 0.0, ey.x(), ey.y(), ey.z(), 0.0,
          ez.x(), ez.y(), ez.z(), 0.0, o.x(),  o.y(),  o.z(),  1.0};
}

nlohmann::json box(const Vec3& min, const Vec3& max) {
  const Vec3 c = 0.5 * (min + max);
  // 1 mm more each way: the glb's float vertices round within 0.1 mm at 4 km from the origin.
  const Vec3 h = (0.5 * (max - min)).array() + 0.001;
  return {{"box", {c.x(), c.y(), c.z(), h.x(), 0.0, 0.0, 0.0, h.y(), 0.0, 0.0, 0.0, h.z()}}};
}

}  // namespace

std::string tileset_json(const GeoFrame& frame, const std::vector<TilesetTile>& tiles) {
  Vec3 min = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 max = -min;
  double children_error = 0.0;
  nlohmann::json children = nlohmann::json::array();
  for (const TilesetTile& t : tiles) {
    nlohmann::json full = {
        {"boundingVolume", box(t.min, t.max)}, {"geometricError", 0.0}, {"content", {{"uri", t.uri}}}};
    Vec3 tmin = t.min, tmax = t.max;
    if (!t.coarse_uri.empty()) {
      tmin = tmin.cwiseMin(t.coarse_min);
      tmax = tmax.cwiseMax(t.coarse_max);
      children_error = std::max(children_error, t.coarse_error_m);
      full = {{"boundingVolume", box(tmin, tmax)},
              {"geometricError", t.coarse_error_m},
              {"refine", "REPLACE"},
              {"content", {{"uri", t.coarse_uri}}},
              {"children", nlohmann::json::array({full})}};
    }
    min = min.cwiseMin(tmin);
    max = max.cwiseMax(tmax);
    children.push_back(full);
  }
  if (tiles.empty()) min = max = Vec3::Zero();
  const double error = std::max((max - min).norm(), children_error);
  nlohmann::json root = {{"boundingVolume", box(min, max)},
                         {"geometricError", error},
                         {"refine", "ADD"},
                         {"transform", frame_to_ecef(frame)},
                         {"children", children}};
  const nlohmann::json j = {
      {"asset", {{"version", "1.1"}, {"generator", "relief"}}}, {"geometricError", error}, {"root", root}};
  return j.dump(1) + "\n";
}

}  // namespace relief::detail

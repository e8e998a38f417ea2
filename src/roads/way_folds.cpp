#include "roads/way_folds.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <optional>
#include <sstream>
#include <utility>
#include <vector>

#include "relief/core/diagnostic_codes.h"
#include "relief/geometry/plane.h"
#include "relief/geometry/types.h"

namespace relief::detail {
namespace {

constexpr double kEarthRadius_m = 6371008.8;
constexpr double kMinLeg_m = 0.01;  // legs shorter than this have no direction to fold

struct Fold {
  bool near_is_z = false;  // the shorter leg is Y-Z (else X-Y)
  double turn_deg = 0.0;
  double shorter_m = 0.0;
  double offset_m = 0.0;  // the shorter leg's far end from the longer leg
};

// Whether the way folds at y between x and z (WGS84), for a road `half_width` wide each side.
std::optional<Fold> fold_at(const LonLat& x, const LonLat& y, const LonLat& z, double half_width) {
  const double ky = kEarthRadius_m * std::numbers::pi / 180.0;
  const double kx = ky * std::cos(y.lat_deg * std::numbers::pi / 180.0);
  const Vec2 u(kx * (x.lon_deg - y.lon_deg), ky * (x.lat_deg - y.lat_deg));
  const Vec2 v(kx * (z.lon_deg - y.lon_deg), ky * (z.lat_deg - y.lat_deg));
  const double lu = u.norm(), lv = v.norm();
  if (lu < kMinLeg_m || lv < kMinLeg_m) return std::nullopt;
  // The interior angle between the legs; the turn is its supplement.
  const double interior = std::atan2(std::abs(cross(u, v)), u.dot(v));
  Fold f;
  f.turn_deg = 180.0 - interior * 180.0 / std::numbers::pi;
  if (f.turn_deg < kFoldMinTurn_deg) return std::nullopt;
  f.near_is_z = lv <= lu;
  f.shorter_m = std::min(lu, lv);
  f.offset_m = f.shorter_m * std::sin(interior);  // its foot lies on the longer leg (interior < 90)
  if (f.offset_m > 2.0 * half_width) return std::nullopt;
  return f;
}

}  // namespace

std::size_t split_folds(OsmRoads& osm, Diagnostics& diagnostics) {
  std::size_t folds = 0;
  std::vector<OsmWay> out;
  out.reserve(osm.ways.size());
  for (const OsmWay& way : osm.ways) {
    const WayAttributes& a = way.attributes;
    const double half_width = 0.5 * a.lane_width_m * (a.lanes_forward + a.lanes_backward);
    OsmWay kept;
    kept.id = way.id;
    kept.attributes = a;
    std::vector<OsmWay> spurs;
    for (std::size_t k = 0; k < way.node_ids.size(); ++k) {
      kept.node_ids.push_back(way.node_ids[k]);
      kept.nodes.push_back(way.nodes[k]);
      while (kept.node_ids.size() >= 3) {
        const std::size_t n = kept.node_ids.size();
        const auto fold = fold_at(kept.nodes[n - 3], kept.nodes[n - 2], kept.nodes[n - 1], half_width);
        if (!fold) break;
        const std::size_t near = fold->near_is_z ? n - 1 : n - 3;
        OsmWay spur;
        spur.id = way.id;
        spur.attributes = a;
        spur.node_ids = {kept.node_ids[near], kept.node_ids[n - 2]};
        spur.nodes = {kept.nodes[near], kept.nodes[n - 2]};
        std::ostringstream msg;
        msg.precision(2);
        msg << std::fixed << "way " << way.id << " folds back at node " << kept.node_ids[n - 2] << " (turns "
            << fold->turn_deg << " degrees; its shorter leg, " << fold->shorter_m << " m to node "
            << kept.node_ids[near] << ", lies " << fold->offset_m << " m from the other: their pavements, "
            << 2.0 * half_width
            << " m wide, overlap along all of it): the stretch is built once, a way of its own";
        Diagnostic d;
        d.severity = Severity::warning;
        d.code = codes::kOsmWayTurnsBack;
        d.message = msg.str();
        d.osm_way_id = way.id;
        d.osm_node_id = kept.node_ids[n - 2];
        diagnostics.report(std::move(d));
        spurs.push_back(std::move(spur));
        kept.node_ids.erase(kept.node_ids.begin() + static_cast<long>(n - 2));
        kept.nodes.erase(kept.nodes.begin() + static_cast<long>(n - 2));
        ++folds;
      }
    }
    out.push_back(std::move(kept));
    for (OsmWay& spur : spurs) out.push_back(std::move(spur));
  }
  osm.ways = std::move(out);
  return folds;
}

}  // namespace relief::detail

#include "relief/export/sumo_surface.h"

#include <pugixml.hpp>

#include <algorithm>
#include <cmath>
#include <optional>

#include "export/sumo_lane_locator.h"
#include "relief/core/errors.h"
#include "relief/roads/road_surface.h"

namespace relief {

struct SumoSurface::Impl {
  pugi::xml_document doc;
  std::optional<detail::LaneLocator> locator;
};

SumoSurface::SumoSurface(const std::filesystem::path& net_file, const RoadModel& model)
    : impl_(std::make_unique<Impl>()) {
  if (!std::filesystem::is_regular_file(net_file)) throw IoError("cannot read '" + net_file.string() + "'");
  const pugi::xml_parse_result parsed = impl_->doc.load_file(net_file.c_str());
  if (!parsed) throw InvalidInput("'" + net_file.string() + "' is not XML: " + parsed.description());
  const pugi::xml_node net = impl_->doc.child("net");
  if (!net) throw InvalidInput("'" + net_file.string() + "' is not a SUMO network (no <net> element)");
  impl_->locator.emplace(net, model);
}

SumoSurface::~SumoSurface() = default;
SumoSurface::SumoSurface(SumoSurface&&) noexcept = default;
SumoSurface& SumoSurface::operator=(SumoSurface&&) noexcept = default;

std::optional<LaneSurfacePoint> SumoSurface::at(const std::string& lane_id, const Vec2& p,
                                                const LaneSurfacePoint* near) {
  const std::optional<detail::LanePoint> on = impl_->locator->locate(
      lane_id, p, near ? std::optional<std::pair<int, double>>({near->odr_road, near->s}) : std::nullopt);
  if (!on) return std::nullopt;
  LaneSurfacePoint out{on->road->id, on->s, on->t, surface_z(*on->road, on->s, on->t), on->beyond};
  if (!on->road->sections.empty()) {
    const LaneSection& section = section_at(*on->road, on->s);
    int right = 0, left = 0;  // the outermost lanes (0: the centre lane where a side has none)
    for (const LaneModel& lane : section.right) right = std::min(right, lane.id);
    for (const LaneModel& lane : section.left) left = std::max(left, lane.id);
    out.outside_m = std::max(
        {0.0, lane_border_t(*on->road, on->s, right) - on->t, on->t - lane_border_t(*on->road, on->s, left)});
  }
  return out;
}

std::optional<double> SumoSurface::slope(const std::string& lane_id, const Vec2& p, double heading,
                                         double half_step_m, const LaneSurfacePoint* near) {
  const Vec2 along(std::cos(heading), std::sin(heading));
  const auto ahead = at(lane_id, p + half_step_m * along, near);
  const auto behind = at(lane_id, p - half_step_m * along, near);
  if (!ahead || !behind || ahead->odr_road != behind->odr_road || !ahead->on_road() || !behind->on_road())
    return std::nullopt;
  return (ahead->z_m - behind->z_m) / (2.0 * half_step_m);
}

}  // namespace relief

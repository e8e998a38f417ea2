#pragma once
// Checks of a written .net.xml against the RoadModel it came from: every lane shape point
// (internal junction lanes included) against the OpenDRIVE surface at the same (x, y), height
// steps where a lane hands over to its internal lane, and grades.

#include <cstddef>
#include <string>
#include <string_view>

#include "relief/roads/road_model.h"

namespace relief {

struct SumoNetCheck {
  std::size_t edges = 0;            ///< normal edges
  std::size_t lanes = 0;            ///< lanes of normal edges
  std::size_t internal_lanes = 0;   ///< junction-internal lanes
  std::size_t junctions = 0;        ///< junction elements other than internal ones
  std::size_t traffic_lights = 0;   ///< tlLogic elements
  std::size_t points = 0;           ///< lane shape points compared with the surface
  std::size_t points_unmapped = 0;  ///< lane points whose OpenDRIVE road is unknown
  double z_max_m = 0.0;             ///< largest |z_sumo - z_odr(x, y)|
  double z_p99_m = 0.0;
  double xy_max_m = 0.0;  ///< largest horizontal distance of a lane centre point to its OpenDRIVE lane centre
  double max_handover_step_m =
      0.0;  ///< |z| step between a lane's end and the internal lane it feeds (and back)
  std::size_t handovers = 0;
  double max_lane_grade_percent = 0.0;           ///< steepest segment (>= 1 m) of a normal lane
  double max_internal_lane_grade_percent = 0.0;  ///< the same for junction-internal lanes
  std::size_t disallowed_lanes = 0;              ///< lanes with a `disallow` list
};

/// Parses `net_xml` (a .net.xml written from `model`; edge/connection params odr.road and
/// odr.lane name the OpenDRIVE counterparts) and measures it. Throws InvalidInput when the
/// text is not a SUMO network (the message names `file`).
[[nodiscard]] SumoNetCheck check_sumo_net(std::string_view net_xml, const RoadModel& model,
                                          const std::string& file);

}  // namespace relief

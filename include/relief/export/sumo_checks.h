#pragma once
// Checks of a written .net.xml against the RoadModel it came from: every lane shape point
// (internal junction lanes included) against the OpenDRIVE surface at the same (x, y), height
// steps where a lane hands over to its internal lane, and grades. And checks of a simulation's
// FCD output (vehicle positions, heights, slopes) against the same surface.
//
// Lanes map to OpenDRIVE roads through the net's params: a normal edge's odr.road and its
// lanes' odr.lane; an internal lane through its connection's odr.road / odr.lane, or, when
// netconvert did not keep those (SUMO 1.15 drops connection params), through the model's
// junction connections between the lanes it joins.

#include <cstddef>
#include <string>
#include <string_view>

#include "relief/geometry/types.h"
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
  /// Points of internal lanes that netconvert drew itself (connections given without a shape,
  /// where the OpenDRIVE lane centre folds): not in the figures below, but measured apart.
  std::size_t points_netconvert_shape = 0;
  double netconvert_shape_z_max_m = 0.0;  ///< largest |z_sumo - z_odr(x, y)| of those points
  double z_max_m = 0.0;                   ///< largest |z_sumo - z_odr(x, y)|
  double z_p99_m = 0.0;
  std::string z_max_lane;           ///< SUMO lane holding the point of z_max_m (empty when no point)
  Vec3 z_max_point = Vec3::Zero();  ///< that point, in the network frame
  double xy_max_m = 0.0;  ///< largest horizontal distance of a lane centre point to its OpenDRIVE lane centre
  std::string xy_max_lane;  ///< SUMO lane holding that point
  double max_handover_step_m =
      0.0;  ///< |z| step between a lane's end and the internal lane it feeds (and back)
  std::size_t handovers = 0;
  /// Largest plan distance between a lane's end and the start of the lane it hands over to
  /// (lane -> internal lane -> lane): a vehicle jumps that far. Its lanes, "from -> to".
  double max_handover_gap_m = 0.0;
  std::string handover_gap_lanes;
  Vec3 handover_gap_point = Vec3::Zero();        ///< the end of the lane handing over
  double max_lane_grade_percent = 0.0;           ///< steepest segment (>= 1 m) of a normal lane
  double max_internal_lane_grade_percent = 0.0;  ///< the same for junction-internal lanes
  std::size_t disallowed_lanes = 0;              ///< lanes with a `disallow` list
  std::size_t lanes_without_z = 0;               ///< lanes with a shape point given without z
  /// Height steps: more than 0.1 m of height within 0.5 m of plan distance and steeper than
  /// 50 % there, along a lane (internal lanes included) or where one hands over to the next.
  /// SF's real 35 % streets are no step; a lane climbing a kerb is.
  std::size_t height_steps = 0;
  std::string first_step_lane;  ///< lane of the first step found (empty: none)
  Vec3 first_step_point = Vec3::Zero();
};

/// Parses `net_xml` (a .net.xml written from `model`; edge/connection params odr.road and
/// odr.lane name the OpenDRIVE counterparts) and measures it. Throws InvalidInput when the
/// text is not a SUMO network (the message names `file`).
/// A height step: more than 0.1 m of rise within 0.5 m of plan, steeper there than the lane's
/// road may be by 15 points, and at least 50 % (SumoOptions::grade_caps; empty: 35 % streets,
/// whose 50 % is the step). A mountain path fitted to its 100 % cap climbs at 60 % and is
/// no step; a street lane that does is.
[[nodiscard]] SumoNetCheck check_sumo_net(std::string_view net_xml, const RoadModel& model,
                                          const std::string& file,
                                          const std::vector<double>& grade_caps = {});

/// What a simulation's FCD output says about heights and slopes along the vehicles' paths.
struct FcdCheck {
  std::size_t timesteps = 0;         ///< <timestep> elements
  std::size_t vehicles = 0;          ///< distinct vehicle ids
  std::size_t samples = 0;           ///< vehicle samples with z compared with the surface (n)
  std::size_t samples_unmapped = 0;  ///< samples whose lane has no OpenDRIVE road
  /// Samples on internal lanes that netconvert drew itself (see SumoNetCheck): left out.
  std::size_t samples_netconvert_shape = 0;
  double z_max_m = 0.0;  ///< largest |z_fcd - z_odr(x, y)|
  double z_p99_m = 0.0;
  std::size_t slope_samples = 0;  ///< samples with a slope compared
  /// Largest |slope_fcd - atan(dz/dl)| in degrees, dz/dl the surface's grade along the lane's
  /// offset line at the sample (dz/ds of the profile on a straight road), signed by the
  /// direction of travel (right lanes drive along s).
  double slope_max_deg = 0.0;
  double slope_p99_deg = 0.0;
};

/// Parses `fcd_xml` (sumo --fcd-output with x, y, z, slope and lane among its attributes; x, y
/// in the network's coordinates) and compares every vehicle sample with the surface of the
/// OpenDRIVE road its lane belongs to in `net_xml` (the .net.xml written from `model`). Samples
/// without z or slope leave those figures out. Throws InvalidInput when either text is not what
/// it should be (the message names `file`, the FCD file, or the network).
[[nodiscard]] FcdCheck check_sumo_fcd(std::string_view fcd_xml, std::string_view net_xml,
                                      const RoadModel& model, const std::string& file);

}  // namespace relief

#pragma once
// Private to the cosim module: every placement measured against the OpenDRIVE surface of the
// lane the vehicle's centre is on (its height, its pitch against the surface's slope along the
// heading, SUMO's own lane height at the front bumper; the vehicle's body against the same
// wheel contacts on that surface), the wheel contacts tallied, the egos' physics bodies apart,
// and the spreads and worst place summed up into a CosimResult.

#include <array>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "relief/cosim/cosim.h"
#include "relief/cosim/sumo_session.h"
#include "relief/cosim/vehicle_pose.h"
#include "relief/export/sumo_surface.h"

namespace relief::detail {

/// The median, 99th percentile (the value at rank floor(0.99 (n - 1))) and largest value;
/// reorders `values`.
Spread spread_of(std::vector<float>& values);

class PlacementMeasures {
 public:
  PlacementMeasures(SumoSurface& odr, const CosimOptions& options) : odr_(odr), options_(options) {}

  /// Notes the vehicle's lane (call once per vehicle and step, before add or unplaced).
  void track_lane(const SumoVehicleState& v);
  /// A vehicle set on the surface at time t; SUMO's own lane height at its bumper measured
  /// when `sumo_placed`. An ego (not `sumo_placed`: its plan position and body are the
  /// physics') adds only to the ego spreads (cosim.h ego_z_error_m).
  void add(const SumoVehicleState& v, const SurfacePose& pose, double t, CosimResult& result,
           bool sumo_placed = true);
  /// A vehicle that could not be set on the surface.
  void unplaced(const SumoVehicleState& v, double t, CosimResult& result);
  /// Fills the spreads, the vehicle count and reports what was not placed or measured.
  void finish(CosimResult& result, Diagnostics& diagnostics);

 private:
  // The mean height of the vehicle's four wheel contacts (vehicle_pose.h's wheel base) on the
  // OpenDRIVE road of `lane` (`near`: the centre's answer there), a contact beyond that road's
  // ends or more than 0.25 m outside its outermost lane borders on the road of another of the
  // vehicle's last lanes; none when one is on neither.
  std::optional<double> odr_body_z(const SumoVehicleState& v, const std::string& lane,
                                   const LaneSurfacePoint& near);

  SumoSurface& odr_;
  const CosimOptions& options_;
  // The last lanes of every vehicle, newest first: its centre, half a length behind the front
  // bumper, may still be on a lane the bumper has left.
  std::unordered_map<std::string, std::array<std::string, 3>> recent_;
  std::vector<float> z_errors_, z_errors_road_, z_errors_junction_, sumo_z_errors_, pitch_errors_,
      wheel_under_, body_errors_, body_errors_road_, body_errors_junction_, ego_z_errors_;
  double worst_z_ = -1.0, worst_body_ = -1.0, worst_under_ = 0.0, worst_ego_z_ = -1.0;
  std::string first_unplaced_, first_unmapped_;
};

}  // namespace relief::detail

#pragma once
// Quality gates: every build checks its own outputs against stated thresholds, and a build whose
// outputs fail one says so loudly (the CLI exits with 4, "built, but outputs failed quality
// gates"; the outputs are still written, so that the failure can be looked at). A gate is only
// evaluated when the output it checks was built.
//
//   fit_converged                 the profile solver met its tolerance (1: yes)
//   fit_limits_violated           limits the fit left violated (ground departure, grades,
//                                 junction grades, clearances, vertical curves), count
//   ground_vs_dem_rmse_m          fitted ground roads vs the DEM between samples, RMSE
//   ground_vs_dem_max_m           and largest
//   junction_height_gap_m         largest height gap between the road ends at a junction (the
//                                 seed paper's continuity bound; the fit's is exactly 0)
//   road_grade_over_cap_percent   elevation records: largest grade over the road's cap
//   connecting_road_grade_over_cap_percent   the same for connecting roads (cap of the steeper
//                                 road they join)
//   link_height_step_m            largest height step between linked lane borders
//   sumo_lanes_without_z          lanes of the .net.xml with a point given without z
//   sumo_lane_z_max_m             largest |z| of a lane point off the OpenDRIVE surface (lanes
//                                 netconvert drew itself included)
//   sumo_height_steps             steps along SUMO lanes and at their hand-overs
//   sumo_handover_gap_m           largest plan gap where a SUMO lane hands over to the next
//                                 (lane -> internal lane -> lane): a vehicle jumps that far
//   road_self_intersections       Road_Road triangle pairs intersecting
//   junctions_open                junctions whose surface could not be meshed
//   ground_holes                  holes of the ground (roads on the ground + terrain)

#include <optional>
#include <string>
#include <vector>

#include "relief/export/report_writer.h"

namespace relief {

/// Thresholds of the gates (a gate passes when its value is at most the threshold, fit_converged
/// when it is at least). Defaults: what a correct build meets on real data with room for
/// rounding, and what a simulation needs (a 0.1 m step unsettles a vehicle).
struct GateThresholds {
  double fit_limits_violated = 0;
  double ground_vs_dem_rmse_m = 2.0;
  double ground_vs_dem_max_m = 16.0;   ///< the fit's departure bound (15 m) + 1 m between samples
  double junction_height_gap_m = 0.1;  ///< the seed paper's "gap < 0.1 m"
  /// The fitted stations keep the cap and the OpenDRIVE records climb no steeper than the
  /// stations (fit_grade_bounded_profile); what is left is the fit's own tolerance and the end
  /// slopes it shares with junctions (measured 0.13 % on NE, 0.33 % on Liechtenstein and 0.31 %
  /// on Portland): the issue's +2 %, as for connecting roads.
  double road_grade_over_cap_percent = 2.0;
  double connecting_road_grade_over_cap_percent = 2.0;
  double link_height_step_m = 0.01;
  double sumo_lanes_without_z = 0;
  double sumo_lane_z_max_m = 0.05;
  double sumo_height_steps = 0;
  /// Half a metre: the horizontal error at which the co-simulation resynchronises a vehicle.
  double sumo_handover_gap_m = 0.5;
  double road_self_intersections = 0;
  double junctions_open = 0;
  double ground_holes = 0;

  /// Sets a threshold by its gate's name ("ground_vs_dem_rmse_m"); false for an unknown name.
  bool set(const std::string& name, double value);
  /// The names of every gate, in the order they are reported.
  [[nodiscard]] static const std::vector<std::string>& names();
};

/// The gates of a finished build's report.
[[nodiscard]] std::vector<Gate> evaluate_gates(const RunReport& report, const GateThresholds& thresholds);

/// Gates that failed.
[[nodiscard]] std::vector<Gate> failed_gates(const std::vector<Gate>& gates);

}  // namespace relief

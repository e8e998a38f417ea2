#pragma once
// Builds the RoadModel (reference lines, elevation, lanes, links, junctions) from the road
// network and its fitted profiles.
//
// - Roads meeting at an intersection (3+ ends) are trimmed back from the junction node by the
//   junction's radius (the widest half-width there plus a margin) to leave room for the junction;
//   every allowed movement gets a connecting road per lane pair, whose reference line runs from
//   the arriving lane's inner border to the departing lane's inner border (paramPoly3, position
//   and heading exact at both ends) and whose elevation is the cubic with the incoming road's
//   height and slope at its start and the outgoing road's at its end.
// - Two junctions joined by a road shorter than their two radii plus min_kept_length_m, one an
//   intersection and the other an intersection or an attribute change that takes room (the
//   nodes where divided streets cross; a bend or lane change next to an intersection), are one
//   junction, the road inside it ("model.junctions_joined"); a movement between two of its
//   members follows the absorbed roads, one-ways only forward.
// - Roads meeting at an attribute change (2 ends) are linked directly, lane to lane, when one
//   continues the other (straight within 3 degrees, same lanes, same width); otherwise both are
//   trimmed and joined by a short transition road that bends and widens from one to the other
//   (lanes present on one side only taper to width 0). Where two one-ways both arrive (or both
//   leave), neither is linked: both end there ("model.no_passage").
// - Where roads leave a junction at a small angle (forks), their ends are trimmed further, in
//   steps, until at each junction the end cross-sections (outermost left to outermost right
//   lane border) of any two roads lie at least junction_end_gap_m apart and clear of each
//   other's lanes, as long as the road keeps min_kept_length_m between its two trims (a loop
//   road, both ends at one junction or at two joined ones: max_trim_fraction per end). A road
//   the trims leave no longer than min_kept_length_m between two junctions that take room (their
//   areas would meet across it, or its ends still overlap others) joins them like a short road
//   above, and the trims run again on the joined junctions (up to 8 rounds), when it is either
//   stuck (its ends still overlap) or no more than 10 m longer than the two radii (longer roads
//   used up at a sharp fork keep their junctions apart); "model.junction_ends_overlap" where
//   the ends still overlap then.
// - At an intersection, an end is trimmed further in the same steps while a turn from or into it
//   is tighter than min_turn_radius_m at its lane centre (the end nearer the turn's corner
//   grows), by at most max_trim_fraction of its road and leaving the road as long as it is wide.
// - A dead end that stops on another road's pavement at about its height, without a shared
//   node (an OSM "almost junction", ways closer than their widths), is trimmed back in steps
//   until its end cross-section clears that pavement by junction_end_gap_m
//   ("model.stray_end_trimmed"; "model.stray_end_overlap" when its least length does not).
// - Reference lines: OSM centrelines rounded at their vertices within plan_tolerance_m, but with
//   arcs no tighter than the road's outermost lane border plus min_radius_margin_m (lane
//   borders fold back inside a tighter arc): a sharp corner then departs from the polyline by
//   more than the tolerance ("model.corner_rounded"); lanes:
//   right lanes drive along the reference line; laneOffset centres the carriageway on the OSM
//   centreline (one-ways have right lanes only).
// - Elevation: C1 cubic pieces through the fitted profile within elevation_tolerance_m.

#include <array>
#include <cstdint>
#include <vector>

#include "relief/core/diagnostics.h"
#include "relief/roads/elevation_sampling.h"
#include "relief/roads/profile_fit.h"
#include "relief/roads/road_model.h"
#include "relief/roads/road_network.h"

namespace relief {

struct RoadModelOptions {
  double plan_tolerance_m = 0.05;  ///< reference line vs OSM polyline
  /// Elevation records vs fitted profile. Where the pieces break depends on whether a piece's
  /// error passes this tolerance, so two builds whose fits agree to micrometres (a tile and the
  /// whole region) can break a road differently and then differ by up to twice it: at 1 cm one
  /// of NE's 5046 roads came out 1.45 mm from the whole build in 500 m tiles. At 0.4 mm they
  /// agree within 1 mm by construction; NE's OpenDRIVE has 28 058 elevation records instead of
  /// 16 526 (file 15.7 MB instead of 14.2 MB).
  double elevation_tolerance_m = 4e-4;
  double junction_margin_m = 2.0;    ///< junction radius beyond the widest half-width
  double max_trim_fraction = 0.4;    ///< share of a road's length per end the junction radius takes at most
  double min_kept_length_m = 1.0;    ///< least length a road keeps when its ends are trimmed further
  double min_radius_margin_m = 0.5;  ///< smallest arc radius beyond the outermost lane border
  double junction_end_gap_m = 0.5;   ///< least distance between road ends at a junction
  /// Least radius of a turn's lane centre at an intersection (0: any): road ends are trimmed back
  /// until the connecting roads between them are this round, each end by at most
  /// max_trim_fraction of its road and leaving it at least as long as it is wide. 3 m: SUMO
  /// draws a 5 m car as a chord behind its front bumper, whose middle then stays on a 3 m lane
  /// (for R > 2.83 m).
  double min_turn_radius_m = 3.0;
  bool u_turns = false;  ///< U-turns: back into the arriving road, or any turn over 150 degrees
  /// Per network road, the grade cap its profile was fitted to (fraction; empty: none known). A
  /// connecting road follows its junction's height surface where that keeps it within the larger
  /// cap of the two roads it joins (less 0.5 %, inside the grade gate's 2 %), else within the
  /// bound of the cubic between its ends.
  std::vector<double> grade_caps;
};

struct RoadModelStats {
  std::size_t roads = 0;  ///< from the network
  std::size_t connecting_roads = 0;
  /// Connecting roads that leave their junction's height surface somewhere, where it is steeper
  /// along them than their grade bound; and the largest height any connecting road lies off that
  /// surface (those roads, and the roads crossing them, which take their departures).
  std::size_t connecting_roads_off_surface = 0;
  double connecting_road_departure_max_m = 0.0;
  std::size_t junctions = 0;                    ///< OpenDRIVE junctions (= network intersections)
  std::size_t junctions_without_movements = 0;  ///< intersections where no movement is possible
  std::size_t direct_links = 0;                 ///< road-to-road links at attribute changes
  std::size_t transition_roads = 0;  ///< short roads where two roads meet at an angle or change lanes
  /// Two-road nodes whose bend was too tight for a transition road's lanes: junctions instead.
  std::size_t transitions_as_junctions = 0;
  std::size_t roads_skipped = 0;  ///< roads without height or too short once trimmed
  /// Largest |elevation record - fitted profile| over the profile's stations (mapped onto the
  /// reference line) of every road.
  double max_elevation_deviation_m = 0.0;
  std::size_t corners_rounded = 0;  ///< roads with a corner widened to their minimum radius
  /// Largest distance of an OSM vertex from its road's reference line where corners were
  /// widened (0 if none was).
  double max_corner_departure_m = 0.0;
  std::size_t junction_ends_trimmed = 0;  ///< road ends trimmed further to clear the other ends
  std::size_t junction_ends_overlap = 0;  ///< junctions whose road ends still overlap
  std::size_t junctions_joined = 0;       ///< intersections joined into a neighbour's junction
  std::size_t roads_absorbed = 0;         ///< roads inside joined junctions (no OpenDRIVE road)
  std::size_t ends_without_passage = 0;   ///< attribute changes between two arriving (leaving) one-ways
  std::size_t stray_ends_trimmed = 0;     ///< dead ends trimmed off another road's pavement
  std::size_t stray_ends_left = 0;        ///< dead ends still on another road at their least length
};

struct RoadModelBuild {
  RoadModel model;
  RoadModelStats stats;
  std::vector<int> model_road_of;  ///< per network road: its index in model.roads, or -1
  /// Per network road: the length of its OSM polyline cut off at its start and at its end for
  /// the junctions there (the model road is what lies between).
  std::vector<std::array<double, 2>> end_trims;
  /// Per network junction: the junction that stands for the joined junction it is part of
  /// (itself when not joined); per network road: 1 where it lies inside a joined junction.
  std::vector<int> joined_into;
  std::vector<std::uint8_t> absorbed;
};

/// Arc length along the road as driven at each of the profile's stations, for the whole
/// untrimmed road: along its reference line (the OSM polyline with every vertex rounded by the
/// options' minimum radius), and in each bend along the centre of the outermost lane on its
/// inside (offset t = outer border - half a lane), which is shorter by t times the angle turned.
/// Where a hairpin's OSM vertex is rounded the driven road is shorter than the polyline, and
/// grades measured along it are steeper: the fit takes its grade and curvature limits there, so
/// that they hold on every lane (a lane's height is the reference line's at the same s).
[[nodiscard]] std::vector<double> driven_stations(const Road& road, const RoadProfile& profile,
                                                  const RoadModelOptions& options);

/// Where the road model cuts each road for its junctions (RoadModelBuild::end_trims) and which
/// junctions it joins, without building the model (plan and attributes only; `profiles` say
/// which roads have a height): the fit's JunctionCuts.
[[nodiscard]] JunctionCuts junction_cuts(const RoadNetwork& network, const std::vector<RoadProfile>& profiles,
                                         const RoadModelOptions& options);

/// `profiles` are parallel to network.roads (stations with fitted z). `junction_gradient`
/// (parallel to network.junctions, or empty) is each junction's tangent plane
/// (ProfileFitResult::junction_gradient): the roads take the cross-slope of an intersection's (three ends or
/// more) plane at their ends as superelevation, eased to level within 50 m (a road up to 100 m long turns
/// from one end's to the other's), and the roads inside a junction lie across it, so that every lane at a
/// junction lies on its plane. Without it every cross-section is level.
[[nodiscard]] RoadModelBuild build_road_model(const RoadNetwork& network,
                                              const std::vector<RoadProfile>& profiles,
                                              const RoadModelOptions& options, Diagnostics& diagnostics,
                                              const std::vector<Vec2>& junction_gradient = {});

}  // namespace relief

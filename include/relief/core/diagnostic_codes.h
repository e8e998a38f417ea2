#pragma once
// The registry of diagnostic codes: every code relief reports (core/diagnostics.h), one constant
// each with its meaning. A code is a stable key of report.json and the report page, so it is
// named here once and the library uses the constant. The test diagnostic_codes_test.cpp fails
// when src/ reports a code by a string literal, when a constant is missing from kAll, and when
// the README's table of codes differs from this registry.

#include <array>
#include <string_view>

namespace relief {

/// A diagnostic code ("module.defect") and a one-line meaning for the README and readers.
struct DiagnosticCode {
  std::string_view code;
  std::string_view meaning;
  /// The code itself, so that a constant goes wherever a code does (Diagnostic::code, report()).
  constexpr operator std::string_view() const { return code; }  // NOLINT(google-explicit-constructor)
};

namespace codes {

// DEM access (terrain/dem_sampler.h).
inline constexpr DiagnosticCode kDemDatumGridMissing{
    "dem.datum_grid_missing", "a more accurate datum transformation needs a PROJ grid that is not installed"};
inline constexpr DiagnosticCode kDemImplausibleHeight{
    "dem.implausible_height", "DEM cells outside the plausible heights (unflagged fill values) are voids"};
inline constexpr DiagnosticCode kDemSpike{
    "dem.spike", "one-cell DEM spikes or pits, far from agreeing neighbours, are voids"};
inline constexpr DiagnosticCode kDemGroundFiltered{
    "dem.ground_filtered",
    "a surface model's buildings, trees and pits are taken down to the ground (--ground-filter)"};

// OSM import (roads/osm_reader.h) and the network (roads/network_builder.h).
inline constexpr DiagnosticCode kOsmMissingNode{
    "osm.missing_node", "a way references a node that is not in the file; the way is split there"};
inline constexpr DiagnosticCode kOsmDegenerateWay{"osm.degenerate_way",
                                                  "a way with fewer than two distinct nodes is skipped"};
inline constexpr DiagnosticCode kOsmWayTurnsBack{"osm.way_turns_back",
                                                 "a way drawn out to a node and back along itself (to the "
                                                 "same node, or folding onto its own pavement): the "
                                                 "stretch is one way of its own"};
inline constexpr DiagnosticCode kOsmOverlappingWays{
    "osm.overlapping_ways", "a way drawn over the nodes of another: the shared stretch is built once"};
inline constexpr DiagnosticCode kOsmTagValue{
    "osm.tag_value", "tag values of a way that relief cannot read fall back to defaults"};
inline constexpr DiagnosticCode kOsmCrossingWithoutNode{
    "osm.crossing_without_node",
    "ways crossing on one level without a shared node are joined by a node there"};
inline constexpr DiagnosticCode kOsmStructuresOnOneLevel{
    "osm.structures_on_one_level",
    "two bridges or two tunnels of one layer crossing without a node are separated with the full clearance, "
    "the one whose span between its ends lies higher above (joining would invent a connection)"};
inline constexpr DiagnosticCode kNetworkDegenerateWay{
    "network.degenerate_way", "a piece of a way between two junctions shorter than 1 cm is dropped"};
inline constexpr DiagnosticCode kNetworkRoadsNarrowed{"network.roads_narrowed",
                                                      "roads on one level drawn closer than their widths get "
                                                      "narrower lanes, so their pavements do not overlap"};
inline constexpr DiagnosticCode kNetworkStubDropped{
    "network.stub_dropped", "a dead-end road shorter than the pavement of the roads it leaves is dropped"};
inline constexpr DiagnosticCode kNetworkRoadsMoved{"network.roads_moved",
                                                   "a road on one level drawn over another's pavement is "
                                                   "moved sideways until their pavements meet"};

// Elevation sampling (roads/elevation_sampling.h).
inline constexpr DiagnosticCode kElevationVoid{"elevation.void",
                                               "road samples in a DEM void are filled along the road"};
inline constexpr DiagnosticCode kElevationUncovered{
    "elevation.uncovered", "road samples outside every DEM are filled along the road (partial coverage)"};
inline constexpr DiagnosticCode kElevationRoadWithoutHeight{
    "elevation.road_without_height", "a road with no DEM height anywhere is left out of the outputs"};

// Profile fit (roads/profile_fit.h).
inline constexpr DiagnosticCode kFitUnanchoredStructure{
    "fit.unanchored_structure",
    "a bridge or tunnel meeting ground roads at fewer than two junctions follows the DEM"};
inline constexpr DiagnosticCode kFitNotConverged{"fit.not_converged",
                                                 "the profile fit did not converge (a defect of relief)"};
inline constexpr DiagnosticCode kFitLimitViolated{
    "fit.limit_violated", "a limit of the profile fit is violated at a place (road station or junction)"};

// Road model (roads/road_model_builder.h).
inline constexpr DiagnosticCode kModelJunctionsJoined{
    "model.junctions_joined", "junctions closer than the road between them can hold are joined into one"};
inline constexpr DiagnosticCode kModelStrayEndTrimmed{
    "model.stray_end_trimmed",
    "a dead end lying on another way (no shared node) was trimmed back clear of it"};
inline constexpr DiagnosticCode kModelStrayEndOverlap{
    "model.stray_end_overlap", "a dead end lying on another way is still there after trimming back"};
inline constexpr DiagnosticCode kModelCornerRounded{
    "model.corner_rounded",
    "sharp corners rounded to the minimum radius take the reference line off the way"};
inline constexpr DiagnosticCode kModelJunctionEndsOverlap{
    "model.junction_ends_overlap", "road ends at a junction still overlap after the largest trim allowed"};
inline constexpr DiagnosticCode kModelNoPassage{
    "model.no_passage", "two roads meet but no lane leads from one into the other (opposed one-ways)"};
inline constexpr DiagnosticCode kModelTransitionAsJunction{
    "model.transition_as_junction",
    "a bend between two roads too tight for their lanes (they would fold, or the inner lane climb past the "
    "cap + 2 %) is a junction, one connecting road per movement"};
inline constexpr DiagnosticCode kOpendriveRoadTooShort{
    "opendrive.road_too_short", "a road with no length left between its junctions is left out"};
inline constexpr DiagnosticCode kOpendriveJunctionWithoutMovements{
    "opendrive.junction_without_movements", "no movement is possible at a junction; its roads end there"};

// Road surface meshes (scene/road_mesh.h) and the mesh stage's checks.
inline constexpr DiagnosticCode kMeshRoadTooShort{"mesh.road_too_short",
                                                  "a road too short to loft has no mesh"};
inline constexpr DiagnosticCode kMeshRoadFailed{"mesh.road_failed",
                                                "lofting a road failed; the road has no mesh"};
inline constexpr DiagnosticCode kMeshWeldUnmatched{
    "mesh.weld_unmatched", "vertices of linked road ends have no partner within 5 mm (lane counts differ)"};
inline constexpr DiagnosticCode kMeshJunctionFailed{
    "mesh.junction_failed", "a junction surface could not be built; its area is open"};
inline constexpr DiagnosticCode kMeshJunctionEndLeftOut{
    "mesh.junction_end_left_out",
    "a road end lying on another of a junction's roads or across its other ends is left out of its surface"};
inline constexpr DiagnosticCode kMeshRoadSelfIntersections{
    "mesh.road_self_intersections", "road surface triangles intersect each other (Road_Road pairs)"};
inline constexpr DiagnosticCode kMeshRoadsOverlapInPlan{
    "mesh.roads_overlap_in_plan", "road triangles on the ground lie under another road seen from above"};
inline constexpr DiagnosticCode kMeshStructureTerrainIntersections{
    "mesh.structure_terrain_intersections",
    "a deck, tunnel or road piece under another road cuts the terrain"};
inline constexpr DiagnosticCode kMeshFarFromOrigin{
    "mesh.far_from_origin", "a mesh file reaches where a float steps by more than 1 mm; tiles keep it exact"};

// SUMO network (export/sumo_network.h) and its stage.
inline constexpr DiagnosticCode kSumoLoopSkipped{
    "sumo.loop_skipped", "a road looping back to its own junction is too short to split; SUMO gets no edge"};
inline constexpr DiagnosticCode kSumoDeadEndSkipped{
    "sumo.dead_end_skipped",
    "a dead end shorter than 2 m (its junction's room used it up) gets no SUMO edge"};
inline constexpr DiagnosticCode kSumoSignalWithoutNode{"sumo.signal_without_node",
                                                       "a junction with a traffic signal has no SUMO node"};
inline constexpr DiagnosticCode kSumoSignalMidRoad{
    "sumo.signal_mid_road", "traffic signals far from any intersection (crossings) get no SUMO light"};
inline constexpr DiagnosticCode kSumoUnmappedLanePoints{"sumo.unmapped_lane_points",
                                                        "SUMO lane points have no OpenDRIVE road under them"};

// Co-simulation (cosim/cosim.h).
inline constexpr DiagnosticCode kCosimVehicleOffSurface{
    "cosim.vehicle_off_surface", "a SUMO vehicle has a wheel where the road surface mesh has no triangle"};
inline constexpr DiagnosticCode kCosimLaneUnmapped{
    "cosim.lane_unmapped",
    "a SUMO vehicle drives a lane with no OpenDRIVE road; its placement is not measured"};
inline constexpr DiagnosticCode kCosimEgoResync{
    "cosim.ego_resync",
    "an ego vehicle drifted past the resync distance from SUMO and was set back onto SUMO's lane"};
inline constexpr DiagnosticCode kDemandCountUnmatched{
    "demand.count_unmatched",
    "a traffic count's OSM way or direction has no edge in the net; the count is left out"};
inline constexpr DiagnosticCode kCosimEgoMissing{"cosim.ego_missing",
                                                 "a vehicle named as an ego never ran in SUMO"};

// The CARLA import package (export/carla_package.h).
inline constexpr DiagnosticCode kCarlaTileGridGap{
    "carla.tile_grid_gap",
    "a tile of a CARLA large map's grid holds no triangles; the package gives it a placeholder triangle"};

// Region tiles (tiles/tiles.h).
inline constexpr DiagnosticCode kTilesLinkUnresolved{
    "tiles.link_unresolved",
    "a link of a tile's road points at a road or junction that no tile owns; dropped"};
inline constexpr DiagnosticCode kTilesHaloGate{
    "tiles.halo_gate",
    "a quality gate of a tile failed only in its halo, which its neighbour owns and checks"};

// Quality gates (export/quality_gates.h).
inline constexpr DiagnosticCode kGateFailed{"gate.failed", "a quality gate failed (the build exits with 4)"};

/// Every code above, in the order of the pipeline.
inline constexpr std::array kAll{kDemDatumGridMissing,
                                 kDemImplausibleHeight,
                                 kDemSpike,
                                 kDemGroundFiltered,
                                 kOsmMissingNode,
                                 kOsmDegenerateWay,
                                 kOsmWayTurnsBack,
                                 kOsmOverlappingWays,
                                 kOsmTagValue,
                                 kOsmCrossingWithoutNode,
                                 kOsmStructuresOnOneLevel,
                                 kNetworkDegenerateWay,
                                 kNetworkRoadsNarrowed,
                                 kNetworkStubDropped,
                                 kNetworkRoadsMoved,
                                 kElevationVoid,
                                 kElevationUncovered,
                                 kElevationRoadWithoutHeight,
                                 kFitUnanchoredStructure,
                                 kFitNotConverged,
                                 kFitLimitViolated,
                                 kModelJunctionsJoined,
                                 kModelStrayEndTrimmed,
                                 kModelStrayEndOverlap,
                                 kModelCornerRounded,
                                 kModelJunctionEndsOverlap,
                                 kModelNoPassage,
                                 kModelTransitionAsJunction,
                                 kOpendriveRoadTooShort,
                                 kOpendriveJunctionWithoutMovements,
                                 kMeshRoadTooShort,
                                 kMeshRoadFailed,
                                 kMeshWeldUnmatched,
                                 kMeshJunctionFailed,
                                 kMeshJunctionEndLeftOut,
                                 kMeshRoadSelfIntersections,
                                 kMeshRoadsOverlapInPlan,
                                 kMeshStructureTerrainIntersections,
                                 kMeshFarFromOrigin,
                                 kCarlaTileGridGap,
                                 kTilesLinkUnresolved,
                                 kTilesHaloGate,
                                 kSumoLoopSkipped,
                                 kSumoDeadEndSkipped,
                                 kSumoSignalWithoutNode,
                                 kSumoSignalMidRoad,
                                 kSumoUnmappedLanePoints,
                                 kCosimVehicleOffSurface,
                                 kCosimLaneUnmapped,
                                 kCosimEgoResync,
                                 kCosimEgoMissing,
                                 kDemandCountUnmatched,
                                 kGateFailed};

}  // namespace codes
}  // namespace relief

#pragma once
// report.json: what was built, from what, and how good it is (the seed paper's validation
// figures), with the frame needed to map every output back to lon/lat.

#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "relief/core/diagnostics.h"
#include "relief/export/sight_writer.h"
#include "relief/geometry/geo_frame.h"
#include "relief/geometry/mesh_quality.h"
#include "relief/roads/profile_fit.h"
#include "relief/roads/road_model_checks.h"
#include "relief/roads/validation.h"
#include "relief/terrain/dem_source.h"

namespace relief {

/// The figures of one way of making the profiles (raw drape, the paper's smoothing, relief's fit).
struct MethodReport {
  std::string method;           ///< "raw", "paper", "relief"
  HeightValidation all;         ///< every road
  HeightValidation ground;      ///< roads on the ground
  HeightValidation structures;  ///< bridges and tunnels
  GradeStats gradient;
  JunctionGapStats junctions;
  CutFillStats cut_fill;                  ///< departure from the DEM drape, roads on the ground
  std::size_t separations = 0;            ///< grade separations: crossings of roads on different layers ...
  std::size_t separations_alongside = 0;  ///< ... of which places where one runs over the other
  double min_clearance_m = 0.0;           ///< smallest upper-minus-lower height at those places
  std::size_t below_clearance = 0;
  /// Places where two pavements overlap in plan with no room for a clearance (same layer, or
  /// near a road's end), where the upper one only has to stay 0.1 m above: every 5 m of them ...
  std::size_t overlaps_ordered = 0;
  std::size_t overlaps_out_of_order = 0;  ///< ... and those where it does not
  double seconds = 0.0;                   ///< time to make the profiles
};

/// relief's fit, as run.
struct FitSummary {
  std::string policy;
  int iterations = 0;
  bool converged = false;
  std::string solver;  ///< the solver's status and method
  std::size_t variables = 0;
  std::size_t held_variables = 0;  ///< of `variables`: held at a neighbouring tile's values
  std::size_t constraints = 0;
  double max_violation_m = 0.0;
  double clearance_m = 0.0;
  double cutoff_wavelength_m = 0.0;
  double max_ground_departure_m = 0.0;
  double max_cross_slope_percent = 0.0;  ///< a road end's roll on its junction's plane (0: its cap)
  std::vector<FitViolation> violations;  ///< limits left violated, worst per road and limit
};

/// The paper's smoothing, as run.
struct PaperSummary {
  int max_iterations = 0;
  std::size_t roads_not_converged = 0;
  double max_shift_m = 0.0;
  std::vector<int> not_converged_roads;
};

/// The OpenDRIVE written, and its checks.
struct OpenDriveSummary {
  std::string file;
  std::string version;    ///< "1.7"
  std::size_t roads = 0;  ///< roads from the network
  std::size_t connecting_roads = 0;
  std::size_t connecting_roads_off_surface = 0;  ///< leaving their junction's height surface somewhere
  /// The most one lies off it by (where it is too steep, or crossing one that left it)
  double connecting_road_departure_max_m = 0.0;
  std::size_t junctions = 0;
  std::size_t junctions_without_movements = 0;  ///< intersections left out: no movement possible
  std::size_t junctions_joined = 0;             ///< intersections joined into a neighbour's junction
  std::size_t roads_absorbed = 0;               ///< network roads inside joined junctions
  std::size_t direct_links = 0;
  std::size_t transition_roads = 0;
  std::size_t transitions_as_junctions = 0;  ///< two-road bends too tight for a transition road
  std::size_t roads_skipped = 0;
  double max_link_gap_m = 0.0;   ///< horizontal, between linked lane borders
  double max_link_step_m = 0.0;  ///< vertical, the same
  std::size_t link_borders_checked = 0;
  /// Where two connecting roads' lane centres cross in a junction, their height difference
  /// (check_connecting_road_crossings): largest, junctions over 0.02 m, the worst junction's id
  /// and place. Measured, not gated: each connecting road still carries its own profile.
  double crossing_max_step_m = 0.0;
  std::size_t crossing_junctions_over = 0;
  int crossing_worst_junction = -1;
  Vec2 crossing_worst_xy = Vec2::Zero();
  /// Connecting roads over the pavement of their junction's roads (check_connecting_roads_over_roads).
  double over_road_max_step_m = 0.0;
  std::size_t over_road_junctions_over = 0;
  int over_road_worst_junction = -1;
  int over_road_worst_road = -1;
  Vec2 over_road_worst_xy = Vec2::Zero();
  double round_trip_max_xy_m = 0.0;  ///< file read back vs the model written
  double round_trip_max_z_m = 0.0;
  std::size_t round_trip_points = 0;
  double elevation_max_deviation_m = 0.0;  ///< elevation records vs the fitted profile
};

/// The SUMO network written, and its checks against the OpenDRIVE surface.
struct SumoSummary {
  std::string file;                                   ///< "NAME.net.xml"
  std::size_t nodes = 0, edges = 0, connections = 0;  ///< plain network given to netconvert
  std::size_t junctions = 0, traffic_lights = 0;      ///< in the .net.xml
  std::size_t lanes = 0, internal_lanes = 0;
  /// Internal lanes netconvert drew itself because the OpenDRIVE lane centre folds back (a
  /// connecting road bending tighter than the lane's offset); left out of the z figures.
  std::size_t internal_lanes_by_netconvert = 0;
  std::size_t signals_mid_road = 0;  ///< OSM signals too far from any junction to control one
  std::map<std::string, std::size_t> restricted_edges;  ///< vehicle class -> edges kept off by grade
  std::map<std::string, double> max_grade_percent;      ///< the limits applied
  std::size_t points_checked = 0;
  double z_max_m = 0.0, z_p99_m = 0.0;    ///< lane points vs the OpenDRIVE surface
  std::string z_max_lane;                 ///< SUMO lane of the z_max_m point
  double netconvert_lanes_z_max_m = 0.0;  ///< the same for internal lanes netconvert drew
  /// Lane points netconvert left off the surface (cut at its junction outlines), given the
  /// surface height before the check (sumo_drape.h): how many moved by more than 1 mm, the
  /// largest move and its lane.
  std::size_t draped_points_moved = 0;
  double drape_max_move_m = 0.0;
  std::string drape_max_move_lane;
  std::size_t draped_points_added = 0;  ///< points put in where a chord left the surface
  /// Internal lanes made to meet their lanes (sumo_seams.h): ends extended along a lane
  /// netconvert cut short and the longest extension; ends moved onto a lane end beside or
  /// behind them and the farthest move.
  std::size_t handover_ends_extended = 0;
  double handover_max_extension_m = 0.0;
  std::string handover_max_extension_lane;
  std::size_t handover_ends_snapped = 0;
  double handover_max_snap_m = 0.0;
  std::string handover_max_snap_lane;
  double xy_max_m = 0.0;             ///< lane centre points vs the OpenDRIVE lane centres
  std::string xy_max_lane;           ///< SUMO lane of the xy_max_m point
  double max_handover_step_m = 0.0;  ///< lane <-> internal lane height step
  double max_handover_gap_m = 0.0;   ///< lane -> internal lane -> lane plan gap
  std::string handover_gap_lanes;    ///< "from -> to" of that gap
  Vec3 handover_gap_point = Vec3::Zero();
  double max_lane_grade_percent = 0.0;           ///< normal lanes
  double max_internal_lane_grade_percent = 0.0;  ///< junction-internal lanes (connecting roads)
  double max_profile_grade_percent = 0.0;        ///< relief's profiles over the same roads
  std::size_t netconvert_warnings = 0;
  std::size_t lanes_without_z = 0;  ///< lanes with a shape point without z
  std::size_t height_steps = 0;     ///< steps along lanes and at hand-overs (sumo_checks.h)
  std::string first_step_lane;
  Vec3 first_step_point = Vec3::Zero();
  std::size_t routes = 0;  ///< vehicles in NAME.rou.xml (0: no demand asked for)
  double step_length_s = 0.0;
};

/// The 3D scene written, and its quality (the full figures are in mesh_report.json).
struct MeshSummary {
  std::vector<std::string> files;  ///< the whole scene's
  double tile_size_m = 0.0;        ///< 0: no tiles written
  std::vector<std::string> tile_files;
  /// NAME.carla.tar.gz when written (BuildOptions::carla_package), the paths inside it, and the
  /// tiles ("X Y") of its large map's grid that hold no triangles and got a placeholder.
  std::string carla_package;
  std::vector<std::string> carla_package_entries;
  std::vector<std::string> carla_placeholder_tiles;
  std::size_t junctions_meshed = 0, junctions_failed = 0;
  std::string first_failed_junction;         ///< "junction J at (x, y, z)"; empty if none failed
  double xodr_surface_max_distance_m = 0.0;  ///< road mesh vs the OpenDRIVE surface
  double seam_road_junction_m = 0.0;
  std::optional<double> seam_road_terrain_m;
  std::optional<MeshQuality> road;     ///< Road_Road
  std::optional<MeshQuality> terrain;  ///< Terrain
  std::size_t ground_holes = 0;        ///< holes of roads on the ground + terrain, welded
  std::size_t ground_components = 0;
  std::size_t ground_portals = 0;  ///< tunnel mouths: openings of the ground by design, not holes
  /// Structure triangles meshed as roads on the ground: decks within 1 m above the DEM (or
  /// below it), tunnel triangles under less than the mouth's height of DEM.
  std::size_t deck_triangles_on_ground = 0, tunnel_triangles_open = 0;
  /// Road triangles off the ground (decks, tunnels, under other roads) x Terrain, intersecting pairs.
  std::size_t structure_terrain_intersecting_pairs = 0;
  std::vector<Vec3> structure_terrain_sites;  ///< the first of those pairs' places
  /// Boundary loops of the ground (when ground_holes > 0): its holes and its tunnel mouths, which
  /// the ground's loops do not tell apart; empty when the ground has no hole.
  std::vector<Vec3> ground_hole_sites;
  /// Road triangles on the ground left out of the ground because another road lies over them
  /// in plan (plan_overlaps); the terrain closes the step between the two.
  std::size_t ground_triangles_under_roads = 0;
  std::size_t terrain_tin_vertices = 0;
  double terrain_max_vertical_error_m = 0.0;
  double terrain_max_cut_m = 0.0, terrain_max_fill_m = 0.0;
  /// Region tiles: the core's lines cut into the terrain (TerrainOptions::core): their points,
  /// the road edges they cross reached at an end, the crossings left open, the faces a flood
  /// from one side of a line met from the other (0 when the lines close); `core_lines` false:
  /// not a region tile (null in the report).
  bool core_lines = false;
  std::size_t core_line_vertices = 0, core_detours = 0, core_blocked = 0, core_leaks = 0;
};

/// One quality gate's outcome (quality_gates.h).
struct Gate {
  std::string name;
  double value = 0.0;
  double threshold = 0.0;
  bool passed = true;
  std::string where;  ///< the place of the worst case, when known and failed
};

struct RunReport {
  std::string name;
  std::string created_utc;  ///< ISO 8601
  GeoFrame frame;
  std::string osm_path;
  std::vector<DemInfo> dems;
  std::vector<DemInfo> reference_dems;
  Interpolation interpolation = Interpolation::bilinear;
  double spacing_m = 1.0;
  std::string nodata_fill;
  NetworkStats network;
  std::size_t samples = 0;
  std::size_t void_samples = 0;
  std::size_t uncovered_samples = 0;
  std::size_t roads_without_height = 0;
  std::string profile_method;         ///< the method whose profiles the outputs carry
  HeightValidation heights;           ///< of profile_method, every road
  GradeStats gradient;                ///< of profile_method
  JunctionGapStats junctions;         ///< of profile_method
  std::vector<MethodReport> methods;  ///< raw, paper, relief: the comparison
  std::optional<FitSummary> fit;
  std::optional<PaperSummary> paper;
  GradeLimits grade_limits = GradeLimits::paper();
  std::optional<OpenDriveSummary> opendrive;
  std::optional<ModelGrades> model_grades;  ///< the road model's elevation records vs the caps
  std::optional<SumoSummary> sumo;
  std::optional<MeshSummary> mesh;
  std::optional<SightSummary> sight;
  std::vector<Gate> gates;
  std::vector<std::pair<std::string, double>> timings_s;  ///< stage -> seconds, in order
  double wall_s = 0.0;               ///< the whole run's wall time (stages may overlap); 0 when not measured
  std::vector<std::string> outputs;  ///< file names written
  const Diagnostics* diagnostics = nullptr;
};

/// The report as pretty-printed JSON. Keys (stable): relief_version, name, created_utc,
/// attribution, frame{crs, origin, proj}, inputs{osm, dems[{path, crs, size_px, pixel_size,
/// vertical_unit, unit_source, nodata, transform, transform_accuracy_m, implausible_cells,
/// spike_cells, off_ground_cells (--ground-filter), missing_grids?, extent_wgs84?}], reference_dems[]},
/// settings{interpolation, spacing_m, nodata_fill}, network{roads, junctions, intersections,
/// attribute_changes, dead_ends, roundabouts, traffic_signals, bridges, tunnels, length_km,
/// bridge_km, tunnel_km, km_by_class}, elevation{samples, void_samples, uncovered_samples,
/// roads_without_height, vs_dem{mae_m, rmse_m, max_m, bias_m, n, error_3d_mean_m,
/// error_3d_max_m}, vs_reference{...} | null}, gradient{compliance_percent, max_percent,
/// p99_percent, steepest_road, by_class{class: {length_km, limit_percent, compliance_percent,
/// max_percent, p99_percent}}}, junctions{max_gap_m, worst_junction, over_bound, bound_m,
/// checked}, sumo{file, nodes, edges, connections, junctions, traffic_lights, lanes,
/// internal_lanes, internal_lanes_by_netconvert, signals_mid_road, restricted_edges{class: n},
/// max_grade_percent{class: %}, points_checked, z_max_m, z_p99_m, z_max_lane, netconvert_lanes_z_max_m,
/// draped_points_moved, drape_max_move_m, drape_max_move_lane, draped_points_added, handover_ends_extended,
/// handover_max_extension_m, handover_max_extension_lane, handover_ends_snapped, handover_max_snap_m,
/// handover_max_snap_lane, xy_max_m, xy_max_lane, max_handover_step_m, max_lane_grade_percent,
/// max_internal_lane_grade_percent, max_profile_grade_percent, netconvert_warnings, routes, step_length_s} |
/// null, profiles{method, fit{...}, paper{...}}, methods{raw|paper|relief: {vs_dem, vs_dem_ground,
/// vs_dem_structures, vs_reference, gradient, junctions, cut_fill, clearance}}, diagnostics{total,
/// counts{code: n}, messages[]}, timings_s{stage: s}, outputs[].
[[nodiscard]] std::string report_json(const RunReport& report);

/// relief's version string ("0.1.0").
[[nodiscard]] std::string relief_version();

}  // namespace relief

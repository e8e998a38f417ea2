#pragma once
// The co-simulation loop (issue 16): SUMO runs the traffic in lockstep steps (0.05 s, 20 Hz), and
// every SUMO vehicle, every step, is set down on relief's 3D surface (the build's scene) on its
// four wheel contacts (vehicle_pose.h): z, pitch and roll from the surface, plan position and
// heading from SUMO. Each placement is measured against the
// OpenDRIVE surface S(road, s, t) of the vehicle's lane (sumo_surface.h): the vehicle's height,
// its pitch against the road's slope along its heading, and SUMO's own lane height.
//
// Inputs come from one relief build: NAME.sumocfg names NAME.net.xml (its net-file), and
// NAME.xodr and NAME.glb lie beside that net. The surface is the scene the .glb carries (roads,
// junctions, sidewalks, terrain: a wheel that leaves the pavement finds the ground), read as it
// was shipped; without a .glb, the .xodr's roads lofted within mesh_tolerance_m.

#include <cstddef>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "relief/core/diagnostics.h"
#include "relief/cosim/ego_controller.h"
#include "relief/cosim/sumo_session.h"

namespace relief {

/// The figures of a run, in the output directory.
inline constexpr const char* kCosimReportFile = "cosim.json";
/// The replay: the scene and every vehicle as an animated box (export/mesh_writer.h).
inline constexpr const char* kCosimReplayFile = "cosim.glb";
/// The co-simulation's figures for a person (and, with LiDARs, their occlusion plot), in the output
/// directory.
inline constexpr const char* kCosimHtmlFile = "cosim.html";
/// The replay in the build's 3D view (when the build wrote view.html): a view.html that loads the
/// build's view/ tiles and replay.js, the vehicles' keys.
inline constexpr const char* kCosimViewFile = "view.html";
inline constexpr const char* kCosimViewReplayFile = "replay.js";

struct CosimInputs {
  std::filesystem::path sumocfg;
  std::filesystem::path net;    ///< the configuration's net-file
  std::filesystem::path xodr;   ///< beside the net: NAME.xodr for NAME.net.xml
  std::filesystem::path scene;  ///< beside the net: NAME.glb; empty when there is none
};

/// Finds the net, the .xodr and the scene of a SUMO configuration written for a relief build.
/// Throws IoError when the net or the .xodr is missing, InvalidInput when the configuration is
/// not XML or names no net-file (the messages name the file).
[[nodiscard]] CosimInputs find_cosim_inputs(const std::filesystem::path& sumocfg);

/// A LiDAR on an ego (relief/sight/lidar.h): a preset, on the named ego or else the first ego,
/// at this height over the ground under the ego's centre.
struct LidarMount {
  std::string preset = "hdl-64e";
  std::string ego;  ///< empty: the first ego
  double height_m = 1.9;
};

/// What the egos' LiDARs saw: per completed sweep (one turn), every other vehicle within range
/// and any of it within the fields of view counted as seen (at least `lidar_min_returns` returns on it) or
/// hidden, and by what: the line from the sensor to the vehicle's centre meets the road (a crest), the
/// terrain, another vehicle, or nothing (too few returns: beyond the sensor's resolution, or outside its
/// fields of view).
struct LidarFigures {
  std::size_t sensors = 0;
  std::size_t sweeps = 0;
  std::size_t sweeps_written = 0;  ///< point clouds written (PCD and PLY each)
  std::size_t points = 0;
  std::size_t rays = 0;
  double seconds = 0.0;  ///< of relief_s: the LiDARs' rays and files
  std::size_t checked = 0, seen = 0;
  std::size_t hidden_by_road = 0, hidden_by_terrain = 0, hidden_by_vehicle = 0, hidden_sparse = 0;
  /// Distance from the sensor at which a vehicle the road hid in the sweep before was first seen.
  std::vector<float> seen_after_crest_m;
  /// The places where the road hid a vehicle (crests), grouped in 25 m cells: where the hidden
  /// lines of sight met the road (their mean), how many sweeps it hid one, and the distances at
  /// which the vehicles it hid were first seen.
  struct Crest {
    Vec3 point = Vec3::Zero();
    double lon = 0.0, lat = 0.0;
    std::size_t hidden = 0;
    std::vector<float> first_seen_m;
  };
  std::vector<Crest> crests;  ///< most hidden first
  /// Per sweep: its time and the vehicles in range seen and hidden (road, terrain, vehicle, too few returns).
  struct Tick {
    double t = 0.0;
    std::size_t seen = 0, road = 0, terrain = 0, vehicle = 0, sparse = 0;
  };
  std::vector<Tick> timeline;
  std::vector<std::string> written;  ///< the first point-cloud files, relative to out_dir
};

struct CosimOptions {
  double step_s = 0.05;               ///< lockstep step (SUMO's --step-length)
  std::optional<double> end_s;        ///< stop at this simulated time; default: the configuration's end,
                                      ///< or when SUMO has no vehicle left to run
  double mesh_tolerance_m = 0.005;    ///< chord tolerance of the road surface lofted without a .glb
  double wheel_under_limit_m = 0.05;  ///< a wheel whose surface lies this far above the body counts
  /// A wheel's surface must lie this close to where SUMO has the vehicle (vehicle_pose.h).
  double max_contact_gap_m = 1.0;
  double trajectory_period_s = 0.0;    ///< trajectory rows this often (0: every step)
  double replay_period_s = 0.5;        ///< replay keys this often (0: no cosim.glb)
  std::vector<std::string> sumo_args;  ///< extra SUMO command-line arguments
  /// Which SUMO: in this process (default), launched over TraCI (sumo-gui to watch), or one
  /// already running (sumo_session.h).
  SumoEndpoint sumo;
  /// Ego vehicles, driven by the physics (ego_world.h) instead of SUMO: these ids, and the
  /// first `ego_count` vehicles to depart (of type `ego_type` when it is set).
  std::vector<std::string> egos;
  std::size_t ego_count = 0;
  std::string ego_type;
  /// An ego whose plan position in SUMO and in the physics lie farther apart than this after
  /// a step is resynchronised: the physics yields (the body is set onto SUMO's lane at SUMO's
  /// position and heading, keeping its speed), SUMO keeps its route and its traffic.
  double resync_m = 0.5;
  EgoDriverOptions driver;
  /// LiDARs on the egos; their point clouds (PCD and PLY, one per turn) every lidar_every_s into
  /// out_dir/lidar/EGO/K_PRESET/NNNNNN.{pcd,ply} (K the sensor's index, NNNNNN its sweep).
  std::vector<LidarMount> lidars;
  double lidar_every_s = 1.0;
  std::size_t lidar_min_returns = 3;
  /// Called about once per simulated 10 s: (simulated time, vehicles now).
  std::function<void(double, std::size_t)> progress;
  /// Polled every step; true ends the run cleanly (what was simulated is written).
  std::function<bool()> stop_requested;
};

/// Percentiles of a measure over every vehicle and step.
struct Spread {
  double p50 = 0.0, p99 = 0.0, max = 0.0;
  std::size_t count = 0;
};

struct CosimResult {
  std::size_t steps = 0;
  double simulated_s = 0.0;
  std::size_t vehicles = 0;          ///< distinct vehicles seen
  std::size_t vehicle_steps = 0;     ///< vehicles x steps placed
  std::size_t max_vehicles = 0;      ///< most at one step
  std::size_t unplaced = 0;          ///< vehicle-steps with two or more contacts on no surface near
  std::size_t unmapped = 0;          ///< vehicle-steps whose centre is on no OpenDRIVE road of its lanes
  std::size_t off_pavement = 0;      ///< wheel contacts on a surface other than road or junction
  std::size_t contacts_missing = 0;  ///< wheel contacts with no surface near (vehicle_pose.h)
  double wall_s = 0.0, sumo_s = 0.0, relief_s = 0.0, setup_s = 0.0;
  bool stopped = false;           ///< ended by stop_requested
  Spread z_error_m;               ///< |placed z - S(road, s, t).z| at the vehicle's centre
  Spread z_error_on_roads_m;      ///< the same where the centre is on a road's lane
  Spread z_error_in_junctions_m;  ///< the same where it is on an internal lane (a junction)
  /// |placed z - the same wheel contacts' mean on the OpenDRIVE surface|: the vehicle set on the
  /// scene against the vehicle set the same way on the .xodr (the body's own sag over a crest,
  /// in both, cancels), where every contact lies on the centre's road; and split as above.
  Spread z_error_body_m, z_error_body_on_roads_m, z_error_body_in_junctions_m;
  Spread sumo_z_error_m;                ///< |SUMO's z - S(road, s, t).z| at the front bumper
  Spread pitch_error_deg;               ///< |pitch - atan(surface slope along the heading)|
  Spread wheel_under_m;                 ///< the deepest contact per vehicle-step (0 when none is under)
  std::size_t wheels_under_road = 0;    ///< contacts deeper than wheel_under_limit_m
  std::string worst_z_place;            ///< vehicle, time, lane and (x, y) of the largest z error
  std::string worst_body_place;         ///< the same for the largest z_error_body_m
  std::string worst_wheel_under_place;  ///< the same for the deepest wheel_under_m
  // The egos.
  std::size_t egos = 0;       ///< distinct ego vehicles driven
  std::size_t ego_steps = 0;  ///< egos x steps
  Spread sync_error_m;        ///< plan distance of SUMO's front bumper from the physics' after a step
  std::size_t resyncs = 0;
  std::size_t ego_steps_held = 0;       ///< steps SUMO drove an ego (its place on its route was ambiguous)
  std::vector<std::string> resync_log;  ///< the first 100: vehicle, time, error, place
  Spread ego_speed_gap_mps;             ///< |SUMO's speed - the physics' speed| of an ego after a step
  /// The egos' z are the physics' bodies on their suspension, not placements: their |z - S.z| at
  /// the centre is measured apart from the vehicles set on the surface (z_error_m and the rest
  /// above), over the steps with all four wheels on the ground; with a wheel off the ground (a
  /// crest taken fast lifts it, vehicle_pose.h wheels_in_air) counted apart, with the largest.
  Spread ego_z_error_m;
  std::string worst_ego_z_place;  ///< vehicle, time, lane and (x, y) of ego_z_error_m.max
  std::size_t ego_steps_wheels_in_air = 0;
  double wheels_in_air_z_max_m = 0.0;
  std::string worst_in_air_place;  ///< the same for wheels_in_air_z_max_m
  double physics_s = 0.0;          ///< of relief_s: the egos' physics and driving
  LidarFigures lidar;
  [[nodiscard]] double real_time_factor() const { return wall_s > 0.0 ? simulated_s / wall_s : 0.0; }
};

/// Runs the co-simulation and writes, in `out_dir` (created), cosim.json, NAME.fcd.xml (SUMO's
/// FCD format, each vehicle with pitch and roll added), NAME.trajectories.csv and the replay
/// cosim.glb (the surface and every vehicle as a box of its SUMO size, animated), all
/// atomically after the run. Throws IoError / InvalidInput for unreadable inputs (the file and
/// the problem), Error when SUMO fails.
CosimResult run_cosim(const CosimInputs& inputs, const CosimOptions& options,
                      const std::filesystem::path& out_dir, Diagnostics& diagnostics);

}  // namespace relief

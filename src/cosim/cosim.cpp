#include "relief/cosim/cosim.h"

#include <nlohmann/json.hpp>
#include <pugixml.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <string>
#include <unordered_map>
#include <vector>

#include "cosim/cosim_report.h"
#include "cosim/ego_drivers.h"
#include "cosim/lidar_rig.h"
#include "cosim/placement_measures.h"
#include "cosim/trajectory_writer.h"
#include "relief/core/atomic_file.h"
#include "relief/core/errors.h"
#include "relief/cosim/sumo_session.h"
#include "relief/cosim/vehicle_pose.h"
#include "relief/export/mesh_writer.h"
#include "relief/export/sumo_surface.h"
#include "relief/export/sumo_tools.h"
#include "relief/roads/opendrive_reader.h"
#include "relief/scene/road_mesh.h"
#include "relief/scene/surface_query.h"
#include "relief/viewer/view_writer.h"

namespace relief {
namespace {

using Clock = std::chrono::steady_clock;
using Json = nlohmann::ordered_json;

constexpr double kDegree = 180.0 / std::numbers::pi;
constexpr double kProgressEvery_s = 10.0;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

Json spread_json(const Spread& s) {
  return Json{{"p50", s.p50}, {"p99", s.p99}, {"max", s.max}, {"count", s.count}};
}

// The 20 crests that hid most, with where and how far away their vehicles were first seen.
Json crests_json(const std::vector<LidarFigures::Crest>& crests) {
  Json out = Json::array();
  for (std::size_t k = 0; k < std::min<std::size_t>(20, crests.size()); ++k) {
    const LidarFigures::Crest& c = crests[k];
    std::vector<float> seen = c.first_seen_m;
    out.push_back({{"x", c.point.x()},
                   {"y", c.point.y()},
                   {"z", c.point.z()},
                   {"lonlat", {c.lon, c.lat}},
                   {"hidden_sweeps", c.hidden},
                   {"first_seen_m", spread_json(detail::spread_of(seen))}});
  }
  return out;
}

void write_cosim_json(const std::filesystem::path& path, const CosimInputs& inputs,
                      const CosimOptions& options, const CosimResult& r) {
  const double run_s = r.sumo_s + r.relief_s;
  Json j;
  j["inputs"] = {{"sumocfg", inputs.sumocfg.string()},
                 {"net", inputs.net.string()},
                 {"xodr", inputs.xodr.string()},
                 {"scene", inputs.scene.string()}};  // empty: the .xodr's roads lofted
  j["step_s"] = options.step_s;
  j["sumo"] = options.sumo.describe();
  j["steps"] = r.steps;
  j["simulated_s"] = r.simulated_s;
  j["stopped_early"] = r.stopped;
  j["vehicles"] = r.vehicles;
  j["max_vehicles"] = r.max_vehicles;
  j["vehicle_steps"] = r.vehicle_steps;
  j["unplaced_vehicle_steps"] = r.unplaced;
  j["unmapped_vehicle_steps"] = r.unmapped;
  j["wall_s"] = r.wall_s;
  j["setup_s"] = r.setup_s;
  j["real_time_factor"] = r.real_time_factor();
  j["sumo_share"] = run_s > 0.0 ? r.sumo_s / run_s : 0.0;
  j["relief_share"] = run_s > 0.0 ? r.relief_s / run_s : 0.0;
  j["physics_share"] = run_s > 0.0 ? r.physics_s / run_s : 0.0;
  j["egos"] = r.egos;
  j["ego_steps"] = r.ego_steps;
  // Without egos every vehicle stands where SUMO puts it: no sync error to measure.
  j["sync_error_m"] = r.egos > 0 ? spread_json(r.sync_error_m) : Json(nullptr);
  j["resync_m"] = options.resync_m;
  j["resyncs"] = r.resyncs;
  j["ego_steps_held_by_sumo"] = r.ego_steps_held;
  j["resync_log"] = r.resync_log;
  j["ego_speed_gap_mps"] = r.egos > 0 ? spread_json(r.ego_speed_gap_mps) : Json(nullptr);
  j["ego_z_error_m"] = r.egos > 0 ? spread_json(r.ego_z_error_m) : Json(nullptr);
  j["worst_ego_z_place"] = r.worst_ego_z_place;
  j["ego_steps_wheels_in_air"] = r.ego_steps_wheels_in_air;
  j["wheels_in_air_z_max_m"] = r.wheels_in_air_z_max_m;
  j["worst_in_air_place"] = r.worst_in_air_place;
  if (options.lidars.empty()) {
    j["lidar"] = nullptr;
  } else {
    const LidarFigures& l = r.lidar;
    Json sensors = Json::array();
    for (const LidarMount& m : options.lidars)
      sensors.push_back(
          {{"preset", m.preset}, {"ego", m.ego.empty() ? "(first ego)" : m.ego}, {"height_m", m.height_m}});
    std::vector<float> crest = l.seen_after_crest_m;
    j["lidar"] = {{"sensors", sensors},
                  {"sweeps", l.sweeps},
                  {"sweeps_written", l.sweeps_written},
                  {"every_s", options.lidar_every_s},
                  {"points", l.points},
                  {"rays", l.rays},
                  {"seconds", l.seconds},
                  {"rays_per_s", l.seconds > 0.0 ? static_cast<double>(l.rays) / l.seconds : 0.0},
                  {"min_returns", options.lidar_min_returns},
                  {"vehicles_checked", l.checked},
                  {"seen", l.seen},
                  {"hidden_by",
                   {{"road", l.hidden_by_road},
                    {"terrain", l.hidden_by_terrain},
                    {"vehicle", l.hidden_by_vehicle},
                    {"too_few_returns", l.hidden_sparse}}},
                  {"seen_after_crest_m", spread_json(detail::spread_of(crest))},
                  {"crests", crests_json(l.crests)},
                  {"files", l.written}};
  }
  j["z_error_m"] = spread_json(r.z_error_m);
  j["z_error_on_roads_m"] = spread_json(r.z_error_on_roads_m);
  j["z_error_in_junctions_m"] = spread_json(r.z_error_in_junctions_m);
  j["z_error_body_m"] = spread_json(r.z_error_body_m);
  j["z_error_body_on_roads_m"] = spread_json(r.z_error_body_on_roads_m);
  j["z_error_body_in_junctions_m"] = spread_json(r.z_error_body_in_junctions_m);
  j["sumo_z_error_m"] = spread_json(r.sumo_z_error_m);
  j["pitch_error_deg"] = spread_json(r.pitch_error_deg);
  j["wheel_under_m"] = spread_json(r.wheel_under_m);
  j["wheels_under_road"] = r.wheels_under_road;
  j["wheel_contacts_off_pavement"] = r.off_pavement;
  j["wheel_contacts_off_surface"] = r.contacts_missing;
  j["wheel_under_limit_m"] = options.wheel_under_limit_m;
  j["worst_z_place"] = r.worst_z_place;
  j["worst_body_place"] = r.worst_body_place;
  j["worst_wheel_under_place"] = r.worst_wheel_under_place;
  write_file_atomically(path, j.dump(2) + "\n");
}

// The build's scene when there is one, else the .xodr's roads lofted within the tolerance.
MeshScene load_surface(const CosimInputs& inputs, const RoadModel& model, const CosimOptions& options,
                       Diagnostics& diagnostics) {
  if (!inputs.scene.empty()) return read_mesh_file(inputs.scene);
  RoadMeshOptions mesh_options;
  mesh_options.tolerance_m = options.mesh_tolerance_m;
  mesh_options.markings = false;
  RoadMeshes meshes = build_road_meshes(model, mesh_options, diagnostics);
  MeshScene scene;
  scene.frame = model.frame;
  scene.meshes.push_back(std::move(meshes.road));
  return scene;
}

// The replay's keys: every vehicle every `period` seconds, tracks in order of first appearance.
class ReplayRecorder {
 public:
  explicit ReplayRecorder(double period_s) : period_s_(period_s) {}

  /// Whether time t takes keys (then the next key is a period later).
  bool due(double t) {
    if (!(period_s_ > 0.0) || t < next_ - 1e-9) return false;
    next_ = t + period_s_;
    return true;
  }
  void add(const SumoVehicleState& v, const SurfacePose& pose, double t) {
    auto [it, added] = index_.try_emplace(v.id, tracks_.size());
    if (added) {
      ReplayTrack& track = tracks_.emplace_back();
      track.name = v.id;
      track.length_m = v.length_m;
      track.width_m = v.width_m;
      track.height_m = v.height_m > 0.0 ? v.height_m : 1.5;
    }
    ReplayTrack& track = tracks_[it->second];
    const Vec2 centre = v.centre();
    track.keys.push_back(
        {t, Vec3(centre.x(), centre.y(), pose.z_m), v.heading(), pose.pitch_rad, pose.roll_rad});
    track.hide_after_s = t + period_s_;
  }
  std::vector<ReplayTrack> take_tracks() { return std::move(tracks_); }

 private:
  double period_s_;
  double next_ = 0.0;
  std::unordered_map<std::string, std::size_t> index_;
  std::vector<ReplayTrack> tracks_;
};

}  // namespace

CosimInputs find_cosim_inputs(const std::filesystem::path& sumocfg) {
  pugi::xml_document doc;
  if (!std::filesystem::is_regular_file(sumocfg)) throw IoError("cannot read '" + sumocfg.string() + "'");
  const pugi::xml_parse_result parsed = doc.load_file(sumocfg.c_str());
  if (!parsed) throw InvalidInput("'" + sumocfg.string() + "' is not XML: " + parsed.description());
  const pugi::xml_node net_file = doc.child("configuration").find_node([](const pugi::xml_node& n) {
    return std::string_view(n.name()) == "net-file";
  });
  const std::string value = net_file.attribute("value").as_string();
  if (value.empty())
    throw InvalidInput("'" + sumocfg.string() + "' names no net-file (<input><net-file value=.../>)");
  CosimInputs inputs;
  inputs.sumocfg = sumocfg;
  inputs.net = std::filesystem::path(value).is_absolute() ? std::filesystem::path(value)
                                                          : sumocfg.parent_path() / value;
  if (!std::filesystem::is_regular_file(inputs.net))
    throw IoError("cannot read the net '" + inputs.net.string() + "' named by '" + sumocfg.string() + "'");
  // SUMO reads the files a configuration names from its folder and splits file options at
  // commas: a comma in that path cuts it apart, and SUMO fails on a file that does not exist.
  if (std::filesystem::absolute(inputs.net).string().find(',') != std::string::npos)
    throw InvalidInput("SUMO cannot read '" + std::filesystem::absolute(inputs.net).string() +
                       "': it splits file paths at commas; move or link the build to a path without one");
  inputs.xodr = inputs.net.parent_path() / (sumo_net_name(inputs.net) + ".xodr");
  if (!std::filesystem::is_regular_file(inputs.xodr))
    throw IoError("cannot read '" + inputs.xodr.string() +
                  "': relief cosim needs the OpenDRIVE file of the net's build beside it");
  const std::filesystem::path glb = inputs.net.parent_path() / (sumo_net_name(inputs.net) + ".glb");
  if (std::filesystem::is_regular_file(glb)) inputs.scene = glb;
  return inputs;
}

CosimResult run_cosim(const CosimInputs& inputs, const CosimOptions& options,
                      const std::filesystem::path& out_dir, Diagnostics& diagnostics) {
  if (!(std::isfinite(options.step_s) && options.step_s > 0.0))
    throw InvalidInput("the co-simulation step must be a finite number > 0");
  if (options.end_s && !(std::isfinite(*options.end_s) && *options.end_s > 0.0))
    throw InvalidInput("the co-simulation end must be a finite time > 0");
  if (!(std::isfinite(options.resync_m) && options.resync_m > 0.0))
    throw InvalidInput("the resync distance must be a finite number > 0");
  const Clock::time_point start = Clock::now();
  CosimResult result;

  // The surface, and the net's lanes mapped onto the OpenDRIVE roads to measure against.
  const RoadModel model = read_opendrive(inputs.xodr);
  const MeshScene scene = load_surface(inputs, model, options, diagnostics);
  const SurfaceQuery query(scene);
  SumoSurface odr(inputs.net, model);
  detail::PlacementMeasures measures(odr, options);
  ReplayRecorder replay(options.replay_period_s);

  std::filesystem::create_directories(out_dir);
  const std::string name = sumo_net_name(inputs.net);
  detail::TrajectoryWriter trajectories(out_dir / (name + ".fcd.xml"),
                                        out_dir / (name + ".trajectories.csv"));

  SumoSession sumo(inputs.sumocfg, options.step_s, options.sumo_args, options.sumo);
  detail::EgoDrivers egos(scene, query, sumo, options);
  detail::LidarRig lidars(scene, options, out_dir, model.frame);
  std::vector<detail::PlacedVehicle> placed;
  const double configured_end = sumo.end_time();
  const std::optional<double> end = options.end_s          ? options.end_s
                                    : configured_end > 0.0 ? std::optional<double>(configured_end)
                                                           : std::nullopt;
  result.setup_s = seconds_since(start);

  double next_progress = kProgressEvery_s, next_row = 0.0;
  for (;;) {
    if (end && sumo.time() >= *end - 1e-9) break;
    if (!end && sumo.expected() <= 0) break;
    if (options.stop_requested && options.stop_requested()) {
      result.stopped = true;
      break;
    }
    Clock::time_point t0 = Clock::now();
    sumo.step();
    std::vector<SumoVehicleState> vehicles = sumo.vehicles();
    result.sumo_s += seconds_since(t0);
    t0 = Clock::now();
    ++result.steps;
    const double t = result.simulated_s = sumo.time();
    egos.after_sumo_step(vehicles, t, result);
    result.max_vehicles = std::max(result.max_vehicles, vehicles.size());
    const bool write_rows = t >= next_row - 1e-9;
    if (write_rows) {
      next_row = t + options.trajectory_period_s;
      trajectories.begin_step(t);
    }
    const bool add_keys = replay.due(t);
    placed.clear();
    for (const SumoVehicleState& v : vehicles) {
      measures.track_lane(v);
      // Where SUMO has the vehicle: its front's height and its slope.
      const double slope = v.slope_deg * std::numbers::pi / 180.0;
      const std::optional<SurfacePose> pose =
          egos.is_ego(v.id)
              ? egos.pose(v.id)
              : place_on_surface(query, v.centre(), v.heading(), wheel_base_of(v.length_m, v.width_m),
                                 v.front.z() - std::tan(slope) * 0.5 * v.length_m, slope,
                                 options.max_contact_gap_m);
      if (!pose) {
        measures.unplaced(v, t, result);
        continue;
      }
      measures.add(v, *pose, t, result, !egos.is_ego(v.id));
      if (lidars.active()) placed.push_back({&v, *pose, egos.is_ego(v.id)});
      if (add_keys) replay.add(v, *pose, t);
      if (write_rows) {
        const Vec2 centre = v.centre();
        trajectories.add({&v.id, &v.type, &v.lane, centre.x(), centre.y(), pose->z_m, v.angle_deg,
                          v.speed_mps, pose->pitch_rad * kDegree, pose->roll_rad * kDegree});
      }
    }
    if (write_rows) trajectories.end_step();
    lidars.step(t, options.step_s, placed);
    const Clock::time_point physics = Clock::now();
    egos.drive(options.step_s);  // the egos' poses reach SUMO with its next step
    result.physics_s += seconds_since(physics);
    result.relief_s += seconds_since(t0);
    if (options.progress && t >= next_progress - 1e-9) {
      options.progress(t, vehicles.size());
      next_progress += kProgressEvery_s;
    }
  }
  measures.finish(result, diagnostics);
  egos.finish(result, diagnostics);
  lidars.finish(result);
  OutputSet outputs;
  if (options.replay_period_s > 0.0) {
    const std::vector<ReplayTrack> tracks = replay.take_tracks();
    const std::string bytes = encode_replay_glb(scene, tracks);
    outputs.add(out_dir / kCosimReplayFile, [&](std::ostream& out) { out << bytes; });
    // The build's view with the traffic on it, when the build wrote one.
    const std::filesystem::path view_dir = inputs.net.parent_path() / "view";
    if (std::filesystem::is_regular_file(view_dir / "index.js")) {
      ViewPageOptions page;
      page.data_dir =
          std::filesystem::relative(std::filesystem::absolute(view_dir), std::filesystem::absolute(out_dir))
              .generic_string();
      page.report = kCosimHtmlFile;
      page.scripts = {kCosimViewReplayFile};
      const std::string script = view_replay_script(tracks);
      outputs.add(out_dir / kCosimViewReplayFile, [&](std::ostream& out) { out << script; });
      outputs.add(out_dir / kCosimViewFile, [&](std::ostream& out) {
        out << view_page(name + " - relief co-simulation replay", page);
      });
    }
  }
  trajectories.commit();
  outputs.commit();
  result.wall_s = seconds_since(start);
  write_cosim_json(out_dir / kCosimReportFile, inputs, options, result);
  write_file_atomically(out_dir / kCosimHtmlFile, detail::cosim_html(inputs, options, result));
  return result;
}

}  // namespace relief

#include "relief/cosim/cosim.h"

#include <nlohmann/json.hpp>
#include <pugixml.hpp>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <numbers>
#include <sstream>
#include <unordered_map>

#include "cosim/trajectory_writer.h"
#include "relief/core/atomic_file.h"
#include "relief/core/diagnostic_codes.h"
#include "relief/core/errors.h"
#include "relief/cosim/sumo_session.h"
#include "relief/cosim/vehicle_pose.h"
#include "relief/export/mesh_writer.h"
#include "relief/export/sumo_surface.h"
#include "relief/roads/opendrive_reader.h"
#include "relief/scene/road_mesh.h"
#include "relief/scene/surface_query.h"

namespace relief {
namespace {

using Clock = std::chrono::steady_clock;
using Json = nlohmann::ordered_json;

constexpr double kDegree = 180.0 / std::numbers::pi;
constexpr double kProgressEvery_s = 10.0;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// The median, 99th percentile (the value at rank floor(0.99 (n - 1))) and largest value.
Spread spread_of(std::vector<float>& values) {
  Spread s;
  s.count = values.size();
  if (values.empty()) return s;
  const auto at = [&](double q) {
    const auto k = static_cast<std::size_t>(q * static_cast<double>(values.size() - 1));
    std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(k), values.end());
    return static_cast<double>(values[k]);
  };
  s.p50 = at(0.5);
  s.p99 = at(0.99);
  s.max = static_cast<double>(*std::max_element(values.begin(), values.end()));
  return s;
}

Json spread_json(const Spread& s) {
  return Json{{"p50", s.p50}, {"p99", s.p99}, {"max", s.max}, {"count", s.count}};
}

std::string net_stem(const std::filesystem::path& net) {
  std::string name = net.filename().string();
  for (const std::string suffix : {".net.xml.gz", ".net.xml"}) {
    if (name.size() > suffix.size() && name.ends_with(suffix))
      return name.substr(0, name.size() - suffix.size());
  }
  return net.stem().string();
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
  j["egos"] = 0;
  j["sync_error_m"] = nullptr;  // no ego vehicles: every vehicle stands where SUMO puts it
  j["resyncs"] = 0;
  j["z_error_m"] = spread_json(r.z_error_m);
  j["z_error_on_roads_m"] = spread_json(r.z_error_on_roads_m);
  j["z_error_in_junctions_m"] = spread_json(r.z_error_in_junctions_m);
  j["sumo_z_error_m"] = spread_json(r.sumo_z_error_m);
  j["pitch_error_deg"] = spread_json(r.pitch_error_deg);
  j["wheel_under_m"] = spread_json(r.wheel_under_m);
  j["wheels_under_road"] = r.wheels_under_road;
  j["wheel_contacts_off_pavement"] = r.off_pavement;
  j["wheel_contacts_off_surface"] = r.contacts_missing;
  j["wheel_under_limit_m"] = options.wheel_under_limit_m;
  j["worst_z_place"] = r.worst_z_place;
  write_file_atomically(path, j.dump(2) + "\n");
}

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
  inputs.xodr = inputs.net.parent_path() / (net_stem(inputs.net) + ".xodr");
  if (!std::filesystem::is_regular_file(inputs.xodr))
    throw IoError("cannot read '" + inputs.xodr.string() +
                  "': relief cosim needs the OpenDRIVE file of the net's build beside it");
  const std::filesystem::path glb = inputs.net.parent_path() / (net_stem(inputs.net) + ".glb");
  if (std::filesystem::is_regular_file(glb)) inputs.scene = glb;
  return inputs;
}

CosimResult run_cosim(const CosimInputs& inputs, const CosimOptions& options,
                      const std::filesystem::path& out_dir, Diagnostics& diagnostics) {
  if (!(std::isfinite(options.step_s) && options.step_s > 0.0))
    throw InvalidInput("the co-simulation step must be a finite number > 0");
  if (options.end_s && !(std::isfinite(*options.end_s) && *options.end_s > 0.0))
    throw InvalidInput("the co-simulation end must be a finite time > 0");
  const Clock::time_point start = Clock::now();
  CosimResult result;

  // The surface (the build's scene, else the .xodr's roads lofted), and the net's lanes mapped
  // onto the OpenDRIVE roads to measure against.
  const RoadModel model = read_opendrive(inputs.xodr);
  MeshScene scene;
  if (!inputs.scene.empty()) {
    scene = read_mesh_file(inputs.scene);
  } else {
    RoadMeshOptions mesh_options;
    mesh_options.tolerance_m = options.mesh_tolerance_m;
    mesh_options.markings = false;
    RoadMeshes meshes = build_road_meshes(model, mesh_options, diagnostics);
    scene.frame = model.frame;
    scene.meshes.push_back(std::move(meshes.road));
  }
  const SurfaceQuery query(scene);
  SumoSurface odr(inputs.net, model);

  std::filesystem::create_directories(out_dir);
  const std::string name = net_stem(inputs.net);
  detail::TrajectoryWriter trajectories(out_dir / (name + ".fcd.xml"),
                                        out_dir / (name + ".trajectories.csv"));

  SumoSession sumo(inputs.sumocfg, options.step_s, options.sumo_args);
  const double configured_end = sumo.end_time();
  const std::optional<double> end = options.end_s          ? options.end_s
                                    : configured_end > 0.0 ? std::optional<double>(configured_end)
                                                           : std::nullopt;
  result.setup_s = seconds_since(start);

  std::vector<float> z_errors, z_errors_road, z_errors_junction, sumo_z_errors, pitch_errors, wheel_under;
  // The last lanes of every vehicle, newest first: its centre, half a length behind the front
  // bumper, may still be on a lane the bumper has left.
  std::unordered_map<std::string, std::array<std::string, 3>> recent;
  double worst_z = -1.0;
  std::string first_unplaced, first_unmapped;
  double next_progress = kProgressEvery_s, next_row = 0.0, next_key = 0.0;
  std::unordered_map<std::string, ReplayTrack> replay;
  std::vector<std::string> replay_order;  // first appearance: the replay's node order
  for (;;) {
    const double now = sumo.time();
    if (end && now >= *end - 1e-9) break;
    if (!end && sumo.expected() <= 0) break;
    if (options.stop_requested && options.stop_requested()) {
      result.stopped = true;
      break;
    }
    Clock::time_point t0 = Clock::now();
    sumo.step();
    const std::vector<SumoVehicleState> vehicles = sumo.vehicles();
    result.sumo_s += seconds_since(t0);
    t0 = Clock::now();
    ++result.steps;
    result.simulated_s = sumo.time();
    result.max_vehicles = std::max(result.max_vehicles, vehicles.size());
    const bool write_rows = result.simulated_s >= next_row - 1e-9;
    const bool add_keys = options.replay_period_s > 0.0 && result.simulated_s >= next_key - 1e-9;
    if (add_keys) next_key = result.simulated_s + options.replay_period_s;
    if (write_rows) {
      next_row = result.simulated_s + options.trajectory_period_s;
      trajectories.begin_step(result.simulated_s);
    }
    for (const SumoVehicleState& v : vehicles) {
      std::array<std::string, 3>& lanes = recent[v.id];
      if (lanes[0] != v.lane) {
        std::rotate(lanes.rbegin(), lanes.rbegin() + 1, lanes.rend());
        lanes[0] = v.lane;
      }
      const Vec2 centre = v.centre();
      const double heading = v.heading();
      // Where SUMO has the vehicle: its front's height and its slope.
      const double slope = v.slope_deg * std::numbers::pi / 180.0;
      const std::optional<SurfacePose> pose = place_on_surface(
          query, centre, heading, wheel_base_of(v.length_m, v.width_m),
          v.front.z() - std::tan(slope) * 0.5 * v.length_m, slope, options.max_contact_gap_m);
      if (!pose) {
        if (result.unplaced++ == 0) {
          std::ostringstream where;
          where << "vehicle '" << v.id << "' on lane '" << v.lane << "' at t = " << result.simulated_s
                << " s (" << centre.x() << ", " << centre.y() << ")";
          first_unplaced = where.str();
        }
        continue;
      }
      ++result.vehicle_steps;
      result.contacts_missing += static_cast<std::size_t>(pose->contacts_missing);
      const double deepest =
          std::max(0.0, *std::max_element(pose->wheel_under_m.begin(), pose->wheel_under_m.end()));
      wheel_under.push_back(static_cast<float>(deepest));
      for (const double under : pose->wheel_under_m)
        if (under > options.wheel_under_limit_m) ++result.wheels_under_road;
      for (const SurfaceKind kind : pose->wheel_kind)
        if (kind != SurfaceKind::road && kind != SurfaceKind::junction) ++result.off_pavement;
      std::optional<LaneSurfacePoint> at_centre;
      const std::string* centre_lane = nullptr;
      for (const std::string& lane : lanes) {
        if (lane.empty()) break;
        at_centre = odr.at(lane, centre);
        if (at_centre && at_centre->on_road()) {
          centre_lane = &lane;
          break;
        }
        at_centre.reset();
      }
      const std::optional<LaneSurfacePoint> at_front = odr.at(v.lane, Vec2(v.front.x(), v.front.y()));
      const std::optional<double> odr_slope =
          centre_lane ? odr.slope(*centre_lane, centre, heading) : std::optional<double>();
      if (at_front && at_front->on_road())
        sumo_z_errors.push_back(static_cast<float>(std::abs(v.front.z() - at_front->z_m)));
      if (!at_centre || !odr_slope) {
        if (result.unmapped++ == 0)
          first_unmapped = "lane '" + v.lane + "' at t = " + std::to_string(result.simulated_s) + " s";
      } else {
        const double z_error = std::abs(pose->z_m - at_centre->z_m);
        z_errors.push_back(static_cast<float>(z_error));
        (centre_lane->starts_with(':') ? z_errors_junction : z_errors_road)
            .push_back(static_cast<float>(z_error));
        pitch_errors.push_back(
            static_cast<float>(std::abs(pose->pitch_rad - std::atan(*odr_slope)) * kDegree));
        if (z_error > worst_z) {
          worst_z = z_error;
          std::ostringstream where;
          where << "vehicle '" << v.id << "' at t = " << result.simulated_s << " s on lane '" << v.lane
                << "' (OpenDRIVE road " << at_centre->odr_road << ", s = " << at_centre->s << ") at ("
                << centre.x() << ", " << centre.y() << "): " << z_error << " m";
          result.worst_z_place = where.str();
        }
      }
      if (add_keys) {
        auto [track, added] = replay.try_emplace(v.id);
        if (added) {
          replay_order.push_back(v.id);
          track->second.name = v.id;
          track->second.length_m = v.length_m;
          track->second.width_m = v.width_m;
          track->second.height_m = v.height_m > 0.0 ? v.height_m : 1.5;
        }
        track->second.keys.push_back({result.simulated_s, Vec3(centre.x(), centre.y(), pose->z_m), heading,
                                      pose->pitch_rad, pose->roll_rad});
        track->second.hide_after_s = result.simulated_s + options.replay_period_s;
      }
      if (write_rows) {
        trajectories.add({&v.id, &v.type, &v.lane, centre.x(), centre.y(), pose->z_m, v.angle_deg,
                          v.speed_mps, pose->pitch_rad * kDegree, pose->roll_rad * kDegree});
      }
    }
    if (write_rows) trajectories.end_step();
    result.relief_s += seconds_since(t0);
    if (options.progress && result.simulated_s >= next_progress - 1e-9) {
      options.progress(result.simulated_s, vehicles.size());
      next_progress += kProgressEvery_s;
    }
  }
  result.vehicles = recent.size();
  result.z_error_m = spread_of(z_errors);
  result.z_error_on_roads_m = spread_of(z_errors_road);
  result.z_error_in_junctions_m = spread_of(z_errors_junction);
  result.sumo_z_error_m = spread_of(sumo_z_errors);
  result.pitch_error_deg = spread_of(pitch_errors);
  result.wheel_under_m = spread_of(wheel_under);
  if (result.unplaced > 0) {
    diagnostics.report(
        Severity::warning, codes::kCosimVehicleOffSurface,
        std::to_string(result.unplaced) +
            " vehicle step(s) with a wheel on no road surface, not placed; the first: " + first_unplaced);
  }
  if (result.unmapped > 0) {
    diagnostics.report(Severity::warning, codes::kCosimLaneUnmapped,
                       std::to_string(result.unmapped) +
                           " vehicle step(s) whose centre lies on no OpenDRIVE road of its last lanes, not "
                           "measured; the first on " +
                           first_unmapped);
  }
  OutputSet outputs;
  if (options.replay_period_s > 0.0) {
    std::vector<ReplayTrack> tracks;
    tracks.reserve(replay_order.size());
    for (const std::string& id : replay_order) tracks.push_back(std::move(replay.at(id)));
    const std::string bytes = encode_replay_glb(scene, tracks);
    outputs.add(out_dir / kCosimReplayFile, [&](std::ostream& out) { out << bytes; });
  }
  trajectories.commit();
  outputs.commit();
  result.wall_s = seconds_since(start);
  write_cosim_json(out_dir / kCosimReportFile, inputs, options, result);
  return result;
}

}  // namespace relief

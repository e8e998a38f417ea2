#include "cosim/lidar_rig.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <numbers>
#include <sstream>

#include "relief/core/atomic_file.h"
#include "relief/core/errors.h"
#include "relief/geometry/crs_transform.h"

namespace relief::detail {
namespace {

constexpr std::size_t kListed = 20;  // point-cloud files listed in cosim.json

const MeshScene kNoScene;

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

LidarBox box_of(const PlacedVehicle& v, int id) {
  LidarBox b;
  b.id = id;
  const Vec2 c = v.state->centre();
  const double height = v.state->height_m > 0.0 ? v.state->height_m : 1.5;
  b.yaw = v.state->heading();
  b.pitch = v.pose.pitch_rad;
  b.roll = v.pose.roll_rad;
  b.half = Vec3(0.5 * v.state->length_m, 0.5 * v.state->width_m, 0.5 * height);
  // The box stands on the body plane: its centre half its height over it along the body's up.
  const Vec3 up = body_to_world(b.yaw, b.pitch, b.roll) * Vec3::UnitZ();
  b.centre = Vec3(c.x(), c.y(), v.pose.z_m) + (0.5 * height + 0.05) * up;
  return b;
}

}  // namespace

LidarRig::LidarRig(const MeshScene& scene, const CosimOptions& options, std::filesystem::path out_dir,
                   GeoFrame frame)
    : scene_(options.lidars.empty() ? kNoScene : scene),
      options_(options),
      out_dir_(std::move(out_dir)),
      frame_(std::move(frame)) {
  if (!(std::isfinite(options.lidar_every_s) && options.lidar_every_s >= 0.0))
    throw InvalidInput("the LiDAR files' period must be a finite number >= 0");
  for (const LidarMount& m : options.lidars) {
    if (!(std::isfinite(m.height_m) && m.height_m > 0.0))
      throw InvalidInput("a LiDAR's mounting height must be a finite number > 0");
    Sensor s;
    s.mount = m;
    s.spec = lidar_preset(m.preset);
    s.ego = m.ego;
    sensors_.push_back(std::move(s));
  }
  figures_.sensors = sensors_.size();
}

void LidarRig::step(double t, double dt, const std::vector<PlacedVehicle>& placed) {
  if (sensors_.empty()) return;
  const auto t0 = std::chrono::steady_clock::now();
  for (Sensor& s : sensors_) {
    const PlacedVehicle* ego = nullptr;
    for (const PlacedVehicle& v : placed)
      if (v.ego && (s.ego.empty() || v.state->id == s.ego)) {
        ego = &v;
        break;
      }
    if (ego == nullptr) continue;
    if (s.ego.empty()) s.ego = ego->state->id;
    const Vec2 c = ego->state->centre();
    s.pose.position = Vec3(c.x(), c.y(), ego->pose.z_m + s.mount.height_m);
    s.pose.yaw = ego->state->heading();
    s.pose.pitch = ego->pose.pitch_rad;
    s.pose.roll = ego->pose.roll_rad;
    s.boxes.clear();
    s.box_ids.clear();
    for (const PlacedVehicle& v : placed) {
      if (&v == ego) continue;
      s.boxes.push_back(box_of(v, static_cast<int>(s.boxes.size())));
      s.box_ids.push_back(v.state->id);
    }
    std::vector<LidarPoint> points = scene_.scan(s.spec, s.pose, s.azimuth, dt, s.boxes, seed_++);
    // Returns on a vehicle name it by its index in this step's boxes: keep the SUMO id's index.
    s.sweep.insert(s.sweep.end(), points.begin(), points.end());
    const double turn = s.spec.rotation_hz * s.spec.horizontal_fov_deg * dt;
    s.azimuth = std::fmod(s.azimuth + turn, s.spec.horizontal_fov_deg);
    s.turned += turn;
    if (s.turned >= s.spec.horizontal_fov_deg - 1e-9) {
      close_sweep(s, t);
      s.turned = 0.0;
    }
  }
  seconds_ += seconds_since(t0);
}

bool LidarRig::in_view(const Sensor& s, const LidarBox& b, double distance) {
  // The box's centre in the sensor's frame; the box counts while any of it lies within the
  // fields of view (its angular half size from its bounding sphere).
  const Vec3 local =
      body_to_world(s.pose.yaw, s.pose.pitch, s.pose.roll).transpose() * (b.centre - s.pose.position);
  const double half =
      distance > b.half.norm() ? std::asin(b.half.norm() / distance) * 180.0 / std::numbers::pi : 90.0;
  const double elevation = std::atan2(local.z(), local.head<2>().norm()) * 180.0 / std::numbers::pi;
  if (elevation + half < s.spec.lower_fov_deg || elevation - half > s.spec.upper_fov_deg) return false;
  if (s.spec.horizontal_fov_deg >= 360.0) return true;
  const double azimuth = std::atan2(local.y(), local.x()) * 180.0 / std::numbers::pi;
  return std::abs(azimuth) - half <= 0.5 * s.spec.horizontal_fov_deg;
}

void LidarRig::close_sweep(Sensor& s, double t) {
  ++figures_.sweeps;
  ++s.frames;
  figures_.points += s.sweep.size();
  // Returns per vehicle of the sweep's last step (the boxes move little within a turn).
  std::vector<std::size_t> returns(s.boxes.size(), 0);
  for (const LidarPoint& p : s.sweep)
    if (p.label == LidarLabel::vehicle && p.object >= 0 &&
        static_cast<std::size_t>(p.object) < returns.size())
      ++returns[static_cast<std::size_t>(p.object)];
  LidarFigures::Tick tick;
  tick.t = t;
  for (std::size_t k = 0; k < s.boxes.size(); ++k) {
    const LidarBox& b = s.boxes[k];
    const double distance = (b.centre - s.pose.position).norm();
    if (distance > s.spec.range_m || !in_view(s, b, distance)) continue;
    ++figures_.checked;
    std::uint8_t state = 0;
    const std::string& id = s.box_ids[k];
    if (returns[k] >= options_.lidar_min_returns) {
      ++figures_.seen;
      ++tick.seen;
    } else {
      const auto obstacle = scene_.first_obstacle(s.pose.position, b.centre);
      state = obstacle ? static_cast<std::uint8_t>(obstacle->first) : 0;
      if (state == static_cast<std::uint8_t>(LidarLabel::road)) {
        ++figures_.hidden_by_road;
        ++tick.road;
        // The crest: the 25 m cell where the line of sight met the road.
        const Vec3& p = obstacle->second;
        const auto cell =
            (static_cast<std::uint64_t>(static_cast<std::int64_t>(std::floor(p.x() / 25.0))) << 32) ^
            static_cast<std::uint64_t>(static_cast<std::int64_t>(std::floor(p.y() / 25.0)) & 0xffffffff);
        auto [it, added] = crest_index_.try_emplace(cell, figures_.crests.size());
        if (added) figures_.crests.emplace_back();
        LidarFigures::Crest& crest = figures_.crests[it->second];
        crest.point =
            (crest.point * static_cast<double>(crest.hidden) + p) / static_cast<double>(crest.hidden + 1);
        ++crest.hidden;
        s.crest_of[id] = cell;
      } else if (state == static_cast<std::uint8_t>(LidarLabel::terrain)) {
        ++figures_.hidden_by_terrain;
        ++tick.terrain;
      } else {
        const Vec3 d = b.centre - s.pose.position;
        bool vehicle = false;
        for (std::size_t j = 0; j < s.boxes.size() && !vehicle; ++j)
          vehicle = j != k && ray_box(s.pose.position, d.normalized(), s.boxes[j], d.norm()).has_value();
        state = vehicle ? static_cast<std::uint8_t>(LidarLabel::vehicle) : 255;
        ++(vehicle ? figures_.hidden_by_vehicle : figures_.hidden_sparse);
        ++(vehicle ? tick.vehicle : tick.sparse);
      }
    }
    const auto last = s.last.find(id);
    if (state == 0 && last != s.last.end() && last->second == static_cast<std::uint8_t>(LidarLabel::road)) {
      figures_.seen_after_crest_m.push_back(static_cast<float>(distance));
      figures_.crests[crest_index_.at(s.crest_of.at(id))].first_seen_m.push_back(
          static_cast<float>(distance));
    }
    s.last[id] = state;
  }
  figures_.timeline.push_back(tick);
  if (t >= s.next_write - 1e-9) {
    s.next_write = t + options_.lidar_every_s;
    std::ostringstream base;
    // One folder per sensor: EGO/K_PRESET (K its place among the --lidar options).
    const std::string folder =
        "lidar/" + s.ego + "/" + std::to_string(&s - sensors_.data()) + "_" + s.mount.preset;
    base << folder << "/" << std::setw(6) << std::setfill('0') << s.frames;
    const std::filesystem::path dir = out_dir_ / folder;
    std::filesystem::create_directories(dir);
    for (const char* ext : {".pcd", ".ply"}) {
      std::ostringstream text;
      (std::string(ext) == ".pcd" ? write_pcd : write_ply)(text, s.sweep);
      write_file_atomically(out_dir_ / (base.str() + ext), text.str());
      if (figures_.written.size() < kListed) figures_.written.push_back(base.str() + ext);
    }
    ++figures_.sweeps_written;
  }
  s.sweep.clear();
}

void LidarRig::finish(CosimResult& result) const {
  result.lidar = figures_;
  std::vector<LidarFigures::Crest>& crests = result.lidar.crests;
  std::stable_sort(
      crests.begin(), crests.end(),
      [](const LidarFigures::Crest& a, const LidarFigures::Crest& b) { return a.hidden > b.hidden; });
  if (!crests.empty() && !frame_.crs().empty()) {
    const CrsTransform to_wgs84(frame_.crs(), "EPSG:4326");
    std::vector<Vec2> lonlat;
    lonlat.reserve(crests.size());
    for (const LidarFigures::Crest& c : crests) lonlat.emplace_back(c.point.head<2>() + frame_.origin());
    to_wgs84.apply(lonlat);
    for (std::size_t k = 0; k < crests.size(); ++k) {
      crests[k].lon = lonlat[k].x();
      crests[k].lat = lonlat[k].y();
    }
  }
  result.lidar.rays = scene_.rays();
  result.lidar.seconds = seconds_;
}

}  // namespace relief::detail

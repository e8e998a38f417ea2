#include "relief/sight/lidar.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <limits>
#include <numbers>
#include <random>

#include <Eigen/Geometry>

#include "relief/core/errors.h"
#include "sight/ray_scene.h"

namespace relief {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

template <typename T>
void put(std::string& out, T value) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  out.append(bytes, sizeof(T));
}

std::string binary_points(const std::vector<LidarPoint>& points) {
  std::string data;
  data.reserve(points.size() * 31);
  for (const LidarPoint& p : points) {
    put(data, static_cast<float>(p.xyz.x()));
    put(data, static_cast<float>(p.xyz.y()));
    put(data, static_cast<float>(p.xyz.z()));
    put(data, p.intensity);
    put(data, p.ring);
    put(data, p.azimuth_deg);
    put(data, p.distance_m);
    put(data, static_cast<std::uint8_t>(p.label));
    put(data, p.object);
  }
  return data;
}

}  // namespace

LidarSpec lidar_preset(std::string_view name) {
  LidarSpec s;
  s.name = std::string(name);
  if (name == "carla-default") return s;
  // The real sensors: every return kept, range noise as their data sheets' accuracy.
  s.atmosphere_attenuation_rate = 0.004;
  s.dropoff_general_rate = 0.0;
  s.dropoff_intensity_limit = 1.0;
  s.dropoff_zero_intensity = 0.0;
  s.rotation_hz = 10.0;
  if (name == "hdl-32e") {
    s.channels = 32;
    s.range_m = 100.0;
    s.points_per_second = 695000.0;
    s.upper_fov_deg = 10.67;
    s.lower_fov_deg = -30.67;
    s.noise_stddev_m = 0.02;
  } else if (name == "hdl-64e") {
    s.channels = 64;
    s.range_m = 120.0;
    s.points_per_second = 1300000.0;
    s.upper_fov_deg = 2.0;
    s.lower_fov_deg = -24.9;
    s.noise_stddev_m = 0.02;
  } else if (name == "os1-64") {
    s.channels = 64;
    s.range_m = 120.0;
    s.points_per_second = 655360.0;
    s.upper_fov_deg = 22.5;
    s.lower_fov_deg = -22.5;
    s.noise_stddev_m = 0.03;
  } else {
    throw InvalidInput("'" + std::string(name) +
                       "' is not a LiDAR preset: carla-default, hdl-32e, hdl-64e, os1-64");
  }
  return s;
}

void check_lidar_spec(const LidarSpec& s) {
  const auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
  const auto rate = [](double v) { return std::isfinite(v) && v >= 0.0 && v <= 1.0; };
  if (s.channels < 1 || s.channels > 65535 || !positive(s.range_m) || !positive(s.points_per_second) ||
      !positive(s.rotation_hz) || !positive(s.horizontal_fov_deg) || s.horizontal_fov_deg > 360.0 ||
      !std::isfinite(s.upper_fov_deg) || !std::isfinite(s.lower_fov_deg) ||
      s.upper_fov_deg < s.lower_fov_deg || s.upper_fov_deg > 90.0 || s.lower_fov_deg < -90.0 ||
      !rate(s.dropoff_general_rate) || !positive(s.dropoff_intensity_limit) ||
      s.dropoff_intensity_limit > 1.0 || !rate(s.dropoff_zero_intensity) ||
      !std::isfinite(s.noise_stddev_m) || s.noise_stddev_m < 0.0 ||
      !std::isfinite(s.atmosphere_attenuation_rate) || s.atmosphere_attenuation_rate < 0.0)
    throw InvalidInput(
        "LiDAR '" + s.name +
        "': channels 1..65535; range, points per second, rotation frequency > 0; horizontal field "
        "of view in (0, 360]; lower <= upper field of view within +-90 deg; drop-off rates in "
        "[0, 1] (intensity limit > 0); noise and attenuation >= 0");
}

namespace {

/// A box with its rotation worked out once (into the box's frame), for many rays.
struct PreparedBox {
  const LidarBox* box;
  Eigen::Matrix3d to_box;
  double radius;  ///< of its bounding sphere
};

std::optional<double> ray_prepared(const Vec3& origin, const Vec3& dir, const PreparedBox& p, double max_m) {
  // The bounding sphere first: most rays pass far from most boxes.
  const Vec3 oc = p.box->centre - origin;
  const double along = oc.dot(dir);
  if (along + p.radius < 0.0 || along - p.radius > max_m ||
      (oc - along * dir).squaredNorm() > p.radius * p.radius)
    return std::nullopt;
  const Vec3 o = p.to_box * (origin - p.box->centre), d = p.to_box * dir;
  const Vec3& half = p.box->half;
  double t0 = 0.0, t1 = max_m;
  for (int k = 0; k < 3; ++k) {
    if (std::abs(d[k]) < 1e-12) {
      if (std::abs(o[k]) > half[k]) return std::nullopt;
      continue;
    }
    double a = (-half[k] - o[k]) / d[k], b = (half[k] - o[k]) / d[k];
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a);
    t1 = std::min(t1, b);
    if (t0 > t1) return std::nullopt;
  }
  return t0;
}

PreparedBox prepare(const LidarBox& box) {
  return {&box, body_to_world(box.yaw, box.pitch, box.roll).transpose(), box.half.norm()};
}

}  // namespace

std::optional<double> ray_box(const Vec3& origin, const Vec3& dir, const LidarBox& box, double max_m) {
  return ray_prepared(origin, dir, prepare(box), max_m);
}

Eigen::Matrix3d body_to_world(double yaw, double pitch, double roll) {
  // Yaw about z, then pitch (nose up positive: a negative turn about y), then roll about x.
  return (Eigen::AngleAxisd(yaw, Vec3::UnitZ()) * Eigen::AngleAxisd(-pitch, Vec3::UnitY()) *
          Eigen::AngleAxisd(roll, Vec3::UnitX()))
      .toRotationMatrix();
}

struct LidarScene::Impl {
  explicit Impl(const MeshScene& scene)
      : rays(scene, [](SurfaceKind k) { return k != SurfaceKind::marking; }) {}
  detail::RayScene rays;
  mutable std::atomic<std::size_t> cast{0};
};

LidarScene::LidarScene(const MeshScene& scene) : impl_(std::make_unique<Impl>(scene)) {}
LidarScene::~LidarScene() = default;
LidarScene::LidarScene(LidarScene&& other) noexcept = default;
LidarScene& LidarScene::operator=(LidarScene&& other) noexcept = default;

std::size_t LidarScene::rays() const {
  return impl_->cast.load();
}

std::optional<std::pair<LidarLabel, Vec3>> LidarScene::first_obstacle(const Vec3& a, const Vec3& b) const {
  const std::optional<detail::RayHit> hit = impl_->rays.first_hit(a, b);
  if (!hit) return std::nullopt;
  return std::make_pair(hit->kind == SurfaceKind::terrain ? LidarLabel::terrain : LidarLabel::road,
                        hit->point);
}

std::uint8_t LidarScene::blocked_by(const Vec3& a, const Vec3& b) const {
  const auto obstacle = first_obstacle(a, b);
  return obstacle ? static_cast<std::uint8_t>(obstacle->first) : 0;
}

std::vector<LidarPoint> LidarScene::scan(const LidarSpec& spec, const LidarPose& pose,
                                         double start_azimuth_deg, double dt,
                                         const std::vector<LidarBox>& vehicles, std::uint64_t seed) const {
  check_lidar_spec(spec);
  if (!(std::isfinite(dt) && dt > 0.0)) throw InvalidInput("LiDAR: a step of " + std::to_string(dt) + " s");
  const Eigen::Matrix3d to_world = body_to_world(pose.yaw, pose.pitch, pose.roll);
  // The boxes the range can reach.
  std::vector<PreparedBox> near;
  for (const LidarBox& b : vehicles)
    if ((b.centre - pose.position).norm() <= spec.range_m + b.half.norm()) near.push_back(prepare(b));
  const auto per_channel =
      static_cast<long>(std::lround(spec.points_per_second * dt / static_cast<double>(spec.channels)));
  const double sweep = spec.rotation_hz * spec.horizontal_fov_deg * dt;
  const double step = per_channel > 0 ? sweep / static_cast<double>(per_channel) : 0.0;
  const double spread =
      spec.channels == 1 ? 0.0 : (spec.upper_fov_deg - spec.lower_fov_deg) / (spec.channels - 1);
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::normal_distribution<double> noise(0.0, spec.noise_stddev_m > 0.0 ? spec.noise_stddev_m : 1.0);
  std::vector<LidarPoint> points;
  points.reserve(static_cast<std::size_t>(std::max(0L, per_channel)) *
                 static_cast<std::size_t>(spec.channels));
  // The rays of this step (those the general drop-off keeps), cast as packets from the sensor.
  struct Ray {
    Vec3 local;
    double azimuth;
    int channel;
  };
  std::vector<Ray> rays;
  rays.reserve(points.capacity());
  std::vector<double> cos_el(static_cast<std::size_t>(spec.channels)), sin_el(cos_el.size());
  for (std::size_t c = 0; c < cos_el.size(); ++c) {
    const double elevation = (spec.upper_fov_deg - static_cast<double>(c) * spread) * kDeg;
    cos_el[c] = std::cos(elevation);
    sin_el[c] = std::sin(elevation);
  }
  for (long i = 0; i < per_channel; ++i) {
    // Within the horizontal field of view, centred on the sensor's x axis (CARLA's convention).
    const double azimuth =
        std::fmod(start_azimuth_deg + step * static_cast<double>(i), spec.horizontal_fov_deg) -
        (spec.horizontal_fov_deg < 360.0 ? 0.5 * spec.horizontal_fov_deg : 0.0);
    const double ca = std::cos(azimuth * kDeg), sa = std::sin(azimuth * kDeg);
    for (int c = 0; c < spec.channels; ++c) {
      if (spec.dropoff_general_rate > 0.0 && uniform(random) < spec.dropoff_general_rate) continue;
      const auto k = static_cast<std::size_t>(c);
      rays.push_back({Vec3(cos_el[k] * ca, cos_el[k] * sa, sin_el[k]), azimuth, c});
    }
  }
  std::vector<Vec3> dirs(rays.size());
  for (std::size_t k = 0; k < rays.size(); ++k) dirs[k] = to_world * rays[k].local;
  std::vector<double> hits(rays.size());
  std::vector<SurfaceKind> kinds(rays.size(), SurfaceKind::road);
  impl_->rays.first_hits(pose.position, dirs.data(), dirs.size(), spec.range_m, hits.data(), kinds.data());
  for (std::size_t k = 0; k < rays.size(); ++k) {
    const Vec3& dir = dirs[k];
    double t = std::min(hits[k], spec.range_m);
    bool hit = std::isfinite(hits[k]);
    LidarLabel label = kinds[k] == SurfaceKind::terrain ? LidarLabel::terrain : LidarLabel::road;
    std::int32_t object = -1;
    for (const PreparedBox& b : near) {
      if (const std::optional<double> tb = ray_prepared(pose.position, dir, b, t)) {
        if (*tb < t || !hit) {
          t = *tb;
          label = LidarLabel::vehicle;
          object = b.box->id;
          hit = true;
        }
      }
    }
    if (!hit || t <= 0.0) continue;
    const double intensity = std::exp(-spec.atmosphere_attenuation_rate * t);
    if (intensity <= spec.dropoff_intensity_limit && spec.dropoff_zero_intensity > 0.0 &&
        uniform(random) >=
            1.0 - spec.dropoff_zero_intensity * (1.0 - intensity / spec.dropoff_intensity_limit))
      continue;
    const double measured = spec.noise_stddev_m > 0.0 ? t + noise(random) : t;
    LidarPoint p;
    p.xyz = measured * rays[k].local;
    p.intensity = static_cast<float>(intensity);
    p.azimuth_deg = static_cast<float>(std::fmod(rays[k].azimuth + 360.0, 360.0));
    p.distance_m = static_cast<float>(measured);
    p.ring = static_cast<std::uint16_t>(rays[k].channel);
    p.label = label;
    p.object = object;
    points.push_back(p);
  }
  const std::size_t cast = rays.size();
  impl_->cast += cast;
  return points;
}

void write_pcd(std::ostream& out, const std::vector<LidarPoint>& points) {
  out << "# .PCD v0.7 - Point Cloud Data file format (relief LiDAR)\nVERSION 0.7\n"
         "FIELDS x y z intensity ring azimuth distance label object\nSIZE 4 4 4 4 2 4 4 1 4\n"
         "TYPE F F F F U F F U I\nCOUNT 1 1 1 1 1 1 1 1 1\nWIDTH "
      << points.size() << "\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " << points.size()
      << "\nDATA binary\n";
  const std::string data = binary_points(points);
  out.write(data.data(), static_cast<std::streamsize>(data.size()));
}

void write_ply(std::ostream& out, const std::vector<LidarPoint>& points) {
  out << "ply\nformat binary_little_endian 1.0\ncomment relief LiDAR: label 1 road, 2 terrain, 3 vehicle "
         "(object "
         "its id)\nelement vertex "
      << points.size()
      << "\nproperty float x\nproperty float y\nproperty float z\nproperty float intensity\nproperty ushort "
         "ring\nproperty float azimuth\nproperty float distance\nproperty uchar label\nproperty int object\n"
         "end_header\n";
  const std::string data = binary_points(points);
  out.write(data.data(), static_cast<std::streamsize>(data.size()));
}

}  // namespace relief

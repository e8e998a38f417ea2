#pragma once
// Rotating multi-channel LiDAR on relief's scene, with CARLA's sensor parameters
// (sensor.lidar.ray_cast: channels, range, points_per_second, rotation_frequency, upper_fov,
// lower_fov, horizontal_fov, atmosphere_attenuation_rate, dropoff_general_rate,
// dropoff_intensity_limit, dropoff_zero_intensity, noise_stddev) and CARLA's model of them:
// channels evenly spread between the lower and the upper field of view; in a step of dt the
// sensor turns rotation_frequency x dt x horizontal_fov and casts points_per_second x dt rays
// (less the general drop-off), spread evenly over the channels and that arc; a return's
// intensity is exp(-attenuation x distance), and one at or under the intensity limit is kept
// with probability 1 - zero_intensity x (1 - intensity / limit); Gaussian noise moves a return
// along its ray. Rays meet the static scene (road and terrain triangles, through Embree) and
// the vehicles' boxes; every return carries its ring, azimuth, distance and what it hit.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <ostream>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <Eigen/Geometry>
#include "relief/geometry/triangle_mesh.h"

#include "relief/geometry/types.h"

namespace relief {

struct LidarSpec {
  std::string name = "carla-default";
  int channels = 32;
  double range_m = 10.0;
  double points_per_second = 56000.0;
  double rotation_hz = 10.0;
  double upper_fov_deg = 10.0;
  double lower_fov_deg = -30.0;
  double horizontal_fov_deg = 360.0;
  double atmosphere_attenuation_rate = 0.004;
  double dropoff_general_rate = 0.45;
  double dropoff_intensity_limit = 0.8;
  double dropoff_zero_intensity = 0.4;
  double noise_stddev_m = 0.0;
};

/// Presets: "carla-default" (CARLA 0.9's blueprint defaults), "hdl-32e" (Velodyne HDL-32E:
/// 32 channels, +10.67 to -30.67 deg, 100 m, 695 000 points/s at 10 Hz), "hdl-64e" (Velodyne
/// HDL-64E S2: 64 channels, +2 to -24.9 deg, 120 m, 1 300 000 points/s), "os1-64" (Ouster OS1-64:
/// 64 channels, +-22.5 deg, 120 m, 1024 x 64 x 10 = 655 360 points/s). The real sensors keep
/// every return (no drop-off) with 2 cm (Velodyne) or 3 cm (Ouster) of range noise. Throws
/// InvalidInput naming the presets for another name.
[[nodiscard]] LidarSpec lidar_preset(std::string_view name);
/// Throws InvalidInput unless the spec can run (channels >= 1, positive range, rate, frequency,
/// fields of view in order, rates in [0, 1]).
void check_lidar_spec(const LidarSpec& spec);

/// The sensor's pose: its origin and its yaw (counter-clockwise from east), pitch and roll (rad).
struct LidarPose {
  Vec3 position = Vec3::Zero();
  double yaw = 0.0, pitch = 0.0, roll = 0.0;
};

/// A vehicle as an oriented box: its centre, heading (yaw), pitch, roll and half sizes (length,
/// width, height halves).
struct LidarBox {
  int id = -1;  ///< the caller's index (e.g. into its vehicles)
  Vec3 centre = Vec3::Zero();
  double yaw = 0.0, pitch = 0.0, roll = 0.0;
  Vec3 half = Vec3(2.25, 0.9, 0.75);
};

enum class LidarLabel : std::uint8_t { road = 1, terrain = 2, vehicle = 3 };

struct LidarPoint {
  Vec3 xyz = Vec3::Zero();  ///< in the sensor's frame (x forward, y left, z up), metres
  float intensity = 0.0F;
  float azimuth_deg = 0.0F;  ///< counter-clockwise from the sensor's x axis, [0, 360)
  float distance_m = 0.0F;
  std::uint16_t ring = 0;  ///< channel, 0 the lowest
  LidarLabel label = LidarLabel::road;
  std::int32_t object = -1;  ///< LidarBox::id for a vehicle, else -1
};

/// The static scene's triangles (every mesh but markings), prepared once.
class LidarScene {
 public:
  explicit LidarScene(const MeshScene& scene);
  ~LidarScene();
  LidarScene(LidarScene&& other) noexcept;
  LidarScene& operator=(LidarScene&& other) noexcept;
  LidarScene(const LidarScene&) = delete;
  LidarScene& operator=(const LidarScene&) = delete;

  /// The returns of one step of `dt` s of a sensor that starts this step at `start_azimuth_deg`
  /// (its own frame) and at `pose`, among `vehicles` (boxes farther than the range are skipped
  /// at once). `seed` makes the drop-off and noise repeatable. Points are in the order cast
  /// (azimuth, then ring).
  [[nodiscard]] std::vector<LidarPoint> scan(const LidarSpec& spec, const LidarPose& pose,
                                             double start_azimuth_deg, double dt,
                                             const std::vector<LidarBox>& vehicles, std::uint64_t seed) const;
  /// Whether the open segment from a to b meets the static scene, and what: road, terrain, or
  /// nothing (then the label is 0).
  [[nodiscard]] std::uint8_t blocked_by(const Vec3& a, const Vec3& b) const;
  /// Where the open segment from a to b first meets the static scene (road or terrain), if it does.
  [[nodiscard]] std::optional<std::pair<LidarLabel, Vec3>> first_obstacle(const Vec3& a, const Vec3& b) const;
  /// Rays cast so far by scan() (all threads), for throughput figures.
  [[nodiscard]] std::size_t rays() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Distance along the ray from `origin` in unit direction `dir` to `box`, if it meets it within
/// `max_m` (the slab test in the box's frame).
[[nodiscard]] std::optional<double> ray_box(const Vec3& origin, const Vec3& dir, const LidarBox& box,
                                            double max_m);

/// The rotation from a sensor's or a box's own frame (x forward, y left, z up) to the world's,
/// for a yaw counter-clockwise from east, a pitch nose up and a roll right side down (rad).
[[nodiscard]] Eigen::Matrix3d body_to_world(double yaw, double pitch, double roll);

/// PCD 0.7 (binary): fields x y z intensity ring azimuth distance label object.
void write_pcd(std::ostream& out, const std::vector<LidarPoint>& points);
/// PLY 1.0 (binary little endian): vertex x y z (float), intensity, ring (ushort), azimuth,
/// distance (float), label (uchar), object (int).
void write_ply(std::ostream& out, const std::vector<LidarPoint>& points);

}  // namespace relief

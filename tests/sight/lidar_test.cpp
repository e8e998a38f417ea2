// LiDAR on exact scenes (relief/sight/lidar.h): rings on a flat plane, a wall, a car behind a
// crest, and the point-cloud files an independent reader (Open3D) opens.

#include "relief/sight/lidar.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <numbers>
#include <sstream>

#include "relief/core/errors.h"

namespace relief {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// A surface z = f(x) over x0..x1, |y| <= half_width, in strips of dx.
TriangleMesh strip_of(const std::function<double(double)>& f, double x0, double x1, double dx,
                      double half_width, SurfaceKind kind = SurfaceKind::road) {
  TriangleMesh m;
  m.name = kind == SurfaceKind::terrain ? "Terrain" : "Road_Road";
  m.kind = kind;
  const auto n = static_cast<std::uint32_t>(std::ceil((x1 - x0) / dx));
  for (std::uint32_t i = 0; i <= n; ++i) {
    const double x = std::min(x1, x0 + i * dx);
    m.vertices.emplace_back(x, -half_width, f(x));
    m.vertices.emplace_back(x, half_width, f(x));
    if (i == 0) continue;
    const std::uint32_t a = 2 * (i - 1), b = a + 1, c = a + 2, d = a + 3;
    m.triangles.push_back({a, c, b});
    m.triangles.push_back({b, c, d});
  }
  return m;
}

LidarSpec exact_spec() {
  LidarSpec s;
  s.name = "exact";
  s.dropoff_general_rate = 0.0;
  s.dropoff_zero_intensity = 0.0;
  s.noise_stddev_m = 0.0;
  return s;
}

// A sensor 2 m over a plane: every ring meets the ground at h / tan(-elevation), within 1 cm.
TEST(Lidar, RingsOnAFlatPlaneFallAtHeightOverTangent) {
  MeshScene scene;
  scene.meshes.push_back(strip_of([](double) { return 10.0; }, -300.0, 300.0, 600.0, 300.0));
  const LidarScene lidar(scene);
  LidarSpec s = exact_spec();
  s.channels = 16;
  s.upper_fov_deg = -2.0;
  s.lower_fov_deg = -32.0;
  s.range_m = 200.0;
  s.points_per_second = 16.0 * 360.0 * 10.0;  // one ray per degree and ring in a turn of 0.1 s
  LidarPose pose;
  pose.position = Vec3(3.0, -4.0, 12.0);
  pose.yaw = 0.7;
  const std::vector<LidarPoint> points = lidar.scan(s, pose, 0.0, 0.1, {}, 1);
  ASSERT_EQ(points.size(), 16u * 360u);
  for (const LidarPoint& p : points) {
    const double elevation = (s.upper_fov_deg - p.ring * 2.0) * kDeg;
    EXPECT_NEAR(p.xyz.head<2>().norm(), 2.0 / std::tan(-elevation), 0.01) << p.ring;
    EXPECT_NEAR(p.xyz.z(), -2.0, 0.005);
    EXPECT_EQ(p.label, LidarLabel::road);
    EXPECT_NEAR(p.intensity, std::exp(-0.004 * p.distance_m), 1e-6);
  }
  EXPECT_EQ(lidar.rays(), 16u * 360u);
}

// A wall 25 m ahead: the level ray returns 25 m, one at azimuth a 25 / cos a.
TEST(Lidar, AWallAtDistanceDReturnsD) {
  TriangleMesh wall;
  wall.kind = SurfaceKind::terrain;
  wall.vertices = {Vec3(25.0, -60.0, -20.0), Vec3(25.0, 60.0, -20.0), Vec3(25.0, 60.0, 20.0),
                   Vec3(25.0, -60.0, 20.0)};
  wall.triangles = {{0, 1, 2}, {0, 2, 3}};
  MeshScene scene;
  scene.meshes.push_back(wall);
  const LidarScene lidar(scene);
  LidarSpec s = exact_spec();
  s.channels = 1;
  s.upper_fov_deg = s.lower_fov_deg = 0.0;
  s.range_m = 100.0;
  s.points_per_second = 3600.0;  // 360 rays a turn
  const std::vector<LidarPoint> points = lidar.scan(s, {}, 0.0, 0.1, {}, 1);
  int front = 0;
  for (const LidarPoint& p : points) {
    ASSERT_EQ(p.label, LidarLabel::terrain);
    const double a = p.azimuth_deg > 180.0 ? p.azimuth_deg - 360.0 : p.azimuth_deg;
    EXPECT_NEAR(p.distance_m, 25.0 / std::cos(a * kDeg), 1e-4) << a;
    if (std::abs(a) < 1e-9) ++front;
  }
  EXPECT_EQ(front, 1);
  EXPECT_GT(points.size(), 100u);  // up to |a| = 67 deg, where the wall ends
  // Noise moves a return along its ray with the spread asked.
  s.noise_stddev_m = 0.05;
  s.points_per_second = 36000.0;
  double sum = 0.0, sq = 0.0;
  int n = 0;
  for (const LidarPoint& p : lidar.scan(s, {}, 0.0, 0.1, {}, 7)) {
    const double a = p.azimuth_deg > 180.0 ? p.azimuth_deg - 360.0 : p.azimuth_deg;
    const double e = p.distance_m - 25.0 / std::cos(a * kDeg);
    sum += e;
    sq += e * e;
    ++n;
  }
  EXPECT_NEAR(sum / n, 0.0, 0.01);
  EXPECT_NEAR(std::sqrt(sq / n), 0.05, 0.005);
}

// A crest z = 20 - x^2 / 2000: a sensor 1.8 m over the road at x = -40 and a car (a 4.5 x 1.8
// x 1.5 m box on the road) at x = X beyond the crest (from about X = 74 m the road hides it). The car is seen
// exactly when the line from the sensor to its nearest top edge clears the road (margin over 5 cm: seen;
// under -5 cm: hidden), with a dense fan of 601 channels over +-3 deg straight ahead.
TEST(Lidar, ACarBehindACrestIsHiddenUntilTheLineOfSightClearsIt) {
  const auto z = [](double x) { return 20.0 - x * x / 2000.0; };
  MeshScene scene;
  scene.meshes.push_back(strip_of(z, -100.0, 250.0, 0.25, 5.0));
  const LidarScene lidar(scene);
  LidarSpec s = exact_spec();
  s.channels = 601;
  s.upper_fov_deg = 3.0;
  s.lower_fov_deg = -3.0;
  s.range_m = 250.0;
  s.horizontal_fov_deg = 0.2;
  s.points_per_second = 601.0 / 0.05;  // one ray per channel in a step
  LidarPose pose;
  pose.position = Vec3(-40.0, 0.0, z(-40.0) + 1.8);
  int seen = 0, hidden = 0;
  for (double x = 5.0; x <= 195.0; x += 1.0) {
    LidarBox car;
    car.id = 7;
    car.centre = Vec3(x, 0.0, z(x) + 0.75);
    const Vec3 top(x - 2.25, 0.0, z(x) + 1.5);
    // The line's lowest clearance over the road between the sensor and the top edge.
    double margin = 1e9;
    for (double u = 0.001; u < 1.0; u += 0.001) {
      const Vec3 p = pose.position + u * (top - pose.position);
      margin = std::min(margin, p.z() - z(p.x()));
    }
    std::size_t returns = 0;
    for (const LidarPoint& p : lidar.scan(s, pose, 0.5 * s.horizontal_fov_deg, 0.05, {car}, 1))
      if (p.label == LidarLabel::vehicle && p.object == 7) ++returns;
    if (margin > 0.05) {
      EXPECT_GT(returns, 0u) << "x " << x << " margin " << margin;
      ++seen;
    } else if (margin < -0.05) {
      EXPECT_EQ(returns, 0u) << "x " << x << " margin " << margin;
      ++hidden;
    }
  }
  EXPECT_GE(seen, 10);
  EXPECT_GE(hidden, 10);
  // blocked_by names the road between the sensor and a car it hides.
  EXPECT_EQ(lidar.blocked_by(pose.position, Vec3(150.0, 0.0, z(150.0) + 0.75)),
            static_cast<std::uint8_t>(LidarLabel::road));
  EXPECT_EQ(lidar.blocked_by(pose.position, Vec3(-20.0, 0.0, z(-20.0) + 1.0)), 0);
}

TEST(Lidar, PresetsAndBadSpecs) {
  for (const char* name : {"carla-default", "hdl-32e", "hdl-64e", "os1-64"})
    EXPECT_NO_THROW(check_lidar_spec(lidar_preset(name)));
  EXPECT_EQ(lidar_preset("hdl-64e").channels, 64);
  EXPECT_DOUBLE_EQ(lidar_preset("os1-64").points_per_second, 1024.0 * 64.0 * 10.0);
  EXPECT_DOUBLE_EQ(lidar_preset("carla-default").range_m, 10.0);
  EXPECT_THROW((void)lidar_preset("hdl-128"), InvalidInput);
  LidarSpec s;
  s.channels = 0;
  EXPECT_THROW(check_lidar_spec(s), InvalidInput);
  s = {};
  s.upper_fov_deg = -40.0;
  EXPECT_THROW(check_lidar_spec(s), InvalidInput);
  s = {};
  s.dropoff_general_rate = 1.5;
  EXPECT_THROW(check_lidar_spec(s), InvalidInput);
  // CARLA's drop-offs: about 45 % of rays are not cast, and weak returns thin out.
  MeshScene scene;
  scene.meshes.push_back(strip_of([](double) { return 0.0; }, -50.0, 50.0, 100.0, 50.0));
  const LidarScene lidar(scene);
  LidarSpec carla = lidar_preset("carla-default");
  carla.range_m = 40.0;
  LidarPose pose;
  pose.position = Vec3(0.0, 0.0, 2.0);
  const std::size_t kept = lidar.scan(carla, pose, 0.0, 1.0, {}, 3).size();
  // 56 000 rays a second; 55 % cast; every ring under the horizon hits the plane within 40 m
  // except the upper ones: the count lies well under the rays.
  EXPECT_LT(kept, 56000u * 55u / 100u);
  EXPECT_GT(kept, 10000u);
}

// PCD and PLY: the headers say what the binary data holds; Open3D (python3-open3d) reads the
// points back.
TEST(Lidar, PointCloudsOpenInOpen3d) {
  MeshScene scene;
  scene.meshes.push_back(strip_of([](double) { return 0.0; }, -50.0, 50.0, 100.0, 50.0));
  const LidarScene lidar(scene);
  LidarPose pose;
  pose.position = Vec3(0.0, 0.0, 2.0);
  const std::vector<LidarPoint> points = lidar.scan(lidar_preset("hdl-32e"), pose, 0.0, 0.1, {}, 5);
  ASSERT_GT(points.size(), 1000u);
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "relief_lidar_test";
  std::filesystem::create_directories(dir);
  {
    std::ofstream pcd(dir / "frame.pcd", std::ios::binary), ply(dir / "frame.ply", std::ios::binary);
    write_pcd(pcd, points);
    write_ply(ply, points);
  }
  const std::string script =
      "import open3d as o3d, sys\n"
      "for f in ('frame.pcd', 'frame.ply'):\n"
      "    pc = o3d.io.read_point_cloud('" +
      dir.string() +
      "/' + f)\n"
      "    assert len(pc.points) == " +
      std::to_string(points.size()) +
      ", (f, len(pc.points))\n"
      "    z = [p[2] for p in pc.points]\n"
      "    assert abs(sum(z) / len(z) + 2.0) < 0.01, (f, sum(z) / len(z))\n";
  std::ofstream(dir / "check.py") << script;
  // Debian's python3, where python3-open3d installs (not a python3 of pyenv's earlier on PATH).
  EXPECT_EQ(std::system(("/usr/bin/python3 " + (dir / "check.py").string()).c_str()), 0);
}

}  // namespace
}  // namespace relief

// `relief lidar --scene NAME.glb --at X,Y[,Z] [--yaw DEG] --preset P --out DIR`: one LiDAR
// sweep (a full turn) from a pose on a built scene, as PCD and PLY (relief/sight/lidar.h).
#include <chrono>
#include <cmath>
#include <iostream>
#include <memory>
#include <numbers>
#include <sstream>

#include "commands.h"
#include "console.h"
#include "options.h"
#include "relief/core/atomic_file.h"
#include "relief/core/errors.h"
#include "relief/export/mesh_writer.h"
#include "relief/scene/surface_query.h"
#include "relief/sight/lidar.h"

namespace relief::cli {
namespace {

struct LidarArgs {
  std::string scene, out, preset = "hdl-64e";
  std::vector<double> at;
  double yaw_deg = 0.0, height_m = 1.9;
  int sweeps = 1;
};

}  // namespace

Runner add_lidar_command(CLI::App& app) {
  auto args = std::make_shared<LidarArgs>();
  CLI::App* cmd = app.add_subcommand("lidar", "One LiDAR sweep from a pose on a built scene, as PCD and PLY");
  cmd->add_option("--scene", args->scene, "the build's 3D scene (NAME.glb, or any mesh file relief reads)")
      ->required();
  cmd->add_option(
         "--at", args->at,
         "sensor position X,Y in the scene's local frame; with Z the sensor's height itself, else --height "
         "over the highest surface there")
      ->required()
      ->delimiter(',')
      ->expected(2, 3);
  cmd->add_option("--yaw", args->yaw_deg, "sensor heading, degrees counter-clockwise from east")
      ->capture_default_str();
  cmd->add_option("--height", args->height_m, "sensor height over the surface at X,Y, m")
      ->capture_default_str()
      ->check(finite_positive());
  cmd->add_option("--preset", args->preset, "carla-default, hdl-32e, hdl-64e or os1-64")
      ->capture_default_str();
  cmd->add_option("--sweeps", args->sweeps, "turns to cast (the files hold the last; more for a timing)")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  cmd->add_option("--out", args->out, "output directory (lidar.pcd, lidar.ply)")->required();
  return [args] {
    return run_reporting_errors([&] {
      const LidarSpec spec = lidar_preset(args->preset);
      const MeshScene scene = read_mesh_file(args->scene);
      LidarPose pose;
      if (args->at.size() == 3) {
        pose.position = Vec3(args->at[0], args->at[1], args->at[2]);
      } else {
        const SurfaceQuery query(scene);
        const std::optional<SurfaceHit> top = query.highest(args->at[0], args->at[1]);
        if (!top)
          throw InvalidInput("no surface of '" + args->scene + "' under (" + std::to_string(args->at[0]) +
                             ", " + std::to_string(args->at[1]) + "): give the height as --at X,Y,Z");
        pose.position = Vec3(args->at[0], args->at[1], top->z_m + args->height_m);
      }
      pose.yaw = args->yaw_deg * std::numbers::pi / 180.0;
      const LidarScene lidar(scene);
      const double turn = 1.0 / spec.rotation_hz;
      std::vector<LidarPoint> points;
      const auto start = std::chrono::steady_clock::now();
      for (int k = 0; k < args->sweeps; ++k)
        points = lidar.scan(spec, pose, 0.0, turn, {}, static_cast<std::uint64_t>(k) + 1);
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      std::filesystem::create_directories(args->out);
      OutputSet files;
      files.add(std::filesystem::path(args->out) / "lidar.pcd",
                [&](std::ostream& o) { write_pcd(o, points); });
      files.add(std::filesystem::path(args->out) / "lidar.ply",
                [&](std::ostream& o) { write_ply(o, points); });
      files.commit();
      std::ostringstream out;
      out << "relief lidar: " << spec.name << " at (" << fixed(pose.position.x(), 2) << ", "
          << fixed(pose.position.y(), 2) << ", " << fixed(pose.position.z(), 2) << ")\n"
          << "  sweep      " << points.size() << " points of "
          << lidar.rays() / static_cast<std::size_t>(args->sweeps) << " rays\n"
          << "  rays       " << lidar.rays() << " in " << fixed(seconds, 3) << " s on one core ("
          << fixed(static_cast<double>(lidar.rays()) / seconds / 1e6, 2) << " M/s)\n"
          << "  wrote      " << args->out << "/lidar.pcd, lidar.ply\n";
      std::cout << out.str();
      return static_cast<int>(kOk);
    });
  };
}

}  // namespace relief::cli

// Benchmark (not a test): the co-simulation's own step, setting N vehicles on a scene's surface
// on their four wheel contacts (cosim/vehicle_pose.h), for N = 100, 1 000 and 5 000 vehicles at
// random places and headings on the Road_Road mesh of a .glb a relief build wrote. Prints the
// time per vehicle and how much faster than real time a 20 Hz step of N vehicles runs on one core.
//   build with -DRELIEF_BUILD_BENCHMARKS=ON, run build/bench/relief_vehicle_placement OUT/NAME.glb
#include <chrono>
#include <cstdio>
#include <random>

#include "relief/cosim/vehicle_pose.h"
#include "relief/export/mesh_writer.h"

int main(int argc, char** argv) {
  using namespace relief;
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s SCENE.glb\n", argv[0]);
    return 2;
  }
  const MeshScene scene = read_mesh_file(argv[1]);
  const auto t0 = std::chrono::steady_clock::now();
  const SurfaceQuery query(scene);
  const double index_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const TriangleMesh* road = nullptr;
  for (const TriangleMesh& m : scene.meshes)
    if (m.name == "Road_Road") road = &m;
  if (road == nullptr || road->triangles.empty()) {
    std::fprintf(stderr, "%s has no Road_Road mesh\n", argv[1]);
    return 3;
  }
  std::printf("%s: %zu triangles indexed in %.3f s\n", argv[1], query.triangles_indexed(), index_s);
  std::mt19937 rng(42);
  const WheelBase wheels = wheel_base_of(5.0, 1.8);
  for (const int n : {100, 1000, 5000}) {
    struct Vehicle {
      Vec2 centre;
      double heading, z;
    };
    std::vector<Vehicle> vehicles;
    std::uniform_int_distribution<std::size_t> pick(0, road->triangles.size() - 1);
    std::uniform_real_distribution<double> angle(-3.14159, 3.14159);
    for (int i = 0; i < n; ++i) {
      const auto& t = road->triangles[pick(rng)];
      const Vec3 c = (road->vertices[t[0]] + road->vertices[t[1]] + road->vertices[t[2]]) / 3.0;
      vehicles.push_back({c.head<2>(), angle(rng), c.z()});
    }
    const int steps = std::max(20, 200000 / n);
    std::size_t placed = 0;
    const auto start = std::chrono::steady_clock::now();
    for (int s = 0; s < steps; ++s)
      for (const Vehicle& v : vehicles) placed += place_on_surface(query, v.centre, v.heading, wheels, v.z) ? 1 : 0;
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const double per_vehicle_us = 1e6 * seconds / (static_cast<double>(steps) * n);
    const double step_s = seconds / steps;
    std::printf("N = %5d: %.2f us per vehicle (4 contacts), a step %.3f ms, %.0fx faster than real time at 20 Hz, "
                "%.1f %% placed\n",
                n, per_vehicle_us, 1e3 * step_s, 0.05 / step_s,
                100.0 * static_cast<double>(placed) / (static_cast<double>(steps) * n));
  }
  return 0;
}

// Benchmark (not a test): the egos' share of a co-simulation step, N ego vehicles (Bullet raycast
// vehicles, cosim/ego_world.h) driven along lanes of a relief scene for 10 simulated seconds:
// the driver (drive_along) and the physics (10 substeps of 5 ms per 0.05 s step), on one core.
// The egos start on random Road_Road triangles heading along straight 200 m paths; the scene's
// BVH build is timed apart.
//   build with -DRELIEF_BUILD_BENCHMARKS=ON, run build/bench/relief_ego_physics OUT/NAME.glb
#include <chrono>
#include <cstdio>
#include <random>
#include <string>

#include "relief/cosim/ego_controller.h"
#include "relief/cosim/ego_world.h"
#include "relief/export/mesh_writer.h"

int main(int argc, char** argv) {
  using namespace relief;
  using Clock = std::chrono::steady_clock;
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s SCENE.glb\n", argv[0]);
    return 2;
  }
  const MeshScene scene = read_mesh_file(argv[1]);
  const TriangleMesh* road = nullptr;
  std::size_t triangles = 0;
  for (const TriangleMesh& m : scene.meshes) {
    if (m.name == "Road_Road") road = &m;
    if (m.kind != SurfaceKind::marking) triangles += m.triangles.size();
  }
  if (road == nullptr || road->triangles.empty()) {
    std::fprintf(stderr, "%s has no Road_Road mesh\n", argv[1]);
    return 3;
  }
  const auto t0 = Clock::now();
  EgoWorld world(scene);
  std::printf("%s: %zu triangles in the physics world, built in %.3f s\n", argv[1], triangles,
              std::chrono::duration<double>(Clock::now() - t0).count());
  std::mt19937 rng(42);
  std::uniform_int_distribution<std::size_t> pick(0, road->triangles.size() - 1);
  std::uniform_real_distribution<double> angle(-3.14159, 3.14159);
  const EgoSpec car = ego_spec_for("passenger", 4.5, 1.8, 1.5);
  int placed = 0;
  for (const int n : {10, 100, 1000}) {
    struct Ego {
      std::string id;
      std::vector<Vec2> path;
    };
    std::vector<Ego> egos;
    for (; placed < n; ++placed) {
      const auto& t = road->triangles[pick(rng)];
      const Vec3 c = (road->vertices[t[0]] + road->vertices[t[1]] + road->vertices[t[2]]) / 3.0;
      const double h = angle(rng);
      world.place("ego" + std::to_string(placed), car, c.head<2>(), h, c.z(), 8.0);
    }
    for (int i = 0; i < n; ++i) {
      const EgoState s = world.state("ego" + std::to_string(i));
      const Vec2 d(std::cos(s.heading_rad), std::sin(s.heading_rad));
      egos.push_back({"ego" + std::to_string(i), {s.centre, s.centre + 200.0 * d}});
    }
    constexpr int kSteps = 200;  // 10 s at 20 Hz
    const auto start = Clock::now();
    for (int step = 0; step < kSteps; ++step) {
      for (const Ego& e : egos) world.set_controls(e.id, drive_along(car, world.state(e.id), e.path, 8.0));
      world.step(0.05);
    }
    const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
    std::printf("N = %4d egos: %.1f us per ego and 0.05 s step (driver + 10 physics substeps), a step %.2f ms, "
                "%.0fx faster than real time\n",
                n, 1e6 * seconds / (kSteps * n), 1e3 * seconds / kSteps, 0.05 * kSteps / seconds);
  }
  return 0;
}

// Benchmark (not a test): relief's profile fit on generated street grids of growing size, to
// show that its cost per junction stays roughly constant. Each grid is n x n junctions 100 m
// apart, every block a residential road sampled every metre, heights from an analytic hilly
// terrain with 1 m noise, and one bridge over a crossing street every 10 blocks.
//   build with -DRELIEF_BUILD_BENCHMARKS=ON, run build/bench/relief_fit_scaling
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>

#include "relief/roads/profile_fit.h"

namespace {

using namespace relief;

double terrain(const Vec2& p) {
  return 40.0 + 25.0 * std::sin(p.x() / 700.0) * std::cos(p.y() / 900.0) +
         8.0 * std::sin(p.x() / 130.0 + p.y() / 170.0);
}

struct Grid {
  RoadNetwork network;
  std::vector<RoadProfile> raw;
};

Grid make_grid(int n) {
  Grid g;
  auto& net = g.network;
  const double block = 100.0;
  const auto junction_id = [n](int i, int j) { return i * n + j; };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      Junction jn;
      jn.id = junction_id(i, j);
      jn.position = Vec2(i * block, j * block);
      net.junctions.push_back(jn);
    }
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, 1.0);
  const auto add_road = [&](int a, int b) {
    Road road;
    road.id = static_cast<int>(net.roads.size());
    road.points = {net.junctions[a].position, net.junctions[b].position};
    road.start_junction = a;
    road.end_junction = b;
    net.junctions[a].ends.push_back({road.id, true});
    net.junctions[b].ends.push_back({road.id, false});
    net.roads.push_back(road);
    RoadProfile p = make_stations(road, 1.0);
    for (std::size_t k = 0; k < p.size(); ++k) p.z[k] = terrain(p.xy[k]) + noise(rng);
    g.raw.push_back(p);
  };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      if (i + 1 < n) add_road(junction_id(i, j), junction_id(i + 1, j));
      if (j + 1 < n) add_road(junction_id(i, j), junction_id(i, j + 1));
    }
  for (Junction& j : net.junctions) {
    j.kind = j.ends.size() >= 3 ? JunctionKind::intersection : JunctionKind::attribute_change;
  }
  return g;
}

}  // namespace

int main() {
  std::printf("%10s %10s %12s %10s %8s %14s\n", "junctions", "roads", "samples", "seconds", "rounds",
              "us/junction");
  for (int n : {10, 20, 40, 70, 100}) {
    const Grid g = make_grid(n);
    std::size_t samples = 0;
    for (const auto& p : g.raw) samples += p.size();
    Diagnostics d;
    const auto t0 = std::chrono::steady_clock::now();
    const ProfileFitResult fit = fit_profiles(g.network, g.raw, {}, d);
    const double dt = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const std::size_t junctions = g.network.junctions.size();
    std::printf("%10zu %10zu %12zu %10.3f %8d %14.1f\n", junctions, g.network.roads.size(), samples, dt,
                fit.iterations, 1e6 * dt / static_cast<double>(junctions));
  }
}

#include "support/mesh_grid.h"

#include <cstdint>

namespace relief::test {

void add_grid(TriangleMesh& mesh, double x0, double y0, int nx, int ny, double z) {
  const auto base = static_cast<std::uint32_t>(mesh.vertices.size());
  for (int j = 0; j <= ny; ++j) {
    for (int i = 0; i <= nx; ++i) mesh.vertices.emplace_back(x0 + i, y0 + j, z);
  }
  const auto at = [&](int i, int j) { return base + static_cast<std::uint32_t>(j * (nx + 1) + i); };
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      mesh.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      mesh.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  }
}

}  // namespace relief::test

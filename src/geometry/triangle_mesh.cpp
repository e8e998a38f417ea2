#include "relief/geometry/triangle_mesh.h"

#include "relief/core/errors.h"

namespace relief {

void TriangleMesh::append(const TriangleMesh& other) {
  const auto base = static_cast<std::uint32_t>(vertices.size());
  const bool keep_normals = normals.size() == vertices.size() && other.normals.size() == other.vertices.size();
  const bool keep_uvs = uvs.size() == vertices.size() && other.uvs.size() == other.vertices.size();
  vertices.insert(vertices.end(), other.vertices.begin(), other.vertices.end());
  for (const auto& t : other.triangles) triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  if (keep_normals) {
    normals.insert(normals.end(), other.normals.begin(), other.normals.end());
  } else {
    normals.clear();
  }
  if (keep_uvs) {
    uvs.insert(uvs.end(), other.uvs.begin(), other.uvs.end());
  } else {
    uvs.clear();
  }
}

TriangleMesh submesh(const TriangleMesh& mesh, const std::vector<std::uint8_t>& keep) {
  if (keep.size() != mesh.triangles.size()) {
    throw InvalidInput("submesh: " + std::to_string(keep.size()) + " flags for " +
                       std::to_string(mesh.triangles.size()) + " triangles");
  }
  TriangleMesh out;
  out.name = mesh.name;
  out.kind = mesh.kind;
  const bool normals = mesh.normals.size() == mesh.vertices.size();
  const bool uvs = mesh.uvs.size() == mesh.vertices.size();
  constexpr std::uint32_t kUnused = ~std::uint32_t{0};
  std::vector<std::uint32_t> index(mesh.vertices.size(), kUnused);
  for (std::size_t i = 0; i < keep.size(); ++i) {
    if (!keep[i]) continue;
    std::array<std::uint32_t, 3> t{};
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t v = mesh.triangles[i][static_cast<std::size_t>(k)];
      if (index[v] == kUnused) {
        index[v] = static_cast<std::uint32_t>(out.vertices.size());
        out.vertices.push_back(mesh.vertices[v]);
        if (normals) out.normals.push_back(mesh.normals[v]);
        if (uvs) out.uvs.push_back(mesh.uvs[v]);
      }
      t[static_cast<std::size_t>(k)] = index[v];
    }
    out.triangles.push_back(t);
  }
  return out;
}

std::vector<Vec3> vertex_normals(const TriangleMesh& mesh) {
  std::vector<Vec3> n(mesh.vertices.size(), Vec3::Zero());
  for (const auto& t : mesh.triangles) {
    const Vec3& a = mesh.vertices[t[0]];
    const Vec3 face = (mesh.vertices[t[1]] - a).cross(mesh.vertices[t[2]] - a);  // |face| = 2 area
    for (const std::uint32_t v : t) n[v] += face;
  }
  for (Vec3& v : n) {
    const double len = v.norm();
    v = len > 0.0 ? Vec3(v / len) : Vec3::UnitZ();
  }
  return n;
}

}  // namespace relief

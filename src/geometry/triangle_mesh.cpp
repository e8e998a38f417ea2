#include "relief/geometry/triangle_mesh.h"

#include <algorithm>
#include <cstring>
#include <unordered_map>

#include <Eigen/Geometry>  // cross()

#include "geometry/edge_order.h"
#include "relief/core/errors.h"

namespace relief {

void TriangleMesh::append(const TriangleMesh& other) {
  const auto base = static_cast<std::uint32_t>(vertices.size());
  const bool keep_normals =
      normals.size() == vertices.size() && other.normals.size() == other.vertices.size();
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

std::vector<std::vector<std::uint32_t>> boundary_loops(const TriangleMesh& mesh) {
  const std::size_t n = mesh.vertices.size();
  // Every edge once per triangle, keyed by its sorted ends; keys seen once are the boundary.
  struct Edge {
    std::uint32_t lo, hi, from, to;
  };
  std::vector<Edge> edges;
  edges.reserve(3 * mesh.triangles.size());
  for (const auto& t : mesh.triangles) {
    for (std::size_t k = 0; k < 3; ++k) {
      const std::uint32_t a = t[k], b = t[(k + 1) % 3];
      if (a >= n || b >= n) {
        throw InvalidInput("boundary_loops: mesh '" + mesh.name + "' has a vertex index out of range");
      }
      if (a != b) edges.push_back({std::min(a, b), std::max(a, b), a, b});
    }
  }
  detail::sort_by_vertex_pair(
      edges, n, [](const Edge& e) { return e.lo; }, [](const Edge& e) { return e.hi; });
  std::vector<Edge> boundary;
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i + 1;
    while (j < edges.size() && edges[j].lo == edges[i].lo && edges[j].hi == edges[i].hi) ++j;
    if (j == i + 1) boundary.push_back(edges[i]);
    i = j;
  }

  // Boundary edges incident to each vertex (compressed rows).
  std::vector<std::uint32_t> first(n + 1, 0), incident(2 * boundary.size());
  for (const Edge& e : boundary) {
    ++first[e.from + 1];
    ++first[e.to + 1];
  }
  for (std::size_t v = 0; v < n; ++v) first[v + 1] += first[v];
  std::vector<std::uint32_t> fill(first.begin(), first.end() - 1);
  for (std::uint32_t i = 0; i < boundary.size(); ++i) {
    incident[fill[boundary[i].from]++] = i;
    incident[fill[boundary[i].to]++] = i;
  }

  // Walk unused edges, following the triangles' direction where possible; when the walk comes
  // back to a vertex already on its path, the part of the path since then is a loop (so loops
  // that touch at a vertex come out separately). A walk that gets stuck (odd vertex degree at a
  // non-manifold edge) leaves an open chain, which is dropped.
  constexpr std::uint32_t kNone = ~std::uint32_t{0};
  std::vector<std::uint8_t> used(boundary.size(), 0);
  std::vector<std::uint32_t> position(n, kNone);
  std::vector<std::uint32_t> path;
  std::vector<std::vector<std::uint32_t>> loops;
  const auto next_edge = [&](std::uint32_t v) {
    std::uint32_t any = kNone;
    for (std::uint32_t k = first[v]; k < first[v + 1]; ++k) {
      const std::uint32_t e = incident[k];
      if (used[e]) continue;
      if (boundary[e].from == v) return e;
      if (any == kNone) any = e;
    }
    return any;
  };
  for (std::uint32_t start = 0; start < boundary.size(); ++start) {
    if (used[start]) continue;
    std::uint32_t v = boundary[start].from;
    path.assign(1, v);
    position[v] = 0;
    for (std::uint32_t e = start; e != kNone; e = next_edge(v)) {
      used[e] = 1;
      v = boundary[e].from == v ? boundary[e].to : boundary[e].from;
      if (position[v] == kNone) {
        position[v] = static_cast<std::uint32_t>(path.size());
        path.push_back(v);
        continue;
      }
      const auto begin = path.begin() + position[v];
      loops.emplace_back(begin, path.end());
      for (auto it = begin + 1; it != path.end(); ++it) position[*it] = kNone;
      path.erase(begin + 1, path.end());
    }
    for (const std::uint32_t u : path) position[u] = kNone;
  }
  return loops;
}

TriangleMesh weld_identical_vertices(const TriangleMesh& mesh) {
  struct Key {
    std::uint64_t x, y, z;
    bool operator==(const Key&) const = default;
  };
  struct Hash {
    std::size_t operator()(const Key& k) const {
      return static_cast<std::size_t>(k.x * 0x9E3779B97F4A7C15ULL ^ (k.y * 0xC2B2AE3D27D4EB4FULL) ^
                                      (k.z * 131));
    }
  };
  std::unordered_map<Key, std::uint32_t, Hash> index;
  index.reserve(mesh.vertices.size());
  TriangleMesh out;
  out.name = mesh.name;
  out.kind = mesh.kind;
  std::vector<std::uint32_t> map(mesh.vertices.size());
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
    Key k{};
    std::memcpy(&k.x, &mesh.vertices[v].x(), sizeof k.x);
    std::memcpy(&k.y, &mesh.vertices[v].y(), sizeof k.y);
    std::memcpy(&k.z, &mesh.vertices[v].z(), sizeof k.z);
    const auto [it, inserted] = index.try_emplace(k, static_cast<std::uint32_t>(out.vertices.size()));
    if (inserted) out.vertices.push_back(mesh.vertices[v]);
    map[v] = it->second;
  }
  out.triangles.reserve(mesh.triangles.size());
  for (const auto& t : mesh.triangles) out.triangles.push_back({map[t[0]], map[t[1]], map[t[2]]});
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

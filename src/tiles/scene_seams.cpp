#include "tiles/scene_seams.h"

#include <bit>
#include <cmath>
#include <cstdint>
#include <string>
#include <unordered_map>

namespace relief::detail {
namespace {

struct Seen {
  double z;
  std::size_t tile;
};

}  // namespace

SeamWeld weld_seams(std::vector<MeshScene>& tiles, double max_dz_m) {
  SeamWeld weld;
  std::unordered_map<std::string, std::unordered_map<PlanKey, std::vector<Seen>, PlanKeyHash>> seen;
  for (std::size_t t = 0; t < tiles.size(); ++t) {
    for (TriangleMesh& mesh : tiles[t].meshes) {
      auto& heights = seen[mesh.name];
      for (Vec3& v : mesh.vertices) {
        std::vector<Seen>& at = heights[plan_key(v)];
        const Seen* nearest = nullptr;
        for (const Seen& s : at) {
          if (s.tile != t && (nearest == nullptr || std::abs(s.z - v.z()) < std::abs(nearest->z - v.z())))
            nearest = &s;
        }
        if (nearest != nullptr) {
          ++weld.shared_vertices;
          const double dz = std::abs(nearest->z - v.z());
          if (dz <= max_dz_m) {
            weld.max_dz_m = std::max(weld.max_dz_m, dz);
            if (dz > 0.0) ++weld.welded;
            v.z() = nearest->z;
            continue;
          }
          SeamApart& apart = weld.left_apart[mesh.name];
          ++apart.vertices;
          if (dz > apart.max_m) {
            apart.max_m = dz;
            apart.at = v;
          }
        }
        at.push_back({v.z(), t});
      }
    }
  }
  return weld;
}

TriangleMesh joined_mesh(const std::vector<MeshScene>& tiles, const std::string& name) {
  TriangleMesh out;
  out.name = name;
  struct Key {
    std::uint64_t x, y, z;
    bool operator==(const Key&) const = default;
  };
  struct KeyHash {
    std::size_t operator()(const Key& k) const {
      return std::hash<std::uint64_t>()((k.x * 0x9E3779B97F4A7C15ull ^ k.y) * 0xBF58476D1CE4E5B9ull ^ k.z);
    }
  };
  std::unordered_map<Key, std::uint32_t, KeyHash> index;
  for (const MeshScene& tile : tiles) {
    for (const TriangleMesh& mesh : tile.meshes) {
      if (mesh.name != name) continue;
      out.kind = mesh.kind;
      std::vector<std::uint32_t> map(mesh.vertices.size());
      for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
        const Vec3& v = mesh.vertices[i];
        const Key key{std::bit_cast<std::uint64_t>(v.x()), std::bit_cast<std::uint64_t>(v.y()),
                      std::bit_cast<std::uint64_t>(v.z())};
        const auto [it, inserted] = index.emplace(key, static_cast<std::uint32_t>(out.vertices.size()));
        if (inserted) out.vertices.push_back(v);
        map[i] = it->second;
      }
      for (const auto& t : mesh.triangles) out.triangles.push_back({map[t[0]], map[t[1]], map[t[2]]});
    }
  }
  return out;
}

}  // namespace relief::detail

#include "relief/scene/road_mesh.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "relief/core/diagnostic_codes.h"
#include "relief/core/errors.h"
#include "scene/junction_surface.h"
#include "scene/lane_loft.h"
#include "scene/mesh_builder.h"

namespace relief {

namespace {

using detail::JunctionEnd;
using detail::LoftedRoad;
using detail::MeshBuilder;

constexpr double kWeldTolerance = 0.005;  // road ends linked directly share vertices this close (m)
constexpr double kShortRoad = 1e-6;       // roads shorter than this are not lofted (m)

void check_options(const RoadMeshOptions& options) {
  if (!(options.tolerance_m > 0.0) || !std::isfinite(options.tolerance_m)) {
    throw InvalidInput("road mesh: tolerance_m must be positive and finite, got " +
                       std::to_string(options.tolerance_m));
  }
  if (!(options.max_spacing_m > 0.0) || !std::isfinite(options.max_spacing_m)) {
    throw InvalidInput("road mesh: max_spacing_m must be positive and finite, got " +
                       std::to_string(options.max_spacing_m));
  }
  if (!(options.marking_lift_m >= 0.0) || !std::isfinite(options.marking_lift_m)) {
    throw InvalidInput("road mesh: marking_lift_m must be non-negative and finite, got " +
                       std::to_string(options.marking_lift_m));
  }
}

/// Welds the vertices of road ends that are linked directly to another road: each vertex is
/// looked up in a spatial hash of the vertices already seen (cells of the weld tolerance, the
/// 27 cells around it) and mapped onto the nearest one of another road within the tolerance.
/// Returns the map (identity where not welded); `unmatched` counts vertices left without partner.
class EndWelder {
 public:
  EndWelder(const TriangleMesh& mesh, double tolerance) : mesh_(mesh), tolerance_(tolerance) {
    remap_.resize(mesh.vertices.size());
    for (std::size_t i = 0; i < remap_.size(); ++i) remap_[i] = static_cast<std::uint32_t>(i);
  }

  void add(const std::vector<std::uint32_t>& vertices, int road) {
    for (const std::uint32_t v : vertices) {
      const Vec3& p = mesh_.vertices[v];
      const std::array<std::int64_t, 3> cell = cell_of(p);
      Entry* best = nullptr;
      double best_distance = tolerance_;
      for (std::int64_t dx = -1; dx <= 1; ++dx) {
        for (std::int64_t dy = -1; dy <= 1; ++dy) {
          for (std::int64_t dz = -1; dz <= 1; ++dz) {
            const auto it = grid_.find(key({cell[0] + dx, cell[1] + dy, cell[2] + dz}));
            if (it == grid_.end()) continue;
            for (Entry& e : it->second) {
              const double d = (mesh_.vertices[e.vertex] - p).norm();
              if (e.road != road && d <= best_distance) {
                best_distance = d;
                best = &e;
              }
            }
          }
        }
      }
      if (best != nullptr) {
        if (best->vertex != v) remap_[v] = best->vertex;
        best->matched = true;
      } else {
        grid_[key(cell)].push_back(Entry{v, road, false});
      }
    }
  }

  [[nodiscard]] std::size_t unmatched() const {
    std::size_t count = 0;
    for (const auto& [k, entries] : grid_) {
      for (const Entry& e : entries) count += e.matched ? 0 : 1;
    }
    return count;
  }

  [[nodiscard]] const std::vector<std::uint32_t>& remap() const { return remap_; }

 private:
  struct Entry {
    std::uint32_t vertex;
    int road;
    bool matched;
  };
  [[nodiscard]] std::array<std::int64_t, 3> cell_of(const Vec3& p) const {
    return {static_cast<std::int64_t>(std::floor(p.x() / tolerance_)),
            static_cast<std::int64_t>(std::floor(p.y() / tolerance_)),
            static_cast<std::int64_t>(std::floor(p.z() / tolerance_))};
  }
  static std::uint64_t key(const std::array<std::int64_t, 3>& c) {
    // 21 bits per axis: cells of 5 mm cover +-5 km, beyond which keys merely collide (and the
    // distance test still decides).
    const auto part = [](std::int64_t v) { return static_cast<std::uint64_t>(v) & 0x1FFFFFu; };
    return part(c[0]) | (part(c[1]) << 21) | (part(c[2]) << 42);
  }

  const TriangleMesh& mesh_;
  double tolerance_;
  std::vector<std::uint32_t> remap_;
  std::unordered_map<std::uint64_t, std::vector<Entry>> grid_;
};

/// Applies a vertex map to the triangles (dropping those that collapse) and to the end lists.
void apply_remap(MeshBuilder& builder, const std::vector<std::uint32_t>& remap) {
  std::size_t kept = 0;
  for (std::size_t i = 0; i < builder.mesh.triangles.size(); ++i) {
    auto t = builder.mesh.triangles[i];
    for (std::uint32_t& v : t) v = remap[v];
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) continue;
    builder.mesh.triangles[kept] = t;
    builder.owner[kept] = builder.owner[i];
    ++kept;
  }
  builder.mesh.triangles.resize(kept);
  builder.owner.resize(kept);
}

void remap_list(std::vector<std::uint32_t>& list, const std::vector<std::uint32_t>& remap) {
  std::vector<std::uint32_t> out;
  for (const std::uint32_t v : list) {
    const std::uint32_t w = remap[v];
    if (out.empty() || out.back() != w) out.push_back(w);
  }
  list = std::move(out);
}

/// Ends of lofted roads linked directly to another lofted road, welded in each mesh. Returns the
/// road and sidewalk vertices left without partner (marks may end where the next road's do not
/// start: a solid line that becomes broken).
std::size_t weld_linked_ends(const RoadModel& model, std::vector<std::optional<LoftedRoad>>& lofted,
                             MeshBuilder& road, MeshBuilder& sidewalk, MeshBuilder& marking) {
  const auto linked_to_road = [&](const std::optional<RoadLink>& link) {
    if (!link || link->element != RoadLink::Element::road) return false;
    const int other = model.road_index(link->id);
    return other >= 0 && lofted[static_cast<std::size_t>(other)].has_value();
  };
  std::size_t unmatched = 0;
  for (int mesh = 0; mesh < 3; ++mesh) {
    MeshBuilder& builder = mesh == 0 ? road : mesh == 1 ? sidewalk : marking;
    EndWelder welder(builder.mesh, kWeldTolerance);
    const auto list = [mesh](detail::RoadEnd& end) -> std::vector<std::uint32_t>& {
      return mesh == 0 ? end.road_vertices : mesh == 1 ? end.sidewalk_vertices : end.marking_vertices;
    };
    for (std::size_t i = 0; i < lofted.size(); ++i) {
      if (!lofted[i]) continue;
      const ModelRoad& r = model.roads[i];
      if (linked_to_road(r.predecessor)) welder.add(list(lofted[i]->start), r.id);
      if (linked_to_road(r.successor)) welder.add(list(lofted[i]->end), r.id);
    }
    if (mesh < 2) unmatched += welder.unmatched();
    apply_remap(builder, welder.remap());
    for (auto& l : lofted) {
      if (!l) continue;
      remap_list(list(l->start), welder.remap());
      remap_list(list(l->end), welder.remap());
    }
  }
  return unmatched;
}

/// The final mesh: unused (welded) vertices removed, normals from the geometry.
TriangleMesh finish(const MeshBuilder& builder, const std::string& name, SurfaceKind kind) {
  TriangleMesh mesh = submesh(builder.mesh, std::vector<std::uint8_t>(builder.mesh.triangles.size(), 1));
  mesh.name = name;
  mesh.kind = kind;
  mesh.normals = vertex_normals(mesh);
  return mesh;
}

}  // namespace

RoadMeshes build_road_meshes(const RoadModel& model, const RoadMeshOptions& options,
                             Diagnostics& diagnostics) {
  check_options(options);
  MeshBuilder road, sidewalk, marking;
  RoadMeshes out;

  // 1. Lofted lanes of every road outside junctions.
  std::vector<std::optional<LoftedRoad>> lofted(model.roads.size());
  for (std::size_t i = 0; i < model.roads.size(); ++i) {
    const ModelRoad& r = model.roads[i];
    if (r.junction != -1) continue;
    Diagnostic d;
    d.road_id = r.id;
    if (!(r.length() > kShortRoad)) {
      d.code = codes::kMeshRoadTooShort;
      d.message =
          "road " + std::to_string(r.id) + " is too short to loft (" + std::to_string(r.length()) + " m)";
      diagnostics.report(std::move(d));
      continue;
    }
    try {
      lofted[i] = detail::loft_road(r, options, road, sidewalk, options.markings ? &marking : nullptr);
      out.max_surface_deviation_m = std::max(out.max_surface_deviation_m, lofted[i]->max_deviation_m);
    } catch (const InvalidInput& e) {
      d.code = codes::kMeshRoadFailed;
      d.message = e.what();
      diagnostics.report(std::move(d));
    }
  }

  // 2. Roads linked end to end share their end vertices.
  const std::size_t unmatched = weld_linked_ends(model, lofted, road, sidewalk, marking);
  if (unmatched > 0) {
    diagnostics.report(Severity::info, codes::kMeshWeldUnmatched,
                       std::to_string(unmatched) +
                           " vertices of directly linked road ends have no partner within 5 mm "
                           "(lane counts differ across the link)");
  }

  // 3. Junction areas: the road ends at each junction and its connecting roads.
  std::unordered_map<int, std::size_t> junction_at;
  for (std::size_t j = 0; j < model.junctions.size(); ++j) junction_at.emplace(model.junctions[j].id, j);
  std::vector<std::vector<std::pair<int, bool>>> end_keys(model.junctions.size());
  std::vector<std::vector<int>> connecting(model.junctions.size());
  for (std::size_t i = 0; i < model.roads.size(); ++i) {
    const ModelRoad& r = model.roads[i];
    const auto touch = [&](const std::optional<RoadLink>& link, bool at_start) {
      if (!link) return;
      if (r.junction != -1) {
        // A connecting road: the road it leaves or reaches ends at its junction.
        const auto it = junction_at.find(r.junction);
        const int other = link->element == RoadLink::Element::road ? model.road_index(link->id) : -1;
        if (it != junction_at.end() && other >= 0 &&
            model.roads[static_cast<std::size_t>(other)].junction == -1) {
          end_keys[it->second].emplace_back(other, link->contact == RoadLink::Contact::start);
        }
      } else if (link->element == RoadLink::Element::junction) {
        const auto it = junction_at.find(link->id);
        if (it != junction_at.end()) end_keys[it->second].emplace_back(static_cast<int>(i), at_start);
      }
    };
    touch(r.predecessor, true);
    touch(r.successor, false);
    if (r.junction != -1) {
      const auto it = junction_at.find(r.junction);
      if (it != junction_at.end()) connecting[it->second].push_back(static_cast<int>(i));
    }
  }
  for (std::size_t j = 0; j < model.junctions.size(); ++j) {
    std::vector<std::pair<int, bool>>& keys = end_keys[j];
    std::sort(keys.begin(), keys.end());
    keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
    std::vector<JunctionEnd> ends;
    for (const auto& [index, at_start] : keys) {
      const std::optional<LoftedRoad>& l = lofted[static_cast<std::size_t>(index)];
      if (!l) continue;
      JunctionEnd e{index, at_start, at_start ? l->start.road_vertices : l->end.road_vertices, {}, {}};
      // Stored left to right looking along +s; out of the junction that is +s at the start.
      if (at_start) {
        std::reverse(e.vertices.begin(), e.vertices.end());
        e.left_edge = l->left_edge;
        e.right_edge = l->right_edge;
      } else {
        e.left_edge.assign(l->right_edge.rbegin(), l->right_edge.rend());
        e.right_edge.assign(l->left_edge.rbegin(), l->left_edge.rend());
      }
      ends.push_back(std::move(e));
    }
    const JunctionModel& junction = model.junctions[j];
    // Where it is: the mean of its road ends' edge vertices.
    Vec3 centre = Vec3::Zero();
    std::size_t corners = 0;
    for (const JunctionEnd& e : ends) {
      for (const std::uint32_t v : e.vertices) centre += road.mesh.vertices[v];
      corners += e.vertices.size();
    }
    if (corners > 0) centre /= static_cast<double>(corners);
    const detail::JunctionSurfaceResult built =
        detail::build_junction_surface(model, junction, std::move(ends), connecting[j], options, road);
    const std::string& problem = built.problem;
    // Where it is, for the messages (only a junction that has one is named).
    const auto place = [&] {
      char at[96];
      std::snprintf(at, sizeof at, " at (%.1f, %.1f, %.2f)", centre.x(), centre.y(), centre.z());
      return "junction " + std::to_string(junction.id) + (corners > 0 ? at : "");
    };
    for (const auto& [index, at_start] : built.left_out) {
      const ModelRoad& left_out = model.roads[static_cast<std::size_t>(index)];
      diagnostics.report(
          Severity::warning, codes::kMeshJunctionEndLeftOut,
          place() + ": the " + (at_start ? "start" : "end") + " of road " + std::to_string(left_out.id) +
              osm_way_note(left_out) +
              " lies on another of its roads or across its other ends (two roads' ends on "
              "each other?); the junction's surface is built without it and that end stays open");
    }
    if (problem.empty()) {
      ++out.junctions_meshed;
    } else {
      ++out.junctions_failed;
      if (out.first_failed_junction.empty()) out.first_failed_junction = place();
      if (corners > 0) out.failed_junctions.push_back({junction.id, centre});
      diagnostics.report(Severity::warning, codes::kMeshJunctionFailed,
                         place() + ": " + problem + "; its area is left open");
    }
  }

  // 4. Final meshes.
  out.road = finish(road, "Road_Road", SurfaceKind::road);
  out.road_triangle_owner = road.owner;
  out.sidewalk = finish(sidewalk, "Road_Sidewalk", SurfaceKind::sidewalk);
  out.sidewalk_triangle_owner = sidewalk.owner;
  out.marking = finish(marking, "Road_Marking", SurfaceKind::marking);
  out.marking_triangle_owner = marking.owner;
  return out;
}

}  // namespace relief

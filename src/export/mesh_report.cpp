#include "relief/export/mesh_report.h"

#include <nlohmann/json.hpp>

#include <cmath>

#include "relief/export/report_writer.h"

namespace relief {
namespace {

using Json = nlohmann::ordered_json;

// Rounds a figure for the report (the step is the precision written).
double round_to(double value, double step) {
  return std::round(value / step) * step;
}

Json optional_length(const std::optional<double>& v) {
  return v ? Json(round_to(*v, 1e-4)) : Json(nullptr);
}

Json mesh_json(const MeshQuality& m) {
  const bool has_vertices = !m.bounds.empty();
  Json sites = Json::array();
  for (const Vec3& p : m.self_intersection_sites) {
    sites.push_back(Json::array({round_to(p.x(), 1e-2), round_to(p.y(), 1e-2), round_to(p.z(), 1e-2)}));
  }
  Json holes = Json::array();
  for (std::size_t k = 0; k < m.hole_sites.size(); ++k) {
    const Vec3& p = m.hole_sites[k];
    holes.push_back(
        {{"at", Json::array({round_to(p.x(), 1e-2), round_to(p.y(), 1e-2), round_to(p.z(), 1e-2)})},
         {"length_m", round_to(m.hole_lengths_m[k], 1e-2)}});
  }
  return {{"name", m.name},
          {"vertices", m.vertices},
          {"triangles", m.triangles},
          {"unused_vertices", m.unused_vertices},
          {"components", m.components},
          {"boundary_edges", m.boundary_edges},
          {"boundary_loops", m.boundary_loops},
          {"holes", m.holes},
          {"hole_sites", holes},
          {"non_manifold_edges", m.non_manifold_edges},
          {"non_manifold_vertices", m.non_manifold_vertices},
          {"inconsistent_orientation_edges", m.inconsistent_orientation_edges},
          {"upside_down_triangles", m.upside_down_triangles},
          {"self_intersecting_pairs",
           m.self_intersections_checked ? Json(m.self_intersecting_pairs) : Json(nullptr)},
          {"self_intersection_sites", sites},
          {"degenerate_triangles", m.degenerate_triangles},
          {"sliver_triangles", m.sliver_triangles},
          {"min_angle_deg", round_to(m.min_angle_deg, 1e-3)},
          {"max_aspect_ratio", round_to(m.max_aspect_ratio, 1e-3)},
          {"area_m2", round_to(m.area_m2, 1e-4)},
          {"bounds", has_vertices ? Json{{"min_x", round_to(m.bounds.min.x(), 1e-4)},
                                         {"min_y", round_to(m.bounds.min.y(), 1e-4)},
                                         {"max_x", round_to(m.bounds.max.x(), 1e-4)},
                                         {"max_y", round_to(m.bounds.max.y(), 1e-4)}}
                                  : Json(nullptr)},
          {"z", has_vertices ? Json{{"min", round_to(m.min_z, 1e-4)}, {"max", round_to(m.max_z, 1e-4)}}
                             : Json(nullptr)}};
}

}  // namespace

std::string mesh_report_json(const std::vector<MeshQuality>& meshes, const MeshReportExtras& extras) {
  Json j;
  j["relief_version"] = relief_version();
  j["file"] = extras.file;
  Json list = Json::array();
  for (const MeshQuality& m : meshes) list.push_back(mesh_json(m));
  j["meshes"] = list;
  j["seams"] = {{"road_junction_max_gap_m", optional_length(extras.seam_road_junction_m)},
                {"road_terrain_max_gap_m", optional_length(extras.seam_road_terrain_m)}};
  j["xodr_surface_max_distance_m"] = optional_length(extras.xodr_surface_max_distance_m);
  return j.dump(2) + "\n";
}

}  // namespace relief

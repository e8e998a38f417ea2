#pragma once
// mesh_report.json: the quality figures of the meshes written (geometry/mesh_quality.h), the
// gaps along the seams between them, and how far the road mesh departs from the OpenDRIVE
// road surface it was built for.

#include <optional>
#include <string>
#include <vector>

#include "relief/geometry/mesh_quality.h"

namespace relief {

/// Figures that concern more than one mesh. A figure that was not measured stays empty and is
/// written as null.
struct MeshReportExtras {
  std::string file;                                   ///< the mesh file the figures are of
  std::optional<double> seam_road_junction_m;         ///< SeamGap::max_gap_m, road -> junction meshes
  std::optional<double> seam_road_terrain_m;          ///< SeamGap::max_gap_m, road -> terrain mesh
  std::optional<double> xodr_surface_max_distance_m;  ///< largest road vertex to .xodr surface distance
};

/// The report as pretty-printed JSON. Keys (stable): relief_version, file,
/// meshes[{name, vertices, triangles, unused_vertices, components, boundary_edges,
/// boundary_loops, holes, hole_sites [{at [x, y, z], length_m}, ...] (the first 20: a loop's mean vertex
/// and its length), non_manifold_edges, non_manifold_vertices,
/// inconsistent_orientation_edges, upside_down_triangles, self_intersecting_pairs (null when
/// not tested), self_intersection_sites [[x, y, z], ...] (the first 20, 1 cm), degenerate_triangles,
/// sliver_triangles, min_angle_deg, max_aspect_ratio, area_m2, bounds{min_x, min_y, max_x, max_y} | null,
/// z{min, max} | null}], seams{road_junction_max_gap_m, road_terrain_max_gap_m}, xodr_surface_max_distance_m.
/// Lengths are rounded to 0.1 mm, angles and ratios to 1e-3, areas to 1e-4 m^2.
[[nodiscard]] std::string mesh_report_json(const std::vector<MeshQuality>& meshes,
                                           const MeshReportExtras& extras);

}  // namespace relief

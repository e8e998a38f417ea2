#include "relief/export/report_writer.h"

#include <nlohmann/json.hpp>

#include <cmath>

#include "export/sight_json.h"
#include "relief/core/number_format.h"
#include "relief/export/geojson_writer.h"

namespace relief {
namespace {

using Json = nlohmann::ordered_json;

Json error_json(const ErrorStats& e) {
  return {{"mae_m", round_to(e.mae_m, 1e-4)},
          {"rmse_m", round_to(e.rmse_m, 1e-4)},
          {"max_m", round_to(e.max_m, 1e-4)},
          {"bias_m", round_to(e.bias_m, 1e-4)},
          {"n", e.n}};
}

Json dem_json(const DemInfo& d) {
  Json j = {{"path", d.path},
            {"crs", d.crs},
            {"size_px", {d.width, d.height}},
            {"pixel_size", {d.pixel_size.x(), d.pixel_size.y()}},
            {"vertical_unit", to_string(d.unit)},
            {"unit_source", d.unit_stated_by_user  ? "user"
                            : d.unit_from_metadata ? "metadata"
                                                   : "assumed"},
            {"nodata", d.nodata ? Json(*d.nodata) : Json(nullptr)},
            {"transform", d.transform_name},
            {"transform_accuracy_m", d.transform_accuracy_m ? Json(*d.transform_accuracy_m) : Json(nullptr)},
            {"implausible_cells", d.implausible_cells},
            {"spike_cells", d.spike_cells},
            {"off_ground_cells", d.off_ground_cells}};
  if (!d.missing_grids.empty()) j["missing_grids"] = d.missing_grids;
  if (d.extent_wgs84) {
    j["extent_wgs84"] = {d.extent_wgs84->min_lon, d.extent_wgs84->min_lat, d.extent_wgs84->max_lon,
                         d.extent_wgs84->max_lat};
  }
  return j;
}

Json optional_int(const std::optional<int>& v) {
  return v ? Json(*v) : Json(nullptr);
}

Json vs_dem_json(const HeightValidation& h) {
  Json j = error_json(h.vs_dem);
  j["error_3d_mean_m"] = round_to(h.error_3d_mean_m, 1e-4);
  j["error_3d_max_m"] = round_to(h.error_3d_max_m, 1e-4);
  j["measured_at"] = "midpoints between samples";
  return j;
}

Json gradient_json(const GradeStats& g) {
  Json by_class = Json::object();
  for (const auto& [cls, c] : g.by_class) {
    by_class[cls] = {{"length_km", round_to(c.length_km, 1e-3)},
                     {"limit_percent", c.limit_percent},
                     {"compliance_percent", round_to(c.compliance_percent, 1e-2)},
                     {"max_percent", round_to(c.max_percent, 1e-2)},
                     {"p99_percent", round_to(c.p99_percent, 1e-2)}};
  }
  return {{"compliance_percent", round_to(g.compliance_percent, 1e-2)},
          {"max_percent", round_to(g.max_percent, 1e-2)},
          {"p99_percent", round_to(g.p99_percent, 1e-2)},
          {"steepest_road", optional_int(g.steepest_road)},
          {"by_class", by_class}};
}

Json junctions_json(const JunctionGapStats& j) {
  return {{"max_gap_m", round_to(j.max_gap_m, 1e-4)},
          {"worst_junction", optional_int(j.worst_junction)},
          {"over_bound", j.over_bound},
          {"bound_m", j.bound_m},
          {"checked", j.checked}};
}

Json method_json(const MethodReport& m) {
  return {{"vs_dem", vs_dem_json(m.all)},
          {"vs_dem_ground", vs_dem_json(m.ground)},
          {"vs_dem_structures", vs_dem_json(m.structures)},
          {"vs_reference", m.all.vs_reference ? error_json(*m.all.vs_reference) : Json(nullptr)},
          {"vs_reference_ground", m.ground.vs_reference ? error_json(*m.ground.vs_reference) : Json(nullptr)},
          {"gradient", gradient_json(m.gradient)},
          {"junctions", junctions_json(m.junctions)},
          {"cut_fill",
           {{"max_fill_m", round_to(m.cut_fill.max_fill_m, 1e-3)},
            {"max_cut_m", round_to(m.cut_fill.max_cut_m, 1e-3)},
            {"mean_abs_m", round_to(m.cut_fill.mean_abs_m, 1e-4)},
            {"km_over_0_5_m", round_to(m.cut_fill.km_over_0_5_m, 1e-3)},
            {"km_over_2_m", round_to(m.cut_fill.km_over_2_m, 1e-3)},
            {"worst_road", optional_int(m.cut_fill.worst_road)},
            {"worst_s_m", round_to(m.cut_fill.worst_s_m, 1e-2)}}},
          {"clearance",
           {{"separations", m.separations},
            {"alongside", m.separations_alongside},
            {"min_m", round_to(m.min_clearance_m, 1e-3)},
            {"below_required", m.below_clearance},
            {"overlaps_ordered", m.overlaps_ordered},
            {"overlaps_out_of_order", m.overlaps_out_of_order}}},
          {"seconds", round_to(m.seconds, 1e-4)}};
}

}  // namespace

std::string relief_version() {
  return "0.1.0";
}

std::string report_json(const RunReport& r) {
  Json j;
  j["relief_version"] = relief_version();
  j["name"] = r.name;
  j["created_utc"] = r.created_utc;
  j["attribution"] = kOsmAttribution;
  j["frame"] = {{"crs", r.frame.crs()},
                {"origin", {r.frame.origin().x(), r.frame.origin().y()}},
                {"proj", r.frame.proj_string()},
                {"note", "local = CRS coordinates - origin; z in metres"}};
  Json dems = Json::array(), refs = Json::array();
  for (const auto& d : r.dems) dems.push_back(dem_json(d));
  for (const auto& d : r.reference_dems) refs.push_back(dem_json(d));
  j["inputs"] = {{"osm", r.osm_path}, {"dems", dems}, {"reference_dems", refs}};
  j["settings"] = {{"interpolation", to_string(r.interpolation)},
                   {"spacing_m", r.spacing_m},
                   {"nodata_fill", r.nodata_fill}};

  const NetworkStats& n = r.network;
  Json km_by_class = Json::object();
  for (const auto& [cls, km] : n.km_by_class) km_by_class[cls] = round_to(km, 1e-3);
  j["network"] = {{"roads", n.roads},
                  {"junctions", n.junctions},
                  {"intersections", n.intersections},
                  {"attribute_changes", n.attribute_changes},
                  {"dead_ends", n.dead_ends},
                  {"roundabouts", n.roundabouts},
                  {"traffic_signals", n.traffic_signals},
                  {"bridges", n.bridges},
                  {"tunnels", n.tunnels},
                  {"length_km", round_to(n.length_km, 1e-3)},
                  {"bridge_km", round_to(n.bridge_km, 1e-3)},
                  {"tunnel_km", round_to(n.tunnel_km, 1e-3)},
                  {"km_by_class", km_by_class}};

  j["elevation"] = {
      {"samples", r.samples},
      {"void_samples", r.void_samples},
      {"uncovered_samples", r.uncovered_samples},
      {"roads_without_height", r.roads_without_height},
      {"profile_method", r.profile_method},
      {"vs_dem", vs_dem_json(r.heights)},
      {"vs_reference", r.heights.vs_reference ? error_json(*r.heights.vs_reference) : Json(nullptr)}};
  j["gradient"] = gradient_json(r.gradient);
  j["junctions"] = junctions_json(r.junctions);

  Json profiles = {{"method", r.profile_method}};
  Json limits = Json::object();
  for (const auto& [cls, percent] : r.grade_limits.percent) limits[std::string(to_string(cls))] = percent;
  profiles["grade_limits_percent"] = limits;
  if (r.fit) {
    Json violations = Json::array();
    for (const FitViolation& v : r.fit->violations) {
      Json item = {{"limit", std::string(to_string(v.limit))},
                   {"x", round_to(v.xy.x(), 1e-2)},
                   {"y", round_to(v.xy.y(), 1e-2)},
                   {"value", round_to(v.value, 1e-6)},
                   {"bound", round_to(v.bound, 1e-6)},
                   {"excess_m", round_to(v.excess_m, 1e-4)},
                   {"places", v.places}};
      if (v.road >= 0) {
        item["road"] = v.road;
        item["osm_way_id"] = v.osm_way_id;
        item["s_m"] = round_to(v.s_m, 1e-2);
      } else {
        item["junction"] = v.junction;
      }
      violations.push_back(item);
    }
    profiles["fit"] = {{"policy", r.fit->policy},
                       {"iterations", r.fit->iterations},
                       {"converged", r.fit->converged},
                       {"solver", r.fit->solver},
                       {"variables", r.fit->variables},
                       {"held_variables", r.fit->held_variables},
                       {"constraints", r.fit->constraints},
                       {"max_violation_m", r.fit->max_violation_m},
                       {"clearance_m", r.fit->clearance_m},
                       {"cutoff_wavelength_m", r.fit->cutoff_wavelength_m},
                       {"max_ground_departure_m", r.fit->max_ground_departure_m},
                       {"max_cross_slope_percent", r.fit->max_cross_slope_percent},
                       {"violations", violations}};
  }
  if (r.paper) {
    profiles["paper"] = {{"max_iterations", r.paper->max_iterations},
                         {"roads_not_converged", r.paper->roads_not_converged},
                         {"not_converged_roads", r.paper->not_converged_roads},
                         {"max_shift_m", round_to(r.paper->max_shift_m, 1e-3)}};
  }
  j["profiles"] = profiles;
  if (r.opendrive) {
    const OpenDriveSummary& o = *r.opendrive;
    j["opendrive"] = {{"file", o.file},
                      {"version", o.version},
                      {"roads", o.roads},
                      {"connecting_roads", o.connecting_roads},
                      {"connecting_roads_off_surface", o.connecting_roads_off_surface},
                      {"connecting_road_departure_max_m", o.connecting_road_departure_max_m},
                      {"junctions", o.junctions},
                      {"junctions_without_movements", o.junctions_without_movements},
                      {"junctions_joined", o.junctions_joined},
                      {"roads_absorbed", o.roads_absorbed},
                      {"direct_links", o.direct_links},
                      {"transition_roads", o.transition_roads},
                      {"transitions_as_junctions", o.transitions_as_junctions},
                      {"roads_skipped", o.roads_skipped},
                      {"max_link_gap_m", o.max_link_gap_m},
                      {"max_link_step_m", o.max_link_step_m},
                      {"link_borders_checked", o.link_borders_checked},
                      {"connecting_road_crossing_max_step_m", o.crossing_max_step_m},
                      {"connecting_road_crossing_junctions_over", o.crossing_junctions_over},
                      {"connecting_road_crossing_worst",
                       {{"junction", o.crossing_worst_junction},
                        {"x", o.crossing_worst_xy.x()},
                        {"y", o.crossing_worst_xy.y()}}},
                      {"connecting_road_over_road_max_step_m", o.over_road_max_step_m},
                      {"connecting_road_over_road_junctions_over", o.over_road_junctions_over},
                      {"connecting_road_over_road_worst",
                       {{"junction", o.over_road_worst_junction},
                        {"road", o.over_road_worst_road},
                        {"x", o.over_road_worst_xy.x()},
                        {"y", o.over_road_worst_xy.y()}}},
                      {"round_trip_max_xy_m", o.round_trip_max_xy_m},
                      {"round_trip_max_z_m", o.round_trip_max_z_m},
                      {"round_trip_points", o.round_trip_points},
                      {"elevation_max_deviation_m", o.elevation_max_deviation_m}};
  } else {
    j["opendrive"] = nullptr;
  }
  if (r.model_grades) {
    const auto grades = [](const GradeCheck& g) {
      return Json{{"max_grade_percent", round_to(g.max_grade_percent, 1e-2)},
                  {"max_excess_percent", round_to(g.max_excess_percent, 1e-2)},
                  {"roads_over", g.roads_over},
                  {"worst_road", g.worst_road},
                  {"worst_s_m", round_to(g.worst_s, 1e-2)},
                  {"worst_x", round_to(g.worst_xy.x(), 1e-2)},
                  {"worst_y", round_to(g.worst_xy.y(), 1e-2)}};
    };
    const CrossSlopeCheck& c = r.model_grades->cross_slopes;
    j["model_grades"] = {{"roads", grades(r.model_grades->roads)},
                         {"connecting_roads", grades(r.model_grades->connecting_roads)},
                         {"cross_slopes",
                          {{"max_percent", round_to(c.max_percent, 1e-2)},
                           {"worst_road", c.worst_road},
                           {"worst_s_m", round_to(c.worst_s, 1e-2)},
                           {"worst_x", round_to(c.worst_xy.x(), 1e-2)},
                           {"worst_y", round_to(c.worst_xy.y(), 1e-2)},
                           {"length_km", round_to(c.length_m / 1000.0, 1e-3)},
                           {"over_8_percent_km", round_to(c.length_over_m / 1000.0, 1e-3)},
                           {"roads_over_8_percent", c.roads_over}}}};
  }
  Json gates = Json::object();
  for (const Gate& g : r.gates) {
    Json item = {{"value", g.value}, {"threshold", g.threshold}, {"passed", g.passed}};
    if (!g.where.empty()) item["where"] = g.where;
    gates[g.name] = item;
  }
  j["gates"] = gates;
  if (r.sumo) {
    const SumoSummary& o = *r.sumo;
    j["sumo"] = {{"file", o.file},
                 {"nodes", o.nodes},
                 {"edges", o.edges},
                 {"connections", o.connections},
                 {"junctions", o.junctions},
                 {"traffic_lights", o.traffic_lights},
                 {"lanes", o.lanes},
                 {"internal_lanes", o.internal_lanes},
                 {"internal_lanes_by_netconvert", o.internal_lanes_by_netconvert},
                 {"signals_mid_road", o.signals_mid_road},
                 {"restricted_edges", o.restricted_edges},
                 {"max_grade_percent", o.max_grade_percent},
                 {"points_checked", o.points_checked},
                 {"z_max_m", round_to(o.z_max_m, 1e-4)},
                 {"z_p99_m", round_to(o.z_p99_m, 1e-4)},
                 {"z_max_lane", o.z_max_lane},
                 {"netconvert_lanes_z_max_m", round_to(o.netconvert_lanes_z_max_m, 1e-4)},
                 {"draped_points_moved", o.draped_points_moved},
                 {"drape_max_move_m", round_to(o.drape_max_move_m, 1e-4)},
                 {"drape_max_move_lane", o.drape_max_move_lane},
                 {"draped_points_added", o.draped_points_added},
                 {"handover_ends_extended", o.handover_ends_extended},
                 {"handover_max_extension_m", round_to(o.handover_max_extension_m, 1e-2)},
                 {"handover_max_extension_lane", o.handover_max_extension_lane},
                 {"handover_ends_snapped", o.handover_ends_snapped},
                 {"handover_max_snap_m", round_to(o.handover_max_snap_m, 1e-2)},
                 {"handover_max_snap_lane", o.handover_max_snap_lane},
                 {"xy_max_m", round_to(o.xy_max_m, 1e-4)},
                 {"xy_max_lane", o.xy_max_lane},
                 {"max_handover_step_m", round_to(o.max_handover_step_m, 1e-4)},
                 {"max_handover_gap_m", round_to(o.max_handover_gap_m, 1e-4)},
                 {"handover_gap_lanes", o.handover_gap_lanes},
                 {"max_lane_grade_percent", round_to(o.max_lane_grade_percent, 1e-2)},
                 {"max_internal_lane_grade_percent", round_to(o.max_internal_lane_grade_percent, 1e-2)},
                 {"max_profile_grade_percent", round_to(o.max_profile_grade_percent, 1e-2)},
                 {"netconvert_warnings", o.netconvert_warnings},
                 {"lanes_without_z", o.lanes_without_z},
                 {"height_steps", o.height_steps},
                 {"first_step_lane", o.first_step_lane},
                 {"routes", o.routes},
                 {"step_length_s", o.step_length_s}};
  } else {
    j["sumo"] = nullptr;
  }
  if (r.mesh) {
    const MeshSummary& m = *r.mesh;
    const auto quality = [](const std::optional<MeshQuality>& q) -> Json {
      if (!q) return nullptr;
      return {{"vertices", q->vertices},
              {"triangles", q->triangles},
              {"components", q->components},
              {"boundary_loops", q->boundary_loops},
              {"holes", q->holes},
              {"non_manifold_edges", q->non_manifold_edges},
              {"non_manifold_vertices", q->non_manifold_vertices},
              {"self_intersecting_pairs", q->self_intersecting_pairs},
              {"upside_down_triangles", q->upside_down_triangles},
              {"degenerate_triangles", q->degenerate_triangles},
              {"sliver_triangles", q->sliver_triangles}};
    };
    j["mesh"] = {{"files", m.files},
                 {"tile_size_m", m.tile_size_m},
                 {"tile_files", m.tile_files},
                 {"junctions_meshed", m.junctions_meshed},
                 {"junctions_failed", m.junctions_failed},
                 {"xodr_surface_max_distance_m", round_to(m.xodr_surface_max_distance_m, 1e-4)},
                 {"seam_road_junction_m", round_to(m.seam_road_junction_m, 1e-4)},
                 {"seam_road_terrain_m",
                  m.seam_road_terrain_m ? Json(round_to(*m.seam_road_terrain_m, 1e-4)) : Json()},
                 {"road", quality(m.road)},
                 {"terrain", quality(m.terrain)},
                 {"ground_holes", m.ground_holes},
                 {"ground_portals", m.ground_portals},
                 {"deck_triangles_on_ground", m.deck_triangles_on_ground},
                 {"tunnel_triangles_open", m.tunnel_triangles_open},
                 {"structure_terrain_intersecting_pairs", m.structure_terrain_intersecting_pairs},
                 {"ground_triangles_under_roads", m.ground_triangles_under_roads},
                 {"ground_components", m.ground_components},
                 {"terrain_tin_vertices", m.terrain_tin_vertices},
                 {"terrain_max_vertical_error_m", round_to(m.terrain_max_vertical_error_m, 1e-4)},
                 {"terrain_max_cut_m", round_to(m.terrain_max_cut_m, 1e-3)},
                 {"terrain_max_fill_m", round_to(m.terrain_max_fill_m, 1e-3)},
                 {"terrain_core_lines", m.core_lines ? Json{{"vertices", m.core_line_vertices},
                                                            {"detours", m.core_detours},
                                                            {"open_crossings", m.core_blocked},
                                                            {"leaks", m.core_leaks}}
                                                     : Json()}};
    j["mesh"]["carla_package"] = m.carla_package.empty()
                                     ? Json()
                                     : Json{{"file", m.carla_package},
                                            {"entries", m.carla_package_entries},
                                            {"placeholder_tiles", m.carla_placeholder_tiles}};
  } else {
    j["mesh"] = nullptr;
  }
  j["sight"] = r.sight ? sight_json(*r.sight) : Json();
  Json methods = Json::object();
  for (const MethodReport& m : r.methods) methods[m.method] = method_json(m);
  j["methods"] = methods;

  Json diag = {{"total", 0}, {"counts", Json::object()}, {"messages", Json::array()}};
  if (r.diagnostics) {
    diag["total"] = r.diagnostics->total();
    for (const auto& [code, count] : r.diagnostics->counts()) diag["counts"][code] = count;
    for (const Diagnostic& d : r.diagnostics->kept()) {
      Json m = {{"severity", to_string(d.severity)}, {"code", d.code}, {"message", d.message}};
      if (d.osm_way_id) m["osm_way_id"] = *d.osm_way_id;
      if (d.osm_node_id) m["osm_node_id"] = *d.osm_node_id;
      if (d.road_id) m["road_id"] = *d.road_id;
      diag["messages"].push_back(m);
    }
  }
  j["diagnostics"] = diag;
  Json timings = Json::object();
  double total = 0.0;
  for (const auto& [stage, s] : r.timings_s) {
    timings[stage] = round_to(s, 1e-4);
    total += s;
  }
  // Stages may overlap (netconvert runs beside the meshes): the total is the wall time when known.
  timings["total"] = round_to(r.wall_s > 0.0 ? r.wall_s : total, 1e-4);
  j["timings_s"] = timings;
  j["outputs"] = r.outputs;
  return j.dump(2) + "\n";
}

}  // namespace relief

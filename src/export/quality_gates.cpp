#include "relief/export/quality_gates.h"

#include <cstdio>
#include <functional>
#include <map>
#include <sstream>

namespace relief {
namespace {

struct Entry {
  const char* name;
  double GateThresholds::*threshold;
};

const std::vector<Entry>& entries() {
  static const std::vector<Entry> list = {
      {"fit_limits_violated", &GateThresholds::fit_limits_violated},
      {"ground_vs_dem_rmse_m", &GateThresholds::ground_vs_dem_rmse_m},
      {"ground_vs_dem_max_m", &GateThresholds::ground_vs_dem_max_m},
      {"junction_height_gap_m", &GateThresholds::junction_height_gap_m},
      {"road_grade_over_cap_percent", &GateThresholds::road_grade_over_cap_percent},
      {"connecting_road_grade_over_cap_percent", &GateThresholds::connecting_road_grade_over_cap_percent},
      {"link_height_step_m", &GateThresholds::link_height_step_m},
      {"sumo_lanes_without_z", &GateThresholds::sumo_lanes_without_z},
      {"sumo_lane_z_max_m", &GateThresholds::sumo_lane_z_max_m},
      {"sumo_height_steps", &GateThresholds::sumo_height_steps},
      {"sumo_handover_gap_m", &GateThresholds::sumo_handover_gap_m},
      {"road_self_intersections", &GateThresholds::road_self_intersections},
      {"junctions_open", &GateThresholds::junctions_open},
      {"ground_holes", &GateThresholds::ground_holes},
  };
  return list;
}

std::string at_xy(const Vec2& p) {
  char text[64];
  std::snprintf(text, sizeof text, "(%.1f, %.1f)", p.x(), p.y());
  return text;
}

std::string at_xyz(const Vec3& p) {
  char text[80];
  std::snprintf(text, sizeof text, "(%.1f, %.1f, %.2f)", p.x(), p.y(), p.z());
  return text;
}

std::string describe(const FitViolation& v) {
  char text[256];
  if (v.road >= 0) {
    std::snprintf(text, sizeof text, "%s on road %d (OSM way %lld) at s = %.1f m %s: %.4g against %.4g",
                  std::string(to_string(v.limit)).c_str(), v.road, static_cast<long long>(v.osm_way_id),
                  v.s_m, at_xy(v.xy).c_str(), v.value, v.bound);
  } else {
    std::snprintf(text, sizeof text, "%s at junction %d %s: %.4g against %.4g",
                  std::string(to_string(v.limit)).c_str(), v.junction, at_xy(v.xy).c_str(), v.value, v.bound);
  }
  return text;
}

}  // namespace

bool GateThresholds::set(const std::string& name, double value) {
  for (const Entry& e : entries()) {
    if (name == e.name) {
      this->*e.threshold = value;
      return true;
    }
  }
  return false;
}

const std::vector<std::string>& GateThresholds::names() {
  static const std::vector<std::string> list = [] {
    std::vector<std::string> n{"fit_converged"};
    for (const Entry& e : entries()) n.emplace_back(e.name);
    return n;
  }();
  return list;
}

std::vector<Gate> evaluate_gates(const RunReport& r, const GateThresholds& t) {
  std::vector<Gate> gates;
  const auto at_most = [&](const char* name, double value, double threshold, const std::string& where = {}) {
    gates.push_back({name, value, threshold, value <= threshold, value <= threshold ? std::string() : where});
  };
  if (r.fit) {
    gates.push_back({"fit_converged", r.fit->converged ? 1.0 : 0.0, 1.0, r.fit->converged,
                     r.fit->converged ? std::string() : r.fit->solver});
    at_most("fit_limits_violated", static_cast<double>(r.fit->violations.size()), t.fit_limits_violated,
            r.fit->violations.empty() ? std::string() : describe(r.fit->violations.front()));
  }
  for (const MethodReport& m : r.methods) {
    if (m.method != r.profile_method) continue;
    // The largest departure names the place for both: where to look first.
    std::string where;
    if (m.ground.max_road >= 0) {
      std::ostringstream text;
      text.precision(1);
      text << std::fixed << "largest at OSM way " << m.ground.max_osm_way << " " << at_xy(m.ground.max_xy)
           << ", road " << std::showpos << m.ground.max_error_m << " m from the DEM";
      where = text.str();
    }
    at_most("ground_vs_dem_rmse_m", m.ground.vs_dem.rmse_m, t.ground_vs_dem_rmse_m, where);
    at_most("ground_vs_dem_max_m", m.ground.vs_dem.max_m, t.ground_vs_dem_max_m, where);
    at_most("junction_height_gap_m", m.junctions.max_gap_m, t.junction_height_gap_m,
            m.junctions.worst_junction ? "junction " + std::to_string(*m.junctions.worst_junction)
                                       : std::string());
  }
  if (r.model_grades) {
    const auto where = [](const GradeCheck& g) {
      return g.worst_road < 0
                 ? std::string()
                 : "road " + std::to_string(g.worst_road) +
                       " at s = " + std::to_string(static_cast<long>(g.worst_s)) + " m " + at_xy(g.worst_xy) +
                       ", grade " + std::to_string(g.max_grade_percent) + " %";
    };
    at_most("road_grade_over_cap_percent", r.model_grades->roads.max_excess_percent,
            t.road_grade_over_cap_percent, where(r.model_grades->roads));
    at_most("connecting_road_grade_over_cap_percent", r.model_grades->connecting_roads.max_excess_percent,
            t.connecting_road_grade_over_cap_percent, where(r.model_grades->connecting_roads));
  }
  if (r.opendrive) at_most("link_height_step_m", r.opendrive->max_link_step_m, t.link_height_step_m);
  if (r.sumo) {
    at_most("sumo_lanes_without_z", static_cast<double>(r.sumo->lanes_without_z), t.sumo_lanes_without_z);
    const bool own = r.sumo->z_max_m >= r.sumo->netconvert_lanes_z_max_m;
    at_most("sumo_lane_z_max_m", std::max(r.sumo->z_max_m, r.sumo->netconvert_lanes_z_max_m),
            t.sumo_lane_z_max_m,
            own ? "lane " + r.sumo->z_max_lane : std::string("an internal lane netconvert drew"));
    at_most("sumo_height_steps", static_cast<double>(r.sumo->height_steps), t.sumo_height_steps,
            r.sumo->height_steps
                ? "lane " + r.sumo->first_step_lane + " at " + at_xyz(r.sumo->first_step_point)
                : std::string());
    at_most("sumo_handover_gap_m", r.sumo->max_handover_gap_m, t.sumo_handover_gap_m,
            r.sumo->handover_gap_lanes.empty()
                ? std::string()
                : "lanes " + r.sumo->handover_gap_lanes + " at " + at_xyz(r.sumo->handover_gap_point));
  }
  if (r.mesh) {
    if (r.mesh->road) {
      std::string where;
      if (!r.mesh->road->self_intersection_sites.empty())
        where = at_xyz(r.mesh->road->self_intersection_sites.front());
      at_most("road_self_intersections", static_cast<double>(r.mesh->road->self_intersecting_pairs),
              t.road_self_intersections, where);
    }
    at_most("junctions_open", static_cast<double>(r.mesh->junctions_failed), t.junctions_open,
            r.mesh->first_failed_junction);
    at_most("ground_holes", static_cast<double>(r.mesh->ground_holes), t.ground_holes);
  }
  return gates;
}

std::vector<Gate> failed_gates(const std::vector<Gate>& gates) {
  std::vector<Gate> failed;
  for (const Gate& g : gates)
    if (!g.passed) failed.push_back(g);
  return failed;
}

}  // namespace relief

// view/index.js: what the view knows besides the geometry: the tiles, roads, profiles, findings.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <set>

#include "relief/core/errors.h"
#include "relief/viewer/view_writer.h"

namespace relief {
namespace {

// Keys sorted (std::map): ordered_json finds a key by a linear scan, quadratic over a city's roads.
using Json = nlohmann::json;

/// Rounded to `decimals` places, so the file carries no float noise.
double rounded(double v, int decimals) {
  const double scale = std::pow(10.0, decimals);
  return std::round(v * scale) / scale;
}

Json xyz(const Vec3& p) {
  return Json::array({rounded(p.x(), 2), rounded(p.y(), 2), rounded(p.z(), 2)});
}

std::string place_text(const Vec3& p) {
  char text[80];
  std::snprintf(text, sizeof text, "(%.1f, %.1f, %.2f)", p.x(), p.y(), p.z());
  return text;
}

/// Up to `count` indices of [0, n), evenly spread, the first and last always among them.
std::vector<std::size_t> spread(std::size_t n, std::size_t count) {
  std::vector<std::size_t> out;
  if (n == 0) return out;
  if (n <= count || count < 2) {
    for (std::size_t i = 0; i < n; ++i) out.push_back(i);
    return out;
  }
  for (std::size_t k = 0; k < count; ++k) out.push_back(k * (n - 1) / (count - 1));
  return out;
}

Json profile_json(const ViewIndexInput& in, std::size_t road, std::size_t points) {
  const RoadProfile& raw = (*in.raw)[road];
  Json p;
  Json s = Json::array(), r = Json::array(), paper = Json::array(), fit = Json::array();
  const auto at = [](const std::vector<RoadProfile>* set, std::size_t road_index, std::size_t i) {
    const RoadProfile& prof = (*set)[road_index];
    return i < prof.z.size() ? Json(rounded(prof.z[i], 2)) : Json();
  };
  // At most one point per 2 m (the drape is sampled every metre or so).
  const double length_m = raw.s.empty() ? 0.0 : raw.s.back();
  const auto count = std::min(points, static_cast<std::size_t>(std::ceil(length_m / 2.0)) + 1);
  for (const std::size_t i : spread(raw.size(), count)) {
    s.push_back(rounded(raw.s[i], 1));
    r.push_back(rounded(raw.z[i], 2));
    if (in.paper) paper.push_back(at(in.paper, road, i));
    if (in.fitted) fit.push_back(at(in.fitted, road, i));
  }
  p["s"] = std::move(s);
  p["raw"] = std::move(r);
  if (in.paper) p["paper"] = std::move(paper);
  if (in.fitted) p["fit"] = std::move(fit);
  return p;
}

/// Steepest grade of a model road's elevation, percent, from its cubic pieces' ends and extrema.
double max_grade_percent(const ModelRoad& road) {
  double g = 0.0;
  const double length = road.length();
  for (int k = 0; k <= 64; ++k) {
    g = std::max(g, std::abs(road.elevation.derivative(length * k / 64.0)));
  }
  return 100.0 * g;
}

}  // namespace

std::vector<ViewFinding> view_findings(const ViewIndexInput& in) {
  std::vector<ViewFinding> out;
  if (in.report)
    for (const Gate& g : in.report->gates)
      if (!g.passed) {
        char text[160];
        std::snprintf(text, sizeof text, "gate %s failed: %g against %g", g.name.c_str(), g.value,
                      g.threshold);
        // A gate's worst place, when its text ends with one: "... at (x, y, z)".
        std::optional<Vec3> at;
        const std::size_t open = g.where.rfind('(');
        double x = 0, y = 0, z = 0;
        if (open != std::string::npos &&
            std::sscanf(g.where.c_str() + open, "(%lf, %lf, %lf)", &x, &y, &z) == 3)
          at = Vec3(x, y, z);
        out.push_back({"gate", text + (g.where.empty() ? std::string() : ", " + g.where), at, 0});
      }
  // Road_Road's and Terrain's own holes are the blocks between the roads and the paved area:
  // the ground (both welded) is what must have none.
  if (in.report && in.report->mesh) {
    const MeshSummary& mesh = *in.report->mesh;
    for (const auto* q : {&mesh.road, &mesh.terrain})
      if (*q)
        for (const Vec3& p : (*q)->self_intersection_sites)
          out.push_back(
              {"self_intersection", (*q)->name + ": triangles intersect at " + place_text(p), p, 0});
    for (const Vec3& p : mesh.structure_terrain_sites)
      out.push_back({"self_intersection",
                     "a deck, tunnel or road under another crosses the terrain at " + place_text(p), p, 0});
    for (const Vec3& p : mesh.ground_hole_sites)
      out.push_back({"hole", "the ground has a hole or a tunnel mouth at " + place_text(p), p, 0});
  }
  for (const auto& [id, p] : in.failed_junctions)
    out.push_back(
        {"junction_open", "junction " + std::to_string(id) + " left open at " + place_text(p), p, 0});
  if (in.sight && in.model)
    for (const SightStretch& st : in.sight->stretches) {
      if (st.points.empty() || st.road < 0 || st.road >= static_cast<int>(in.model->roads.size())) continue;
      const ModelRoad& road = in.model->roads[static_cast<std::size_t>(st.road)];
      char text[200];
      std::snprintf(text, sizeof text,
                    "sight %.1f m of %.1f m needed at %.0f km/h over %.0f m (%s, hidden by %s)",
                    st.available_m, st.required_m, st.speed_mps * 3.6, st.length_m(),
                    road.name.empty() ? ("road " + std::to_string(road.id)).c_str() : road.name.c_str(),
                    to_string(st.obstacle));
      out.push_back({"sight", text, st.points[st.points.size() / 2], road.id});
    }
  return out;
}

std::string view_index_script(const ViewTiles& tiles, const ViewIndexInput& in, const ViewOptions& options) {
  if (!in.report || !in.model || !in.network || !in.raw)
    throw InvalidInput("view index: report, model, network and raw profiles are required");
  const std::size_t n = in.network->roads.size();
  for (const auto* set : {in.raw, in.paper, in.fitted})
    if (set && set->size() != n) throw InvalidInput("view index: a profile set is not parallel to the roads");

  Json j;
  const RunReport& report = *in.report;
  j["name"] = report.name;
  j["created_utc"] = report.created_utc;
  j["frame"] = {{"crs", report.frame.crs()},
                {"origin", Json::array({report.frame.origin().x(), report.frame.origin().y()})},
                {"proj", report.frame.proj_string()}};
  j["tile_size_m"] = tiles.tile_size_m;
  j["triangles"] = tiles.triangles;
  Json tile_list = Json::array();
  for (const ViewTile& t : tiles.tiles)
    tile_list.push_back(
        {{"file", t.filename},
         {"x", t.x},
         {"y", t.y},
         {"bounds", Json::array({rounded(t.bounds.min.x(), 2), rounded(t.bounds.min.y(), 2),
                                 rounded(t.bounds.max.x(), 2), rounded(t.bounds.max.y(), 2)})},
         {"z", Json::array({rounded(t.z_min, 2), rounded(t.z_max, 2)})},
         {"triangles", t.triangles},
         {"marks_file", t.marks_filename},
         {"marks_triangles", t.marks_triangles},
         {"lod_file", t.lod_filename},
         {"lod_triangles", t.lod_triangles}});
  j["tiles"] = std::move(tile_list);
  j["owners"] = tiles.owners;

  // Roads and junctions by OpenDRIVE id; profiles by network road.
  Json roads = Json::object(), profiles = Json::object();
  std::set<int> profiled;
  for (const ModelRoad& r : in.model->roads) {
    Json road;
    road["name"] = r.name;
    road["junction"] = r.junction;
    road["length_m"] = rounded(r.length(), 1);
    road["max_grade_percent"] = rounded(max_grade_percent(r), 1);
    road["osm_way_ids"] = r.osm_way_ids;
    if (r.speed_mps) road["speed_kmh"] = rounded(*r.speed_mps * 3.6, 0);
    road["network_road"] = r.source_road;
    if (r.source_road >= 0 && static_cast<std::size_t>(r.source_road) < n) {
      const Road& source = in.network->roads[static_cast<std::size_t>(r.source_road)];
      road["class"] = std::string(to_string(source.attributes.highway));
      road["lanes"] = source.attributes.lanes_forward + source.attributes.lanes_backward;
      road["bridge"] = source.attributes.bridge;
      road["tunnel"] = source.attributes.tunnel;
      if (profiled.insert(r.source_road).second)
        profiles[std::to_string(r.source_road)] =
            profile_json(in, static_cast<std::size_t>(r.source_road), options.profile_points);
      // Where along its OSM road this piece lies (trimmed at junctions, split at transitions):
      // the stations nearest its two ends.
      const RoadProfile& raw = (*in.raw)[static_cast<std::size_t>(r.source_road)];
      if (!raw.xy.empty()) {
        const auto station_near = [&](const Vec2& p) {
          std::size_t best = 0;
          for (std::size_t i = 1; i < raw.xy.size(); ++i)
            if ((raw.xy[i] - p).squaredNorm() < (raw.xy[best] - p).squaredNorm()) best = i;
          return raw.s[best];
        };
        const double a = station_near(r.plan.at(0.0).position),
                     b = station_near(r.plan.at(r.length()).position);
        road["profile_s"] = Json::array({rounded(std::min(a, b), 1), rounded(std::max(a, b), 1)});
      }
    } else {
      road["class"] = "connecting road";
    }
    roads[std::to_string(r.id)] = std::move(road);
  }
  j["roads"] = std::move(roads);
  Json junctions = Json::object();
  for (const JunctionModel& jm : in.model->junctions) junctions[std::to_string(jm.id)] = {{"name", jm.name}};
  j["junctions"] = std::move(junctions);
  j["profiles"] = std::move(profiles);

  Json findings = Json::array();
  for (const ViewFinding& f : view_findings(in)) {
    Json item = {{"kind", f.kind}, {"text", f.text}};
    item["at"] = f.at ? xyz(*f.at) : Json();
    if (f.road != 0) item["road"] = f.road;
    findings.push_back(std::move(item));
  }
  j["findings"] = std::move(findings);
  Json gates = Json::array();
  for (const Gate& g : report.gates)
    gates.push_back({{"name", g.name},
                     {"value", g.value},
                     {"threshold", g.threshold},
                     {"passed", g.passed},
                     {"where", g.where}});
  j["gates"] = std::move(gates);
  return "window.RELIEF_VIEW = " + j.dump(-1, ' ', false, Json::error_handler_t::replace) + ";\n";
}

}  // namespace relief

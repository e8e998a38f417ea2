#include "export/report_html_sight.h"

#include <algorithm>

#include "export/html_text.h"
#include "export/svg_plot.h"
#include "relief/geometry/polygon.h"

namespace relief::html {
namespace {

std::string osm_link(double lon, double lat) {
  return "<a href=\"https://www.openstreetmap.org/?mlat=" + fixed(lat, 6) + "&amp;mlon=" + fixed(lon, 6) +
         "#map=19/" + fixed(lat, 6) + "/" + fixed(lon, 6) + "\">" + fixed(lat, 5) + ", " + fixed(lon, 5) +
         "</a>";
}

void write_map(std::string& h, const RoadNetwork& network, const SightResult& result) {
  Vec2 lo = Vec2::Constant(1e300), hi = -lo;
  for (const Road& road : network.roads)
    for (const Vec2& p : road.points) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
  if (!(lo.x() <= hi.x())) return;
  const double dx = std::max(hi.x() - lo.x(), 1.0), dy = std::max(hi.y() - lo.y(), 1.0);
  const double margin = 14, max_w = 1100, max_h = 800;
  const double scale = std::min((max_w - 2 * margin) / dx, (max_h - 2 * margin) / dy);
  const double w = dx * scale + 2 * margin, ht = dy * scale + 2 * margin;
  const Axes a{{lo.x(), lo.x() + dx, margin, w - margin}, {lo.y(), lo.y() + dy, ht - margin, margin}};
  h +=
      "<figure><figcaption>Red: lanes whose sight distance falls short of the stopping sight distance "
      "(both directions drawn on the road's line); dots: where the first hidden line of sight meets the road "
      "(white) or the terrain (amber). North up.</figcaption>\n";
  svg_open(h, w, ht, "Map of the stretches short of stopping sight distance", "map sight");
  for (const Road& road : network.roads) {
    h += "<polyline class=\"nh\" points=\"";
    for (const Vec2& p : road.points) h += fixed(a.x(p.x()), 1) + "," + fixed(a.y(p.y()), 1) + " ";
    h.back() = '"';
    h += "/>\n";
  }
  for (const SightStretch& s : result.stretches) {
    h += "<polyline class=\"short\" points=\"";
    for (const Vec3& p : s.points) h += fixed(a.x(p.x()), 1) + "," + fixed(a.y(p.y()), 1) + " ";
    h.back() = '"';
    h += "/>\n";
  }
  for (const SightStretch& s : result.stretches) {
    if (s.obstacle == SightObstacle::none) continue;
    h += "<circle class=\"" + std::string(to_string(s.obstacle)) + "\" cx=\"" +
         fixed(a.x(s.obstacle_point.x()), 1) + "\" cy=\"" + fixed(a.y(s.obstacle_point.y()), 1) +
         "\" r=\"2.2\"/>\n";
  }
  h += "</svg></figure>\n";
}

}  // namespace

std::string sight_css() {
  return ".sight polyline.short{stroke:#ff4d4d;stroke-width:3}.sight circle.road{fill:#f4f6f9}"
         ".sight circle.terrain{fill:#ffb020}\n";
}

void write_sight_section(std::string& h, const RunReport& r, const RoadNetwork& network,
                         const SightResult* result) {
  if (!r.sight) return;
  const SightSummary& s = *r.sight;
  const double pct = s.km_checked > 0.0 ? 100.0 * s.km_short / s.km_checked : 0.0;
  h += "<h2>Sight distance</h2>\n<p class=\"sub\">At every " + fixed(s.options.step_m, 1) +
       " m of every driving lane, in its direction of travel: how far ahead along the lane (through its "
       "links) an "
       "eye " +
       fixed(s.options.eye_height_m, 2) + " m above it sees an object " +
       fixed(s.options.object_height_m, 2) +
       " m high, with the scene's roads and terrain as obstacles, against AASHTO's stopping sight distance v "
       "t + "
       "v&sup2; / (2 (a + g G)) at the road's speed (t = " +
       fixed(s.options.reaction_s, 1) + " s, a = " + fixed(s.options.deceleration_mps2, 1) +
       " m/s&sup2;, G the grade over that distance). Lane-km count each "
       "lane and direction. Buildings and trees are not in the scene: this is what the ground and the road "
       "hide. "
       "Layer: " +
       esc(s.file) + ".</p>\n";
  h += "<table class=\"kv\">\n<tr><th>lane-km checked</th><td>" + fixed(s.km_checked, 2) +
       "</td></tr>\n<tr><th>lane-km short</th><td>" + fixed(s.km_short, 3) + " (" + fixed(pct, 2) +
       " %) in " + std::to_string(s.stretches) + " stretches</td></tr>\n<tr><th>lines of sight</th><td>" +
       std::to_string(s.rays) + " against " + std::to_string(s.obstacle_triangles) + " triangles in " +
       fixed(s.seconds, 2) + " s</td></tr>\n</table>\n";
  h += "<table class=\"sightclass\">\n<tr><th class=\"l\">class</th><th>lane-km</th><th>short lane-km</th>"
       "<th>short %</th></tr>\n";
  for (const auto& [cls, f] : s.by_class)
    h += "<tr><td class=\"l\">" + esc(cls) + "</td><td>" + fixed(f.km_checked, 2) + "</td><td>" +
         fixed(f.km_short, 3) + "</td><td>" +
         fixed(f.km_checked > 0.0 ? 100.0 * f.km_short / f.km_checked : 0.0, 2) + "</td></tr>\n";
  h += "</table>\n";
  if (result != nullptr && !result->stretches.empty()) write_map(h, network, *result);
  if (s.worst.empty()) return;
  h += "<h3>Worst places (smallest available / required)</h3>\n<table class=\"sightworst\">\n<tr><th "
       "class=\"l\">road</th><th class=\"l\">class</th><th>lane</th><th>s from&ndash;to m</th><th>available "
       "m</th>"
       "<th>required m</th><th>speed km/h</th><th>grade %</th><th class=\"l\">hidden by</th><th "
       "class=\"l\">where</th></tr>\n";
  for (const SightPlace& p : s.worst) {
    std::string ways;
    for (const std::int64_t w : p.osm_way_ids) ways += (ways.empty() ? " (way " : ", ") + std::to_string(w);
    if (!ways.empty()) ways += ")";
    h += "<tr><td class=\"l\">" + esc(p.name.empty() ? "road " + std::to_string(p.road) : p.name) + " [" +
         std::to_string(p.road) + "]" + esc(ways) + "</td><td class=\"l\">" + esc(p.road_class) +
         "</td><td>" + std::to_string(p.lane) + "</td><td>" + fixed(p.s_from, 1) + "&ndash;" +
         fixed(p.s_to, 1) + "</td><td>" + fixed(p.available_m, 1) + "</td><td>" + fixed(p.required_m, 1) +
         "</td><td>" + fixed(p.speed_mps * 3.6, 0) + "</td><td>" + fixed(p.grade_percent, 1) +
         "</td><td class=\"l\">" + esc(p.obstacle) + "</td><td class=\"l\">" + osm_link(p.lon, p.lat) +
         "</td></tr>\n";
  }
  h += "</table>\n";
}

}  // namespace relief::html

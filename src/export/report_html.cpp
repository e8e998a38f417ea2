#include "relief/export/report_html.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <string_view>

#include "core/base64.h"
#include "export/html_text.h"
#include "export/report_html_sight.h"
#include "export/svg_plot.h"
#include "relief/core/errors.h"
#include "relief/core/number_format.h"
#include "relief/export/geojson_writer.h"
#include "relief/geometry/polyline.h"
#include "relief/roads/highway_class.h"
#include "relief/roads/validation.h"

namespace relief {
namespace {

using namespace html;

constexpr std::string_view kDash = "\xE2\x80\x94";  // em dash: no value

std::string method_label(std::string_view method) {
  if (method == "raw") return "Raw DEM drape";
  if (method == "paper") return "Paper smoothing";
  if (method == "relief") return "relief fit";
  return esc(method);
}

std::string road_title(const Road& road) {
  std::string t = "Road " + std::to_string(road.id);
  if (!road.attributes.name.empty()) t += " \xC2\xB7 " + esc(road.attributes.name);
  t += " \xC2\xB7 ";
  t += to_string(road.attributes.highway);
  if (road.attributes.bridge) t += " \xC2\xB7 bridge";
  if (road.attributes.tunnel) t += " \xC2\xB7 tunnel";
  if (road.attributes.layer != 0) t += " (layer " + std::to_string(road.attributes.layer) + ")";
  return t;
}

// ---------------------------------------------------------------------------------------------
// The profile sets being compared.

struct Series {
  std::string method;                        // "raw", "paper", "relief"
  const std::vector<RoadProfile>* profiles;  // parallel to the roads
  const char* css;                           // line class in the plots
};

std::vector<Series> series_of(const HtmlReportInput& in) {
  std::vector<Series> s{{"raw", in.raw, "s-raw"}};
  if (in.paper) s.push_back({"paper", in.paper, "s-paper"});
  if (in.fitted) s.push_back({"relief", in.fitted, "s-relief"});
  return s;
}

double max_grade(const RoadProfile& p) {
  const std::vector<double> g = segment_grades_percent(p);
  return g.empty() ? 0.0 : *std::max_element(g.begin(), g.end());
}

double road_length(const RoadProfile& p) {
  return p.s.empty() ? 0.0 : p.s.back();
}

// ---------------------------------------------------------------------------------------------
// Page parts: header, cards, tables.

constexpr std::string_view kStyle = R"(
body{font:14px/1.45 system-ui,-apple-system,"Segoe UI",Roboto,sans-serif;color:#1d2330;margin:0;background:#f4f6f9}
main{max-width:1240px;margin:0 auto;padding:20px 28px 60px}
h1{font-size:26px;margin:8px 0 2px}h2{font-size:19px;margin:34px 0 10px;border-bottom:2px solid #d9dee7;padding-bottom:4px}
h3{font-size:15px;margin:18px 0 6px}
.sub{color:#5b6474}.attr{font-size:12px;color:#5b6474}
figure.overview{margin:12px 0 4px}figure.overview img{max-width:100%;height:auto;border:1px solid #d9dee7;border-radius:6px}
figure.overview figcaption{font-size:12px;color:#5b6474}
table{border-collapse:collapse;background:#fff;margin:6px 0 12px;font-variant-numeric:tabular-nums}
th,td{border:1px solid #dde2ea;padding:4px 9px;text-align:right;vertical-align:top}
th{background:#eef1f5;font-weight:600}td.l,th.l{text-align:left}
tr.group td{background:#f7f8fa;font-weight:600;text-align:left;color:#394255}
.chosen{background:#e3efff}th.chosen{background:#c9defc}
table.kv td:first-child{color:#5b6474;text-align:left}table.kv td{text-align:left}
.cards{display:flex;flex-wrap:wrap;gap:10px}
.card{background:#fff;border:1px solid #dde2ea;border-radius:6px;padding:9px 14px;min-width:140px}
.card b{display:block;font-size:21px}.card span{color:#5b6474;font-size:12px}
.row{display:flex;flex-wrap:wrap;gap:18px;align-items:flex-start}
.plots{display:grid;grid-template-columns:repeat(auto-fill,minmax(560px,1fr));gap:14px}
figure{margin:0;background:#fff;border:1px solid #dde2ea;border-radius:6px;padding:8px}
figcaption{font-size:13px;margin:0 0 4px}
svg{display:block;max-width:100%;height:auto}
svg text{font:11px system-ui,sans-serif;fill:#394255}
.ax{stroke:#394255;stroke-width:1}.grid{stroke:#e6e9ef;stroke-width:1}
.s-raw{fill:none;stroke:#8a8f99;stroke-width:1.2}
.s-paper{fill:none;stroke:#d95f02;stroke-width:1.5;stroke-dasharray:6 3}
.s-relief{fill:none;stroke:#1b6fd1;stroke-width:1.8}
.b-raw{fill:#8a8f99}.b-paper{fill:#f08a3c}.b-relief{fill:#1b6fd1}
.lim{stroke:#c0392b;stroke-width:1;stroke-dasharray:4 3}
.map{background:#1f232b;border-radius:4px}.map text{fill:#d8dce4}.map .ax{stroke:#d8dce4}
.map polyline{fill:none;stroke-width:1.4;stroke-linecap:round;stroke-linejoin:round}
.map polyline.br{stroke-width:3.4}.map polyline.tu{stroke-dasharray:3 2.5}.map polyline.nh{stroke:#5c626e}
details{background:#fff;border:1px solid #dde2ea;border-radius:6px;padding:6px 10px}
code{font-size:12px}
tr.fail td{background:#fde8e6}tr.fail strong{color:#b3261e}tr.pass td:nth-child(4){color:#2e7d32}
)";

void write_kv(std::string& h, std::string_view key, const std::string& value_html) {
  h += "<tr><td>";
  h += key;
  h += "</td><td>";
  h += value_html;
  h += "</td></tr>\n";
}

std::string dem_description(const DemInfo& d) {
  std::string s = "<code>" + esc(d.path) + "</code><br/>CRS " + esc(d.crs) + ", " + std::to_string(d.width) +
                  " \xC3\x97 " + std::to_string(d.height) + " px, unit " + esc(to_string(d.unit)) + " (" +
                  (d.unit_stated_by_user  ? "user"
                   : d.unit_from_metadata ? "metadata"
                                          : "assumed") +
                  ")";
  if (d.nodata) s += ", nodata " + fixed(*d.nodata, 2);
  s += "<br/>transform: " + (d.transform_name.empty() ? std::string(kDash) : esc(d.transform_name));
  if (d.transform_accuracy_m) s += ", accuracy " + fixed(*d.transform_accuracy_m, 2) + " m";
  if (!d.missing_grids.empty()) s += "<br/>missing grids: " + esc(d.missing_grids);
  if (d.implausible_cells > 0 || d.spike_cells > 0) {
    s += "<br/>treated as voids: " + std::to_string(d.implausible_cells) + " cells of implausible height, " +
         std::to_string(d.spike_cells) + " one-cell spikes or pits";
  }
  if (d.off_ground_cells > 0) {
    s += "<br/>surface model: " + std::to_string(d.off_ground_cells) +
         " cells of buildings, trees or pits taken to the ground";
  }
  return s;
}

/// The picture first (linked to the 3D view when there is one), then the link.
void write_overview(std::string& h, const HtmlReportInput& in) {
  if (!in.overview_png.empty()) {
    h += "<figure class=\"overview\">";
    if (!in.view_page.empty()) h += "<a href=\"" + esc(in.view_page) + "\">";
    h += "<img alt=\"the scene from the south, roads coloured by grade\" src=\"data:image/png;base64,";
    detail::append_base64(h, in.overview_png);
    h += "\"/>";
    if (!in.view_page.empty()) h += "</a>";
    h += "<figcaption>The scene from the south, roads coloured by grade (0 % green, 10 % yellow, 20 % red, "
         "30 % and steeper purple).</figcaption></figure>\n";
  }
  if (!in.view_page.empty())
    h += "<p class=\"view\"><a href=\"" + esc(in.view_page) +
         "\">Open the interactive 3D view</a> (roads by grade or height over the DEM, profiles on click, the "
         "findings marked).</p>\n";
}

void write_header(std::string& h, const RunReport& r) {
  h += "<h1>relief report";
  if (!r.name.empty()) h += ": " + esc(r.name);
  h += "</h1>\n<p class=\"sub\">created " + esc(r.created_utc) + " \xC2\xB7 relief " + esc(relief_version()) +
       "</p>\n<p class=\"attr\">";
  // The attribution with its link made clickable (the only external URL of the page).
  const std::string attribution = kOsmAttribution;
  const std::string url = "https://www.openstreetmap.org/copyright";
  const std::size_t at = attribution.find(url);
  if (at == std::string::npos) {
    h += esc(attribution);
  } else {
    h += esc(attribution.substr(0, at)) + "<a href=\"" + url + "\">" + url + "</a>" +
         esc(attribution.substr(at + url.size()));
  }
  h += "</p>\n<h2>Inputs and frame</h2>\n<table class=\"kv\">\n";
  write_kv(h, "OSM", "<code>" + esc(r.osm_path) + "</code>");
  for (const DemInfo& d : r.dems) write_kv(h, "DEM", dem_description(d));
  for (const DemInfo& d : r.reference_dems) write_kv(h, "reference DEM", dem_description(d));
  if (r.reference_dems.empty()) write_kv(h, "reference DEM", "none");
  write_kv(h, "frame",
           esc(r.frame.crs()) + ", origin (" + fixed(r.frame.origin().x(), 3) + ", " +
               fixed(r.frame.origin().y(), 3) + ") m; local = CRS \xE2\x88\x92 origin");
  write_kv(h, "sampling",
           "every " + fixed(r.spacing_m, 2) + " m, " + esc(to_string(r.interpolation)) +
               ", voids: " + esc(r.nodata_fill));
  // Grade limits grouped by value: "8.0 %: motorway, trunk, ...".
  std::map<double, std::string> by_limit;
  for (const auto& [cls, percent] : r.grade_limits.percent) {
    std::string& classes = by_limit[percent];
    if (!classes.empty()) classes += ", ";
    classes += to_string(cls);
  }
  std::string limits;
  for (const auto& [percent, classes] : by_limit) {
    limits += (limits.empty() ? "" : "<br/>") + fixed(percent, 1) + " %: " + classes;
  }
  write_kv(h, "grade limits", limits.empty() ? std::string(kDash) : limits);
  h += "</table>\n";
}

void card(std::string& h, const std::string& value, std::string_view label) {
  h += "<div class=\"card\"><b>" + value + "</b><span>";
  h += label;
  h += "</span></div>\n";
}

void write_cards(std::string& h, const RunReport& r) {
  const NetworkStats& n = r.network;
  h += "<h2>Summary</h2>\n<div class=\"cards\">\n";
  card(h, integer(n.roads), "roads");
  card(h, integer(n.junctions) + " / " + integer(n.intersections), "junctions / intersections");
  card(h, fixed(n.length_km, 2), "km of road");
  card(h, integer(n.bridges) + " / " + integer(n.tunnels),
       "bridges / tunnels (" + fixed(n.bridge_km, 2) + " / " + fixed(n.tunnel_km, 2) + " km)");
  card(h, integer(r.samples),
       "samples (" + integer(r.void_samples) + " void, " + integer(r.uncovered_samples) + " uncovered)");
  card(h, r.profile_method.empty() ? std::string(kDash) : method_label(r.profile_method), "profiles written");
  if (r.fit) {
    card(h, esc(r.fit->policy), "fit policy");
    card(h, std::to_string(r.fit->iterations) + (r.fit->converged ? " \xE2\x9C\x93" : " \xE2\x9C\x97"),
         r.fit->converged ? "fit iterations, converged" : "fit iterations, NOT converged");
    card(h, std::to_string(r.fit->violations.size()), "limits left violated");
    card(h, fixed(r.fit->max_violation_m, 3) + " m", "fit max violation");
  }
  if (r.paper) {
    card(h, integer(r.paper->roads_not_converged),
         "paper: roads not converged (of " + std::to_string(r.paper->max_iterations) + " iterations)");
  }
  if (r.opendrive) {
    const OpenDriveSummary& o = *r.opendrive;
    card(h, integer(o.junctions) + " / " + integer(o.connecting_roads),
         "OpenDRIVE " + esc(o.version) + " junctions / connecting roads");
    card(h, fixed(1000.0 * std::max(o.max_link_gap_m, o.max_link_step_m), 2) + " mm",
         "largest lane-border gap at links");
    card(h, fixed(1000.0 * std::max(o.round_trip_max_xy_m, o.round_trip_max_z_m), 3) + " mm",
         "OpenDRIVE read back vs written");
  }
  h += "</div>\n";
}

// One row of the comparison: a label, a stable key (for tests and scripts) and the value of
// each method as text.
template <class F>
void comparison_row(std::string& h, const RunReport& r, std::string_view label, std::string_view key,
                    F value) {
  h += "<tr data-key=\"";
  h += key;
  h += "\"><td class=\"l\">";
  h += label;
  h += "</td>";
  for (const MethodReport& m : r.methods) {
    h += m.method == r.profile_method ? "<td class=\"chosen\">" : "<td>";
    h += value(m);
    h += "</td>";
  }
  h += "</tr>\n";
}

void group_row(std::string& h, const RunReport& r, std::string_view label) {
  h += "<tr class=\"group\"><td colspan=\"" + std::to_string(r.methods.size() + 1) + "\">";
  h += label;
  h += "</td></tr>\n";
}

// Rows MAE / RMSE / max of an ErrorStats picked by `pick` (nullptr = not available).
template <class Pick>
void error_rows(std::string& h, const RunReport& r, std::string_view what, std::string_view key, Pick pick) {
  const auto row = [&](std::string_view stat, std::string_view label, double ErrorStats::*field) {
    comparison_row(h, r, std::string(label) + " " + std::string(what) + " (m)",
                   std::string(key) + "_" + std::string(stat) + "_m", [&](const MethodReport& m) {
                     const ErrorStats* e = pick(m);
                     return e && e->n > 0 ? fixed(e->*field, 3) : std::string(kDash);
                   });
  };
  row("mae", "MAE", &ErrorStats::mae_m);
  row("rmse", "RMSE", &ErrorStats::rmse_m);
  row("max", "max |error|", &ErrorStats::max_m);
}

void write_comparison(std::string& h, const RunReport& r) {
  h += "<h2>Profile methods compared</h2>\n";
  if (r.methods.empty()) {
    h += "<p>No method figures.</p>\n";
    return;
  }
  h += "<table class=\"cmp\">\n<tr><th class=\"l\">figure</th>";
  for (const MethodReport& m : r.methods) {
    h += m.method == r.profile_method ? "<th class=\"chosen\">" : "<th>";
    h += method_label(m.method);
    if (m.method == r.profile_method) h += "<br/>(written)";
    h += "</th>";
  }
  h += "</tr>\n";
  group_row(h, r, "Heights against the DEM (midpoints between samples)");
  error_rows(h, r, "on ground", "dem_ground", [](const MethodReport& m) { return &m.ground.vs_dem; });
  error_rows(h, r, "on structures", "dem_structures",
             [](const MethodReport& m) { return &m.structures.vs_dem; });
  group_row(h, r, "Heights against the reference DEM (samples)");
  error_rows(h, r, "on ground", "ref_ground",
             [](const MethodReport& m) { return m.ground.vs_reference ? &*m.ground.vs_reference : nullptr; });
  error_rows(h, r, "all roads", "ref_all",
             [](const MethodReport& m) { return m.all.vs_reference ? &*m.all.vs_reference : nullptr; });
  group_row(h, r, "Gradient");
  comparison_row(h, r, "max grade (%)", "grade_max",
                 [](const MethodReport& m) { return fixed(m.gradient.max_percent, 2); });
  comparison_row(h, r, "p99 grade (%)", "grade_p99",
                 [](const MethodReport& m) { return fixed(m.gradient.p99_percent, 2); });
  comparison_row(h, r, "compliance (% of length)", "compliance",
                 [](const MethodReport& m) { return fixed(m.gradient.compliance_percent, 2); });
  group_row(h, r, "Junctions and grade separations");
  comparison_row(h, r, "largest junction gap (m)", "junction_gap",
                 [](const MethodReport& m) { return fixed(m.junctions.max_gap_m, 3); });
  comparison_row(h, r, "junctions over bound", "junction_over", [](const MethodReport& m) {
    return integer(m.junctions.over_bound) + " of " + integer(m.junctions.checked) + " (&gt; " +
           fixed(m.junctions.bound_m, 2) + " m)";
  });
  comparison_row(h, r, "grade separations", "separations",
                 [](const MethodReport& m) { return integer(m.separations); });
  comparison_row(h, r, "min clearance (m)", "min_clearance", [](const MethodReport& m) {
    return m.separations > 0 ? fixed(m.min_clearance_m, 2) : std::string(kDash);
  });
  comparison_row(h, r, "below required clearance", "below_clearance",
                 [](const MethodReport& m) { return integer(m.below_clearance); });
  group_row(h, r, "Cut and fill against the DEM drape (roads on the ground)");
  comparison_row(h, r, "max cut (m)", "max_cut",
                 [](const MethodReport& m) { return fixed(m.cut_fill.max_cut_m, 2); });
  comparison_row(h, r, "max fill (m)", "max_fill",
                 [](const MethodReport& m) { return fixed(m.cut_fill.max_fill_m, 2); });
  comparison_row(h, r, "mean |dz| (m)", "mean_abs_dz",
                 [](const MethodReport& m) { return fixed(m.cut_fill.mean_abs_m, 3); });
  comparison_row(h, r, "km departing &gt; 0.5 m", "km_over_0_5",
                 [](const MethodReport& m) { return fixed(m.cut_fill.km_over_0_5_m, 3); });
  comparison_row(h, r, "km departing &gt; 2 m", "km_over_2",
                 [](const MethodReport& m) { return fixed(m.cut_fill.km_over_2_m, 3); });
  group_row(h, r, "Cost");
  comparison_row(h, r, "time (s)", "seconds", [](const MethodReport& m) { return fixed(m.seconds, 3); });
  h += "</table>\n";
}

void write_class_tables(std::string& h, const RunReport& r) {
  h += "<h2>Gradient compliance by class</h2>\n<div class=\"row\">\n";
  for (const MethodReport& m : r.methods) {
    h += "<div><h3>" + method_label(m.method) + "</h3>\n<table data-method=\"" + esc(m.method) +
         "\">\n<tr><th class=\"l\">class</th><th>km</th><th>limit %</th><th>compliance %</th>"
         "<th>max %</th><th>p99 %</th></tr>\n";
    for (const auto& [cls, c] : m.gradient.by_class) {
      h += "<tr><td class=\"l\">" + esc(cls) + "</td><td>" + fixed(c.length_km, 3) + "</td><td>" +
           fixed(c.limit_percent, 1) + "</td><td>" + fixed(c.compliance_percent, 2) + "</td><td>" +
           fixed(c.max_percent, 2) + "</td><td>" + fixed(c.p99_percent, 2) + "</td></tr>\n";
    }
    h += "</table></div>\n";
  }
  h += "</div>\n";
}

// The quality gates first, failed ones marked; then the limits the fit left violated, where.
void write_gates(std::string& h, const RunReport& r) {
  if (r.gates.empty()) return;
  std::size_t failed = 0;
  for (const Gate& g : r.gates) failed += g.passed ? 0 : 1;
  h += "<h2>Quality gates</h2>\n<p class=\"sub\">" +
       (failed ? integer(failed) + " of " + integer(r.gates.size()) +
                     " gates failed: the outputs are written, but do not meet their thresholds (exit code 4)."
               : "Every gate passed.") +
       "</p>\n<table class=\"gates\">\n<tr><th class=\"l\">gate</th><th>value</th><th>threshold</th>"
       "<th class=\"l\">result</th><th class=\"l\">where</th></tr>\n";
  for (const Gate& g : r.gates) {
    h += std::string("<tr class=\"") + (g.passed ? "pass" : "fail") + "\"><td class=\"l\"><code>" +
         esc(g.name) + "</code></td><td>" + fixed(g.value, 4) + "</td><td>" + fixed(g.threshold, 4) +
         "</td><td class=\"l\">" + (g.passed ? "passed" : "<strong>FAILED</strong>") +
         "</td><td class=\"l\">" + esc(g.where) + "</td></tr>\n";
  }
  h += "</table>\n";
  if (r.fit && !r.fit->violations.empty()) {
    h += "<h3>Limits the fit left violated</h3>\n<table class=\"violations\">\n<tr><th class=\"l\">limit</th>"
         "<th>road</th><th>OSM way</th><th>s (m)</th><th>x</th><th>y</th><th>value</th><th>bound</th>"
         "<th>excess (m)</th><th>places</th></tr>\n";
    std::size_t shown = 0;
    for (const FitViolation& v : r.fit->violations) {
      if (++shown > 200) break;
      h += "<tr><td class=\"l\">" + esc(to_string(v.limit)) + "</td><td>" +
           (v.road >= 0 ? std::to_string(v.road) : "J" + std::to_string(v.junction)) + "</td><td>" +
           (v.road >= 0 ? std::to_string(v.osm_way_id) : std::string()) + "</td><td>" + fixed(v.s_m, 1) +
           "</td><td>" + fixed(v.xy.x(), 1) + "</td><td>" + fixed(v.xy.y(), 1) + "</td><td>" +
           fixed(v.value, 4) + "</td><td>" + fixed(v.bound, 4) + "</td><td>" + fixed(v.excess_m, 3) +
           "</td><td>" + integer(v.places) + "</td></tr>\n";
    }
    h += "</table>\n";
  }
}

void write_diagnostics(std::string& h, const RunReport& r) {
  h += "<h2>Diagnostics</h2>\n";
  if (!r.diagnostics || r.diagnostics->total() == 0) {
    h += "<p>None.</p>\n";
    return;
  }
  const Diagnostics& d = *r.diagnostics;
  h += "<table>\n<tr><th class=\"l\">code</th><th>count</th></tr>\n";
  for (const auto& [code, count] : d.counts()) {
    h += "<tr><td class=\"l\"><code>" + esc(code) + "</code></td><td>" + integer(count) + "</td></tr>\n";
  }
  h += "</table>\n<details><summary>" + integer(d.kept().size()) + " kept messages of " + integer(d.total()) +
       "</summary>\n<table>\n<tr><th class=\"l\">severity</th><th class=\"l\">code</th>"
       "<th class=\"l\">message</th><th>way</th><th>node</th><th>road</th></tr>\n";
  const auto opt = [](const auto& v) { return v ? std::to_string(*v) : std::string(); };
  for (const Diagnostic& m : d.kept()) {
    h += "<tr><td class=\"l\">" + esc(to_string(m.severity)) + "</td><td class=\"l\"><code>" + esc(m.code) +
         "</code></td><td class=\"l\">" + esc(m.message) + "</td><td>" + opt(m.osm_way_id) + "</td><td>" +
         opt(m.osm_node_id) + "</td><td>" + opt(m.road_id) + "</td></tr>\n";
  }
  h += "</table></details>\n";
}

void write_timings(std::string& h, const RunReport& r) {
  if (r.timings_s.empty() && r.outputs.empty()) return;
  h += "<h2>Run</h2>\n<div class=\"row\">\n";
  if (!r.timings_s.empty()) {
    h += "<table>\n<tr><th class=\"l\">stage</th><th>s</th></tr>\n";
    double total = 0.0;
    for (const auto& [stage, s] : r.timings_s) {
      h += "<tr><td class=\"l\">" + esc(stage) + "</td><td>" + fixed(s, 3) + "</td></tr>\n";
      total += s;
    }
    h += "<tr><th class=\"l\">total</th><th>" + fixed(total, 3) + "</th></tr>\n</table>\n";
  }
  if (!r.outputs.empty()) {
    h += "<table>\n<tr><th class=\"l\">outputs</th></tr>\n";
    for (const std::string& o : r.outputs) h += "<tr><td class=\"l\"><code>" + esc(o) + "</code></td></tr>\n";
    h += "</table>\n";
  }
  h += "</div>\n";
}

// Indices of at most ~max_points samples keeping each bucket's minimum and maximum of z (so that
// peaks and dips survive) plus both ends.
std::vector<std::size_t> downsample(const RoadProfile& p, std::size_t max_points) {
  std::vector<std::size_t> idx;
  const std::size_t n = p.size();
  if (n <= max_points) {
    idx.resize(n);
    for (std::size_t i = 0; i < n; ++i) idx[i] = i;
    return idx;
  }
  const std::size_t buckets = std::max<std::size_t>(1, (max_points - 2) / 2);
  idx.push_back(0);
  for (std::size_t b = 0; b < buckets; ++b) {
    const std::size_t i0 = 1 + b * (n - 2) / buckets, i1 = 1 + (b + 1) * (n - 2) / buckets;
    if (i0 >= i1) continue;
    std::size_t lo = i0, hi = i0;
    for (std::size_t i = i0; i < i1; ++i) {
      if (p.z[i] < p.z[lo]) lo = i;
      if (p.z[i] > p.z[hi]) hi = i;
    }
    idx.push_back(std::min(lo, hi));
    if (lo != hi) idx.push_back(std::max(lo, hi));
  }
  idx.push_back(n - 1);
  return idx;
}

// ---------------------------------------------------------------------------------------------
// Plot 1: elevation profiles.

constexpr std::size_t kMaxSeriesPoints = 800;

void profile_plot(std::string& h, const HtmlReportInput& in, const std::vector<Series>& series, int r) {
  const Road& road = in.network->roads[static_cast<std::size_t>(r)];
  double z0 = 1e300, z1 = -1e300, s1 = 0.0;
  std::string caption = road_title(road) + " \xE2\x80\x94 max grade";
  for (const Series& s : series) {
    const RoadProfile& p = (*s.profiles)[static_cast<std::size_t>(r)];
    if (!p.has_height || p.size() < 2) continue;
    for (double z : p.z) z0 = std::min(z0, z), z1 = std::max(z1, z);
    s1 = std::max(s1, road_length(p));
    caption += " " + s.method + " " + fixed(max_grade(p), 1) + " %";
  }
  if (z0 > z1 || s1 <= 0.0) return;
  // At least 2 m of height range so that a flat road does not show noise as hills.
  const double pad = std::max(0.06 * (z1 - z0), std::max(0.0, 2.0 - (z1 - z0)) / 2.0);
  z0 -= pad, z1 += pad;
  const double width = 560, height = 250;
  const Axes a{{0.0, s1, 52, width - 12}, {z0, z1, height - 40, 12}};

  h += "<figure><figcaption>" + caption + "</figcaption>\n";
  svg_open(h, width, height, "Elevation profile of road " + std::to_string(road.id));
  draw_axes(h, a, "s (m)", "z (m)", 6, 5);
  for (const Series& s : series) {
    const RoadProfile& p = (*s.profiles)[static_cast<std::size_t>(r)];
    if (!p.has_height || p.size() < 2) continue;
    h += "<polyline class=\"";
    h += s.css;
    h += "\" data-method=\"" + s.method + "\" points=\"";
    for (std::size_t i : downsample(p, kMaxSeriesPoints)) {
      h += fixed(a.x(p.s[i]), 1) + "," + fixed(a.y(p.z[i]), 1) + " ";
    }
    h.back() = '"';
    h += "/>\n";
  }
  // Legend, top right.
  double lx = width - 12 - 100.0 * static_cast<double>(series.size());
  for (const Series& s : series) {
    h += "<line class=\"";
    h += s.css;
    h += "\" x1=\"" + fixed(lx, 1) + "\" x2=\"" + fixed(lx + 22, 1) + "\" y1=\"22\" y2=\"22\"/>\n";
    svg_text(h, lx + 26, 26, "start", s.method == "raw" ? "DEM drape" : s.method);
    lx += 100;
  }
  h += "</svg></figure>\n";
}

// Roads to plot: the steepest roads on the ground by raw grade, then the structures (longest
// first), each road once.
std::pair<std::vector<int>, std::vector<int>> roads_to_plot(const HtmlReportInput& in) {
  const auto& roads = in.network->roads;
  const auto& raw = *in.raw;
  std::vector<std::pair<double, int>> steep, structures;
  for (std::size_t r = 0; r < roads.size(); ++r) {
    if (!raw[r].has_height || raw[r].size() < 2) continue;
    const WayAttributes& at = roads[r].attributes;
    if (at.bridge || at.tunnel) {
      structures.emplace_back(road_length(raw[r]), static_cast<int>(r));
    } else if (road_length(raw[r]) >= in.steep_road_min_length_m) {
      steep.emplace_back(max_grade(raw[r]), static_cast<int>(r));
    }
  }
  const auto take = [](std::vector<std::pair<double, int>>& v, int n) {
    std::stable_sort(v.begin(), v.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
    std::vector<int> out;
    for (std::size_t i = 0; i < v.size() && static_cast<int>(i) < n; ++i) out.push_back(v[i].second);
    return out;
  };
  return {take(steep, in.steepest_roads), take(structures, in.max_structure_plots)};
}

void write_profiles(std::string& h, const HtmlReportInput& in, const std::vector<Series>& series) {
  const auto [steep, structures] = roads_to_plot(in);
  h += "<h2>Elevation profiles</h2>\n<p class=\"sub\">Grey: the DEM drape (raw samples); dashed orange: "
       "the paper's smoothing; blue: relief's fit. Lines are thinned to at most " +
       integer(kMaxSeriesPoints) + " points, keeping each stretch's highest and lowest sample.</p>\n";
  h += "<h3>Steepest roads on the ground (by raw grade, at least " + fixed(in.steep_road_min_length_m, 0) +
       " m long)</h3>\n<div class=\"plots\">\n";
  for (int r : steep) profile_plot(h, in, series, r);
  if (steep.empty()) h += "<p>None.</p>\n";
  h += "</div>\n<h3>Bridges and tunnels (longest first)</h3>\n<div class=\"plots\">\n";
  for (int r : structures) profile_plot(h, in, series, r);
  if (structures.empty()) h += "<p>None.</p>\n";
  h += "</div>\n";
}

// ---------------------------------------------------------------------------------------------
// Plot 2: grade histogram.

constexpr double kBinPercent = 2.0;
constexpr std::size_t kBins = 21;  // 0-2, ..., 38-40, 40+

struct Histogram {
  std::array<double, kBins> metres{};
  double total_m = 0.0;
};

Histogram grade_histogram(const std::vector<RoadProfile>& profiles) {
  Histogram hist;
  for (const RoadProfile& p : profiles) {
    if (!p.has_height) continue;
    const std::vector<double> g = segment_grades_percent(p);
    for (std::size_t i = 0; i < g.size(); ++i) {
      const double len = p.s[i + 1] - p.s[i];
      const auto bin = std::min(kBins - 1, static_cast<std::size_t>(std::max(0.0, g[i]) / kBinPercent));
      hist.metres[bin] += len;
      hist.total_m += len;
    }
  }
  return hist;
}

void write_histogram(std::string& h, const RunReport& r, const std::vector<Series>& series) {
  std::vector<Histogram> hists;
  double top = 0.0;
  for (const Series& s : series) {
    hists.push_back(grade_histogram(*s.profiles));
    for (double m : hists.back().metres) top = std::max(top, m / 1000.0);
  }
  const double width = 1100, height = 320;
  const double ymax = top > 0.0 ? std::ceil(top / nice_step(top, 5) - 1e-9) * nice_step(top, 5) : 1.0;
  const Axes a{{0.0, kBinPercent * kBins, 56, width - 16}, {0.0, ymax, height - 42, 30}};
  h += "<h2>Grade distribution</h2>\n<figure><figcaption>Length of road (km) by |grade|, bins of 2 %, "
       "the last bin holds everything from 40 %. Red dashes: the class limits.</figcaption>\n";
  svg_open(h, width, height, "Grade histogram");
  draw_axes(h, a, "|grade| (%)", "km", 10, 5);
  const double bin_px = a.x(kBinPercent) - a.x(0.0);
  const double bar_px = (bin_px - 4.0) / static_cast<double>(series.size());
  for (std::size_t k = 0; k < series.size(); ++k) {
    h += "<g class=\"b-" + series[k].method + "\" data-method=\"" + series[k].method + "\" data-total-m=\"" +
         fixed(hists[k].total_m, 3) + "\">\n";
    for (std::size_t b = 0; b < kBins; ++b) {
      const double km = hists[k].metres[b] / 1000.0;
      const double x = a.x(kBinPercent * static_cast<double>(b)) + 2.0 + bar_px * static_cast<double>(k);
      h += "<rect x=\"" + fixed(x, 1) + "\" y=\"" + fixed(a.y(km), 1) + "\" width=\"" + fixed(bar_px, 1) +
           "\" height=\"" + fixed(a.y(0.0) - a.y(km), 1) + "\" data-m=\"" + fixed(hists[k].metres[b], 3) +
           "\"/>\n";
    }
    h += "</g>\n";
  }
  std::set<double> limits;
  for (const auto& [cls, percent] : r.grade_limits.percent) limits.insert(percent);
  for (double lim : limits) {
    const double x = a.x(lim);
    h += "<line class=\"lim\" x1=\"" + fixed(x, 1) + "\" x2=\"" + fixed(x, 1) + "\" y1=\"" +
         fixed(a.y.p0, 1) + "\" y2=\"" + fixed(a.y.p1 - 8, 1) + "\"/>\n";
    svg_text(h, x, a.y.p1 - 11, "middle", fixed(lim, 0) + " %", " fill=\"#c0392b\"");
  }
  svg_text(h, a.x(kBinPercent * (kBins - 0.5)), a.y.p0 + 31, "middle", "40+");
  double lx = width - 16 - 130.0 * static_cast<double>(series.size());
  for (const Series& s : series) {
    h += "<rect class=\"b-" + s.method + "\" x=\"" + fixed(lx, 1) +
         "\" y=\"12\" width=\"12\" height=\"10\"/>\n";
    svg_text(h, lx + 16, 21, "start", method_label(s.method));
    lx += 130;
  }
  h += "</svg></figure>\n";
}

// ---------------------------------------------------------------------------------------------
// Plot 3: maps of the network.

// A classed colour scale: value v falls in class k when edges[k-1] <= v < edges[k].
struct ColourScale {
  std::string prefix;         // CSS class prefix ("g", "d")
  std::vector<double> edges;  // size = colours - 1, ascending
  std::vector<std::string> colours;
  std::vector<std::string> labels;  // one per class
  [[nodiscard]] std::size_t classify(double v) const {
    return static_cast<std::size_t>(std::upper_bound(edges.begin(), edges.end(), v) - edges.begin());
  }
};

// NOLINTBEGIN(bugprone-suspicious-missing-comma): each label is split after its \x escape, so
// that the digit after the en dash is not read as part of it.
ColourScale grade_scale() {
  return {"g",
          {2, 4, 6, 8, 10, 12, 15, 20},
          {"#1a9850", "#66bd63", "#a6d96a", "#d9ef8b", "#fee08b", "#fdae61", "#f46d43", "#d73027", "#7f0000"},
          {"0\xE2\x80\x93"
           "2",
           "2\xE2\x80\x93"
           "4",
           "4\xE2\x80\x93"
           "6",
           "6\xE2\x80\x93"
           "8",
           "8\xE2\x80\x93"
           "10",
           "10\xE2\x80\x93"
           "12",
           "12\xE2\x80\x93"
           "15",
           "15\xE2\x80\x93"
           "20",
           "20+ %"}};
}

ColourScale departure_scale() {
  return {"d",
          {-2.0, -0.5, -0.1, 0.1, 0.5, 2.0},
          {"#3b8bd4", "#79b8e0", "#bcdcf0", "#8a8f99", "#f6c6a8", "#ef8a62", "#e0302f"},
          {"cut &gt; 2",
           "2\xE2\x80\x93"
           "0.5",
           "0.5\xE2\x80\x93"
           "0.1",
           "\xC2\xB1"
           "0.1",
           "0.1\xE2\x80\x93"
           "0.5",
           "0.5\xE2\x80\x93"
           "2",
           "fill &gt; 2 m"}};
}
// NOLINTEND(bugprone-suspicious-missing-comma)

constexpr double kMapPieceM = 5.0;      // colour resolution along a road
constexpr double kMapToleranceM = 0.5;  // Douglas–Peucker tolerance

// Map extent and the data-to-pixel transform (equal aspect, north up).
struct MapFrame {
  Axes a;
  double width, height;
};

MapFrame map_frame(const HtmlReportInput& in) {
  Aabb2 box;
  for (const Road& road : in.network->roads) {
    for (const Vec2& p : road.points) box.extend(p);
  }
  if (box.empty()) box.extend(Vec2(0, 0));
  const double dx = std::max(box.max.x() - box.min.x(), 1.0), dy = std::max(box.max.y() - box.min.y(), 1.0);
  const double margin = 14, max_w = 1100, max_h = 900;
  const double scale = std::min((max_w - 2 * margin) / dx, (max_h - 2 * margin) / dy);
  const double w = dx * scale + 2 * margin, hgt = dy * scale + 2 * margin;
  const double x0 = box.min.x(), y0 = box.min.y();
  return {{{x0, x0 + dx, margin, w - margin}, {y0, y0 + dy, hgt - margin, margin}}, w, hgt + 56};
}

// Road `r` drawn as runs of pieces of ~kMapPieceM that fall in the same colour class, each run
// one polyline simplified to kMapToleranceM. `value(r, i0, i1)` is the figure of the piece
// between stations i0 and i1 of `p`.
template <class Value>
void map_road(std::string& h, const MapFrame& f, const Road& road, const RoadProfile& p, std::size_t r,
              const ColourScale& cs, const Value& value) {
  if (p.size() < 2) return;
  const std::string structure = road.attributes.bridge ? " br" : road.attributes.tunnel ? " tu" : "";
  const auto emit = [&](std::size_t a, std::size_t b, const std::string& cls) {
    // Douglas-Peucker on the perpendicular distance in plan.
    const std::vector<std::uint8_t> keep =
        douglas_peucker(b - a + 1, kMapToleranceM, [&](std::size_t i, std::size_t k, std::size_t j) {
          const Vec2 d = p.xy[a + j] - p.xy[a + i], v = p.xy[a + k] - p.xy[a + i];
          const double len = d.norm();
          return len > 0.0 ? std::abs(d.x() * v.y() - d.y() * v.x()) / len : v.norm();
        });
    h += "<polyline class=\"" + cls + structure + "\" points=\"";
    for (std::size_t i = a; i <= b; ++i) {
      if (keep[i - a]) h += fixed(f.a.x(p.xy[i].x()), 1) + "," + fixed(f.a.y(p.xy[i].y()), 1) + " ";
    }
    h.back() = '"';
    h += "/>\n";
  };
  if (!p.has_height) {
    emit(0, p.size() - 1, "nh");
    return;
  }
  const std::size_t none = cs.colours.size();
  std::size_t run_start = 0, piece_start = 0, run_class = none;
  for (std::size_t i = 1; i < p.size(); ++i) {
    // Close a piece once it is long enough (or at the road's end).
    if (p.s[i] - p.s[piece_start] < kMapPieceM && i + 1 < p.size()) continue;
    const std::size_t k = cs.classify(value(r, piece_start, i));
    if (k != run_class && run_class != none) {
      emit(run_start, piece_start, cs.prefix + std::to_string(run_class));
      run_start = piece_start;
    }
    run_class = k;
    piece_start = i;
  }
  emit(run_start, p.size() - 1, cs.prefix + std::to_string(run_class));
}

void map_legend(std::string& h, const MapFrame& f, const ColourScale& cs, std::string_view unit) {
  const double y = f.height - 34, w = 64;
  double x = 14;
  for (std::size_t k = 0; k < cs.colours.size(); ++k, x += w) {
    h += "<rect x=\"" + fixed(x, 1) + "\" y=\"" + fixed(y, 1) + "\" width=\"" + fixed(w, 1) +
         "\" height=\"10\" fill=\"" + cs.colours[k] + "\"/>\n";
    svg_text(h, x + w / 2, y + 23, "middle", cs.labels[k]);
  }
  svg_text(h, x + 8, y + 9, "start", std::string(unit));
  // Scale bar, bottom right, and a north arrow.
  const double metres_per_px = (f.a.x.d1 - f.a.x.d0) / (f.a.x.p1 - f.a.x.p0);
  const double bar_m = nice_step(160 * metres_per_px, 1), bar_px = bar_m / metres_per_px;
  const double bx = f.width - 20 - bar_px;
  h += "<path class=\"ax\" fill=\"none\" d=\"M" + fixed(bx, 1) + " " + fixed(y, 1) + "v6h" +
       fixed(bar_px, 1) + "v-6\"/>\n";
  svg_text(h, bx + bar_px / 2, y + 23, "middle",
           bar_m >= 1000 ? fixed(bar_m / 1000, 0) + " km" : fixed(bar_m, bar_m >= 1 ? 0 : 1) + " m");
  svg_text(h, bx - 24, y + 10, "middle", "N \xE2\x86\x91", " font-weight=\"bold\"");
}

// CSS of a scale's colour classes (in the page's <style>).
std::string scale_css(const ColourScale& cs) {
  std::string css;
  for (std::size_t k = 0; k < cs.colours.size(); ++k) {
    css += ".map ." + cs.prefix + std::to_string(k) + "{stroke:" + cs.colours[k] + "}";
  }
  return css + "\n";
}

template <class Value>
void write_map(std::string& h, const HtmlReportInput& in, const std::vector<RoadProfile>& profiles,
               const ColourScale& cs, std::string_view title, const std::string& caption,
               std::string_view unit, const Value& value) {
  const MapFrame f = map_frame(in);
  h += "<figure><figcaption>" + caption + "</figcaption>\n";
  svg_open(h, f.width, f.height, title, "map");
  // Structures last so that they lie on top of the roads they cross.
  for (int pass = 0; pass < 2; ++pass) {
    for (std::size_t r = 0; r < in.network->roads.size(); ++r) {
      const Road& road = in.network->roads[r];
      const bool structure = road.attributes.bridge || road.attributes.tunnel;
      if (structure == (pass == 1)) map_road(h, f, road, profiles[r], r, cs, value);
    }
  }
  map_legend(h, f, cs, unit);
  h += "</svg></figure>\n";
}

// The profiles the maps show: relief's fit, else the paper's, else raw.
const Series& map_series(const std::vector<Series>& series) {
  return series.back();
}

void write_maps(std::string& h, const HtmlReportInput& in, const std::vector<Series>& series) {
  const Series& shown = map_series(series);
  const std::vector<RoadProfile>& profiles = *shown.profiles;
  const std::vector<RoadProfile>& raw = *in.raw;
  h += "<h2>Network maps</h2>\n";
  write_map(h, in, profiles, grade_scale(), "Map of the network coloured by grade",
            "|grade| of the " + method_label(shown.method) + " profiles, over pieces of " +
                fixed(kMapPieceM, 0) + " m. Bridges thick, tunnels dashed, grey: no height. North up.",
            "|grade| %", [&](std::size_t r, std::size_t i0, std::size_t i1) {
              const RoadProfile& p = profiles[r];
              const double ds = p.s[i1] - p.s[i0];
              return ds > 0.0 ? 100.0 * std::abs(p.z[i1] - p.z[i0]) / ds : 0.0;
            });
  if (shown.method == "raw") return;
  write_map(h, in, profiles, departure_scale(), "Map of the network coloured by departure from the DEM",
            "Height of the " + method_label(shown.method) +
                " profiles minus the DEM drape, mean over pieces of " + fixed(kMapPieceM, 0) +
                " m: blue below the terrain (cut), red above (fill). Bridges and tunnels are expected to "
                "depart.",
            "m", [&](std::size_t r, std::size_t i0, std::size_t i1) {
              const RoadProfile& p = profiles[r];
              if (!raw[r].has_height) return 0.0;
              double sum = 0.0;
              for (std::size_t i = i0; i <= i1; ++i) sum += p.z[i] - height_at_station(raw[r], p.s[i]);
              return sum / static_cast<double>(i1 - i0 + 1);
            });
}

void check_input(const HtmlReportInput& in) {
  if (!in.report) throw InvalidInput("report.html: no report figures were given.");
  if (!in.network) throw InvalidInput("report.html: no road network was given.");
  if (!in.raw) throw InvalidInput("report.html: no raw (DEM drape) profiles were given.");
  const std::size_t roads = in.network->roads.size();
  const auto check = [&](const std::vector<RoadProfile>* p, std::string_view what) {
    if (p && p->size() != roads) {
      throw InvalidInput("report.html: " + std::string(what) + " profiles: " + std::to_string(p->size()) +
                         " for " + std::to_string(roads) + " roads.");
    }
  };
  check(in.raw, "raw");
  check(in.paper, "paper");
  check(in.fitted, "fitted");
}

}  // namespace

void write_report_html(std::ostream& out, const HtmlReportInput& in) {
  check_input(in);
  const RunReport& r = *in.report;
  const std::vector<Series> series = series_of(in);
  std::string h;
  h.reserve(1 << 20);
  h += "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\"/>\n<title>relief report";
  if (!r.name.empty()) h += ": " + esc(r.name);
  h += "</title>\n<style>";
  h += kStyle;
  h += scale_css(grade_scale());
  h += scale_css(departure_scale());
  h += sight_css();
  h += "</style>\n</head>\n<body>\n<main>\n";
  write_header(h, r);
  write_overview(h, in);
  write_gates(h, r);
  write_cards(h, r);
  write_comparison(h, r);
  write_class_tables(h, r);
  write_profiles(h, in, series);
  write_histogram(h, r, series);
  write_maps(h, in, series);
  write_sight_section(h, r, *in.network, in.sight);
  write_diagnostics(h, r);
  write_timings(h, r);
  h += "</main>\n</body>\n</html>\n";
  out.write(h.data(), static_cast<std::streamsize>(h.size()));
}

}  // namespace relief

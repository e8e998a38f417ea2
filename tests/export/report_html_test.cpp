#include "relief/export/report_html.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <regex>
#include <sstream>

#include "relief/core/errors.h"
#include "support/synthetic.h"
#include "support/test_data.h"

namespace relief {
namespace {

// Four roads, 650 m in all: a ground road climbing at 11 % named with markup characters, a
// primary climbing at 5 % due north, a bridge whose DEM drape dips into a valley at 25 %, and a
// tunnel at 3 %.
struct World {
  RoadNetwork network;
  std::vector<RoadProfile> raw, paper, fitted;
  RunReport report;
  Diagnostics diagnostics;
};

void set_heights(RoadProfile& p, const std::function<double(const Vec2&)>& f) {
  for (std::size_t i = 0; i < p.size(); ++i) p.z[i] = f(p.xy[i]);
}

MethodReport method(const std::string& name, double rmse_ground_m, double max_grade_percent) {
  MethodReport m;
  m.method = name;
  m.ground.vs_dem = ErrorStats{rmse_ground_m * 0.8, rmse_ground_m, rmse_ground_m * 3.0, 0.0, 450};
  m.structures.vs_dem = ErrorStats{1.5, 2.0, 5.0, 0.0, 200};
  m.gradient.max_percent = max_grade_percent;
  m.gradient.by_class["residential"] =
      GradeClassStats{0.1, 15.0, 100.0, max_grade_percent, max_grade_percent};
  m.separations = 1;
  m.min_clearance_m = 4.5;
  return m;
}

World make_world() {
  World w;
  WayAttributes street;
  street.name = "Main <&> \"St\"";
  WayAttributes primary;
  primary.highway = HighwayClass::primary;
  WayAttributes bridge;
  bridge.bridge = true;
  bridge.layer = 1;
  WayAttributes tunnel;
  tunnel.tunnel = true;
  tunnel.layer = -1;
  w.network = test::make_network({{Vec2(0, 0), Vec2(100, 0)},
                                  {Vec2(100, 0), Vec2(100, 200)},
                                  {Vec2(100, 200), Vec2(300, 200)},
                                  {Vec2(0, 0), Vec2(0, -150)}},
                                 {street, primary, bridge, tunnel});
  for (const Road& road : w.network.roads) w.raw.push_back(make_stations(road, 1.0));
  set_heights(w.raw[0], [](const Vec2& p) { return 0.11 * p.x(); });
  set_heights(w.raw[1], [](const Vec2& p) { return 11.0 + 0.05 * p.y(); });
  set_heights(w.raw[2], [](const Vec2& p) { return 21.0 - 0.25 * (100.0 - std::abs(p.x() - 200.0)); });
  set_heights(w.raw[3], [](const Vec2& p) { return 0.03 * p.y(); });
  w.paper = w.raw;
  w.fitted = w.raw;
  set_heights(w.fitted[0], [](const Vec2& p) { return 0.09 * p.x(); });
  set_heights(w.fitted[2], [](const Vec2&) { return 21.0; });

  RunReport& r = w.report;
  r.name = "test <run>";
  r.created_utc = "2024-01-01T00:00:00Z";
  r.frame = w.network.frame;
  r.osm_path = "roads & more.osm";
  r.network = network_stats(w.network);
  r.profile_method = "relief";
  r.methods = {method("raw", 0.1234, 33.3), method("paper", 0.0567, 14.0), method("relief", 0.0089, 11.0)};
  FitSummary fit;
  fit.policy = "soft";
  fit.iterations = 7;
  fit.converged = true;
  fit.solver = "converged (interior point)";
  fit.variables = 650;
  fit.constraints = 1300;
  fit.max_violation_m = 0.0012;
  fit.clearance_m = 4.5;
  fit.cutoff_wavelength_m = 40.0;
  r.fit = fit;
  r.paper = PaperSummary{50, 1, 0.8, {2}};
  w.diagnostics.report(Severity::warning, "osm.missing_node", "way 5 misses <node> 7 & \x01 \xff bytes");
  r.diagnostics = &w.diagnostics;
  return w;
}

std::string render(const HtmlReportInput& in) {
  std::ostringstream out;
  write_report_html(out, in);
  return out.str();
}

HtmlReportInput input_of(const World& w, bool smoothed) {
  HtmlReportInput in;
  in.report = &w.report;
  in.network = &w.network;
  in.raw = &w.raw;
  if (smoothed) {
    in.paper = &w.paper;
    in.fitted = &w.fitted;
  }
  in.steepest_roads = 2;
  return in;
}

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

// Parses the page with Python's XML parser; returns its exit status (0: well-formed and holding
// `svgs` <svg> elements).
int parse_with_python(const std::string& html, int svgs) {
  const auto path = test::scratch_dir("report_html") / "report.html";
  std::ofstream(path) << html;
  const std::string cmd =
      "python3 -c \"import sys, xml.etree.ElementTree as E; r = E.parse(sys.argv[1]).getroot(); "
      "sys.exit(0 if sum(1 for _ in r.iter('svg')) == int(sys.argv[2]) else 3)\" '" +
      path.string() + "' " + std::to_string(svgs);
  return std::system(cmd.c_str());
}

// The <tr> whose data-key is `key`.
std::string row(const std::string& html, const std::string& key) {
  const std::size_t at = html.find("<tr data-key=\"" + key + "\"");
  if (at == std::string::npos) return {};
  return html.substr(at, html.find("</tr>", at) - at);
}

TEST(ReportHtml, ParsesAsXmlWithOnePlotPerProfileHistogramAndMaps) {
  const World w = make_world();
  // Raw only: 2 steepest + 2 structures + histogram + grade map.
  const std::string raw_only = render(input_of(w, false));
  EXPECT_EQ(count(raw_only, "<svg "), 6u);
  EXPECT_EQ(parse_with_python(raw_only, 6), 0);
  // With smoothed profiles, also the map of the departure from the DEM. (Parsed last, so that
  // the scratch file keeps the full page to look at.)
  const std::string html = render(input_of(w, true));
  EXPECT_EQ(count(html, "<svg "), 7u);
  EXPECT_EQ(parse_with_python(html, 7), 0);
  EXPECT_EQ(html.find("<script"), std::string::npos);
  // The only external address is the OSM copyright link (href and its text).
  EXPECT_EQ(count(html, "http"), count(html, "https://www.openstreetmap.org/copyright"));
  EXPECT_NE(html.find("ODbL"), std::string::npos);
}

TEST(ReportHtml, EscapesTextFromTheData) {
  const World w = make_world();
  const std::string html = render(input_of(w, true));
  EXPECT_NE(html.find("Main &lt;&amp;&gt; &quot;St&quot;"), std::string::npos);
  EXPECT_EQ(html.find("Main <&>"), std::string::npos);
  EXPECT_NE(html.find("test &lt;run&gt;"), std::string::npos);
  EXPECT_NE(html.find("roads &amp; more.osm"), std::string::npos);
  EXPECT_NE(html.find("misses &lt;node&gt; 7 &amp; \xEF\xBF\xBD \xEF\xBF\xBD bytes"), std::string::npos);
}

TEST(ReportHtml, DemCellsTreatedAsVoidsAppearWhenThereAreSome) {
  World w = make_world();
  DemInfo dem;
  dem.path = "dem.tif";
  w.report.dems = {dem};
  EXPECT_EQ(render(input_of(w, true)).find("treated as voids"), std::string::npos);
  w.report.dems[0].implausible_cells = 2;
  w.report.dems[0].spike_cells = 1;
  EXPECT_NE(render(input_of(w, true))
                .find("treated as voids: 2 cells of implausible height, 1 one-cell spikes or pits"),
            std::string::npos);
}

TEST(ReportHtml, OpenDriveFiguresAppearWhenAFileWasWritten) {
  World w = make_world();
  EXPECT_EQ(render(input_of(w, true)).find("OpenDRIVE"), std::string::npos);
  OpenDriveSummary o;
  o.version = "1.7";
  o.junctions = 43;
  o.connecting_roads = 257;
  o.max_link_gap_m = 0.00088;
  o.round_trip_max_z_m = 4e-6;
  w.report.opendrive = o;
  const std::string html = render(input_of(w, true));
  EXPECT_NE(html.find("43 / 257"), std::string::npos);
  EXPECT_NE(html.find("0.88 mm"), std::string::npos);
  EXPECT_NE(html.find("0.004 mm"), std::string::npos);
  EXPECT_EQ(parse_with_python(html, 7), 0);
}

TEST(ReportHtml, ComparisonTableHasEachMethodsRmseAndHighlightsTheWrittenOne) {
  const World w = make_world();
  const std::string html = render(input_of(w, true));
  const std::string rmse = row(html, "dem_ground_rmse_m");
  ASSERT_FALSE(rmse.empty());
  const std::size_t raw = rmse.find("<td>0.123</td>"), paper = rmse.find("<td>0.057</td>"),
                    relief = rmse.find("<td class=\"chosen\">0.009</td>");
  ASSERT_NE(raw, std::string::npos) << rmse;
  ASSERT_NE(paper, std::string::npos) << rmse;
  ASSERT_NE(relief, std::string::npos) << rmse;
  EXPECT_LT(raw, paper);
  EXPECT_LT(paper, relief);
  EXPECT_NE(row(html, "dem_structures_rmse_m").find("<td>2.000</td>"), std::string::npos);
  // No reference DEM: a dash in every column.
  EXPECT_EQ(count(row(html, "ref_ground_rmse_m"), "\xE2\x80\x94"), 3u);
  EXPECT_NE(row(html, "grade_max").find("<td>33.30</td>"), std::string::npos);
  EXPECT_NE(row(html, "min_clearance").find("<td class=\"chosen\">4.50</td>"), std::string::npos);
}

TEST(ReportHtml, HistogramBinsSumToTheRoadLength) {
  const World w = make_world();
  const std::string html = render(input_of(w, true));
  const std::regex group(
      R"re(<g class="b-(\w+)" data-method="\w+" data-total-m="([0-9.]+)">([\s\S]*?)</g>)re");
  const std::regex bar(R"re(data-m="([0-9.]+)")re");
  int groups = 0;
  for (auto it = std::sregex_iterator(html.begin(), html.end(), group); it != std::sregex_iterator(); ++it) {
    ++groups;
    EXPECT_NEAR(std::stod((*it)[2]), 650.0, 1e-6) << (*it)[1];
    const std::string bars = (*it)[3];
    double sum = 0.0;
    std::vector<double> bins;
    for (auto b = std::sregex_iterator(bars.begin(), bars.end(), bar); b != std::sregex_iterator(); ++b) {
      bins.push_back(std::stod((*b)[1]));
      sum += bins.back();
    }
    ASSERT_EQ(bins.size(), 21u);
    EXPECT_NEAR(sum, 650.0, 0.01) << (*it)[1];
    // The tunnel (3 %) fills the 2-4 % bin, the primary (5 %) the 4-6 % bin.
    EXPECT_NEAR(bins[1], 150.0, 1e-6) << (*it)[1];
    EXPECT_NEAR(bins[2], 200.0, 1e-6) << (*it)[1];
    // The 11 % street: 10-12 % for raw and paper, 8-10 % for the fit; the bridge's 25 % drape
    // in 24-26 %, flat (0-2 %) once fitted.
    const bool fit = (*it)[1] == "relief";
    EXPECT_NEAR(fit ? bins[4] : bins[5], 100.0, 1e-6) << (*it)[1];
    EXPECT_NEAR(fit ? bins[0] : bins[12], 200.0, 1e-6) << (*it)[1];
  }
  EXPECT_EQ(groups, 3);
}

TEST(ReportHtml, ProfilesShowTheSteepestRoadFirstAndMapIsNorthUp) {
  const World w = make_world();
  const std::string html = render(input_of(w, false));
  const std::size_t first = html.find("<figcaption>Road ");
  ASSERT_NE(first, std::string::npos);
  EXPECT_EQ(html.compare(first, 22, "<figcaption>Road 0 \xC2\xB7 "), 0);
  // The primary (5 %, class g2) runs due north: its points go up the page (svg y decreases).
  const std::regex north(R"re(<polyline class="g2" points="([0-9.]+),([0-9.]+) ([0-9.]+),([0-9.]+)"/>)re");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(html, m, north));
  EXPECT_DOUBLE_EQ(std::stod(m[1]), std::stod(m[3]));
  EXPECT_GT(std::stod(m[2]), std::stod(m[4]) + 100.0);
  EXPECT_NE(html.find(" br\" points="), std::string::npos);
  EXPECT_NE(html.find(" tu\" points="), std::string::npos);
}

TEST(ReportHtml, ThrowsOnMissingOrMismatchedInputs) {
  const World w = make_world();
  HtmlReportInput in = input_of(w, true);
  in.network = nullptr;
  EXPECT_THROW(render(in), InvalidInput);
  in = input_of(w, true);
  in.report = nullptr;
  EXPECT_THROW(render(in), InvalidInput);
  in = input_of(w, true);
  in.raw = nullptr;
  EXPECT_THROW(render(in), InvalidInput);
  const std::vector<RoadProfile> short_set(w.raw.begin(), w.raw.end() - 1);
  in = input_of(w, true);
  in.raw = &short_set;
  EXPECT_THROW(render(in), InvalidInput);
}

// A city-sized network (1200 roads, 144 km, 1 m stations, wiggly centrelines, a noisy drape)
// must give a page of sane size: the maps are simplified, the profiles thinned.
TEST(ReportHtml, CityNetworkStaysUnderThreeMegabytes) {
  constexpr int kNodes = 25;
  constexpr double kBlockM = 120.0;
  std::vector<Polyline2> lines;
  std::vector<WayAttributes> attributes;
  for (int i = 0; i < kNodes; ++i) {
    for (int j = 0; j + 1 < kNodes; ++j) {
      for (int dir = 0; dir < 2; ++dir) {
        Polyline2 line;
        for (int k = 0; k <= 6; ++k) {
          const double along = (j + k / 6.0) * kBlockM,
                       across = i * kBlockM + (k % 6 ? 1.5 * std::sin(k) : 0.0);
          line.push_back(dir == 0 ? Vec2(along, across) : Vec2(across, along));
        }
        lines.push_back(line);
        WayAttributes a;
        a.bridge = lines.size() % 97 == 0;
        a.tunnel = lines.size() % 89 == 0;
        attributes.push_back(a);
      }
    }
  }
  const RoadNetwork network = test::make_network(lines, attributes);
  ASSERT_EQ(network.roads.size(), 1200u);
  const auto terrain = [](const Vec2& p) { return 60.0 * std::sin(p.x() / 400.0) * std::cos(p.y() / 700.0); };
  std::vector<RoadProfile> raw, fitted;
  std::uint32_t seed = 12345;
  for (const Road& road : network.roads) {
    raw.push_back(make_stations(road, 1.0));
    fitted.push_back(raw.back());
    set_heights(fitted.back(), terrain);
    set_heights(raw.back(), [&](const Vec2& p) {
      seed = seed * 1664525u + 1013904223u;
      return terrain(p) + 0.3 * (static_cast<double>(seed >> 8) / 16777216.0 - 0.5);
    });
  }
  RunReport report;
  report.methods = {method("raw", 0.1, 30.0), method("relief", 0.05, 15.0)};
  report.profile_method = "relief";
  HtmlReportInput in;
  in.report = &report;
  in.network = &network;
  in.raw = &raw;
  in.paper = &fitted;
  in.fitted = &fitted;
  const std::string html = render(in);
  const auto path = test::scratch_dir("report_html_city") / "report.html";
  std::ofstream(path) << html;
  EXPECT_LT(html.size(), 3'000'000u);
  // 6 steepest, 12 structures (of 25), histogram, two maps.
  EXPECT_EQ(count(html, "<svg "), 6u + 12u + 3u);
}

}  // namespace
}  // namespace relief

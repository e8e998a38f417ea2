#pragma once
// report.html: the validation report for a person to look at — the comparison of the profile
// methods (raw DEM drape, the seed paper's smoothing, relief's fit) as tables, and plots as
// inline SVG (no scripts, no external files): elevation profiles of the steepest roads and of
// every structure (DEM vs paper vs fitted), a grade histogram, and a map of the network
// coloured by grade.

#include <ostream>
#include <vector>

#include "relief/export/report_writer.h"
#include "relief/roads/elevation_sampling.h"
#include "relief/roads/road_network.h"
#include "relief/sight/sight_distance.h"

namespace relief {

struct HtmlReportInput {
  const RunReport* report = nullptr;                 ///< the figures (required)
  const RoadNetwork* network = nullptr;              ///< required
  const std::vector<RoadProfile>* raw = nullptr;     ///< DEM drape (required), parallel to roads
  const std::vector<RoadProfile>* paper = nullptr;   ///< optional
  const std::vector<RoadProfile>* fitted = nullptr;  ///< optional (relief's fit)
  int steepest_roads = 6;                            ///< how many steepest roads to plot
  /// Only roads on the ground at least this long compete for "steepest" (short stubs next to
  /// structures or DEM steps give meaningless 1 m grades).
  double steep_road_min_length_m = 20.0;
  int max_structure_plots = 12;        ///< bridges and tunnels plotted, longest first
  const SightResult* sight = nullptr;  ///< optional: the sight-distance map's stretches
  std::string view_page;               ///< the interactive view beside the report ("view.html"), if any
  std::string overview_png;            ///< the scene's picture (viewer/overview_image.h), shown first
};

/// Writes a self-contained HTML5 page that is also well-formed XML (every text from the data
/// escaped). Sections: inputs and frame, summary, the methods compared (one column per entry
/// of report->methods, the written one highlighted), compliance by class, elevation profiles,
/// grade histogram (length-weighted |grade| in 2 % bins, 40 %+ last; each method's <g> carries
/// data-total-m and each bar data-m, in metres), maps coloured by grade and, when a smoothed
/// profile set is given, by departure from the DEM drape, diagnostics, timings.
/// Throws InvalidInput when report, network or raw is null or a profile set is not parallel to
/// the roads.
void write_report_html(std::ostream& out, const HtmlReportInput& input);

}  // namespace relief

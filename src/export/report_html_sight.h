#pragma once
// Private to the export module: report.html's sight-distance section (a map of the short
// stretches and a table of the worst places).

#include <string>

#include "relief/export/report_writer.h"
#include "relief/roads/road_network.h"
#include "relief/sight/sight_distance.h"

namespace relief::html {

/// The section, when the report has sight figures; `result` (optional) draws the map.
void write_sight_section(std::string& h, const RunReport& r, const RoadNetwork& network,
                         const SightResult* result);

/// CSS of the section's map.
[[nodiscard]] std::string sight_css();

}  // namespace relief::html

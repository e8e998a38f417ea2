#include "tiles/sumo_merge.h"

#include <sstream>

#include "relief/core/scratch_dir.h"
#include "relief/export/sumo_mapping.h"
#include "relief/export/sumo_net_build.h"
#include "relief/export/sumo_plain_xml.h"

namespace relief::detail {

std::vector<double> model_grade_caps(const RoadModel& model, const ProfileFitOptions& fit) {
  std::vector<double> caps(model.roads.size(), -1.0);
  for (std::size_t i = 0; i < model.roads.size(); ++i) {
    const ModelRoad& road = model.roads[i];
    if (road.junction < 0 && road.highway) caps[i] = grade_limit(fit, *road.highway);
  }
  return caps;
}

nlohmann::json merge_sumo_net(const RoadModel& model, const SumoOptions& options, const GateThresholds& gates,
                              const std::filesystem::path& dir, const std::string& name, OutputSet& files,
                              std::vector<std::filesystem::path>& written,
                              std::vector<std::string>& failed_gates, Diagnostics& diagnostics) {
  // Junction ids in the options are a tile's; the merged junctions carry their lights.
  SumoOptions region = options;
  region.signalled_junctions.clear();
  SumoNetBuild net;
  {
    const ScratchDir scratch(dir);
    net = build_sumo_net(model, region, scratch.path(), name, diagnostics);
  }
  const auto add = [&](const std::string& file, auto&& write) {
    files.add(dir / file, write);
    written.push_back(dir / file);
  };
  add(name + ".net.xml", [&](std::ostream& o) { o << net.run.net_xml; });
  add(name + ".nod.xml", [&](std::ostream& o) { write_sumo_nodes(o, net.plain); });
  add(name + ".edg.xml", [&](std::ostream& o) { write_sumo_edges(o, net.plain); });
  add(name + ".con.xml", [&](std::ostream& o) { write_sumo_connections(o, net.plain); });
  add(name + ".sumo_mapping.json", [&](std::ostream& o) { write_sumo_mapping(o, net.plain); });

  const SumoNetCheck& c = net.check;
  // The build's SUMO gates (quality_gates.h), over the whole region.
  const double z_max = std::max(c.z_max_m, c.netconvert_shape_z_max_m);
  const auto gate = [&](const std::string& what, double value, double threshold, const std::string& where) {
    if (value <= threshold) return;
    std::ostringstream text;
    text << "merge: " << what << " " << value << " (at most " << threshold << ")"
         << (where.empty() ? "" : ", ") << where;
    failed_gates.push_back(text.str());
  };
  gate("sumo_lanes_without_z", static_cast<double>(c.lanes_without_z), gates.sumo_lanes_without_z, "");
  gate("sumo_lane_z_max_m", z_max, gates.sumo_lane_z_max_m, "lane " + c.z_max_lane);
  gate("sumo_height_steps", static_cast<double>(c.height_steps), gates.sumo_height_steps,
       c.height_steps > 0 ? "lane " + c.first_step_lane : std::string());
  gate("sumo_handover_gap_m", c.max_handover_gap_m, gates.sumo_handover_gap_m, c.handover_gap_lanes);
  return {{"file", name + ".net.xml"},
          {"nodes", net.plain.stats.nodes},
          {"edges", c.edges},
          {"lanes", c.lanes},
          {"internal_lanes", c.internal_lanes},
          {"junctions", c.junctions},
          {"traffic_lights", c.traffic_lights},
          {"connections", net.plain.stats.connections},
          {"lanes_without_z", c.lanes_without_z},
          {"z_max_m", z_max},
          {"z_p99_m", c.z_p99_m},
          {"z_max_lane", c.z_max_lane},
          {"height_steps", c.height_steps},
          {"max_handover_gap_m", c.max_handover_gap_m},
          {"netconvert_warnings", net.run.warnings},
          {"seconds", net.build_seconds + net.netconvert_seconds + net.check_seconds}};
}

}  // namespace relief::detail

#include "relief/export/sumo_net_build.h"

#include <chrono>

namespace relief {
namespace {

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

}  // namespace

SumoNetBuild build_sumo_net(const RoadModel& model, SumoOptions options,
                            const std::filesystem::path& work_dir, const std::string& name,
                            Diagnostics& diagnostics) {
  SumoNetBuild out;
  const auto t_build = std::chrono::steady_clock::now();
  std::vector<SumoRoadInfo> info(model.roads.size());
  for (std::size_t i = 0; i < model.roads.size(); ++i) {
    if (model.roads[i].highway) info[i].highway = *model.roads[i].highway;
  }
  for (const JunctionModel& j : model.junctions) {
    if (j.traffic_signal) options.signalled_junctions.insert(j.id);
  }
  out.plain = build_sumo_network(model, info, options, diagnostics);
  out.build_seconds = seconds_since(t_build);
  const auto t_netconvert = std::chrono::steady_clock::now();
  out.run = run_netconvert(out.plain, work_dir, name);
  out.netconvert_seconds = seconds_since(t_netconvert);
  const auto t_check = std::chrono::steady_clock::now();
  out.drape = drape_sumo_net(out.run.net_xml, model, name + ".net.xml");
  out.check = check_sumo_net(out.run.net_xml, model, name + ".net.xml", options.grade_caps);
  out.check_seconds = seconds_since(t_check);
  return out;
}

}  // namespace relief

#include "pipeline/sight_stage.h"

#include <string>

namespace relief {

SightResult compute_sight(const SightStageInput& in) {
  std::vector<std::string> classes;
  classes.reserve(in.model.roads.size());
  for (const ModelRoad& road : in.model.roads) {
    classes.emplace_back(
        road.source_road >= 0
            ? std::string(
                  to_string(in.network.roads[static_cast<std::size_t>(road.source_road)].attributes.highway))
            : std::string("junction"));
  }
  return sight_distances(in.model, in.scene, in.options.sight, classes);
}

SightSummary write_sight_outputs(const SightStageInput& in, const SightResult& result, double seconds,
                                 OutputSet& files, std::vector<std::filesystem::path>& written,
                                 std::vector<std::string>& names) {
  SightSummary summary = summarize_sight(result, in.model, in.model.frame, in.options.sight);
  summary.file = in.name + ".sight.geojson";
  summary.seconds = seconds;
  const std::filesystem::path path = in.options.out_dir / summary.file;
  files.add(path, [&](std::ostream& out) { write_sight_geojson(out, result, in.model, in.model.frame); });
  written.push_back(path);
  names.push_back(summary.file);
  return summary;
}

}  // namespace relief

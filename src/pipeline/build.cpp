#include "relief/pipeline/build.h"

#include <chrono>
#include <ctime>
#include <iomanip>
#include <sstream>

#include "relief/core/atomic_file.h"
#include "relief/core/errors.h"
#include "relief/export/geojson_writer.h"
#include "relief/roads/network_builder.h"
#include "pipeline/stages.h"

namespace relief {
namespace {

std::string utc_now() {
  const std::time_t now = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&now, &tm);
  std::ostringstream out;
  out << std::put_time(&tm, "%Y-%m-%dT%H:%M:%SZ");
  return out.str();
}

}  // namespace

std::optional<Output> parse_output(std::string_view text) {
  if (text == "geojson") return Output::geojson;
  if (text == "report") return Output::report;
  return std::nullopt;
}

std::string_view to_string(Output output) {
  switch (output) {
    case Output::geojson: return "geojson";
    case Output::report: return "report";
  }
  return "unknown";
}

std::string default_name(const std::filesystem::path& osm_path) {
  std::string name = osm_path.filename().string();
  for (const char* ext : {".gz", ".bz2", ".pbf", ".osm", ".xml"}) {
    const std::string e(ext);
    if (name.size() > e.size() && name.compare(name.size() - e.size(), e.size(), e) == 0) {
      name.resize(name.size() - e.size());
    }
  }
  return name.empty() ? "relief" : name;
}

BuildResult build(const BuildOptions& options, Diagnostics& diagnostics, const ProgressFn& progress) {
  StageTimer timer(progress);
  BuildResult result;
  RunReport& report = result.report;
  report.name = options.name.empty() ? default_name(options.osm_path) : options.name;
  report.created_utc = utc_now();
  report.osm_path = options.osm_path.string();
  report.interpolation = options.dem.interpolation;
  report.spacing_m = options.sampling.spacing_m;
  report.nodata_fill = std::string(to_string(options.sampling.nodata_fill));
  report.diagnostics = &diagnostics;

  const LoadedNetwork loaded = load_network(options, diagnostics, timer);
  const RoadNetwork& network = loaded.network;
  report.frame = network.frame;

  const DemSampler dem = timer.run("open DEM", [&] {
    return DemSampler(options.dem_paths, network.frame, network_bounds(network), options.dem,
                      &diagnostics);
  });
  report.dems = dem.sources();

  const ElevationSamples samples = timer.run("sample elevation", [&] {
    return sample_elevation(network, dem, options.sampling, diagnostics);
  });
  report.samples = samples.samples;
  report.void_samples = samples.void_samples;
  report.uncovered_samples = samples.uncovered_samples;
  report.roads_without_height = samples.roads_without_height;

  std::optional<DemSampler> reference;
  if (!options.reference_dem_paths.empty()) {
    reference = timer.run("open reference DEM", [&] {
      return DemSampler(options.reference_dem_paths, network.frame, network_bounds(network),
                        options.reference_dem, &diagnostics);
    });
    report.reference_dems = reference->sources();
  }
  timer.run("validate", [&] {
    report.network = network_stats(network);
    report.heights = validate_heights(samples.profiles, dem, reference ? &*reference : nullptr);
    report.gradient = grade_stats(network, samples.profiles, options.grade_limits);
    report.junctions = junction_gaps(network, samples.profiles);
    return 0;
  });

  // Every output goes to a temporary first; all are renamed together at the end.
  std::error_code ec;
  std::filesystem::create_directories(options.out_dir, ec);
  if (ec) {
    throw IoError("cannot create the output directory '" + options.out_dir.string() +
                  "': " + ec.message());
  }
  OutputSet files;
  const auto path_of = [&](const std::string& suffix) { return options.out_dir / (report.name + suffix); };
  if (options.outputs.count(Output::geojson)) {
    timer.run("write GeoJSON", [&] {
      files.add(path_of(".geojson"), [&](std::ostream& out) { write_geojson(out, network, samples.profiles); });
      return 0;
    });
    report.outputs.push_back(report.name + ".geojson");
    result.written.push_back(path_of(".geojson"));
  }
  if (options.outputs.count(Output::report)) {
    report.outputs.push_back("report.json");
    result.written.push_back(options.out_dir / "report.json");
    report.timings_s = timer.timings();
    files.add(options.out_dir / "report.json", [&](std::ostream& out) { out << report_json(report); });
  }
  files.commit();
  report.timings_s = timer.timings();
  return result;
}

}  // namespace relief

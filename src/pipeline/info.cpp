#include "relief/pipeline/info.h"

#include "pipeline/stages.h"

namespace relief {

InfoResult inspect(const BuildOptions& options, Diagnostics& diagnostics) {
  StageTimer timer{ProgressFn{}};
  const LoadedNetwork loaded = load_network(options, diagnostics, timer);
  InfoResult info;
  info.osm_path = options.osm_path.string();
  info.osm_header_bounds = loaded.osm.header_bounds;
  info.roads_bounds = loaded.osm.bounds;
  info.frame = loaded.network.frame;
  info.ways_read = loaded.osm.ways_read;
  info.highway_ways = loaded.osm.highway_ways;
  info.road_ways = loaded.osm.ways.size();
  info.network = network_stats(loaded.network);

  // Coverage: sample like build() would, but count instead of refusing.
  SamplingOptions sampling = options.sampling;
  sampling.allow_partial = true;
  sampling.nodata_fill = NodataFill::interpolate;
  Diagnostics quiet;
  const DemSampler dem(options.dem_paths, loaded.network.frame, network_bounds(loaded.network), options.dem,
                       &diagnostics);
  info.dems = dem.sources();
  const ElevationSamples samples = sample_elevation(loaded.network, dem, sampling, quiet);
  info.samples = samples.samples;
  if (samples.samples > 0) {
    const auto n = static_cast<double>(samples.samples);
    info.void_percent = 100.0 * static_cast<double>(samples.void_samples) / n;
    info.uncovered_percent = 100.0 * static_cast<double>(samples.uncovered_samples) / n;
    info.covered_percent = 100.0 - info.void_percent - info.uncovered_percent;
  }
  return info;
}

}  // namespace relief

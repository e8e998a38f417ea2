#include "pipeline/stages.h"

#include "relief/roads/network_builder.h"

namespace relief {

LoadedNetwork load_network(const BuildOptions& options, Diagnostics& diagnostics, StageTimer& timer) {
  LoadedNetwork loaded;
  loaded.osm = timer.run("read OSM", [&] { return read_osm(options.osm_path, options.osm, diagnostics); });
  const LonLat centre = options.frame_centre.value_or(loaded.osm.bounds.centre());
  const GeoFrame frame = options.crs ? GeoFrame::in_crs(*options.crs, centre) : GeoFrame::utm_at(centre);
  loaded.network = timer.run("build network", [&] { return build_network(loaded.osm, frame, diagnostics); });
  return loaded;
}

Aabb2 network_bounds(const RoadNetwork& network) {
  Aabb2 box;
  for (const Road& road : network.roads) {
    for (const Vec2& p : road.points) box.extend(p);
  }
  return box;
}

}  // namespace relief

#include "support/synthetic.h"

#include <cmath>
#include <map>

#include "support/test_data.h"

namespace relief::test {

GeoFrame synthetic_frame() {
  return GeoFrame("EPSG:32610", Vec2(550000.0, 4180000.0));
}

std::string write_local_dem(const std::string& name, double extent_m, double cell_m,
                            const std::function<double(double, double)>& f, std::optional<double> nodata) {
  const GeoFrame frame = synthetic_frame();
  const int n = static_cast<int>(std::lround(2.0 * extent_m / cell_m));
  const double x0 = frame.origin().x() - extent_m;
  const double y0 = frame.origin().y() + extent_m;
  DemGrid grid = make_dem_grid(frame.crs(), x0, y0, cell_m, cell_m, n, n, [&](double x, double y) {
    return f(x - frame.origin().x(), y - frame.origin().y());
  });
  grid.nodata = nodata;
  const auto path = (scratch_dir("dem_" + name) / (name + ".tif")).string();
  write_geotiff(path, grid);
  return path;
}

RoadNetwork make_network(const std::vector<Polyline2>& roads, const std::vector<WayAttributes>& attributes) {
  RoadNetwork net;
  net.frame = synthetic_frame();
  std::map<std::pair<long, long>, int> junction_at;
  const auto junction = [&](const Vec2& p) {
    const std::pair<long, long> key{std::lround(p.x() * 1000.0), std::lround(p.y() * 1000.0)};
    const auto it = junction_at.find(key);
    if (it != junction_at.end()) return it->second;
    Junction j;
    j.id = static_cast<int>(net.junctions.size());
    j.position = p;
    j.osm_node_id = j.id + 1;
    net.junctions.push_back(j);
    junction_at[key] = j.id;
    return j.id;
  };
  for (std::size_t i = 0; i < roads.size(); ++i) {
    Road road;
    road.id = static_cast<int>(i);
    road.points = roads[i];
    road.osm_way_ids = {static_cast<std::int64_t>(100 + i)};
    for (std::size_t k = 0; k < road.points.size(); ++k)
      road.osm_node_ids.push_back(static_cast<std::int64_t>(1000 * (i + 1) + k));
    if (i < attributes.size()) road.attributes = attributes[i];
    road.start_junction = junction(road.points.front());
    road.end_junction = junction(road.points.back());
    net.junctions[road.start_junction].ends.push_back({road.id, true});
    net.junctions[road.end_junction].ends.push_back({road.id, false});
    net.roads.push_back(road);
  }
  for (Junction& j : net.junctions) {
    j.kind = j.ends.size() >= 3   ? JunctionKind::intersection
             : j.ends.size() == 2 ? JunctionKind::attribute_change
                                  : JunctionKind::dead_end;
  }
  return net;
}

std::vector<RoadProfile> drape(const RoadNetwork& network, const std::function<double(const Vec2&)>& ground,
                               double spacing_m) {
  std::vector<RoadProfile> out;
  out.reserve(network.roads.size());
  for (const Road& road : network.roads) {
    RoadProfile p = make_stations(road, spacing_m);
    for (std::size_t i = 0; i < p.size(); ++i) p.z[i] = ground(p.xy[i]);
    out.push_back(std::move(p));
  }
  return out;
}

}  // namespace relief::test

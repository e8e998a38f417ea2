#pragma once
// GeoJSON (RFC 7946) of the 3D road network: one LineString feature per road, coordinates
// [lon, lat, z] in WGS84 degrees and metres, every elevation sample of the road. Opens in QGIS.

#include <ostream>

#include "relief/roads/elevation_sampling.h"
#include "relief/roads/road_network.h"

namespace relief {

/// Attribution carried by every output built from OpenStreetMap data (ODbL).
inline constexpr const char* kOsmAttribution =
    "Road data (c) OpenStreetMap contributors, licensed under the ODbL "
    "(https://www.openstreetmap.org/copyright)";

/// Writes the network. Feature properties: id, class, name, lanes, lanes_forward,
/// lanes_backward, oneway, bridge, tunnel, layer, maxspeed_kmh (or null), roundabout,
/// length_m, max_grade_percent, start_junction, end_junction, osm_way_ids. The collection
/// carries foreign members "relief_frame" {crs, origin, proj} and "attribution".
/// Roads without height are left out. Lon/lat at 1e-7 degrees, z at 1 mm.
void write_geojson(std::ostream& out, const RoadNetwork& network, const std::vector<RoadProfile>& profiles);

}  // namespace relief

// A program outside the project that finds relief with find_package and links relief::relief.
#include <relief/geometry/geo_frame.h>
#include <relief/pipeline/build.h>

#include <iostream>

int main() {
  const relief::GeoFrame frame = relief::GeoFrame::utm_at({-122.4, 37.75});
  std::cout << frame.crs() << " " << relief::default_name("x/sf.osm.pbf") << "\n";
  return frame.crs() == "EPSG:32610" && relief::default_name("x/sf.osm.pbf") == "sf" ? 0 : 1;
}

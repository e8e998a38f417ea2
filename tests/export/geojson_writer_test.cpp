#include "relief/export/geojson_writer.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <sstream>

#include "relief/geometry/crs_transform.h"
#include "support/synthetic.h"

namespace relief {
namespace {

TEST(GeoJsonWriter, WritesOneLineStringPerRoadInLonLatWithHeights) {
  WayAttributes a;
  a.highway = HighwayClass::primary;
  a.name = "Potrero \"Ave\"";
  a.lanes_forward = 2;
  a.lanes_backward = 1;
  a.bridge = true;
  a.layer = 1;
  a.maxspeed_mps = 25 * 0.44704;
  RoadNetwork net = test::make_network({{{0, 0}, {10, 0}}, {{10, 0}, {10, 10}}}, {a});
  std::vector<RoadProfile> profiles(2);
  for (int r = 0; r < 2; ++r) {
    profiles[r] = make_stations(net.roads[r], 5.0);
    for (std::size_t i = 0; i < profiles[r].size(); ++i) profiles[r].z[i] = 12.0 + static_cast<double>(i);
  }
  profiles[1].has_height = false;  // left out
  std::ostringstream out;
  write_geojson(out, net, profiles);
  const auto j = nlohmann::json::parse(out.str());
  EXPECT_EQ(j["type"], "FeatureCollection");
  EXPECT_NE(j["attribution"].get<std::string>().find("OpenStreetMap"), std::string::npos);
  EXPECT_EQ(j["relief_frame"]["crs"], "EPSG:32610");
  ASSERT_EQ(j["features"].size(), 1u);
  const auto& f = j["features"][0];
  EXPECT_EQ(f["properties"]["class"], "primary");
  EXPECT_EQ(f["properties"]["name"], "Potrero \"Ave\"");
  EXPECT_EQ(f["properties"]["lanes"], 3);
  EXPECT_EQ(f["properties"]["bridge"], true);
  EXPECT_EQ(f["properties"]["tunnel"], false);
  EXPECT_EQ(f["properties"]["layer"], 1);
  EXPECT_NEAR(f["properties"]["maxspeed_kmh"].get<double>(), 40.2, 0.05);
  EXPECT_EQ(f["properties"]["osm_way_ids"], nlohmann::json::array({100}));
  const auto& coords = f["geometry"]["coordinates"];
  ASSERT_EQ(coords.size(), 3u);
  // The first point is the frame origin: back to lon/lat with PROJ, to 1e-7 degrees.
  const Vec2 origin_lonlat = CrsTransform("EPSG:32610", "EPSG:4326").apply(net.frame.origin());
  EXPECT_NEAR(coords[0][0].get<double>(), origin_lonlat.x(), 1e-7);
  EXPECT_NEAR(coords[0][1].get<double>(), origin_lonlat.y(), 1e-7);
  EXPECT_NEAR(coords[2][2].get<double>(), 14.0, 1e-9);
}

}  // namespace
}  // namespace relief

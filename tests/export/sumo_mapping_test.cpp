#include "relief/export/sumo_mapping.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <sstream>

#include "support/sumo_ramp.h"
#include "support/synthetic.h"

namespace relief {
namespace {

// The ramp; road 1 built from OSM ways 11 and 12.
SumoPlainNetwork ramp_network() {
  RoadModel model = test::ramp_model();
  model.frame = test::synthetic_frame();
  for (ModelRoad& road : model.roads)
    if (road.id == 1) road.osm_way_ids = {11, 12};
  Diagnostics diagnostics;
  return build_sumo_network(model, {}, SumoOptions{}, diagnostics);
}

std::string mapping_text(const SumoPlainNetwork& net) {
  std::ostringstream out;
  write_sumo_mapping(out, net);
  return out.str();
}

// Every SUMO lane of the ramp names its OpenDRIVE road and lane: lanes "1_0" (lane -1, along s)
// and "-1_0" (lane 1, against s) of road 1, "3_0" of road 3; the one connection its connecting
// road 2; each lane the OSM ways its road came from (for traffic counts given per way). The
// frame's origin is printed with millimetres.
TEST(SumoMapping, NamesTheOpenDriveLaneOfEverySumoLaneAndConnection) {
  const std::string text = mapping_text(ramp_network());
  EXPECT_NE(text.find("\"origin\": [550000.000, 4180000.000]"), std::string::npos) << text;
  const nlohmann::json j = nlohmann::json::parse(text);
  EXPECT_EQ(j["frame"]["crs"], "EPSG:32610");
  const nlohmann::json lanes = nlohmann::json::parse(R"([
    {"sumo_lane": "1_0", "odr_road": 1, "odr_lane": -1, "along_s": true, "osm_ways": [11, 12]},
    {"sumo_lane": "-1_0", "odr_road": 1, "odr_lane": 1, "along_s": false, "osm_ways": [11, 12]},
    {"sumo_lane": "3_0", "odr_road": 3, "odr_lane": -1, "along_s": true, "osm_ways": []}])");
  EXPECT_EQ(j["lanes"], lanes);
  const nlohmann::json connections = nlohmann::json::parse(R"([
    {"from_lane": "1_0", "to_lane": "3_0", "odr_road": 2, "odr_lane": -1}])");
  EXPECT_EQ(j["connections"], connections);
}

// A direct road-to-road link has no OpenDRIVE connecting road: it is left out; an empty network
// still gives valid JSON with empty lists.
TEST(SumoMapping, DirectLinksAreLeftOutAndAnEmptyNetworkIsValidJson) {
  SumoPlainNetwork net = ramp_network();
  SumoConnection direct;
  direct.from = "-1";
  direct.to = "1";
  net.connections.push_back(direct);
  EXPECT_EQ(nlohmann::json::parse(mapping_text(net))["connections"].size(), 1u);
  net.edges.clear();
  net.connections.clear();
  const nlohmann::json empty = nlohmann::json::parse(mapping_text(net));
  EXPECT_TRUE(empty["lanes"].empty());
  EXPECT_TRUE(empty["connections"].empty());
}

// The CRS is the user's (--crs takes any PROJ string) and ids come from the data: the file is
// JSON whatever they hold (the HTML escaper used before made '&' an entity and left '"' and
// '\\' to break the file).
TEST(SumoMapping, CrsAndIdsAreJsonEscaped) {
  SumoPlainNetwork net = ramp_network();
  const std::string crs = "+proj=tmerc +title=\"a & b\" +path=C:\\grids";
  net.frame = GeoFrame(crs, net.frame.origin());
  net.edges.front().id = "edge\"1\\";
  const nlohmann::json j = nlohmann::json::parse(mapping_text(net));
  EXPECT_EQ(j["frame"]["crs"], crs);
  EXPECT_EQ(j["lanes"][0]["sumo_lane"], "edge\"1\\_0");
}

}  // namespace
}  // namespace relief

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <pugixml.hpp>

#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "relief/core/diagnostics.h"
#include "relief/core/errors.h"
#include "relief/cosim/sumo_session.h"
#include "relief/demand/demand.h"
#include "relief/demand/grade_routing.h"
#include "relief/demand/net_edges.h"
#include "relief/demand/traffic_counts.h"
#include "relief/pipeline/build.h"
#include "support/test_data.h"

namespace relief {
namespace {

namespace fs = std::filesystem;

NetEdge edge(const std::string& id, Vec3 from, Vec3 to, std::vector<std::int64_t> ways,
             double speed = 13.89) {
  NetEdge e;
  e.id = id;
  e.shape = {from, to};
  e.length_m = (to - from).norm();
  e.speed_mps = speed;
  e.osm_way_ids = std::move(ways);
  return e;
}

fs::path write(const fs::path& path, const std::string& text) {
  std::ofstream(path) << text;
  return path;
}

TEST(NetEdges, BearingAndGradeFollowTheShape) {
  const NetEdge north = edge("n", Vec3(0, 0, 0), Vec3(0, 100, 10), {});
  EXPECT_NEAR(north.bearing_deg(), 0.0, 1e-9);
  EXPECT_NEAR(north.mean_grade(), 0.1, 1e-12);
  EXPECT_NEAR(edge("w", Vec3(0, 0, 5), Vec3(-50, 0, 0), {}).bearing_deg(), 270.0, 1e-9);
  EXPECT_NEAR(edge("w", Vec3(0, 0, 5), Vec3(-50, 0, 0), {}).mean_grade(), -0.1, 1e-12);
}

TEST(NetEdges, ReadsTheNetAndTheOsmWaysOfItsMapping) {
  const fs::path dir = test::scratch_dir("net_edges");
  const fs::path net = write(dir / "t.net.xml", R"(<net>
  <edge id=":J0_0" function="internal"><lane id=":J0_0_0" length="3" speed="5" shape="0,0 1,1"/></edge>
  <edge id="1" from="a" to="b"><lane id="1_0" length="100" speed="13.89" disallow="truck trailer" shape="0,0,0 0,100,10"/></edge>
  <edge id="-1" from="b" to="a"><lane id="-1_0" length="100" speed="13.89" shape="0,100,10 0,0,0"/></edge>
</net>)");
  write(dir / "t.sumo_mapping.json", R"({"lanes": [{"sumo_lane": "1_0", "odr_road": 1, "osm_ways": [7, 8]},
      {"sumo_lane": "-1_0", "odr_road": 1, "osm_ways": [7, 8]}]})");
  const std::vector<NetEdge> edges = read_net_edges(net);
  ASSERT_EQ(edges.size(), 2u);  // the internal edge left out
  EXPECT_EQ(edges[0].id, "1");
  EXPECT_EQ(edges[0].osm_way_ids, (std::vector<std::int64_t>{7, 8}));
  EXPECT_FALSE(edges[0].allows("truck"));
  EXPECT_TRUE(edges[1].allows("truck"));
  EXPECT_NEAR(edges[0].mean_grade(), 0.1, 1e-12);
  EXPECT_THROW((void)read_net_edges(dir / "none.net.xml"), IoError);
  EXPECT_THROW((void)read_net_edges(write(dir / "bad.net.xml", "<net")), InvalidInput);
}

TEST(TrafficCounts, ReadsDirectionsAndSaysWhichLineIsWrong) {
  const fs::path dir = test::scratch_dir("counts_read");
  const std::vector<CountRow> rows = read_counts_csv(
      write(dir / "c.csv", "osm_way,direction,count\n# a comment\n7,NB,100\n7,wb,20\n8,both,30\n9,135,5\n"));
  ASSERT_EQ(rows.size(), 4u);
  EXPECT_EQ(rows[0].osm_way, 7);
  EXPECT_DOUBLE_EQ(*rows[0].bearing_deg, 0.0);
  EXPECT_DOUBLE_EQ(*rows[1].bearing_deg, 270.0);
  EXPECT_FALSE(rows[2].bearing_deg.has_value());
  EXPECT_DOUBLE_EQ(*rows[3].bearing_deg, 135.0);
  EXPECT_EQ(rows[3].line, 6);
  const auto message = [&](const std::string& text) {
    try {
      (void)read_counts_csv(write(dir / "bad.csv", text));
    } catch (const InvalidInput& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message("way,direction,count\n").find("no column 'osm_way'"), std::string::npos);
  EXPECT_NE(message("osm_way,direction,count\n7,NB,-1\n").find("line 2: the count must be"),
            std::string::npos);
  EXPECT_NE(message("osm_way,direction,count\n7,up,1\n").find("unknown direction 'up'"), std::string::npos);
  EXPECT_NE(message("osm_way,direction,count\n7x,NB,1\n").find("line 2"), std::string::npos);
  EXPECT_THROW((void)read_counts_csv(dir / "none.csv"), IoError);
}

// A two-way way 7 north-south in two pieces, a one-way way 8 going east: a northbound count
// lands on both northbound pieces, "both" on a two-way way splits evenly, on a one-way way it
// all goes one way, and a direction no edge travels or an unknown way is reported.
TEST(TrafficCounts, GoOntoTheEdgesOfTheirWayThatTravelTheirDirection) {
  const std::vector<NetEdge> edges = {
      edge("n1", Vec3(0, 0, 0), Vec3(0, 100, 0), {7}), edge("n2", Vec3(0, 100, 0), Vec3(5, 200, 0), {7}),
      edge("s1", Vec3(0, 100, 0), Vec3(0, 0, 0), {7}), edge("s2", Vec3(5, 200, 0), Vec3(0, 100, 0), {7}),
      edge("e", Vec3(0, 0, 0), Vec3(100, 10, 0), {8})};
  std::vector<CountRow> rows(5);
  rows[0] = {7, 0.0, 100.0, 2};
  rows[1] = {7, std::nullopt, 40.0, 3};
  rows[2] = {8, std::nullopt, 30.0, 4};
  rows[3] = {8, 270.0, 5.0, 5};
  rows[4] = {99, 0.0, 5.0, 6};
  const CountsOnEdges c = counts_on_edges(rows, edges);
  std::map<std::string, double> on;
  for (const EdgeCount& e : c.edges) on[e.edge] = e.count;
  EXPECT_DOUBLE_EQ(on["n1"], 120.0);
  EXPECT_DOUBLE_EQ(on["n2"], 120.0);
  EXPECT_DOUBLE_EQ(on["s1"], 20.0);
  EXPECT_DOUBLE_EQ(on["s2"], 20.0);
  EXPECT_DOUBLE_EQ(on["e"], 30.0);
  ASSERT_EQ(c.unmatched.size(), 2u);
  EXPECT_NE(c.unmatched[0].find("line 5"), std::string::npos);
  EXPECT_NE(c.unmatched[1].find("OSM way 99"), std::string::npos);
  std::ostringstream xml;
  write_edge_counts(xml, c, 0.0, 3600.0);
  pugi::xml_document doc;
  ASSERT_TRUE(doc.load_string(xml.str().c_str()));
  EXPECT_DOUBLE_EQ(doc.child("data")
                       .child("interval")
                       .find_child_by_attribute("edge", "id", "n2")
                       .attribute("entered")
                       .as_double(),
                   120.0);
}

// Uphill a loaded truck goes only as fast as its power carries it; a car on a gentle climb and
// everything downhill at the limit.
TEST(GradeRouting, TrucksCrawlUpSteepEdgesAndCarsDoNot) {
  const NetEdge climb = edge("up", Vec3(0, 0, 0), Vec3(0, 100, 15), {}, 13.89);
  const NetEdge descent = edge("down", Vec3(0, 100, 15), Vec3(0, 0, 0), {}, 13.89);
  const double limit_time = climb.length_m / 13.89;
  EXPECT_NEAR(grade_travel_time(descent, "truck"), descent.length_m / 13.89, 1e-9);
  const double truck = grade_travel_time(climb, "truck");
  EXPECT_NEAR(truck, climb.length_m / 7.8, 0.02 * climb.length_m / 7.8);  // ego_test's 15 % truck
  EXPECT_GT(truck, 1.7 * limit_time);
  EXPECT_NEAR(grade_travel_time(climb, "passenger"), limit_time, 1e-9);  // 110 kW carry 15 % at 14 m/s
  std::ostringstream xml;
  NetEdge closed = climb;
  closed.id = "closed";
  closed.disallow = {"truck"};
  write_grade_weights(xml, {climb, descent, closed}, "truck");
  pugi::xml_document doc;
  ASSERT_TRUE(doc.load_string(xml.str().c_str()));
  const pugi::xml_node interval = doc.child("meandata").child("interval");
  EXPECT_NEAR(interval.find_child_by_attribute("edge", "id", "up").attribute("traveltime").as_double(), truck,
              1e-3);
  EXPECT_TRUE(interval.find_child_by_attribute("edge", "id", "closed").empty());
}

}  // namespace
}  // namespace relief

namespace relief {
namespace {

// The hill fixture built once with its SUMO net.
const fs::path& hill_net() {
  static const fs::path net = [] {
    BuildOptions o;
    o.osm_path = test::fixture("hill/hill.osm");
    o.dem_paths = {test::fixture("hill/hill_dem.asc").string()};
    o.out_dir = test::scratch_dir("demand_hill");
    Diagnostics d;
    (void)build(o, d);
    return fs::path(o.out_dir) / "hill.net.xml";
  }();
  return net;
}

std::map<std::string, std::vector<std::string>> routes_of(const fs::path& file) {
  pugi::xml_document doc;
  EXPECT_TRUE(doc.load_file(file.c_str())) << file;
  std::map<std::string, std::vector<std::string>> routes;
  for (const pugi::xml_node& v : doc.child("routes").children("vehicle")) {
    std::istringstream in(v.child("route").attribute("edges").as_string());
    for (std::string e; in >> e;) routes[v.attribute("id").as_string()].push_back(e);
  }
  return routes;
}

// The example counts (fixtures/hill/counts.csv) reproduced by routeSampler within GEH 5 on every
// counted edge, the config SUMO runs with the emission device; trucks routed on their grade
// travel times never take longer by them than the trucks routed on the limits.
TEST(Demand, TheHillsCountsAreReproducedAndTrucksRouteOnTheGrades) {
  TrafficDemandOptions o;
  o.end_s = 3600.0;
  o.trucks = 30;
  Diagnostics d;
  const fs::path out = test::scratch_dir("demand_counts");
  const TrafficDemand r =
      make_traffic_demand(hill_net(), {test::fixture("hill/counts.csv"), {}, {}, {}}, out, o, d);
  EXPECT_EQ(r.count_rows, 5u);
  EXPECT_GE(r.counted_edges, 10u);
  EXPECT_TRUE(r.unmatched.empty());
  EXPECT_DOUBLE_EQ(r.geh_ok_share, 1.0);
  EXPECT_LT(r.worst_geh, 5.0);
  EXPECT_GE(r.vehicles, 300u);
  EXPECT_GE(r.trucks, 20u);
  std::ifstream json(out / kDemandReportFile);
  const nlohmann::json j = nlohmann::json::parse(json);
  EXPECT_EQ(j.at("counted_edges").get<std::size_t>(), r.counted_edges);
  pugi::xml_document config;
  ASSERT_TRUE(config.load_file(r.config.c_str()));
  EXPECT_STREQ(config.child("configuration")
                   .child("emissions")
                   .child("device.emissions.probability")
                   .attribute("value")
                   .as_string(),
               "1");

  // The same trucks routed on the speed limits.
  o.grade_routing = false;
  const fs::path flat = test::scratch_dir("demand_counts_flat");
  (void)make_traffic_demand(hill_net(), {test::fixture("hill/counts.csv"), {}, {}, {}}, flat, o, d);
  std::map<std::string, double> weight;
  for (const NetEdge& e : read_net_edges(hill_net())) weight[e.id] = grade_travel_time(e, "truck");
  const auto on_grades = routes_of(out / "hill.trucks.rou.xml"),
             on_limits = routes_of(flat / "hill.trucks.rou.xml");
  ASSERT_EQ(on_grades.size(), on_limits.size());
  for (const auto& [id, route] : on_grades) {
    ASSERT_TRUE(on_limits.contains(id)) << id;
    double graded = 0.0, limited = 0.0;
    for (const std::string& e : route) graded += weight[e];
    for (const std::string& e : on_limits.at(id)) limited += weight[e];
    EXPECT_LE(graded, limited + 1e-3) << id;
  }
  // SUMO runs the configuration (in this process, 20 min at 0.5 s): every vehicle gets the
  // emission device, and PHEMlight's fuel feels the hill: cars whose route climbs over 10 m
  // burn 1.44 times as much per metre as those whose route descends as much (measured; with
  // SUMO's HBEFA3 class, which has no slope, the same trips give 1.17: speed alone).
  {
    SumoSession sumo(r.config, 0.5, {"--end", "1200"});
    while (sumo.time() < 1200.0 - 1e-9) sumo.step();
  }
  std::map<std::string, double> top, bottom;
  for (const NetEdge& e : read_net_edges(hill_net())) {
    top[e.id] = e.shape.back().z();
    bottom[e.id] = e.shape.front().z();
  }
  const auto car_routes = routes_of(out / "hill.counted.rou.xml");
  pugi::xml_document trips;
  ASSERT_TRUE(trips.load_file((out / "hill.tripinfo.xml").c_str()));
  double up_fuel = 0.0, up_m = 0.0, down_fuel = 0.0, down_m = 0.0;
  std::size_t finished = 0;
  for (const pugi::xml_node& t : trips.child("tripinfos").children("tripinfo")) {
    ++finished;
    const pugi::xml_node e = t.child("emissions");
    ASSERT_FALSE(e.empty());
    const auto it = car_routes.find(t.attribute("id").as_string());
    if (it == car_routes.end()) continue;
    const double rise = top[it->second.back()] - bottom[it->second.front()];
    const double fuel = e.attribute("fuel_abs").as_double(), length = t.attribute("routeLength").as_double();
    if (rise > 10.0) {
      up_fuel += fuel;
      up_m += length;
    } else if (rise < -10.0) {
      down_fuel += fuel;
      down_m += length;
    }
  }
  EXPECT_GE(finished, 100u);
  ASSERT_GT(up_m, 0.0);
  ASSERT_GT(down_m, 0.0);
  EXPECT_GT(up_fuel / up_m, 1.3 * down_fuel / down_m);

  // Counts that fit no edge are bad input.
  std::ofstream(out / "nowhere.csv") << "osm_way,direction,count\n999,NB,10\n";
  EXPECT_THROW((void)make_traffic_demand(hill_net(), {out / "nowhere.csv", {}, {}, {}}, out / "none", o, d),
               InvalidInput);
}

}  // namespace
}  // namespace relief

#include "relief/core/subprocess.h"
#include "relief/export/sumo_tools.h"

namespace relief {
namespace {

// A choice of routes from S to T: straight over an 80 m hill (40 % up and down, 400 m) or around
// it on the level (800 m). On their grade travel times duarouter sends a loaded truck around (it
// would crawl up at 3 m/s) and a car over (110 kW carry it up at the limit); on the speed limits
// both go over.
TEST(Demand, DuarouterOnGradeWeightsSendsATruckAroundTheHillAndACarOverIt) {
  const fs::path dir = test::scratch_dir("demand_detour");
  write(dir / "d.nod.xml", R"(<nodes>
  <node id="O" x="-100" y="0" z="0"/><node id="S" x="0" y="0" z="0"/><node id="M" x="200" y="0" z="80"/>
  <node id="T" x="400" y="0" z="0"/><node id="E" x="500" y="0" z="0"/>
  <node id="A" x="0" y="200" z="0"/><node id="B" x="400" y="200" z="0"/></nodes>)");
  write(dir / "d.edg.xml", R"(<edges>
  <edge id="in" from="O" to="S" numLanes="1" speed="13.89"/><edge id="out" from="T" to="E" numLanes="1" speed="13.89"/>
  <edge id="up" from="S" to="M" numLanes="1" speed="13.89"/><edge id="down" from="M" to="T" numLanes="1" speed="13.89"/>
  <edge id="a" from="S" to="A" numLanes="1" speed="13.89"/><edge id="ab" from="A" to="B" numLanes="1" speed="13.89"/>
  <edge id="b" from="B" to="T" numLanes="1" speed="13.89"/></edges>)");
  const fs::path net = dir / "d.net.xml";
  const ProcessResult nc =
      run_process({sumo_tool("netconvert").string(), "-n", (dir / "d.nod.xml").string(), "-e",
                   (dir / "d.edg.xml").string(), "-o", net.string(), "--no-turnarounds", "true"},
                  sumo_tool_environment());
  ASSERT_EQ(nc.exit_code, 0) << nc.output;
  const std::vector<NetEdge> edges = read_net_edges(net);
  write(dir / "trips.xml", R"(<routes><vType id="t" vClass="truck"/><vType id="c" vClass="passenger"/>
  <trip id="truck" type="t" depart="0" from="in" to="out"/><trip id="car" type="c" depart="0" from="in" to="out"/>
</routes>)");
  // Routes with the weights of `vclass` (none: on the limits).
  const auto routed = [&](const std::string& vclass) {
    std::vector<std::string> argv = {sumo_tool("duarouter").string(),
                                     "-n",
                                     net.string(),
                                     "--route-files",
                                     (dir / "trips.xml").string(),
                                     "-o",
                                     (dir / (vclass + ".rou.xml")).string(),
                                     "--no-step-log",
                                     "true"};
    if (!vclass.empty()) {
      std::ofstream weights(dir / (vclass + ".weights.xml"));
      write_grade_weights(weights, edges, vclass);
      weights.close();
      argv.insert(argv.end(), {"--weight-files", (dir / (vclass + ".weights.xml")).string()});
    }
    const ProcessResult r = run_process(argv, sumo_tool_environment());
    EXPECT_EQ(r.exit_code, 0) << r.output;
    return routes_of(dir / (vclass + ".rou.xml"));
  };
  const std::vector<std::string> over = {"in", "up", "down", "out"}, around = {"in", "a", "ab", "b", "out"};
  EXPECT_EQ(routed("truck")["truck"], around);
  EXPECT_EQ(routed("passenger")["car"], over);
  EXPECT_EQ(routed("")["truck"], over);
}

}  // namespace
}  // namespace relief

#include "relief/demand/zones.h"
#include "relief/geometry/crs_transform.h"

namespace relief {
namespace {

// Two zones drawn in WGS84 around points of a net in UTM 10 with an offset; a third, a
// MultiPolygon with a hole. Each edge goes to the zone its middle lies in.
TEST(Zones, PolygonsInWgs84TakeTheEdgesWhoseMiddleLiesInside) {
  const NetLocation loc{Vec2(-550000.0, -4180000.0), "+proj=utm +zone=10 +datum=WGS84 +units=m +no_defs"};
  const CrsTransform to_wgs84(loc.projection, "EPSG:4326");
  const auto lonlat = [&](double x, double y) { return to_wgs84.apply(Vec2(x, y) - loc.offset); };
  const auto ring = [&](double x0, double y0, double x1, double y1) {
    nlohmann::json r = nlohmann::json::array();
    for (const auto& [x, y] : {std::pair{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}, {x0, y0}}) {
      const Vec2 p = lonlat(x, y);
      r.push_back({p.x(), p.y()});
    }
    return r;
  };
  nlohmann::json fc = {{"type", "FeatureCollection"}, {"features", nlohmann::json::array()}};
  fc["features"].push_back({{"type", "Feature"},
                            {"properties", {{"id", "a"}}},
                            {"geometry", {{"type", "Polygon"}, {"coordinates", {ring(0, 0, 100, 100)}}}}});
  fc["features"].push_back(
      {{"type", "Feature"},
       {"properties", {{"name", "b"}}},
       {"geometry",
        {{"type", "MultiPolygon"}, {"coordinates", {{ring(200, 0, 400, 200), ring(250, 50, 350, 150)}}}}}});
  const fs::path dir = test::scratch_dir("zones");
  write(dir / "z.geojson", fc.dump());
  std::vector<Zone> zones = read_zones_geojson(dir / "z.geojson", loc);
  ASSERT_EQ(zones.size(), 2u);
  EXPECT_EQ(zones[1].id, "b");
  const std::vector<NetEdge> edges = {
      edge("in_a", Vec3(10, 50, 0), Vec3(90, 50, 0), {}),
      edge("across", Vec3(50, 50, 0), Vec3(250, 50, 0), {}),  // middle at x 150
      edge("in_b", Vec3(210, 10, 0), Vec3(230, 10, 0), {}),
      edge("in_hole", Vec3(290, 100, 0), Vec3(310, 100, 0), {})};
  assign_edges(zones, edges);
  EXPECT_EQ(zones[0].edges, (std::vector<std::string>{"in_a"}));
  EXPECT_EQ(zones[1].edges, (std::vector<std::string>{"in_b"}));
  // A feature without an id, a point, a repeated id: bad input naming the feature.
  fc["features"].push_back({{"type", "Feature"},
                            {"properties", {{"id", "a"}}},
                            {"geometry", {{"type", "Polygon"}, {"coordinates", {ring(0, 0, 1, 1)}}}}});
  write(dir / "twice.geojson", fc.dump());
  EXPECT_THROW((void)read_zones_geojson(dir / "twice.geojson", loc), InvalidInput);
  write(
      dir / "point.geojson",
      R"({"features": [{"properties": {"id": "p"}, "geometry": {"type": "Point", "coordinates": [0, 0]}}]})");
  try {
    (void)read_zones_geojson(dir / "point.geojson", loc);
    FAIL() << "a point is no zone";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("feature 0 (zone 'p'): a Point geometry"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW((void)read_od_csv(write(dir / "od.csv", "from,to,count\n")), InvalidInput);
  EXPECT_EQ(read_od_csv(write(dir / "od.csv", "origin,destination,count\na,b,12\n")).front().count, 12.0);
}

// The example OD matrix between the hill's three zones (fixtures/hill/od.csv, zones.geojson):
// every relation's trips, each route from an edge of its origin zone to one of its destination.
TEST(Demand, AnOdMatrixBetweenZonesBecomesRoutesFromZoneToZone) {
  TrafficDemandOptions o;
  Diagnostics d;
  const fs::path out = test::scratch_dir("demand_od");
  const TrafficDemand r = make_traffic_demand(
      hill_net(), {{}, test::fixture("hill/od.csv"), test::fixture("hill/zones.geojson"), {}}, out, o, d);
  EXPECT_EQ(r.od_rows, 4u);
  EXPECT_EQ(r.zones, 3u);
  EXPECT_EQ(r.od_trips, 230u);  // 100 + 80 + 30 + 20
  pugi::xml_document taz;
  ASSERT_TRUE(taz.load_file((out / "hill.taz.xml").c_str()));
  std::map<std::string, std::set<std::string>> zone_edges;
  for (const pugi::xml_node& t : taz.child("additional").children("taz")) {
    std::istringstream in(t.attribute("edges").as_string());
    for (std::string e; in >> e;) zone_edges[t.attribute("id").as_string()].insert(e);
  }
  ASSERT_EQ(zone_edges.size(), 3u);
  pugi::xml_document routes;
  ASSERT_TRUE(routes.load_file((out / "hill.od.rou.xml").c_str()));
  std::size_t checked = 0;
  for (const pugi::xml_node& v : routes.child("routes").children("vehicle")) {
    std::istringstream in(v.child("route").attribute("edges").as_string());
    std::vector<std::string> edges;
    for (std::string e; in >> e;) edges.push_back(e);
    ASSERT_FALSE(edges.empty());
    EXPECT_TRUE(zone_edges[v.attribute("fromTaz").as_string()].contains(edges.front()))
        << v.attribute("id").as_string();
    EXPECT_TRUE(zone_edges[v.attribute("toTaz").as_string()].contains(edges.back()))
        << v.attribute("id").as_string();
    ++checked;
  }
  EXPECT_EQ(checked, 230u);
  // A relation naming a zone the zones do not have is bad input.
  write(out / "bad_od.csv", "origin,destination,count\nwest,nowhere,5\n");
  EXPECT_THROW(
      (void)make_traffic_demand(hill_net(), {{}, out / "bad_od.csv", test::fixture("hill/zones.geojson"), {}},
                                out / "bad", o, d),
      InvalidInput);
}

// A matrix with a class column: each class's relations become trips of its vehicle type,
// routed on its own grade weights, in a routes file of its own that the configuration lists.
TEST(Demand, AnOdMatrixPerVehicleClassRoutesEachClassOnItsWeights) {
  TrafficDemandOptions o;
  Diagnostics d;
  const fs::path out = test::scratch_dir("demand_od_class");
  write(out / "od.csv",
        "origin,destination,count,class\nwest,east,60,car\neast,west,25,truck\n"
        "centre,west,15,car\nwest,centre,10,passenger\n");
  const TrafficDemand r = make_traffic_demand(
      hill_net(), {{}, out / "od.csv", test::fixture("hill/zones.geojson"), {}}, out / "run", o, d);
  EXPECT_EQ(r.od_rows, 4u);
  EXPECT_EQ(r.od_trips, 110u);
  EXPECT_EQ(r.od_truck_trips, 25u);
  const auto types_in = [](const fs::path& file) {
    pugi::xml_document doc;
    EXPECT_TRUE(doc.load_file(file.c_str())) << file;
    std::map<std::string, std::size_t> types;
    for (const pugi::xml_node& v : doc.child("routes").children("vehicle"))
      ++types[v.attribute("type").as_string()];
    return types;
  };
  EXPECT_EQ(types_in(out / "run" / "hill.od.rou.xml"), (std::map<std::string, std::size_t>{{"car", 85}}));
  EXPECT_EQ(types_in(out / "run" / "hill.od_truck.rou.xml"),
            (std::map<std::string, std::size_t>{{"truck", 25}}));
  std::ifstream config(r.config);
  const std::string text((std::istreambuf_iterator<char>(config)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("hill.od_truck.rou.xml"), std::string::npos);
  const nlohmann::json report = nlohmann::json::parse(std::ifstream(out / "run" / "demand.json"));
  EXPECT_EQ(report.at("od_truck_trips").get<int>(), 25);
  // An unknown class is bad input, named with its line.
  write(out / "bad.csv", "origin,destination,count,class\nwest,east,5,bus\n");
  try {
    (void)make_traffic_demand(hill_net(), {{}, out / "bad.csv", test::fixture("hill/zones.geojson"), {}},
                              out / "bad", o, d);
    ADD_FAILURE() << "a bus class was taken";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("line 2"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("'bus'"), std::string::npos) << e.what();
  }
}

// Turn counts at the hill's signalised crossing of 21th Street (way 101) and Avenue B (201):
// each movement goes onto the one pair of edges the net connects in those directions, and
// routeSampler.py reproduces every turn within GEH 5; with the edge counts too, both are fed to
// it at once.
TEST(Demand, TurnCountsBecomeEdgeRelationsThatTheSampledRoutesReproduce) {
  TrafficDemandOptions o;
  Diagnostics d;
  const fs::path out = test::scratch_dir("demand_turns");
  write(out / "turns.csv",
        "from_way,from_direction,to_way,to_direction,count\n"
        "101,EB,201,NB,40\n101,EB,201,SB,25\n201,SB,101,WB,15\n101,NB,201,NB,5\n");
  TrafficDemandInputs inputs;
  inputs.turns_csv = out / "turns.csv";
  const TrafficDemand r = make_traffic_demand(hill_net(), inputs, out / "run", o, d);
  EXPECT_EQ(r.turn_rows, 4u);
  EXPECT_EQ(r.counted_turns, 3u);
  ASSERT_EQ(r.unmatched.size(), 1u);  // way 101 runs east-west: no northbound edge
  EXPECT_NE(r.unmatched.front().find("line 5"), std::string::npos) << r.unmatched.front();
  pugi::xml_document turns;
  ASSERT_TRUE(turns.load_file((out / "run" / "hill.turns.xml").c_str()));
  std::map<double, std::size_t> counts;
  for (const pugi::xml_node& t : turns.child("data").child("interval").children("edgeRelation"))
    ++counts[t.attribute("count").as_double()];
  EXPECT_EQ(counts, (std::map<double, std::size_t>{{15.0, 1}, {25.0, 1}, {40.0, 1}}));
  const nlohmann::json report = nlohmann::json::parse(std::ifstream(out / "run" / "demand.json"));
  ASSERT_EQ(report.at("turns").size(), 3u);
  for (const nlohmann::json& t : report.at("turns")) {
    EXPECT_LT(t.at("geh").get<double>(), 5.0) << t.dump();
    EXPECT_NE(t.at("from").get<std::string>(), t.at("to").get<std::string>());
  }
  EXPECT_EQ(r.geh_ok_share, 1.0);
  // With the fixture's edge counts: one sampling on both (turns of 40 into a 30-vehicle edge
  // cannot all hold, so only that both were counted is asserted).
  inputs.counts_csv = test::fixture("hill/counts.csv");
  const TrafficDemand both = make_traffic_demand(hill_net(), inputs, out / "both", o, d);
  EXPECT_EQ(both.counted_turns, 3u);
  EXPECT_GT(both.counted_edges, 10u);
  EXPECT_TRUE(fs::exists(out / "both" / "hill.counts.xml"));
  EXPECT_TRUE(fs::exists(out / "both" / "hill.turns.xml"));
  // Turn counts alone, none of which fits, are bad input.
  write(out / "none.csv", "from_way,from_direction,to_way,to_direction,count\n101,NB,201,NB,5\n");
  TrafficDemandInputs none;
  none.turns_csv = out / "none.csv";
  EXPECT_THROW((void)make_traffic_demand(hill_net(), none, out / "none", o, d), InvalidInput);
}

}  // namespace
}  // namespace relief

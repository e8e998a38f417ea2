#include "relief/roads/network_builder.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <iostream>
#include <string>

#include "relief/core/errors.h"
#include "relief/geometry/polyline.h"
#include "support/osm_sketch.h"
#include "support/test_data.h"

namespace relief {
namespace {

using test::OsmSketch;

// UTM scale (0.99963 here: -0.04 %) and 1e-7 degree rounding keep short sketch lengths
// within a few cm.
constexpr double kLengthTolerance_m = 0.05;
// For longer lengths: the scale error plus rounding.
double length_tolerance_m(double length) {
  return 5e-4 * length + 0.02;
}

RoadNetwork build_file(const std::filesystem::path& path, Diagnostics& diagnostics,
                       const OsmReadOptions& options = {}) {
  const OsmRoads osm = read_osm(path, options, diagnostics);
  return build_network(osm, GeoFrame::utm_at(osm.bounds.centre()), diagnostics);
}

RoadNetwork build(const OsmSketch& sketch, const std::string& name, Diagnostics& diagnostics) {
  return build_file(sketch.write(test::scratch_dir(name) / "sketch.osm"), diagnostics);
}

std::vector<std::int64_t> ids(const std::string& letters) {
  std::vector<std::int64_t> out;
  for (const char c : letters) out.push_back(OsmSketch::node_id(c));
  return out;
}

// The road whose nodes are exactly `letters`, in this order.
const Road* road_through(const RoadNetwork& net, const std::string& letters) {
  const auto want = ids(letters);
  for (const Road& r : net.roads) {
    if (r.osm_node_ids == want) return &r;
  }
  return nullptr;
}

const Junction& junction_at(const RoadNetwork& net, char letter) {
  for (const Junction& j : net.junctions) {
    if (j.osm_node_id == OsmSketch::node_id(letter)) return j;
  }
  throw std::runtime_error(std::string("no junction at ") + letter);
}

// Every road end is listed at its junction and vice versa; ids are indices.
void expect_consistent(const RoadNetwork& net) {
  for (std::size_t i = 0; i < net.roads.size(); ++i) {
    const Road& r = net.roads[i];
    EXPECT_EQ(r.id, static_cast<int>(i));
    ASSERT_GE(r.points.size(), 2u);
    EXPECT_EQ(r.points.size(), r.osm_node_ids.size());
    const Junction& s = net.junctions.at(static_cast<std::size_t>(r.start_junction));
    const Junction& e = net.junctions.at(static_cast<std::size_t>(r.end_junction));
    EXPECT_EQ(s.osm_node_id, r.osm_node_ids.front());
    EXPECT_EQ(e.osm_node_id, r.osm_node_ids.back());
    EXPECT_EQ((s.position - r.points.front()).norm(), 0.0);
    EXPECT_EQ((e.position - r.points.back()).norm(), 0.0);
    EXPECT_NE(std::find(s.ends.begin(), s.ends.end(), RoadEnd{r.id, true}), s.ends.end());
    EXPECT_NE(std::find(e.ends.begin(), e.ends.end(), RoadEnd{r.id, false}), e.ends.end());
  }
  std::size_t ends = 0;
  for (std::size_t i = 0; i < net.junctions.size(); ++i) {
    EXPECT_EQ(net.junctions[i].id, static_cast<int>(i));
    ends += net.junctions[i].ends.size();
  }
  EXPECT_EQ(ends, 2 * net.roads.size());
}

TEST(NetworkBuilder, TJunction) {
  const auto sketch = OsmSketch(R"(
      A---B---C
          |
          D
  )",
                                /*grid_m=*/10.0)
                          .way({"ABC"}, {{"highway", "residential"}})
                          .way({"BD"}, {{"highway", "service"}, {"oneway", "yes"}})
                          .node_tags('B', {{"highway", "traffic_signals"}});
  Diagnostics diagnostics;
  const RoadNetwork net = build(sketch, "builder_t", diagnostics);
  expect_consistent(net);

  ASSERT_EQ(net.roads.size(), 3u);
  EXPECT_EQ(net.roads[0].osm_node_ids, ids("AB"));
  EXPECT_EQ(net.roads[1].osm_node_ids, ids("BC"));
  EXPECT_EQ(net.roads[2].osm_node_ids, ids("BD"));
  EXPECT_EQ(net.roads[2].osm_way_ids, (std::vector<std::int64_t>{2}));
  EXPECT_TRUE(net.roads[2].attributes.oneway);
  for (const Road& r : net.roads) EXPECT_NEAR(length_m(r.points), 40.0, kLengthTolerance_m) << r.id;

  ASSERT_EQ(net.junctions.size(), 4u);
  EXPECT_EQ(net.count(JunctionKind::intersection), 1u);
  EXPECT_EQ(net.count(JunctionKind::dead_end), 3u);
  EXPECT_EQ(net.count(JunctionKind::attribute_change), 0u);
  const Junction& b = junction_at(net, 'B');
  EXPECT_EQ(b.kind, JunctionKind::intersection);
  EXPECT_EQ(b.ends.size(), 3u);
  EXPECT_TRUE(b.traffic_signal);
  EXPECT_FALSE(junction_at(net, 'A').traffic_signal);
  EXPECT_EQ(junction_at(net, 'D').kind, JunctionKind::dead_end);
  // First appearance order: A, B, C, D.
  EXPECT_EQ(net.junctions[0].osm_node_id, OsmSketch::node_id('A'));
  EXPECT_EQ(net.junctions[1].osm_node_id, OsmSketch::node_id('B'));
  EXPECT_EQ(net.roundabouts, 0u);
  EXPECT_EQ(diagnostics.total(), 0u);

  // Local frame: small coordinates, metric distances.
  EXPECT_NEAR((junction_at(net, 'D').position - junction_at(net, 'A').position).norm(),
              std::hypot(40.0, 40.0), kLengthTolerance_m);
  EXPECT_LT(net.junctions[0].position.norm(), 1000.0);
}

TEST(NetworkBuilder, WaysWithEqualTagsMergeIntoOneRoad) {
  const auto sketch = OsmSketch("A---B---C")
                          .way("AB", {{"highway", "residential"}, {"name", "Vermont"}})
                          .way("BC", {{"highway", "residential"}, {"name", "Vermont"}});
  Diagnostics diagnostics;
  const RoadNetwork net = build(sketch, "builder_merge", diagnostics);
  expect_consistent(net);
  ASSERT_EQ(net.roads.size(), 1u);
  EXPECT_EQ(net.roads[0].osm_node_ids, ids("ABC"));
  EXPECT_EQ(net.roads[0].osm_way_ids, (std::vector<std::int64_t>{1, 2}));
  EXPECT_NEAR(length_m(net.roads[0].points), 80.0, kLengthTolerance_m);
  EXPECT_EQ(net.junctions.size(), 2u);
  EXPECT_EQ(net.count(JunctionKind::dead_end), 2u);
}

TEST(NetworkBuilder, DifferentTagsGiveAnAttributeChange) {
  const auto sketch = OsmSketch("A---B---C")
                          .way("AB", {{"highway", "residential"}})
                          .way("BC", {{"highway", "residential"}, {"bridge", "yes"}, {"layer", "1"}});
  Diagnostics diagnostics;
  const RoadNetwork net = build(sketch, "builder_change", diagnostics);
  expect_consistent(net);
  ASSERT_EQ(net.roads.size(), 2u);
  EXPECT_FALSE(net.roads[0].attributes.bridge);
  EXPECT_TRUE(net.roads[1].attributes.bridge);
  EXPECT_EQ(net.count(JunctionKind::attribute_change), 1u);
  EXPECT_EQ(junction_at(net, 'B').kind, JunctionKind::attribute_change);
  EXPECT_EQ(net.count(JunctionKind::dead_end), 2u);
}

TEST(NetworkBuilder, TwoWayPiecesMergeHeadToHeadWithLanesSwapped) {
  // B->A has 2 lanes forward; B->C has 2 lanes backward: one road C-B-A with 2 lanes forward.
  const auto sketch =
      OsmSketch("A---B---C")
          .way("BA", {{"highway", "primary"}, {"lanes:forward", "2"}, {"lanes:backward", "1"}})
          .way("BC", {{"highway", "primary"}, {"lanes:forward", "1"}, {"lanes:backward", "2"}});
  Diagnostics diagnostics;
  const RoadNetwork net = build(sketch, "builder_head_to_head", diagnostics);
  expect_consistent(net);
  ASSERT_EQ(net.roads.size(), 1u);
  EXPECT_EQ(net.roads[0].osm_node_ids, ids("CBA"));
  EXPECT_EQ(net.roads[0].osm_way_ids, (std::vector<std::int64_t>{2, 1}));
  EXPECT_EQ(net.roads[0].attributes.lanes_forward, 2);
  EXPECT_EQ(net.roads[0].attributes.lanes_backward, 1);

  // The same lane tags on both ways differ once one is reversed: no merge.
  const auto same_tags =
      OsmSketch("A---B---C")
          .way("BA", {{"highway", "primary"}, {"lanes:forward", "2"}, {"lanes:backward", "1"}})
          .way("BC", {{"highway", "primary"}, {"lanes:forward", "2"}, {"lanes:backward", "1"}});
  const RoadNetwork apart = build(same_tags, "builder_head_to_head_apart", diagnostics);
  EXPECT_EQ(apart.roads.size(), 2u);
  EXPECT_EQ(apart.count(JunctionKind::attribute_change), 1u);
}

TEST(NetworkBuilder, OnewaysMergeOnlyHeadToTail) {
  const OsmSketch::Tags oneway{{"highway", "residential"}, {"oneway", "yes"}};
  Diagnostics diagnostics;

  const RoadNetwork chained =
      build(OsmSketch("A---B---C").way("AB", oneway).way("BC", oneway), "builder_ow_chain", diagnostics);
  ASSERT_EQ(chained.roads.size(), 1u);
  EXPECT_EQ(chained.roads[0].osm_node_ids, ids("ABC"));
  EXPECT_TRUE(chained.roads[0].attributes.oneway);

  // Chained by walking back from the second way: the road still runs A -> C.
  const RoadNetwork backwards =
      build(OsmSketch("A---B---C").way("BC", oneway).way("AB", oneway), "builder_ow_backwards", diagnostics);
  ASSERT_EQ(backwards.roads.size(), 1u);
  EXPECT_EQ(backwards.roads[0].osm_node_ids, ids("ABC"));
  EXPECT_EQ(backwards.roads[0].osm_way_ids, (std::vector<std::int64_t>{2, 1}));

  const RoadNetwork head_to_head =
      build(OsmSketch("A---B---C").way("AB", oneway).way("CB", oneway), "builder_ow_h2h", diagnostics);
  expect_consistent(head_to_head);
  ASSERT_EQ(head_to_head.roads.size(), 2u);
  EXPECT_EQ(head_to_head.roads[0].osm_node_ids, ids("AB"));
  EXPECT_EQ(head_to_head.roads[1].osm_node_ids, ids("CB"));
  EXPECT_EQ(junction_at(head_to_head, 'B').kind, JunctionKind::attribute_change);

  const RoadNetwork tail_to_tail =
      build(OsmSketch("A---B---C").way("BA", oneway).way("BC", oneway), "builder_ow_t2t", diagnostics);
  ASSERT_EQ(tail_to_tail.roads.size(), 2u);
  EXPECT_EQ(tail_to_tail.roads[0].osm_node_ids, ids("BA"));
  EXPECT_EQ(tail_to_tail.roads[1].osm_node_ids, ids("BC"));

  // oneway=-1 is normalised first, then merges head to tail.
  const RoadNetwork reversed = build(
      OsmSketch("A---B---C").way("BA", {{"highway", "residential"}, {"oneway", "-1"}}).way("BC", oneway),
      "builder_ow_reverse", diagnostics);
  ASSERT_EQ(reversed.roads.size(), 1u);
  EXPECT_EQ(reversed.roads[0].osm_node_ids, ids("ABC"));
}

TEST(NetworkBuilder, OnewayPairOfADividedRoad) {
  const auto sketch = OsmSketch(R"(
        B-------C
       /         \
  G---A           D---H
       \         /
        E-------F
  )")
                          .way("GA", {{"highway", "primary"}})
                          .way("ABCD", {{"highway", "primary"}, {"oneway", "yes"}})
                          .way("DFEA", {{"highway", "primary"}, {"oneway", "yes"}})
                          .way("DH", {{"highway", "primary"}});
  Diagnostics diagnostics;
  const RoadNetwork net = build(sketch, "builder_pair", diagnostics);
  expect_consistent(net);
  ASSERT_EQ(net.roads.size(), 4u);
  const Road* east = road_through(net, "ABCD");
  const Road* west = road_through(net, "DFEA");
  ASSERT_NE(east, nullptr);
  ASSERT_NE(west, nullptr);
  EXPECT_TRUE(east->attributes.oneway);
  EXPECT_TRUE(west->attributes.oneway);
  EXPECT_EQ(east->attributes.lanes_forward, 2);
  EXPECT_EQ(east->attributes.lanes_backward, 0);
  EXPECT_EQ(east->start_junction, west->end_junction);
  EXPECT_EQ(east->end_junction, west->start_junction);
  EXPECT_EQ(net.count(JunctionKind::intersection), 2u);
  EXPECT_EQ(net.count(JunctionKind::dead_end), 2u);
  EXPECT_EQ(junction_at(net, 'A').ends.size(), 3u);
  // A-B and C-D: 2 columns east, 2 rows north (20 m, 40 m); B-C: 8 columns (80 m).
  const double expected = 2 * std::hypot(20.0, 40.0) + 80.0;
  EXPECT_NEAR(length_m(east->points), expected, length_tolerance_m(expected));
  EXPECT_NEAR(length_m(west->points), expected, length_tolerance_m(expected));
}

OsmSketch roundabout_sketch() {
  return OsmSketch(R"(
        E
        |
        A
       / \
   H--D   B--F
       \ /
        C
        |
        G
  )")
      .way("ABCDA", {{"highway", "primary"}, {"junction", "roundabout"}})
      .way("EA", {{"highway", "residential"}})
      .way("BF", {{"highway", "residential"}})
      .way("CG", {{"highway", "residential"}})
      .way("DH", {{"highway", "residential"}});
}

TEST(NetworkBuilder, RoundaboutWithFourArms) {
  Diagnostics diagnostics;
  const RoadNetwork net = build(roundabout_sketch(), "builder_roundabout", diagnostics);
  expect_consistent(net);
  ASSERT_EQ(net.roads.size(), 8u);
  for (const char* ring : {"AB", "BC", "CD", "DA"}) {
    const Road* r = road_through(net, ring);
    ASSERT_NE(r, nullptr) << ring;
    EXPECT_TRUE(r->attributes.roundabout);
    EXPECT_TRUE(r->attributes.oneway);  // implied by junction=roundabout
    EXPECT_NEAR(length_m(r->points), std::hypot(20.0, 40.0), kLengthTolerance_m) << ring;
  }
  EXPECT_EQ(net.count(JunctionKind::intersection), 4u);
  EXPECT_EQ(net.count(JunctionKind::dead_end), 4u);
  for (const char c : std::string("ABCD")) EXPECT_TRUE(junction_at(net, c).roundabout) << c;
  for (const char c : std::string("EFGH")) EXPECT_FALSE(junction_at(net, c).roundabout) << c;
  EXPECT_EQ(net.roundabouts, 1u);
}

TEST(NetworkBuilder, SeparateRingsCountAsSeparateRoundabouts) {
  const auto sketch = OsmSketch(R"(
      A---B       P---Q
      |   |       |   |
      D---C       S---R
  )")
                          .way("ABCDA", {{"highway", "tertiary"}, {"junction", "roundabout"}})
                          .way("PQRSP", {{"highway", "tertiary"}, {"junction", "circular"}});
  Diagnostics diagnostics;
  const RoadNetwork net = build(sketch, "builder_two_rings", diagnostics);
  expect_consistent(net);
  // A closed way stays one loop road, its two ends at one junction.
  ASSERT_EQ(net.roads.size(), 2u);
  EXPECT_EQ(net.roads[0].start_junction, net.roads[0].end_junction);
  EXPECT_EQ(net.roads[0].osm_node_ids, ids("ABCDA"));
  EXPECT_NEAR(length_m(net.roads[0].points), 160.0, length_tolerance_m(160.0));
  ASSERT_EQ(net.junctions.size(), 2u);
  EXPECT_EQ(net.junctions[0].ends.size(), 2u);
  EXPECT_TRUE(net.junctions[0].roundabout);
  EXPECT_EQ(net.roundabouts, 2u);
}

TEST(NetworkBuilder, WayUsingANodeTwiceIsSplitThere) {
  // A lollipop: A-B, then the loop B-C-D-B.
  const auto sketch = OsmSketch(R"(
      A---B---C
           \  |
              D
  )")
                          .way("ABCDB", {{"highway", "residential"}});
  Diagnostics diagnostics;
  const RoadNetwork net = build(sketch, "builder_lollipop", diagnostics);
  expect_consistent(net);
  ASSERT_EQ(net.roads.size(), 2u);
  EXPECT_EQ(net.roads[0].osm_node_ids, ids("AB"));
  EXPECT_EQ(net.roads[1].osm_node_ids, ids("BCDB"));
  EXPECT_EQ(junction_at(net, 'B').kind, JunctionKind::intersection);
  EXPECT_EQ(junction_at(net, 'B').ends.size(), 3u);
}

TEST(NetworkBuilder, MissingNodeSplitsButDoesNotStopTheBuild) {
  const auto path = test::scratch_dir("builder_missing") / "missing.osm";
  std::ofstream(path) << R"(<?xml version='1.0' encoding='UTF-8'?>
<osm version="0.6" generator="hand">
  <node id="1" version="1" lat="37.7500000" lon="-122.4000000"/>
  <node id="2" version="1" lat="37.7500000" lon="-122.3990000"/>
  <node id="4" version="1" lat="37.7500000" lon="-122.3970000"/>
  <node id="5" version="1" lat="37.7500000" lon="-122.3960000"/>
  <way id="10" version="1">
    <nd ref="1"/><nd ref="2"/><nd ref="3"/><nd ref="4"/><nd ref="5"/>
    <tag k="highway" v="residential"/>
  </way>
</osm>
)";
  Diagnostics diagnostics;
  const RoadNetwork net = build_file(path, diagnostics);
  expect_consistent(net);
  ASSERT_EQ(net.roads.size(), 2u);
  EXPECT_EQ(net.roads[0].osm_node_ids, (std::vector<std::int64_t>{1, 2}));
  EXPECT_EQ(net.roads[1].osm_node_ids, (std::vector<std::int64_t>{4, 5}));
  EXPECT_EQ(net.count(JunctionKind::dead_end), 4u);
  EXPECT_EQ(diagnostics.count("osm.missing_node"), 1u);
  // 0.001 degrees of longitude at 37.75 N is about 88 m.
  EXPECT_NEAR(length_m(net.roads[0].points), 88.0, 0.2);
}

// Builds an OsmRoads in code: one way per entry, nodes given as (id, lon, lat).
OsmWay make_way(std::int64_t id, std::vector<std::tuple<std::int64_t, double, double>> nodes) {
  OsmWay w;
  w.id = id;
  for (const auto& [nid, lon, lat] : nodes) {
    w.node_ids.push_back(nid);
    w.nodes.push_back({lon, lat});
  }
  return w;
}

TEST(NetworkBuilder, DuplicatePointsAreRemovedAndZeroLengthPiecesReported) {
  OsmRoads osm;
  // Nodes 1 and 2 share a position, as do 4 and 5.
  osm.ways.push_back(make_way(10, {{1, -122.4, 37.75}, {2, -122.4, 37.75}}));
  osm.ways.push_back(
      make_way(11, {{2, -122.4, 37.75}, {3, -122.399, 37.75}, {4, -122.398, 37.75}, {5, -122.398, 37.75}}));
  osm.bounds = {-122.4, 37.75, -122.398, 37.75};
  Diagnostics diagnostics;
  const RoadNetwork net = build_network(osm, GeoFrame::utm_at({-122.399, 37.75}), diagnostics);
  expect_consistent(net);
  ASSERT_EQ(net.roads.size(), 1u);
  // The duplicate inside the way goes; the end node (shared with other ways, if any) stays.
  EXPECT_EQ(net.roads[0].osm_node_ids, (std::vector<std::int64_t>{2, 3, 5}));
  EXPECT_EQ(diagnostics.count("network.degenerate_way"), 1u);
  EXPECT_EQ(diagnostics.kept().at(0).osm_way_id, 10);

  OsmRoads only_degenerate;
  only_degenerate.ways.push_back(make_way(10, {{1, -122.4, 37.75}, {2, -122.4, 37.75}}));
  EXPECT_THROW((void)build_network(only_degenerate, GeoFrame::utm_at({-122.4, 37.75}), diagnostics),
               InvalidInput);
}

TEST(NetworkBuilder, LongChainMergesInLinearTime) {
  // 200000 two-node ways end to end, every other one drawn backwards: one road. A quadratic
  // merge would take minutes here.
  constexpr int kWays = 200000;
  OsmRoads osm;
  osm.ways.reserve(kWays);
  const auto lon = [](int i) { return -122.45 + 1e-6 * i; };
  for (int i = 0; i < kWays; ++i) {
    if (i % 2 == 0) {
      osm.ways.push_back(make_way(i + 1, {{i + 1, lon(i), 37.75}, {i + 2, lon(i + 1), 37.75}}));
    } else {
      osm.ways.push_back(make_way(i + 1, {{i + 2, lon(i + 1), 37.75}, {i + 1, lon(i), 37.75}}));
    }
  }
  osm.bounds = {lon(0), 37.75, lon(kWays), 37.75};
  Diagnostics diagnostics;
  const RoadNetwork net = build_network(osm, GeoFrame::utm_at({-122.35, 37.75}), diagnostics);
  ASSERT_EQ(net.roads.size(), 1u);
  EXPECT_EQ(net.roads[0].points.size(), static_cast<std::size_t>(kWays) + 1);
  EXPECT_EQ(net.roads[0].osm_way_ids.size(), static_cast<std::size_t>(kWays));
  EXPECT_EQ(net.roads[0].osm_node_ids.front(), 1);
  EXPECT_EQ(net.count(JunctionKind::dead_end), 2u);
}

struct NetworkFigures {
  std::size_t roads = 0, junctions = 0, intersections = 0, attribute_changes = 0, dead_ends = 0;
  std::size_t signals = 0, bridges = 0, tunnels = 0, oneways = 0;
  double km = 0.0;
};

NetworkFigures figures(const RoadNetwork& net, const char* label) {
  NetworkFigures f;
  f.roads = net.roads.size();
  f.junctions = net.junctions.size();
  f.intersections = net.count(JunctionKind::intersection);
  f.attribute_changes = net.count(JunctionKind::attribute_change);
  f.dead_ends = net.count(JunctionKind::dead_end);
  for (const Junction& j : net.junctions) f.signals += j.traffic_signal ? 1 : 0;
  for (const Road& r : net.roads) {
    f.bridges += r.attributes.bridge ? 1 : 0;
    f.tunnels += r.attributes.tunnel ? 1 : 0;
    f.oneways += r.attributes.oneway ? 1 : 0;
    f.km += length_m(r.points) / 1000.0;
  }
  std::cout << "[" << label << "] roads " << f.roads << ", junctions " << f.junctions << " (intersections "
            << f.intersections << ", attribute changes " << f.attribute_changes << ", dead ends "
            << f.dead_ends << "), signalised junctions " << f.signals << ", bridge roads " << f.bridges
            << ", tunnel roads " << f.tunnels << ", one-way roads " << f.oneways << ", roundabouts "
            << net.roundabouts << ", " << f.km << " km\n";
  return f;
}

TEST(NetworkBuilder, PotreroRealData) {
  RELIEF_REQUIRE_SHARED_DATA();
  Diagnostics diagnostics;
  const RoadNetwork net = build_file(test::shared_data("sf-potrero/sf-potrero.osm.gz"), diagnostics);
  expect_consistent(net);
  const NetworkFigures f = figures(net, "potrero");
  EXPECT_EQ(net.frame.crs(), "EPSG:32610");
  // Measured (Dec 2022 extract, motor roads only); the build is deterministic. 25th Street's
  // last 3.3 m past a service road (OSM way 24444477) lie on that road's pavement and are
  // dropped as a stub, which leaves 25th Street and the service road a corner. The service road
  // OSM way 565104379 ends in a turning loop drawn as a narrow triangle, whose last corner turns
  // 154.8 degrees with legs 5.31 m apart where the shorter (12.5 m) ends: their pavements, 5.5 m
  // wide, overlap along all of it, so the corner's tip is built once, a dead end of its own
  // (osm.way_turns_back; 95 roads, 89 junctions, 42 intersections, 38 dead ends, 7.727 km before).
  EXPECT_EQ(f.roads, 97u);
  EXPECT_EQ(f.junctions, 91u);
  EXPECT_EQ(f.intersections, 43u);
  EXPECT_EQ(f.attribute_changes, 9u);
  EXPECT_EQ(f.dead_ends, 39u);
  EXPECT_EQ(f.signals, 0u);
  EXPECT_EQ(f.bridges, 1u);  // 23rd Street over US-101
  EXPECT_EQ(f.tunnels, 0u);
  EXPECT_EQ(net.roundabouts, 0u);
  EXPECT_NEAR(f.km, 7.714, 0.01);
  EXPECT_EQ(diagnostics.count("osm.way_turns_back"), 1u);
  EXPECT_EQ(diagnostics.count("osm.degenerate_way"), 6u);
  EXPECT_EQ(diagnostics.count("network.degenerate_way"), 0u);
}

TEST(NetworkBuilder, NortheastRealData) {
  RELIEF_REQUIRE_SHARED_DATA();
  Diagnostics diagnostics;
  const RoadNetwork net = build_file(test::shared_data("sf-ne/sf_ne_drive_2017.osm.gz"), diagnostics);
  expect_consistent(net);
  const NetworkFigures f = figures(net, "ne");
  // Measured (Oct 2017 drive network); the build is deterministic. 57 of the attribute changes
  // are where turn:lanes (and the lane count it implies) starts or changes along a street.
  EXPECT_EQ(f.roads, 1223u);
  EXPECT_EQ(f.junctions, 811u);
  EXPECT_EQ(f.intersections, 532u);
  EXPECT_EQ(f.attribute_changes, 159u);
  EXPECT_EQ(f.dead_ends, 120u);
  // 367 of the 421 signal nodes are road ends; the others sit inside roads (mid-block).
  EXPECT_EQ(f.signals, 367u);
  EXPECT_EQ(f.bridges, 8u);
  EXPECT_EQ(f.tunnels, 4u);
  EXPECT_EQ(f.oneways, 708u);
  EXPECT_EQ(net.roundabouts, 0u);
  EXPECT_NEAR(f.km, 129.81, 0.05);
  EXPECT_EQ(diagnostics.count("network.degenerate_way"), 0u);

  // Broadway (Robert C Levy) and Stockton tunnels are tunnel roads.
  bool broadway = false;
  bool stockton = false;
  for (const Road& r : net.roads) {
    if (!r.attributes.tunnel) continue;
    broadway = broadway || r.attributes.name == "Robert C Levy Tunnel";
    stockton = stockton || r.attributes.name == "Stockton Tunnel";
    EXPECT_TRUE(r.attributes.layer == -1 || r.attributes.name == "1st Street") << r.attributes.name;
  }
  EXPECT_TRUE(broadway);
  EXPECT_TRUE(stockton);
}

}  // namespace
}  // namespace relief

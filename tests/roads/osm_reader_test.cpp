#include "relief/roads/osm_reader.h"

#include <gtest/gtest.h>
#include <zlib.h>

#include <algorithm>
#include <fstream>
#include <iostream>
#include <iterator>
#include <string>

// libosmium only to write PBF/bz2 copies of test files; the library reads them itself.
#include <osmium/io/any_input.hpp>
#include <osmium/io/any_output.hpp>

#include "relief/core/errors.h"
#include "support/osm_sketch.h"
#include "support/test_data.h"

namespace relief {
namespace {

using test::OsmSketch;

OsmRoads read(const std::filesystem::path& path, Diagnostics& diagnostics, OsmReadOptions options = {}) {
  return read_osm(path, options, diagnostics);
}

const OsmWay* find_way(const OsmRoads& roads, std::int64_t id) {
  const auto it =
      std::find_if(roads.ways.begin(), roads.ways.end(), [id](const OsmWay& w) { return w.id == id; });
  return it == roads.ways.end() ? nullptr : &*it;
}

std::vector<std::int64_t> ids(const std::string& letters) {
  std::vector<std::int64_t> out;
  for (const char c : letters) out.push_back(OsmSketch::node_id(c));
  return out;
}

std::string read_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void write_bytes(const std::filesystem::path& path, std::string_view bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

void gzip_file(const std::filesystem::path& in, const std::filesystem::path& out) {
  const std::string data = read_bytes(in);
  gzFile gz = gzopen(out.string().c_str(), "wb9");
  ASSERT_NE(gz, nullptr);
  ASSERT_EQ(gzwrite(gz, data.data(), static_cast<unsigned>(data.size())), static_cast<int>(data.size()));
  ASSERT_EQ(gzclose(gz), Z_OK);
}

// Copies any OSM file to another format with libosmium (test only).
void convert_with_osmium(const std::filesystem::path& in, const std::filesystem::path& out) {
  osmium::io::Reader reader(in.string());
  osmium::io::Writer writer(out.string(), reader.header(), osmium::io::overwrite::allow);
  while (osmium::memory::Buffer buffer = reader.read()) writer(std::move(buffer));
  writer.close();
  reader.close();
}

OsmSketch t_junction() {
  return OsmSketch(R"(
      A---B---C
          |
          D
  )")
      .way("ABC", {{"highway", "residential"}, {"name", "Main"}})
      .way("BD", {{"highway", "service"}, {"oneway", "yes"}})
      .way("CD", {{"highway", "footway"}})
      .node_tags('B', {{"highway", "traffic_signals"}})
      .node_tags('D', {{"highway", "stop"}});
}

TEST(OsmReader, ReadsSketchWaysNodesAndSignals) {
  const auto dir = test::scratch_dir("osm_reader_sketch");
  const auto sketch = t_junction();
  Diagnostics diagnostics;
  const OsmRoads roads = read(sketch.write(dir / "t.osm"), diagnostics);

  EXPECT_EQ(roads.ways_read, 3u);
  EXPECT_EQ(roads.highway_ways, 3u);
  EXPECT_EQ(roads.ways_skipped_class, 1u);  // the footway
  ASSERT_EQ(roads.ways.size(), 2u);
  EXPECT_EQ(roads.ways[0].id, 1);
  EXPECT_EQ(roads.ways[0].node_ids, ids("ABC"));
  EXPECT_EQ(roads.ways[0].attributes.name, "Main");
  EXPECT_EQ(roads.ways[1].node_ids, ids("BD"));
  EXPECT_TRUE(roads.ways[1].attributes.oneway);
  EXPECT_EQ(roads.ways[1].attributes.highway, HighwayClass::service);

  ASSERT_EQ(roads.ways[0].nodes.size(), 3u);
  EXPECT_NEAR(roads.ways[0].nodes[2].lon_deg, sketch.lonlat('C').lon_deg, 1e-9);
  EXPECT_NEAR(roads.ways[0].nodes[2].lat_deg, sketch.lonlat('C').lat_deg, 1e-9);
  EXPECT_NEAR(roads.ways[0].nodes[0].lon_deg, -122.40, 1e-9);
  EXPECT_NEAR(roads.ways[0].nodes[0].lat_deg, 37.75, 1e-9);

  EXPECT_EQ(roads.traffic_signals, (std::unordered_set<std::int64_t>{OsmSketch::node_id('B')}));
  EXPECT_FALSE(roads.header_bounds.has_value());
  EXPECT_DOUBLE_EQ(roads.bounds.min_lon, sketch.lonlat('A').lon_deg);
  EXPECT_DOUBLE_EQ(roads.bounds.max_lon, sketch.lonlat('C').lon_deg);
  EXPECT_DOUBLE_EQ(roads.bounds.min_lat, sketch.lonlat('D').lat_deg);
  EXPECT_DOUBLE_EQ(roads.bounds.max_lat, sketch.lonlat('A').lat_deg);
  EXPECT_EQ(diagnostics.total(), 0u);
}

TEST(OsmReader, IncludeNonMotorKeepsFootways) {
  const auto dir = test::scratch_dir("osm_reader_non_motor");
  Diagnostics diagnostics;
  OsmReadOptions options;
  options.include_non_motor = true;
  const OsmRoads roads = read(t_junction().write(dir / "t.osm"), diagnostics, options);
  ASSERT_EQ(roads.ways.size(), 3u);
  EXPECT_EQ(roads.ways[2].attributes.highway, HighwayClass::footway);
  EXPECT_EQ(roads.ways_skipped_class, 0u);
}

TEST(OsmReader, ReversesOnewayMinusOne) {
  const auto dir = test::scratch_dir("osm_reader_reverse");
  Diagnostics diagnostics;
  const OsmRoads roads =
      read(OsmSketch("A--B--C")
               .way("ABC", {{"highway", "primary"}, {"oneway", "-1"}, {"lanes:backward", "2"}})
               .write(dir / "r.osm"),
           diagnostics);
  ASSERT_EQ(roads.ways.size(), 1u);
  EXPECT_EQ(roads.ways[0].node_ids, ids("CBA"));
  EXPECT_TRUE(roads.ways[0].attributes.oneway);
  EXPECT_EQ(roads.ways[0].attributes.lanes_forward, 2);
  EXPECT_EQ(roads.ways[0].attributes.lanes_backward, 0);
}

TEST(OsmReader, HeaderBounds) {
  const auto dir = test::scratch_dir("osm_reader_bounds");
  Diagnostics diagnostics;
  const OsmRoads roads = read(OsmSketch("A--B")
                                  .way("AB", {{"highway", "residential"}})
                                  .bounds({-122.41, 37.74, -122.39, 37.76})
                                  .write(dir / "b.osm"),
                              diagnostics);
  ASSERT_TRUE(roads.header_bounds.has_value());
  EXPECT_NEAR(roads.header_bounds->min_lon, -122.41, 1e-7);
  EXPECT_NEAR(roads.header_bounds->min_lat, 37.74, 1e-7);
  EXPECT_NEAR(roads.header_bounds->max_lon, -122.39, 1e-7);
  EXPECT_NEAR(roads.header_bounds->max_lat, 37.76, 1e-7);
}

TEST(OsmReader, MissingNodeSplitsTheWayAndIsReported) {
  const auto dir = test::scratch_dir("osm_reader_missing");
  // Node 3 is referenced by way 10 but absent; way 11 keeps a single present node.
  const auto path = dir / "missing.osm";
  write_bytes(path, R"(<?xml version='1.0' encoding='UTF-8'?>
<osm version="0.6" generator="hand">
  <node id="1" version="1" lat="37.7500000" lon="-122.4000000"/>
  <node id="2" version="1" lat="37.7500000" lon="-122.3990000"/>
  <node id="4" version="1" lat="37.7500000" lon="-122.3970000"/>
  <node id="5" version="1" lat="37.7500000" lon="-122.3960000"/>
  <way id="10" version="1">
    <nd ref="1"/><nd ref="2"/><nd ref="3"/><nd ref="4"/><nd ref="5"/>
    <tag k="highway" v="residential"/>
  </way>
  <way id="11" version="1">
    <nd ref="6"/><nd ref="1"/>
    <tag k="highway" v="service"/>
  </way>
</osm>
)");
  Diagnostics diagnostics;
  const OsmRoads roads = read(path, diagnostics);
  ASSERT_EQ(roads.ways.size(), 2u);
  EXPECT_EQ(roads.ways[0].id, 10);
  EXPECT_EQ(roads.ways[0].node_ids, (std::vector<std::int64_t>{1, 2}));
  EXPECT_EQ(roads.ways[1].id, 10);
  EXPECT_EQ(roads.ways[1].node_ids, (std::vector<std::int64_t>{4, 5}));
  EXPECT_EQ(roads.ways_with_missing_nodes, 2u);
  EXPECT_EQ(roads.missing_node_refs, 2u);

  ASSERT_EQ(diagnostics.count("osm.missing_node"), 2u);
  const Diagnostic& d = diagnostics.kept().at(0);
  EXPECT_EQ(d.code, "osm.missing_node");
  EXPECT_EQ(d.severity, Severity::warning);
  EXPECT_EQ(d.osm_way_id, 10);
  EXPECT_EQ(d.osm_node_id, 3);
  EXPECT_NE(d.message.find("way 10"), std::string::npos) << d.message;
  EXPECT_NE(d.message.find("node 3"), std::string::npos) << d.message;
  EXPECT_EQ(diagnostics.kept().at(1).osm_way_id, 11);
  EXPECT_EQ(diagnostics.kept().at(1).osm_node_id, 6);
}

TEST(OsmReader, DegenerateWayIsReportedAndSkipped) {
  const auto dir = test::scratch_dir("osm_reader_degenerate");
  Diagnostics diagnostics;
  const OsmRoads roads = read(OsmSketch("A--B")
                                  .way("AB", {{"highway", "residential"}})
                                  .way("AA", {{"highway", "residential"}})
                                  .write(dir / "d.osm"),
                              diagnostics);
  ASSERT_EQ(roads.ways.size(), 1u);
  EXPECT_EQ(diagnostics.count("osm.degenerate_way"), 1u);
  EXPECT_EQ(diagnostics.kept().at(0).osm_way_id, 2);
}

// A way drawn out to a node and straight back has no reference line through that node (its legs
// lie on each other: Liechtenstein's path 351947855, A-B-A, stopped a build with "plan view: no
// geometry records"). The stretch is built once, a way of its own; the way goes on from where
// it turned.
TEST(OsmReader, WayTurningStraightBackIsBuiltOnce) {
  const auto dir = test::scratch_dir("osm_reader_turns_back");
  Diagnostics diagnostics;
  const OsmRoads roads = read(OsmSketch("A--B--C\n|\nD--E")
                                  .way("ABA", {{"highway", "residential"}})
                                  .way("DABCBAE", {{"highway", "residential"}})
                                  .write(dir / "t.osm"),
                              diagnostics);
  std::vector<std::vector<std::int64_t>> got;
  for (const OsmWay& w : roads.ways) {
    got.push_back(w.node_ids);
    EXPECT_EQ(w.node_ids.size(), w.nodes.size());
    EXPECT_EQ(w.attributes.highway, HighwayClass::residential);
  }
  // Way 2's spur A-B runs over way 1's: built once (osm.overlapping_ways).
  EXPECT_EQ(got, (std::vector<std::vector<std::int64_t>>{ids("AB"), ids("BC"), ids("DAE")}));
  EXPECT_EQ(roads.ways[0].id, 1);
  EXPECT_EQ(roads.ways[2].id, 2);
  ASSERT_EQ(diagnostics.count("osm.way_turns_back"), 3u);
  EXPECT_EQ(diagnostics.count("osm.overlapping_ways"), 1u);
  EXPECT_NE(diagnostics.kept().at(0).message.find("turns straight back at node"), std::string::npos);
}

// A street drawn twice (JOSM's "duplicated ways"), once reversed, and a way running along part
// of another: each segment is built once, by the higher class (then the lower id); a way
// reduced to nothing is gone, the rest of a way is kept. Drawn twice, the hill fixture's 20th
// Street made four junctions one (its roads "too short to hold both"), with every gate passed.
TEST(OsmReader, WaysOverTheNodesOfAnotherAreBuiltOnce) {
  const auto dir = test::scratch_dir("osm_reader_overlaps");
  Diagnostics diagnostics;
  const OsmRoads roads = read(OsmSketch("A--B--C--D\n|\nE")
                                  .way("ABCD", {{"highway", "residential"}})  // way 1
                                  .way("DCBA", {{"highway", "residential"}})  // 2: way 1 reversed
                                  .way("EABC", {{"highway", "primary"}})      // 3: a higher class over AB, BC
                                  .way("ABCD", {{"highway", "residential"}})  // 4: way 1 again
                                  .write(dir / "o.osm"),
                              diagnostics);
  std::vector<std::pair<std::int64_t, std::vector<std::int64_t>>> got;
  for (const OsmWay& w : roads.ways) got.emplace_back(w.id, w.node_ids);
  EXPECT_EQ(got, (std::vector<std::pair<std::int64_t, std::vector<std::int64_t>>>{{1, ids("CD")},
                                                                                  {3, ids("EABC")}}));
  // One per way and way run over: 1 over 3; 2 over 1 and 3; 4 over 3 and 1.
  EXPECT_EQ(diagnostics.count("osm.overlapping_ways"), 5u);
  bool named = false;
  for (const Diagnostic& d : diagnostics.kept())
    named |= d.osm_way_id == 1 && d.message.find("runs over 2 segment(s) of way 3") != std::string::npos &&
             d.message.find("the rest of it is kept") != std::string::npos;
  EXPECT_TRUE(named);
}

TEST(OsmReader, BadTagValuesAreReported) {
  const auto dir = test::scratch_dir("osm_reader_bad_tags");
  Diagnostics diagnostics;
  const OsmRoads roads =
      read(OsmSketch("A--B").way("AB", {{"highway", "residential"}, {"lanes", "many"}}).write(dir / "t.osm"),
           diagnostics);
  ASSERT_EQ(roads.ways.size(), 1u);
  EXPECT_EQ(diagnostics.count("osm.tag_value"), 1u);
  EXPECT_EQ(diagnostics.kept().at(0).osm_way_id, 1);
}

TEST(OsmReader, BboxClipCutsAtTheEdge) {
  const auto dir = test::scratch_dir("osm_reader_clip");
  // A-B-F-G runs along the top row; the way dips south to C, outside the box.
  const auto sketch = OsmSketch(R"(
      A---B---F---G

            C
  )")
                          .way("ABCFG", {{"highway", "residential"}})
                          .way("FC", {{"highway", "service"}});  // shares segment C-F
  // Box: everything north of halfway between the rows (row 2 is 40 m south).
  const double mid_lat = 0.5 * (sketch.lonlat('A').lat_deg + sketch.lonlat('C').lat_deg);
  OsmReadOptions options;
  options.bbox = LonLatBox{-122.41, mid_lat, -122.39, 37.76};
  Diagnostics diagnostics;
  const OsmRoads roads = read(sketch.write(dir / "clip.osm"), diagnostics, options);

  ASSERT_EQ(roads.ways.size(), 2u);
  const OsmWay& west = roads.ways[0];
  const OsmWay& east = roads.ways[1];
  EXPECT_EQ(west.id, 1);
  EXPECT_EQ(east.id, 1);
  ASSERT_EQ(west.node_ids.size(), 3u);
  ASSERT_EQ(east.node_ids.size(), 3u);
  EXPECT_EQ(west.node_ids[0], OsmSketch::node_id('A'));
  EXPECT_EQ(west.node_ids[1], OsmSketch::node_id('B'));
  EXPECT_LT(west.node_ids[2], 0);
  EXPECT_LT(east.node_ids[0], 0);
  EXPECT_NE(west.node_ids[2], east.node_ids[0]);
  EXPECT_EQ(east.node_ids[1], OsmSketch::node_id('F'));
  EXPECT_EQ(east.node_ids[2], OsmSketch::node_id('G'));

  // B-C is cut halfway (the box edge is halfway in latitude), C-F likewise.
  const LonLat b = sketch.lonlat('B');
  const LonLat c = sketch.lonlat('C');
  const LonLat f = sketch.lonlat('F');
  EXPECT_DOUBLE_EQ(west.nodes[2].lat_deg, mid_lat);
  EXPECT_NEAR(west.nodes[2].lon_deg, 0.5 * (b.lon_deg + c.lon_deg), 1e-10);
  EXPECT_DOUBLE_EQ(east.nodes[0].lat_deg, mid_lat);
  EXPECT_NEAR(east.nodes[0].lon_deg, 0.5 * (c.lon_deg + f.lon_deg), 1e-10);

  // Way 2 runs F -> C over way 1's segment: built once, as way 1's, before the clip.
  EXPECT_EQ(diagnostics.count("osm.overlapping_ways"), 1u);

  EXPECT_DOUBLE_EQ(roads.bounds.min_lat, mid_lat);
}

TEST(OsmReader, BboxClipDropsWaysOutsideAndThrowsWhenNothingIsLeft) {
  const auto dir = test::scratch_dir("osm_reader_clip_out");
  const auto path = OsmSketch("A--B").way("AB", {{"highway", "residential"}}).write(dir / "o.osm");
  OsmReadOptions options;
  options.bbox = LonLatBox{-122.0, 37.0, -121.9, 37.1};
  Diagnostics diagnostics;
  EXPECT_THROW((void)read(path, diagnostics, options), InvalidInput);
}

TEST(OsmReader, MissingFileThrowsIoError) {
  Diagnostics diagnostics;
  const auto path = test::scratch_dir("osm_reader_nofile") / "nowhere.osm";
  try {
    (void)read(path, diagnostics);
    FAIL() << "no exception";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("cannot open OSM file '" + path.string() + "'"), std::string::npos)
        << e.what();
  }
}

TEST(OsmReader, FileWithoutRoadsThrowsInvalidInput) {
  const auto dir = test::scratch_dir("osm_reader_noroads");
  const auto path = OsmSketch("A--B--C")
                        .way("AB", {{"building", "yes"}})
                        .way("BC", {{"highway", "footway"}})
                        .write(dir / "noroads.osm");
  Diagnostics diagnostics;
  try {
    (void)read(path, diagnostics);
    FAIL() << "no exception";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("contains no roads"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
  }
}

TEST(OsmReader, MalformedXmlThrowsInvalidInput) {
  const auto dir = test::scratch_dir("osm_reader_malformed");
  const auto path = dir / "bad.osm";
  write_bytes(path,
              "<?xml version='1.0'?>\n<osm version=\"0.6\">\n  <node id=\"1\" lat=\"37.7\" "
              "lon=\"-122.4\">\n</osm>\n");
  Diagnostics diagnostics;
  EXPECT_THROW((void)read(path, diagnostics), InvalidInput);
}

TEST(OsmReader, UnknownExtensionThrowsInvalidInput) {
  const auto dir = test::scratch_dir("osm_reader_extension");
  const auto path = OsmSketch("A--B").way("AB", {{"highway", "residential"}}).write(dir / "roads.txt");
  Diagnostics diagnostics;
  try {
    (void)read(path, diagnostics);
    FAIL() << "no exception";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("unknown format"), std::string::npos) << e.what();
  }
}

TEST(OsmReader, TruncatedGzipThrowsInvalidInput) {
  const auto dir = test::scratch_dir("osm_reader_truncated");
  const auto xml = t_junction().write(dir / "t.osm");
  gzip_file(xml, dir / "t.osm.gz");
  // The complete .osm.gz reads fine ...
  Diagnostics diagnostics;
  EXPECT_EQ(read(dir / "t.osm.gz", diagnostics).ways.size(), 2u);
  // ... half of it does not.
  const std::string bytes = read_bytes(dir / "t.osm.gz");
  write_bytes(dir / "half.osm.gz", std::string_view(bytes).substr(0, bytes.size() / 2));
  try {
    (void)read(dir / "half.osm.gz", diagnostics);
    FAIL() << "no exception";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("is malformed or truncated"), std::string::npos) << e.what();
  }
}

TEST(OsmReader, TruncatedRealGzipThrowsInvalidInput) {
  RELIEF_REQUIRE_SHARED_DATA();
  const auto dir = test::scratch_dir("osm_reader_truncated_real");
  const std::string bytes = read_bytes(test::shared_data("sf-potrero/sf-potrero.osm.gz"));
  write_bytes(dir / "half.osm.gz", std::string_view(bytes).substr(0, bytes.size() / 2));
  Diagnostics diagnostics;
  EXPECT_THROW((void)read(dir / "half.osm.gz", diagnostics), InvalidInput);
}

TEST(OsmReader, TruncatedPbfThrowsInvalidInput) {
  const auto dir = test::scratch_dir("osm_reader_truncated_pbf");
  convert_with_osmium(t_junction().write(dir / "t.osm"), dir / "t.osm.pbf");
  const std::string bytes = read_bytes(dir / "t.osm.pbf");
  write_bytes(dir / "half.osm.pbf", std::string_view(bytes).substr(0, bytes.size() / 2));
  Diagnostics diagnostics;
  EXPECT_THROW((void)read(dir / "half.osm.pbf", diagnostics), InvalidInput);
}

void expect_same_roads(const OsmRoads& a, const OsmRoads& b) {
  EXPECT_EQ(a.ways_read, b.ways_read);
  EXPECT_EQ(a.highway_ways, b.highway_ways);
  EXPECT_EQ(a.traffic_signals, b.traffic_signals);
  ASSERT_EQ(a.ways.size(), b.ways.size());
  for (std::size_t i = 0; i < a.ways.size(); ++i) {
    EXPECT_EQ(a.ways[i].id, b.ways[i].id);
    EXPECT_EQ(a.ways[i].node_ids, b.ways[i].node_ids);
    EXPECT_TRUE(a.ways[i].attributes == b.ways[i].attributes) << "way " << a.ways[i].id;
    ASSERT_EQ(a.ways[i].nodes.size(), b.ways[i].nodes.size());
    for (std::size_t k = 0; k < a.ways[i].nodes.size(); ++k) {
      EXPECT_NEAR(a.ways[i].nodes[k].lon_deg, b.ways[i].nodes[k].lon_deg, 1e-9);
      EXPECT_NEAR(a.ways[i].nodes[k].lat_deg, b.ways[i].nodes[k].lat_deg, 1e-9);
    }
  }
}

TEST(OsmReader, PbfReadsLikeXml) {
  const auto dir = test::scratch_dir("osm_reader_pbf");
  const auto xml = t_junction().write(dir / "t.osm");
  convert_with_osmium(xml, dir / "t.osm.pbf");
  Diagnostics diagnostics;
  const OsmRoads from_xml = read(xml, diagnostics);
  const OsmRoads from_pbf = read(dir / "t.osm.pbf", diagnostics);
  expect_same_roads(from_xml, from_pbf);
}

TEST(OsmReader, PotreroAsPbfReadsLikeGzip) {
  RELIEF_REQUIRE_SHARED_DATA();
  const auto dir = test::scratch_dir("osm_reader_potrero_pbf");
  const auto gz = test::shared_data("sf-potrero/sf-potrero.osm.gz");
  convert_with_osmium(gz, dir / "potrero.osm.pbf");
  convert_with_osmium(gz, dir / "potrero.osm.bz2");
  Diagnostics diagnostics;
  const OsmRoads from_gz = read(gz, diagnostics);
  expect_same_roads(from_gz, read(dir / "potrero.osm.pbf", diagnostics));
  expect_same_roads(from_gz, read(dir / "potrero.osm.bz2", diagnostics));
  ASSERT_TRUE(read(dir / "potrero.osm.pbf", diagnostics).header_bounds.has_value());
}

TEST(OsmReader, PotreroRealData) {
  RELIEF_REQUIRE_SHARED_DATA();
  Diagnostics diagnostics;
  const OsmRoads roads = read(test::shared_data("sf-potrero/sf-potrero.osm.gz"), diagnostics);
  OsmReadOptions all;
  all.include_non_motor = true;
  const OsmRoads with_paths = read(test::shared_data("sf-potrero/sf-potrero.osm.gz"), diagnostics, all);

  const auto count = [](const OsmRoads& r, auto pred) {
    return std::count_if(r.ways.begin(), r.ways.end(), pred);
  };
  const auto bridges = count(roads, [](const OsmWay& w) { return w.attributes.bridge; });
  const auto motorway =
      count(roads, [](const OsmWay& w) { return w.attributes.highway == HighwayClass::motorway; });
  std::cout << "[potrero] ways read " << roads.ways_read << ", highway ways " << roads.highway_ways
            << ", motor road ways " << roads.ways.size() << " (with paths " << with_paths.ways.size()
            << "), bridges " << bridges << " (with paths "
            << count(with_paths, [](const OsmWay& w) { return w.attributes.bridge; })
            << "), missing node refs " << roads.missing_node_refs << " in " << roads.ways_with_missing_nodes
            << " ways\n";

  EXPECT_EQ(roads.ways_read, 671u);
  EXPECT_EQ(roads.highway_ways, 90u);
  EXPECT_EQ(roads.ways_skipped_class, 12u);  // 10 footways, 2 steps
  EXPECT_EQ(with_paths.ways_skipped_class, 0u);
  // Six highway ways keep a single node after osmconvert's clip: degenerate, reported.
  EXPECT_EQ(roads.ways.size(), 72u);
  EXPECT_EQ(with_paths.ways.size(), 84u);
  EXPECT_EQ(diagnostics.count("osm.degenerate_way"), 2 * 6u);
  EXPECT_EQ(motorway, 3);
  ASSERT_TRUE(roads.header_bounds.has_value());
  EXPECT_NEAR(roads.header_bounds->min_lon, -122.4039, 1e-6);
  EXPECT_NEAR(roads.header_bounds->max_lat, 37.75558, 1e-6);

  // 23rd Street crosses US-101 on a bridge (bridge=yes, layer=1); a footbridge is the other.
  EXPECT_EQ(bridges, 1);
  EXPECT_EQ(count(with_paths, [](const OsmWay& w) { return w.attributes.bridge; }), 2);
  const OsmWay* bridge = find_way(roads, 24547840);
  ASSERT_NE(bridge, nullptr);
  EXPECT_TRUE(bridge->attributes.bridge);
  EXPECT_EQ(bridge->attributes.layer, 1);
  EXPECT_EQ(bridge->attributes.name, "23rd Street");
}

TEST(OsmReader, NortheastRealData) {
  RELIEF_REQUIRE_SHARED_DATA();
  Diagnostics diagnostics;
  const OsmRoads roads = read(test::shared_data("sf-ne/sf_ne_drive_2017.osm.gz"), diagnostics);
  const auto count = [&](auto pred) { return std::count_if(roads.ways.begin(), roads.ways.end(), pred); };
  const auto tunnels = count([](const OsmWay& w) { return w.attributes.tunnel; });
  const auto bridges = count([](const OsmWay& w) { return w.attributes.bridge; });
  const auto oneways = count([](const OsmWay& w) { return w.attributes.oneway; });
  const auto lanes = count([](const OsmWay& w) { return w.attributes.lanes_tagged; });
  std::cout << "[ne] ways read " << roads.ways_read << ", highway ways " << roads.highway_ways
            << ", road ways " << roads.ways.size() << ", signals " << roads.traffic_signals.size()
            << ", tunnels " << tunnels << ", bridges " << bridges << ", one-ways " << oneways
            << ", lanes tagged " << lanes << ", diagnostics " << diagnostics.total() << "\n";

  EXPECT_EQ(roads.highway_ways, 943u);
  // 29 highway=corridor ways (indoor passages) are not modelled.
  EXPECT_EQ(roads.ways.size(), 914u);
  EXPECT_EQ(roads.ways_skipped_class, 29u);
  EXPECT_EQ(roads.traffic_signals.size(), 421u);
  EXPECT_EQ(roads.missing_node_refs, 0u);
  // Broadway (Robert C Levy) and Stockton tunnels, two ways each, and 1st Street's
  // building passage.
  EXPECT_EQ(tunnels, 5);
  EXPECT_EQ(bridges, 9);
  for (const std::int64_t id : {8921175, 26938250, 417099350, 417099351}) {
    const OsmWay* w = find_way(roads, id);
    ASSERT_NE(w, nullptr) << id;
    EXPECT_TRUE(w->attributes.tunnel) << id;
    EXPECT_EQ(w->attributes.layer, -1) << id;
  }
  EXPECT_EQ(find_way(roads, 417099350)->attributes.name, "Stockton Tunnel");
  const OsmWay* hyde = find_way(roads, 26938417);
  ASSERT_NE(hyde, nullptr);
  EXPECT_TRUE(hyde->attributes.bridge);
  EXPECT_EQ(hyde->attributes.name, "Hyde Street");
  EXPECT_EQ(lanes, 545);
}

}  // namespace
}  // namespace relief

#include "relief/export/opendrive_writer.h"

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <locale>
#include <numbers>
#include <regex>
#include <sstream>

#include "relief/core/errors.h"
#include "relief/roads/opendrive_reader.h"
#include "support/plan_records.h"
#include "support/test_data.h"

namespace relief {
namespace {

namespace fs = std::filesystem;

// ---------------------------------------------------------------------------------------------
// Models built in code.

using test::arc_record;
using test::line_record;

// The next record starting where `g` ends.
Pose2 end_of(const PlanGeometry& g) {
  return evaluate(g, g.length);
}

LaneModel lane(int id, const std::string& type, CubicProfile width, RoadMark::Type mark,
               std::optional<int> predecessor = std::nullopt, std::optional<int> successor = std::nullopt) {
  LaneModel l;
  l.id = id;
  l.type = type;
  l.width = std::move(width);
  l.mark.type = mark;
  l.predecessor = predecessor;
  l.successor = successor;
  return l;
}

RoadLink road_link(int id, RoadLink::Contact contact) {
  return {RoadLink::Element::road, id, contact};
}
RoadLink junction_link(int id) {
  return {RoadLink::Element::junction, id, RoadLink::Contact::start};
}

// Road 1: a two-way street (line + arc, two lanes each way, two lane sections, a lane offset)
// ending in junction 100; road 3 (paramPoly3) connects it to road 2 (line + spiral).
RoadModel sample_model() {
  RoadModel m;
  m.frame = GeoFrame("EPSG:32610", Vec2(550000.0, 4180000.0));
  m.name = "sample & <test>";

  ModelRoad r1;
  r1.id = 1;
  r1.name = "Main \"Street\"";
  r1.source_road = 0;
  const PlanGeometry l1 = line_record(0.0, Vec2(0.0, 0.0), 0.0, 50.0);
  const PlanGeometry a1 =
      arc_record(50.0, end_of(l1).position, end_of(l1).heading, 10.0 * std::numbers::pi, 0.02);
  r1.plan = PlanView({l1, a1});
  r1.elevation = CubicProfile({{0.0, {10.0, 0.02, 0.0, 0.0}}, {40.0, {10.8, 0.02, 1e-4, -1e-6}}});
  r1.lane_offset = CubicProfile({{0.0, {0.25, 0.0, 0.0, 0.0}}, {30.0, {0.25, 0.0, -3e-4, 4e-6}}});
  r1.speed_mps = 13.4112;
  LaneSection s0;
  s0.s = 0.0;
  s0.left = {lane(1, "driving", CubicProfile::constant(3.5), RoadMark::Type::broken, std::nullopt, 1),
             lane(2, "sidewalk", CubicProfile::constant(2.0), RoadMark::Type::none)};
  s0.right = {
      lane(-1, "driving", CubicProfile({{0.0, {3.5, 0.0, 0.0, 0.0}}, {20.0, {3.5, 0.01, -2e-4, 0.0}}}),
           RoadMark::Type::broken, std::nullopt, -1),
      lane(-2, "shoulder", CubicProfile::constant(1.0), RoadMark::Type::solid)};
  s0.centre_mark = {RoadMark::Type::solid_solid, "yellow", 0.15};
  LaneSection s1;
  s1.s = 60.0;
  s1.left = {lane(1, "driving", CubicProfile::constant(3.5), RoadMark::Type::solid, 1)};
  s1.right = {lane(-1, "driving", CubicProfile::constant(3.5), RoadMark::Type::solid, -1, -1)};
  s1.centre_mark = {RoadMark::Type::broken_solid, "standard", 0.12};
  r1.sections = {s0, s1};
  r1.successor = junction_link(100);

  // Connecting road 3 from the end of road 1: a normalized paramPoly3.
  ModelRoad r3;
  r3.id = 3;
  r3.junction = 100;
  PlanGeometry c;
  c.kind = PlanGeometry::Kind::param_poly3;
  const Pose2 p1 = r1.plan.at(r1.plan.length());
  c.start = p1.position;
  c.heading = p1.heading;
  c.u = {0.0, 20.0, 1.5, -0.5};
  c.v = {0.0, 0.0, 6.0, -2.5};
  c.normalized = true;
  c.length = param_poly3_length(c.u, c.v, 1.0);
  r3.plan = PlanView({c});
  r3.elevation = CubicProfile::constant(12.0);
  LaneSection s3;
  s3.right = {lane(-1, "driving", CubicProfile::constant(3.5), RoadMark::Type::none, -1, -1)};
  r3.sections = {s3};
  r3.predecessor = road_link(1, RoadLink::Contact::end);
  r3.successor = road_link(2, RoadLink::Contact::start);

  // Road 2 from the end of the connector: line + spiral.
  ModelRoad r2;
  r2.id = 2;
  r2.name = "Second";
  r2.type = "rural";
  const Pose2 p3 = end_of(c);
  const PlanGeometry l2 = line_record(0.0, p3.position, p3.heading, 20.0);
  PlanGeometry sp = line_record(20.0, end_of(l2).position, end_of(l2).heading, 30.0);
  sp.kind = PlanGeometry::Kind::spiral;
  sp.curvature_start = 0.0;
  sp.curvature_end = -0.01;
  r2.plan = PlanView({l2, sp});
  r2.elevation = CubicProfile::constant(12.0);
  LaneSection s2;
  s2.left = {lane(1, "driving", CubicProfile::constant(3.25), RoadMark::Type::solid)};
  s2.right = {lane(-1, "driving", CubicProfile::constant(3.25), RoadMark::Type::solid, -1)};
  s2.centre_mark = {RoadMark::Type::broken, "standard", 0.12};
  r2.sections = {s2};
  r2.predecessor = junction_link(100);

  m.roads = {r1, r2, r3};
  JunctionModel j;
  j.id = 100;
  j.name = "Main / Second";
  JunctionConnection conn;
  conn.id = 0;
  conn.incoming_road = 1;
  conn.connecting_road = 3;
  conn.contact = RoadLink::Contact::start;
  conn.lane_links = {{-1, -1}};
  j.connections = {conn};
  m.junctions = {j};
  return m;
}

// One straight road and one quarter circle, with lanes: small enough for a golden file.
RoadModel tiny_model() {
  RoadModel m;
  m.frame = GeoFrame("EPSG:32610", Vec2(550000.0, 4180000.0));
  m.name = "tiny";
  ModelRoad r;
  r.id = 7;
  r.name = "Quarter";
  const PlanGeometry l = line_record(0.0, Vec2(0.0, 0.0), 0.0, 10.0);
  r.plan = PlanView({l, arc_record(10.0, Vec2(10.0, 0.0), 0.0, 5.0 * std::numbers::pi, 0.1)});
  r.elevation = CubicProfile(std::vector<CubicPiece>{{0.0, {5.0, 0.01, 0.0, 0.0}}});
  r.speed_mps = 13.889;
  LaneSection s;
  s.left = {lane(1, "driving", CubicProfile::constant(3.0), RoadMark::Type::broken)};
  s.right = {lane(-1, "driving", CubicProfile::constant(3.0), RoadMark::Type::solid)};
  s.centre_mark = {RoadMark::Type::solid, "yellow", 0.12};
  r.sections = {s};
  m.roads = {r};
  return m;
}

std::string to_xodr(const RoadModel& model, const OpenDriveOptions& options = {}) {
  std::ostringstream out;
  write_opendrive(out, model, options);
  return out.str();
}

fs::path write_xodr(const std::string& name, const RoadModel& model, const OpenDriveOptions& options = {}) {
  const fs::path path = test::scratch_dir("opendrive_writer_" + name) / (name + ".xodr");
  std::ofstream(path, std::ios::binary) << to_xodr(model, options);
  return path;
}

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// ---------------------------------------------------------------------------------------------
// Schema validation through the command-line validators.

// ../shared/opendrive-xsd beside the source tree, as a normalised path: xmllint compiles the
// schema's circular includes twice when the path contains "..".
fs::path xsd_dir() {
  return (fs::path(RELIEF_SOURCE_DIR) / ".." / "shared" / "opendrive-xsd").lexically_normal();
}

bool have_command(const std::string& command) {
  return std::system(("command -v " + command + " >/dev/null 2>&1").c_str()) == 0;
}

// Runs `command`, returns "" on exit status 0, else its output.
std::string run_failing(const std::string& command, const fs::path& log) {
  const int status = std::system((command + " >" + log.string() + " 2>&1").c_str());
  if (status != -1 && WIFEXITED(status) && WEXITSTATUS(status) == 0) return {};
  return "exit status " + std::to_string(status) + ": " + read_text(log);
}

TEST(OpenDriveWriter, ValidatesAgainstTheOpenDrive17Schema) {
  const fs::path xsd = xsd_dir() / "1.7.0" / "opendrive_17_core.xsd";
  if (!fs::exists(xsd)) GTEST_SKIP() << "no " << xsd;
  if (!have_command("xmllint")) GTEST_SKIP() << "no xmllint";
  const fs::path file = write_xodr("v17", sample_model());
  EXPECT_EQ(
      run_failing("xmllint --noout --schema " + xsd.string() + " " + file.string(), file.string() + ".log"),
      "");
}

TEST(OpenDriveWriter, ValidatesAgainstTheOpenDrive18Schema) {
  const fs::path xsd = xsd_dir() / "1.8.1" / "OpenDRIVE_Core.xsd";
  if (!fs::exists(xsd)) GTEST_SKIP() << "no " << xsd;
  if (std::system("/usr/bin/python3 -c 'import xmlschema' >/dev/null 2>&1") != 0)
    GTEST_SKIP() << "no python3-xmlschema";
  OpenDriveOptions options;
  options.rev_minor = 8;
  const fs::path file = write_xodr("v18", sample_model(), options);
  const std::string text = read_text(file);
  EXPECT_NE(text.find("<license "), std::string::npos);
  EXPECT_NE(text.find("revMinor=\"8\""), std::string::npos);
  EXPECT_EQ(run_failing("/usr/bin/python3 -c \"import xmlschema; xmlschema.XMLSchema11('" + xsd.string() +
                            "').validate('" + file.string() + "')\"",
                        file.string() + ".log"),
            "");
}

TEST(OpenDriveWriter, WritesOpenDrive14WithWholeSpeedsAndNoOffset) {
  if (!have_command("xmllint")) GTEST_SKIP() << "no xmllint";
  OpenDriveOptions options;
  options.rev_minor = 4;
  const fs::path file = write_xodr("v14", sample_model(), options);
  const std::string text = read_text(file);
  EXPECT_NE(text.find("revMinor=\"4\""), std::string::npos);
  EXPECT_EQ(text.find("<offset"), std::string::npos);                            // 1.4 has no header offset
  EXPECT_NE(text.find("<speed max=\"48\" unit=\"km/h\"/>"), std::string::npos);  // 30 mph
  // The 1.4H schema is not among the shared ones; validate when someone adds it, else check
  // that the file is well-formed.
  const fs::path xsd = xsd_dir() / "1.4" / "OpenDRIVE_1.4H.xsd";
  const std::string schema = fs::exists(xsd) ? " --schema " + xsd.string() : "";
  EXPECT_EQ(run_failing("xmllint --noout" + schema + " " + file.string(), file.string() + ".log"), "");
}

// ---------------------------------------------------------------------------------------------
// Content.

TEST(OpenDriveWriter, MatchesTheGoldenFileAtFixedPrecision) {
  OpenDriveOptions options;
  options.decimals = 3;
  options.date = "2024-05-01T00:00:00";
  const std::string text = to_xodr(tiny_model(), options);
  const fs::path golden = fs::path(RELIEF_SOURCE_DIR) / "tests" / "export" / "golden" / "tiny_1_7.xodr";
  if (std::getenv("RELIEF_UPDATE_GOLDEN") != nullptr) std::ofstream(golden, std::ios::binary) << text;
  ASSERT_TRUE(fs::exists(golden)) << golden;
  EXPECT_EQ(text, read_text(golden));
}

TEST(OpenDriveWriter, HeaderBoundsCoverTheReferenceLines) {
  // A 10 m line along +x, then a quarter circle of radius 10 ending at (20, 10).
  const std::string text = to_xodr(tiny_model());
  const auto value = [&](const std::string& name) {
    std::smatch m;
    EXPECT_TRUE(std::regex_search(text, m, std::regex(" " + name + "=\"([-0-9.]+)\""))) << name;
    return std::stod(m[1]);
  };
  EXPECT_NEAR(value("north"), 10.0, 1e-9);
  EXPECT_NEAR(value("south"), 0.0, 1e-9);
  EXPECT_NEAR(value("east"), 20.0, 1e-9);
  EXPECT_NEAR(value("west"), 0.0, 1e-9);
}

TEST(OpenDriveWriter, CarriesAttributionAndGeoReference) {
  const RoadModel model = tiny_model();
  const std::string text = to_xodr(model);
  EXPECT_NE(text.find("<!-- Road data (c) OpenStreetMap contributors"), std::string::npos);
  EXPECT_NE(text.find("<userData code=\"attribution\" value=\"Road data (c) OpenStreetMap"),
            std::string::npos);
  EXPECT_NE(text.find("<geoReference><![CDATA[" + model.frame.proj_string() + "]]></geoReference>"),
            std::string::npos);
}

TEST(OpenDriveWriter, NumbersIgnoreTheStreamLocaleAndNeverPrintMinusZero) {
  struct Comma : std::numpunct<char> {
    char do_decimal_point() const override { return ','; }
  };
  RoadModel model = tiny_model();
  model.roads[0].elevation = CubicProfile(std::vector<CubicPiece>{{0.0, {-1e-12, -0.0, 0.0, 0.0}}});
  OpenDriveOptions options;
  options.decimals = 3;
  std::ostringstream out;
  out.imbue(std::locale(std::locale::classic(), new Comma));
  write_opendrive(out, model, options);
  // Fixed decimals for values, the shortest exact text for coefficients; no "-0" either way.
  EXPECT_NE(out.str().find("<elevation s=\"0.000\" a=\"0.000\" b=\"0\" c=\"0\" d=\"0\""), std::string::npos)
      << out.str();
  EXPECT_EQ(out.str().find("\"-0.000\""), std::string::npos);
  EXPECT_FALSE(std::regex_search(out.str(), std::regex("[0-9],[0-9]")));
}

TEST(OpenDriveWriter, OrdersLanesLeftDescendingThenCentreThenRight) {
  const std::string text = to_xodr(sample_model());
  const auto at = [&](const std::string& needle) { return text.find(needle); };
  const auto l2 = at("<lane id=\"2\"");
  const auto l1 = at("<lane id=\"1\"");
  const auto c0 = at("<lane id=\"0\"");
  const auto r1 = at("<lane id=\"-1\"");
  const auto r2 = at("<lane id=\"-2\"");
  ASSERT_NE(r2, std::string::npos);
  EXPECT_LT(l2, l1);
  EXPECT_LT(l1, c0);
  EXPECT_LT(c0, r1);
  EXPECT_LT(r1, r2);
}

// ---------------------------------------------------------------------------------------------
// Round trip through relief's reader.

void expect_poly(const Poly3& a, const Poly3& b, const std::string& what) {
  EXPECT_NEAR(a.a, b.a, 1e-9) << what;
  EXPECT_NEAR(a.b, b.b, 1e-9) << what;
  EXPECT_NEAR(a.c, b.c, 1e-9) << what;
  EXPECT_NEAR(a.d, b.d, 1e-9) << what;
}

void expect_profile(const CubicProfile& read, const CubicProfile& written, const std::string& what) {
  const CubicProfile expected = written.empty() ? CubicProfile::constant(0.0) : written;
  ASSERT_EQ(read.pieces().size(), expected.pieces().size()) << what;
  for (std::size_t i = 0; i < read.pieces().size(); ++i) {
    EXPECT_NEAR(read.pieces()[i].s, expected.pieces()[i].s, 1e-9) << what;
    expect_poly(read.pieces()[i].poly, expected.pieces()[i].poly, what);
  }
}

void expect_mark(const RoadMark& read, const RoadMark& written, const std::string& what) {
  EXPECT_EQ(read.type, written.type) << what;
  EXPECT_EQ(read.color, written.color) << what;
  EXPECT_NEAR(read.width_m, written.width_m, 1e-9) << what;
}

void expect_lanes(const std::vector<LaneModel>& read, const std::vector<LaneModel>& written,
                  const std::string& what) {
  ASSERT_EQ(read.size(), written.size()) << what;
  for (std::size_t i = 0; i < read.size(); ++i) {
    const std::string w = what + " lane " + std::to_string(written[i].id);
    EXPECT_EQ(read[i].id, written[i].id) << w;
    EXPECT_EQ(read[i].type, written[i].type) << w;
    EXPECT_EQ(read[i].predecessor, written[i].predecessor) << w;
    EXPECT_EQ(read[i].successor, written[i].successor) << w;
    expect_profile(read[i].width, written[i].width, w + " width");
    expect_mark(read[i].mark, written[i].mark, w + " mark");
  }
}

void expect_link(const std::optional<RoadLink>& read, const std::optional<RoadLink>& written,
                 const std::string& what) {
  ASSERT_EQ(read.has_value(), written.has_value()) << what;
  if (!read) return;
  EXPECT_EQ(read->element, written->element) << what;
  EXPECT_EQ(read->id, written->id) << what;
  if (written->element == RoadLink::Element::road) {
    EXPECT_EQ(read->contact, written->contact) << what;
  }
}

TEST(OpenDriveWriter, RoundTripsThroughTheReader) {
  const RoadModel written = sample_model();
  const RoadModel read = parse_opendrive(to_xodr(written), "round trip");
  EXPECT_EQ(read.name, written.name);
  EXPECT_EQ(read.frame.crs(), written.frame.crs());
  EXPECT_NEAR((read.frame.origin() - written.frame.origin()).norm(), 0.0, 1e-9);
  ASSERT_EQ(read.roads.size(), written.roads.size());
  for (std::size_t r = 0; r < read.roads.size(); ++r) {
    const ModelRoad& a = read.roads[r];
    const ModelRoad& b = written.roads[r];
    const std::string what = "road " + std::to_string(b.id);
    EXPECT_EQ(a.id, b.id);
    EXPECT_EQ(a.name, b.name);
    EXPECT_EQ(a.junction, b.junction) << what;
    EXPECT_EQ(a.type, b.type) << what;
    ASSERT_EQ(a.speed_mps.has_value(), b.speed_mps.has_value()) << what;
    if (b.speed_mps) {
      EXPECT_NEAR(*a.speed_mps, *b.speed_mps, 1e-9) << what;
    }
    expect_link(a.predecessor, b.predecessor, what + " predecessor");
    expect_link(a.successor, b.successor, what + " successor");
    EXPECT_NEAR(a.length(), b.length(), 1e-9) << what;
    ASSERT_EQ(a.plan.records().size(), b.plan.records().size()) << what;
    for (std::size_t i = 0; i < a.plan.records().size(); ++i) {
      const PlanGeometry& x = a.plan.records()[i];
      const PlanGeometry& y = b.plan.records()[i];
      EXPECT_EQ(x.kind, y.kind) << what;
      EXPECT_NEAR(x.s, y.s, 1e-9) << what;
      EXPECT_NEAR((x.start - y.start).norm(), 0.0, 1e-9) << what;
      EXPECT_NEAR(x.heading, y.heading, 1e-9) << what;
      EXPECT_NEAR(x.length, y.length, 1e-9) << what;
      EXPECT_NEAR(x.curvature, y.curvature, 1e-9) << what;
      EXPECT_NEAR(x.curvature_start, y.curvature_start, 1e-9) << what;
      EXPECT_NEAR(x.curvature_end, y.curvature_end, 1e-9) << what;
      expect_poly(x.u, y.u, what + " u");
      expect_poly(x.v, y.v, what + " v");
      EXPECT_EQ(x.normalized, y.normalized) << what;
    }
    expect_profile(a.elevation, b.elevation, what + " elevation");
    expect_profile(a.superelevation, b.superelevation, what + " superelevation");
    // An empty lane offset is left out, so it stays empty.
    ASSERT_EQ(a.lane_offset.pieces().size(), b.lane_offset.pieces().size()) << what;
    if (!b.lane_offset.empty()) expect_profile(a.lane_offset, b.lane_offset, what + " lane offset");
    ASSERT_EQ(a.sections.size(), b.sections.size()) << what;
    for (std::size_t k = 0; k < a.sections.size(); ++k) {
      const std::string ws = what + " section " + std::to_string(k);
      EXPECT_NEAR(a.sections[k].s, b.sections[k].s, 1e-9) << ws;
      expect_lanes(a.sections[k].left, b.sections[k].left, ws);
      expect_lanes(a.sections[k].right, b.sections[k].right, ws);
      expect_mark(a.sections[k].centre_mark, b.sections[k].centre_mark, ws + " centre");
    }
  }
  ASSERT_EQ(read.junctions.size(), 1u);
  const JunctionModel& j = read.junctions[0];
  EXPECT_EQ(j.id, 100);
  EXPECT_EQ(j.name, "Main / Second");
  ASSERT_EQ(j.connections.size(), 1u);
  EXPECT_EQ(j.connections[0].id, 0);
  EXPECT_EQ(j.connections[0].incoming_road, 1);
  EXPECT_EQ(j.connections[0].connecting_road, 3);
  EXPECT_EQ(j.connections[0].contact, RoadLink::Contact::start);
  EXPECT_EQ(j.connections[0].lane_links, (std::vector<std::pair<int, int>>{{-1, -1}}));
  // The same surface: the connector's end point evaluates identically.
  const Pose2 e_read = read.roads[2].plan.at(read.roads[2].length());
  const Pose2 e_written = written.roads[2].plan.at(written.roads[2].length());
  EXPECT_NEAR((e_read.position - e_written.position).norm(), 0.0, 1e-8);
}

// ---------------------------------------------------------------------------------------------
// Errors.

TEST(OpenDriveWriter, ThrowsOnNonFiniteNumbersNamingTheRoad) {
  RoadModel model = sample_model();
  model.roads[1].elevation = CubicProfile(
      std::vector<CubicPiece>{{0.0, {12.0, std::numeric_limits<double>::quiet_NaN(), 0.0, 0.0}}});
  try {
    (void)to_xodr(model);
    FAIL() << "no exception";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("road 2"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("<elevation>"), std::string::npos) << e.what();
  }
  RoadModel inf = sample_model();
  inf.roads[0].speed_mps = std::numeric_limits<double>::infinity();
  EXPECT_THROW((void)to_xodr(inf), InvalidInput);
}

TEST(OpenDriveWriter, ThrowsOnModelsOpenDriveCannotExpress) {
  RoadModel no_plan = sample_model();
  no_plan.roads[1].plan = PlanView();
  EXPECT_THROW((void)to_xodr(no_plan), InvalidInput);

  RoadModel no_roads = sample_model();
  no_roads.roads.clear();
  no_roads.junctions.clear();
  EXPECT_THROW((void)to_xodr(no_roads), InvalidInput);

  RoadModel late_section = sample_model();
  late_section.roads[0].sections[0].s = 1.0;
  EXPECT_THROW((void)to_xodr(late_section), InvalidInput);

  RoadModel no_section = sample_model();
  no_section.roads[0].sections.clear();
  EXPECT_THROW((void)to_xodr(no_section), InvalidInput);

  RoadModel bad_lane = sample_model();
  bad_lane.roads[0].sections[0].left[0].type = "highway";
  EXPECT_THROW((void)to_xodr(bad_lane), InvalidInput);

  RoadModel wrong_side = sample_model();
  wrong_side.roads[0].sections[0].right[0].id = 3;
  EXPECT_THROW((void)to_xodr(wrong_side), InvalidInput);

  RoadModel empty_junction = sample_model();
  empty_junction.junctions[0].connections.clear();
  EXPECT_THROW((void)to_xodr(empty_junction), InvalidInput);

  OpenDriveOptions v15;
  v15.rev_minor = 5;
  EXPECT_THROW((void)to_xodr(sample_model(), v15), InvalidInput);
}

}  // namespace
}  // namespace relief

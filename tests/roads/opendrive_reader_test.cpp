#include "relief/roads/opendrive_reader.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>

#include "relief/core/errors.h"
#include "support/test_data.h"

namespace relief {
namespace {

// A file in the style of other tools: 1.4 header, no relief userData, a spiral, a deprecated
// poly3, two lane sections with several width records, km/h speeds, a junction.
constexpr const char* kForeign = R"(<?xml version="1.0" standalone="yes"?>
<OpenDRIVE>
  <header revMajor="1" revMinor="4" name="foreign" version="1.00" date="Tue Mar 1 2022" north="0" south="0" east="0" west="0">
    <geoReference><![CDATA[+proj=tmerc +lat_0=0 +lon_0=-123 +k=0.9996 +x_0=500000 +y_0=0 +datum=WGS84 +units=m +no_defs]]></geoReference>
  </header>
  <road name="Spiral Road" length="86.0" id="5" junction="-1">
    <link>
      <successor elementType="junction" elementId="9"/>
    </link>
    <type s="0.0" type="town">
      <speed max="50" unit="km/h"/>
    </type>
    <planView>
      <geometry s="0.0" x="-10.0" y="5.0" hdg="0.0" length="20.0"><line/></geometry>
      <geometry s="20.0" x="10.0" y="5.0" hdg="0.0" length="30.0"><spiral curvStart="0.0" curvEnd="0.02"/></geometry>
      <geometry s="50.0" x="39.0" y="8.0" hdg="0.3" length="16.0"><arc curvature="0.02"/></geometry>
      <geometry s="66.0" x="54.0" y="12.0" hdg="0.62" length="20.0"><poly3 a="0.0" b="0.0" c="0.01" d="-0.0002"/></geometry>
    </planView>
    <elevationProfile>
      <elevation s="0.0" a="3.0" b="0.01" c="0.0" d="0.0"/>
      <elevation s="50.0" a="3.5" b="0.01" c="0.001" d="-1e-5"/>
    </elevationProfile>
    <lateralProfile>
      <superelevation s="0.0" a="0.0" b="0.0" c="0.0" d="0.0"/>
    </lateralProfile>
    <lanes>
      <laneOffset s="0.0" a="0.5" b="0" c="0" d="0"/>
      <laneSection s="0.0">
        <left>
          <lane id="2" type="sidewalk" level="false">
            <width sOffset="0.0" a="2.0" b="0.0" c="0.0" d="0.0"/>
          </lane>
          <lane id="1" type="driving" level="false">
            <link><successor id="1"/></link>
            <width sOffset="0.0" a="3.0" b="0.0" c="0.0" d="0.0"/>
            <width sOffset="10.0" a="3.0" b="0.05" c="0.0" d="0.0"/>
            <roadMark sOffset="0.0" type="broken" weight="standard" color="standard" width="0.13"/>
          </lane>
        </left>
        <center>
          <lane id="0" type="none" level="false">
            <roadMark sOffset="0.0" type="solid solid" weight="standard" color="yellow" width="0.15"/>
          </lane>
        </center>
        <right>
          <lane id="-1" type="driving" level="false">
            <link><successor id="-1"/></link>
            <width sOffset="0.0" a="3.5" b="0.0" c="0.0" d="0.0"/>
            <roadMark sOffset="0.0" type="botts dots" color="white"/>
          </lane>
        </right>
      </laneSection>
      <laneSection s="40.0">
        <left>
          <lane id="1" type="driving" level="false">
            <link><predecessor id="1"/></link>
            <width sOffset="0.0" a="3.5" b="0.0" c="0.0" d="0.0"/>
          </lane>
        </left>
        <center><lane id="0" type="none" level="false"/></center>
        <right>
          <lane id="-2" type="shoulder" level="false">
            <width sOffset="0.0" a="1.0" b="0.0" c="0.0" d="0.0"/>
          </lane>
          <lane id="-1" type="driving" level="false">
            <link><predecessor id="-1"/></link>
            <width sOffset="20.0" a="3.0" b="0.0" c="0.0" d="0.0"/>
            <width sOffset="0.0" a="3.5" b="-0.025" c="0.0" d="0.0"/>
          </lane>
        </right>
      </laneSection>
    </lanes>
    <objects/>
    <signals/>
  </road>
  <road name="" length="12.0" id="6" junction="9">
    <link>
      <predecessor elementType="road" elementId="5" contactPoint="end"/>
    </link>
    <planView>
      <geometry s="0" x="0" y="0" hdg="0" length="12"><paramPoly3 aU="0" bU="12" cU="0" dU="0" aV="0" bV="0" cV="0" dV="0" pRange="arcLength"/></geometry>
    </planView>
    <lanes>
      <laneSection s="0">
        <center><lane id="0" type="none"/></center>
        <right><lane id="-1" type="driving"><width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane></right>
      </laneSection>
    </lanes>
  </road>
  <junction id="9" name="J">
    <connection id="0" incomingRoad="5" connectingRoad="6" contactPoint="start">
      <laneLink from="-1" to="-1"/>
    </connection>
  </junction>
</OpenDRIVE>
)";

TEST(OpenDriveReader, ReadsAForeignFile) {
  const RoadModel m = parse_opendrive(kForeign, "foreign.xodr");
  EXPECT_EQ(m.name, "foreign");
  EXPECT_EQ(m.frame.crs(),
            "+proj=tmerc +lat_0=0 +lon_0=-123 +k=0.9996 +x_0=500000 +y_0=0 +datum=WGS84 +units=m +no_defs");
  EXPECT_EQ(m.frame.origin(), Vec2::Zero());
  ASSERT_EQ(m.roads.size(), 2u);

  const ModelRoad& r = m.roads[0];
  EXPECT_EQ(r.id, 5);
  EXPECT_EQ(r.name, "Spiral Road");
  EXPECT_EQ(r.junction, -1);
  EXPECT_EQ(r.type, "town");
  ASSERT_TRUE(r.speed_mps.has_value());
  EXPECT_NEAR(*r.speed_mps, 50.0 / 3.6, 1e-12);
  EXPECT_FALSE(r.predecessor.has_value());
  ASSERT_TRUE(r.successor.has_value());
  EXPECT_EQ(r.successor->element, RoadLink::Element::junction);
  EXPECT_EQ(r.successor->id, 9);

  const auto& g = r.plan.records();
  ASSERT_EQ(g.size(), 4u);
  EXPECT_EQ(g[0].kind, PlanGeometry::Kind::line);
  EXPECT_EQ(g[0].start, Vec2(-10.0, 5.0));
  EXPECT_EQ(g[1].kind, PlanGeometry::Kind::spiral);
  EXPECT_DOUBLE_EQ(g[1].curvature_start, 0.0);
  EXPECT_DOUBLE_EQ(g[1].curvature_end, 0.02);
  EXPECT_EQ(g[2].kind, PlanGeometry::Kind::arc);
  EXPECT_DOUBLE_EQ(g[2].curvature, 0.02);
  EXPECT_DOUBLE_EQ(g[2].heading, 0.3);
  EXPECT_DOUBLE_EQ(r.length(), 86.0);

  // poly3 v(u) = 0.01 u^2 - 0.0002 u^3 becomes a normalized paramPoly3 u = U p, v = v(U p) whose
  // arc length is the record length: every point lies on the cubic, the end at arc length 20.
  const PlanGeometry& p = g[3];
  EXPECT_EQ(p.kind, PlanGeometry::Kind::param_poly3);
  EXPECT_TRUE(p.normalized);
  EXPECT_DOUBLE_EQ(p.length, 20.0);
  EXPECT_NEAR(param_poly3_length(p.u, p.v, 1.0), 20.0, 1e-9);
  const double u_end = p.u.b;
  EXPECT_GT(u_end, 19.0);
  EXPECT_LT(u_end, 20.0);
  for (const double ds : {0.0, 5.0, 12.5, 20.0}) {
    const Pose2 q = evaluate(p, ds);
    // Back into the record's local frame.
    const Vec2 d = q.position - p.start;
    const double lu = d.x() * std::cos(p.heading) + d.y() * std::sin(p.heading);
    const double lv = -d.x() * std::sin(p.heading) + d.y() * std::cos(p.heading);
    EXPECT_NEAR(lv, 0.01 * lu * lu - 0.0002 * lu * lu * lu, 1e-9) << ds;
  }

  ASSERT_EQ(r.elevation.pieces().size(), 2u);
  EXPECT_DOUBLE_EQ(r.elevation.pieces()[1].s, 50.0);
  EXPECT_DOUBLE_EQ(r.elevation.pieces()[1].poly.d, -1e-5);
  EXPECT_EQ(r.superelevation.pieces().size(), 1u);
  ASSERT_EQ(r.lane_offset.pieces().size(), 1u);
  EXPECT_DOUBLE_EQ(r.lane_offset.value(10.0), 0.5);

  ASSERT_EQ(r.sections.size(), 2u);
  const LaneSection& s0 = r.sections[0];
  EXPECT_DOUBLE_EQ(s0.s, 0.0);
  ASSERT_EQ(s0.left.size(), 2u);
  EXPECT_EQ(s0.left[0].id, 1);  // innermost first
  EXPECT_EQ(s0.left[1].id, 2);
  EXPECT_EQ(s0.left[1].type, "sidewalk");
  ASSERT_EQ(s0.left[0].width.pieces().size(), 2u);
  EXPECT_DOUBLE_EQ(s0.left[0].width.pieces()[1].s, 10.0);  // sOffset, from the section start
  EXPECT_DOUBLE_EQ(s0.left[0].width.value(20.0), 3.5);
  EXPECT_EQ(s0.left[0].successor, 1);
  EXPECT_FALSE(s0.left[0].predecessor.has_value());
  EXPECT_EQ(s0.left[0].mark.type, RoadMark::Type::broken);
  EXPECT_DOUBLE_EQ(s0.left[0].mark.width_m, 0.13);
  EXPECT_EQ(s0.left[1].mark.type, RoadMark::Type::none);  // no roadMark at all
  EXPECT_EQ(s0.centre_mark.type, RoadMark::Type::solid_solid);
  EXPECT_EQ(s0.centre_mark.color, "yellow");
  EXPECT_EQ(s0.right[0].mark.type, RoadMark::Type::broken);  // botts dots
  EXPECT_EQ(s0.right[0].mark.color, "white");
  EXPECT_DOUBLE_EQ(s0.right[0].mark.width_m, RoadMark{}.width_m);

  const LaneSection& s1 = r.sections[1];
  EXPECT_DOUBLE_EQ(s1.s, 40.0);
  ASSERT_EQ(s1.right.size(), 2u);
  EXPECT_EQ(s1.right[0].id, -1);
  EXPECT_EQ(s1.right[1].id, -2);
  EXPECT_EQ(s1.right[0].predecessor, -1);
  // Width records out of order in the file are sorted by sOffset.
  ASSERT_EQ(s1.right[0].width.pieces().size(), 2u);
  EXPECT_DOUBLE_EQ(s1.right[0].width.pieces()[0].s, 0.0);
  EXPECT_DOUBLE_EQ(s1.right[0].width.value(10.0), 3.25);
  EXPECT_DOUBLE_EQ(s1.right[0].width.value(25.0), 3.0);

  const ModelRoad& c = m.roads[1];
  EXPECT_EQ(c.id, 6);
  EXPECT_EQ(c.junction, 9);
  EXPECT_EQ(c.plan.records()[0].kind, PlanGeometry::Kind::param_poly3);
  EXPECT_FALSE(c.plan.records()[0].normalized);  // pRange="arcLength"
  EXPECT_TRUE(c.elevation.empty());
  EXPECT_FALSE(c.speed_mps.has_value());
  ASSERT_TRUE(c.predecessor.has_value());
  EXPECT_EQ(c.predecessor->element, RoadLink::Element::road);
  EXPECT_EQ(c.predecessor->id, 5);
  EXPECT_EQ(c.predecessor->contact, RoadLink::Contact::end);

  ASSERT_EQ(m.junctions.size(), 1u);
  EXPECT_EQ(m.junctions[0].id, 9);
  EXPECT_EQ(m.junctions[0].name, "J");
  ASSERT_EQ(m.junctions[0].connections.size(), 1u);
  const JunctionConnection& jc = m.junctions[0].connections[0];
  EXPECT_EQ(jc.incoming_road, 5);
  EXPECT_EQ(jc.connecting_road, 6);
  EXPECT_EQ(jc.contact, RoadLink::Contact::start);
  EXPECT_EQ(jc.lane_links, (std::vector<std::pair<int, int>>{{-1, -1}}));
}

TEST(OpenDriveReader, ReadsFromAFile) {
  const auto path = test::scratch_dir("opendrive_reader_file") / "foreign.xodr";
  std::ofstream(path) << kForeign;
  const RoadModel m = read_opendrive(path);
  EXPECT_EQ(m.roads.size(), 2u);
  EXPECT_EQ(m.junctions.size(), 1u);
}

TEST(OpenDriveReader, RestoresReliefsFrameFromItsUserData) {
  const std::string xml = R"(<OpenDRIVE><header revMajor="1" revMinor="7">
    <geoReference><![CDATA[+proj=tmerc +lat_0=0 +lon_0=-123 +k=0.9996 +x_0=-50000 +y_0=-4180000 +datum=WGS84 +units=m +no_defs]]></geoReference>
    <userData code="relief:crs" value="EPSG:32610"/><userData code="relief:origin" value="550000.000 4180000.000"/>
  </header>
  <road id="1" junction="-1" length="1"><planView><geometry s="0" x="0" y="0" hdg="0" length="1"><line/></geometry></planView>
  <lanes><laneSection s="0"><center><lane id="0" type="none"/></center></laneSection></lanes></road></OpenDRIVE>)";
  const RoadModel m = parse_opendrive(xml);
  EXPECT_EQ(m.frame.crs(), "EPSG:32610");
  EXPECT_EQ(m.frame.origin(), Vec2(550000.0, 4180000.0));
}

// The OSM records relief writes as userData (a region merged from tiles builds SUMO from them).
TEST(OpenDriveReader, RestoresOsmWaysHighwayAndTrafficLightsFromUserData) {
  const std::string xml = R"(<OpenDRIVE><header revMajor="1" revMinor="7"/>
  <road id="1" junction="-1" length="1"><planView><geometry s="0" x="0" y="0" hdg="0" length="1"><line/></geometry></planView>
  <lanes><laneSection s="0"><center><lane id="0" type="none"/></center></laneSection></lanes>
  <userData code="relief:osm_ways" value="4000000001 17"/><userData code="relief:highway" value="motorway_link"/></road>
  <road id="2" junction="-1" length="1"><planView><geometry s="0" x="0" y="0" hdg="0" length="1"><line/></geometry></planView>
  <lanes><laneSection s="0"><center><lane id="0" type="none"/></center></laneSection></lanes></road>
  <junction id="3"><connection id="0" incomingRoad="1" connectingRoad="2" contactPoint="start"/>
  <userData code="relief:traffic_signal" value="true"/></junction>
  <junction id="4"><connection id="0" incomingRoad="2" connectingRoad="1" contactPoint="start"/></junction>
  </OpenDRIVE>)";
  const RoadModel m = parse_opendrive(xml);
  ASSERT_EQ(m.roads.size(), 2u);
  EXPECT_EQ(m.roads[0].osm_way_ids, (std::vector<std::int64_t>{4000000001, 17}));
  EXPECT_EQ(m.roads[0].highway, HighwayClass::motorway_link);
  EXPECT_TRUE(m.roads[1].osm_way_ids.empty());
  EXPECT_FALSE(m.roads[1].highway.has_value());
  ASSERT_EQ(m.junctions.size(), 2u);
  EXPECT_TRUE(m.junctions[0].traffic_signal);
  EXPECT_FALSE(m.junctions[1].traffic_signal);
}

// ---------------------------------------------------------------------------------------------
// Errors.

std::string minimal_road(const std::string& inner) {
  return R"(<OpenDRIVE><header revMajor="1" revMinor="7"/><road id="7" junction="-1" length="10">)" + inner +
         "</road></OpenDRIVE>";
}

constexpr const char* kPlan =
    R"(<planView><geometry s="0" x="0" y="0" hdg="0" length="10"><line/></geometry></planView>)";
constexpr const char* kLanes =
    R"(<lanes><laneSection s="0"><center><lane id="0" type="none"/></center></laneSection></lanes>)";

// The message of the InvalidInput thrown by parsing `xml` ("" when nothing is thrown).
std::string invalid_input_message(const std::string& xml) {
  try {
    (void)parse_opendrive(xml, "test.xodr");
  } catch (const InvalidInput& e) {
    return e.what();
  }
  return {};
}

TEST(OpenDriveReader, MinimalRoadParses) {
  const RoadModel m = parse_opendrive(minimal_road(std::string(kPlan) + kLanes));
  ASSERT_EQ(m.roads.size(), 1u);
  EXPECT_DOUBLE_EQ(m.roads[0].length(), 10.0);
}

TEST(OpenDriveReader, MissingFileIsAnIoError) {
  const auto dir = test::scratch_dir("opendrive_reader_missing");
  EXPECT_THROW((void)read_opendrive(dir / "absent.xodr"), IoError);
  EXPECT_THROW((void)read_opendrive(dir), IoError);
  try {
    (void)read_opendrive(dir / "absent.xodr");
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("absent.xodr"), std::string::npos) << e.what();
  }
}

TEST(OpenDriveReader, NotXmlIsInvalidInput) {
  EXPECT_THROW((void)parse_opendrive("this is { not xml"), InvalidInput);
  EXPECT_THROW((void)parse_opendrive(""), InvalidInput);
  EXPECT_THROW((void)parse_opendrive("<OpenDRIVE><header>"), InvalidInput);
  const auto path = test::scratch_dir("opendrive_reader_not_xml") / "bad.xodr";
  std::ofstream(path) << "{\"type\": \"FeatureCollection\"}";
  try {
    (void)read_opendrive(path);
    FAIL() << "no exception";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("bad.xodr"), std::string::npos) << e.what();
  }
}

TEST(OpenDriveReader, OtherXmlIsInvalidInput) {
  EXPECT_NE(invalid_input_message("<osm version=\"0.6\"/>").find("no <OpenDRIVE>"), std::string::npos);
  EXPECT_NE(invalid_input_message("<OpenDRIVE><header/></OpenDRIVE>").find("no <road>"), std::string::npos);
}

TEST(OpenDriveReader, RoadWithoutPlanViewIsInvalidInputNamingTheRoad) {
  const std::string message = invalid_input_message(minimal_road(kLanes));
  EXPECT_NE(message.find("test.xodr"), std::string::npos) << message;
  EXPECT_NE(message.find("road 7"), std::string::npos) << message;
  EXPECT_NE(message.find("planView"), std::string::npos) << message;
  EXPECT_NE(invalid_input_message(minimal_road(std::string("<planView/>") + kLanes)).find("no geometry"),
            std::string::npos);
}

TEST(OpenDriveReader, BadNumbersAreInvalidInputNamingRoadAndElement) {
  const std::string bad_hdg =
      R"(<planView><geometry s="0" x="0" y="0" hdg="north" length="10"><line/></geometry></planView>)";
  const std::string message = invalid_input_message(minimal_road(bad_hdg + kLanes));
  EXPECT_NE(message.find("road 7"), std::string::npos) << message;
  EXPECT_NE(message.find("<geometry> attribute 'hdg'"), std::string::npos) << message;
  EXPECT_NE(message.find("north"), std::string::npos) << message;

  const std::string nan_elevation =
      std::string(kPlan) +
      R"(<elevationProfile><elevation s="0" a="nan" b="0" c="0" d="0"/></elevationProfile>)" + kLanes;
  EXPECT_NE(invalid_input_message(minimal_road(nan_elevation)).find("<elevation> attribute 'a'"),
            std::string::npos);

  const std::string missing_length =
      R"(<planView><geometry s="0" x="0" y="0" hdg="0"><line/></geometry></planView>)";
  EXPECT_NE(invalid_input_message(minimal_road(missing_length + kLanes)).find("'length' is missing"),
            std::string::npos);

  EXPECT_NE(
      invalid_input_message(R"(<OpenDRIVE><header/><road id="A1" junction="-1" length="1"/></OpenDRIVE>)")
          .find("not an integer"),
      std::string::npos);

  const std::string bad_width =
      std::string(kPlan) +
      R"(<lanes><laneSection s="0"><center><lane id="0" type="none"/></center><right>
      <lane id="-1" type="driving"><width sOffset="0" a="3,5" b="0" c="0" d="0"/></lane></right></laneSection></lanes>)";
  EXPECT_NE(invalid_input_message(minimal_road(bad_width)).find("<width> attribute 'a'"), std::string::npos);
}

TEST(OpenDriveReader, MalformedOsmRecordsAreInvalidInputNamingTheRoad) {
  const std::string ways = invalid_input_message(
      minimal_road(std::string(kPlan) + kLanes + R"(<userData code="relief:osm_ways" value="12 x"/>)"));
  EXPECT_NE(ways.find("road 7"), std::string::npos) << ways;
  EXPECT_NE(ways.find("OSM way ids"), std::string::npos) << ways;
  const std::string highway = invalid_input_message(
      minimal_road(std::string(kPlan) + kLanes + R"(<userData code="relief:highway" value="runway"/>)"));
  EXPECT_NE(highway.find("highway class"), std::string::npos) << highway;
}

TEST(OpenDriveReader, UnsupportedRecordsAreInvalidInput) {
  const std::string border = std::string(kPlan) +
                             R"(<lanes><laneSection s="0"><center><lane id="0" type="none"/></center><right>
      <lane id="-1" type="driving"><border sOffset="0" a="3.5" b="0" c="0" d="0"/></lane></right></laneSection></lanes>)";
  EXPECT_NE(invalid_input_message(minimal_road(border)).find("<border>"), std::string::npos);
  const std::string no_kind = R"(<planView><geometry s="0" x="0" y="0" hdg="0" length="10"/></planView>)";
  EXPECT_NE(invalid_input_message(minimal_road(no_kind + kLanes)).find("no line, arc"), std::string::npos);
  const std::string left_negative = std::string(kPlan) +
                                    R"(<lanes><laneSection s="0"><left><lane id="-1" type="driving"/></left>
      <center><lane id="0" type="none"/></center></laneSection></lanes>)";
  EXPECT_NE(invalid_input_message(minimal_road(left_negative)).find("not positive"), std::string::npos);
  EXPECT_NE(invalid_input_message(minimal_road(kPlan)).find("no <lanes>"), std::string::npos);
}

}  // namespace
}  // namespace relief

#include "relief/roads/way_attributes.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace relief {
namespace {

using Tags = std::map<std::string, std::string, std::less<>>;

ParsedWay parse(const Tags& tags, std::string* warnings = nullptr) {
  const auto parsed = parse_way_tags(tags, warnings);
  EXPECT_TRUE(parsed.has_value());
  return parsed.value_or(ParsedWay{});
}

TEST(ParseWayTags, TurnLanesPerDirection) {
  const ParsedWay one = parse({{"highway", "primary"},
                               {"oneway", "yes"},
                               {"lanes", "3"},
                               {"turn:lanes", "left|through| through;right"}});
  EXPECT_EQ(one.attributes.turn_forward, (std::vector<std::string>{"left", "through", "through;right"}));
  EXPECT_TRUE(one.attributes.turn_backward.empty());
  // A reversed one-way keeps turn:lanes (it describes the direction of travel).
  const ParsedWay rev =
      parse({{"highway", "primary"}, {"oneway", "-1"}, {"lanes", "2"}, {"turn:lanes", "left|"}});
  EXPECT_EQ(rev.attributes.turn_forward, (std::vector<std::string>{"left", ""}));
  // Two-way: each direction has its own tag, and its lane count must match.
  const ParsedWay two = parse({{"highway", "secondary"},
                               {"lanes:forward", "2"},
                               {"lanes:backward", "1"},
                               {"turn:lanes:forward", "left|through"},
                               {"turn:lanes:backward", "none"}});
  EXPECT_EQ(two.attributes.turn_forward.size(), 2u);
  EXPECT_EQ(two.attributes.turn_backward, (std::vector<std::string>{"none"}));
  // Without a lanes tag, turn:lanes says how many lanes there are.
  const ParsedWay implied =
      parse({{"highway", "residential"}, {"oneway", "yes"}, {"turn:lanes", "left|through|right"}});
  EXPECT_EQ(implied.attributes.lanes_forward, 3);
  EXPECT_EQ(implied.attributes.turn_forward.size(), 3u);
  std::string warnings;
  const ParsedWay bad =
      parse({{"highway", "primary"}, {"oneway", "yes"}, {"lanes", "2"}, {"turn:lanes", "left|through|right"}},
            &warnings);
  EXPECT_TRUE(bad.attributes.turn_forward.empty());
  EXPECT_NE(warnings.find("turn:lanes"), std::string::npos);
}

TEST(LaneAllows, Movements) {
  EXPECT_TRUE(lane_allows("left", "left"));
  EXPECT_FALSE(lane_allows("left", "through"));
  EXPECT_TRUE(lane_allows("through;right", "right"));
  EXPECT_TRUE(lane_allows("through;right", "through"));
  EXPECT_TRUE(lane_allows("slight_left", "left"));
  EXPECT_TRUE(lane_allows("slight_left", "through"));
  EXPECT_TRUE(lane_allows("", "through"));
  EXPECT_TRUE(lane_allows("none", "through"));
  EXPECT_FALSE(lane_allows("none", "left"));
  EXPECT_FALSE(lane_allows("reverse", "through"));
  EXPECT_TRUE(lane_allows("merge_to_left", "through"));
}

TEST(ParseSpeed, UnitsAndSymbols) {
  EXPECT_NEAR(*parse_speed_mps("25 mph"), 11.176, 1e-9);
  EXPECT_NEAR(*parse_speed_mps("25mph"), 11.176, 1e-9);
  EXPECT_NEAR(*parse_speed_mps("50"), 13.888888889, 1e-8);
  EXPECT_NEAR(*parse_speed_mps("50 km/h"), 13.888888889, 1e-8);
  EXPECT_NEAR(*parse_speed_mps(" 50 kmh "), 13.888888889, 1e-8);
  EXPECT_NEAR(*parse_speed_mps("10 knots"), 5.144444444, 1e-8);
  EXPECT_NEAR(*parse_speed_mps("7.5 mph"), 3.3528, 1e-9);
  for (const char* bad :
       {"none", "signals", "walk", "US:urban", "", "fast", "0", "-30", "30 mps", "25 mph;35 mph"}) {
    EXPECT_FALSE(parse_speed_mps(bad).has_value()) << bad;
  }
}

TEST(ParseLength, MetresFeetInches) {
  EXPECT_DOUBLE_EQ(*parse_length_m("3.5"), 3.5);
  EXPECT_DOUBLE_EQ(*parse_length_m("3.5 m"), 3.5);
  EXPECT_DOUBLE_EQ(*parse_length_m("7m"), 7.0);
  EXPECT_NEAR(*parse_length_m("12'"), 3.6576, 1e-12);
  EXPECT_NEAR(*parse_length_m("12 ft"), 3.6576, 1e-12);
  EXPECT_NEAR(*parse_length_m("12'6\""), 3.81, 1e-12);
  for (const char* bad : {"wide", "", "3,5", "12'6", "-3", "3.5 furlongs"}) {
    EXPECT_FALSE(parse_length_m(bad).has_value()) << bad;
  }
}

TEST(ParseWayTags, UnmodelledHighwayOrNoHighwayIsNullopt) {
  EXPECT_FALSE(parse_way_tags({{"highway", "construction"}}).has_value());
  EXPECT_FALSE(parse_way_tags({{"highway", "platform"}}).has_value());
  EXPECT_FALSE(parse_way_tags({{"building", "yes"}}).has_value());
  EXPECT_TRUE(parse_way_tags({{"highway", "footway"}}).has_value());  // the reader filters those
}

TEST(ParseWayTags, ClassDefaults) {
  const ParsedWay w = parse({{"highway", "residential"}, {"name", "Vermont Street"}});
  EXPECT_EQ(w.attributes.highway, HighwayClass::residential);
  EXPECT_FALSE(w.reversed);
  EXPECT_FALSE(w.attributes.oneway);
  EXPECT_EQ(w.attributes.lanes_forward, 1);
  EXPECT_EQ(w.attributes.lanes_backward, 1);
  EXPECT_FALSE(w.attributes.lanes_tagged);
  EXPECT_DOUBLE_EQ(w.attributes.lane_width_m, 3.0);
  EXPECT_FALSE(w.attributes.width_tagged);
  EXPECT_FALSE(w.attributes.bridge);
  EXPECT_FALSE(w.attributes.tunnel);
  EXPECT_EQ(w.attributes.layer, 0);
  EXPECT_FALSE(w.attributes.maxspeed_mps.has_value());
  EXPECT_EQ(w.attributes.name, "Vermont Street");
  EXPECT_FALSE(w.attributes.roundabout);
}

struct OnewayRow {
  Tags tags;
  bool oneway;
  bool reversed;
  int forward;
  int backward;
};

TEST(ParseWayTags, OnewayAndLanesTable) {
  const OnewayRow rows[] = {
      {{{"highway", "residential"}, {"oneway", "yes"}}, true, false, 1, 0},
      {{{"highway", "residential"}, {"oneway", "true"}}, true, false, 1, 0},
      {{{"highway", "residential"}, {"oneway", "1"}}, true, false, 1, 0},
      {{{"highway", "residential"}, {"oneway", "-1"}}, true, true, 1, 0},
      {{{"highway", "residential"}, {"oneway", "reverse"}}, true, true, 1, 0},
      {{{"highway", "residential"}, {"oneway", "no"}}, false, false, 1, 1},
      {{{"highway", "primary"}}, false, false, 2, 2},
      // Motorways and roundabouts are one-way unless tagged otherwise.
      {{{"highway", "motorway"}}, true, false, 2, 0},
      {{{"highway", "motorway"}, {"oneway", "no"}}, false, false, 2, 2},
      {{{"highway", "secondary"}, {"junction", "roundabout"}}, true, false, 1, 0},
      {{{"highway", "secondary"}, {"junction", "roundabout"}, {"oneway", "no"}}, false, false, 1, 1},
      // lanes: one-way -> all forward; two-way -> split, odd lane forward.
      {{{"highway", "primary"}, {"lanes", "3"}, {"oneway", "yes"}}, true, false, 3, 0},
      {{{"highway", "primary"}, {"lanes", "3"}}, false, false, 2, 1},
      {{{"highway", "primary"}, {"lanes", "4"}}, false, false, 2, 2},
      {{{"highway", "residential"}, {"lanes", "1"}}, false, false, 1, 1},
      {{{"highway", "residential"}, {"lanes", "2"}}, false, false, 1, 1},
      // lanes:forward / lanes:backward win; a missing one comes from the total.
      {{{"highway", "primary"}, {"lanes", "5"}, {"lanes:forward", "3"}, {"lanes:backward", "2"}},
       false,
       false,
       3,
       2},
      {{{"highway", "primary"}, {"lanes", "5"}, {"lanes:forward", "2"}}, false, false, 2, 3},
      {{{"highway", "residential"}, {"lanes:backward", "2"}}, false, false, 1, 2},
      // oneway=-1: the way is reversed, so its backward lanes are our forward lanes.
      {{{"highway", "primary"}, {"oneway", "-1"}, {"lanes:backward", "3"}, {"lanes:forward", "1"}},
       true,
       true,
       3,
       0},
      {{{"highway", "primary"}, {"oneway", "-1"}, {"lanes", "2"}}, true, true, 2, 0},
      // Bad lane counts fall back to defaults.
      {{{"highway", "secondary"}, {"lanes", "two"}}, false, false, 1, 1},
      {{{"highway", "secondary"}, {"lanes", "0"}}, false, false, 1, 1},
  };
  for (const auto& r : rows) {
    std::string trace;
    for (const auto& [k, v] : r.tags) trace += k + "=" + v + " ";
    SCOPED_TRACE(trace);
    const ParsedWay w = parse(r.tags);
    EXPECT_EQ(w.attributes.oneway, r.oneway);
    EXPECT_EQ(w.reversed, r.reversed);
    EXPECT_EQ(w.attributes.lanes_forward, r.forward);
    EXPECT_EQ(w.attributes.lanes_backward, r.backward);
  }
}

TEST(ParseWayTags, LanesTaggedFlag) {
  EXPECT_TRUE(parse({{"highway", "primary"}, {"lanes", "3"}}).attributes.lanes_tagged);
  EXPECT_TRUE(parse({{"highway", "primary"}, {"lanes:forward", "1"}}).attributes.lanes_tagged);
  EXPECT_FALSE(parse({{"highway", "primary"}, {"lanes", "x"}}).attributes.lanes_tagged);
}

TEST(ParseWayTags, WidthGivesLaneWidth) {
  const ParsedWay two_way = parse({{"highway", "residential"}, {"width", "7"}});
  EXPECT_DOUBLE_EQ(two_way.attributes.lane_width_m, 3.5);
  EXPECT_TRUE(two_way.attributes.width_tagged);

  const ParsedWay three =
      parse({{"highway", "primary"}, {"lanes", "3"}, {"oneway", "yes"}, {"width", "10.5 m"}});
  EXPECT_DOUBLE_EQ(three.attributes.lane_width_m, 3.5);

  const ParsedWay feet = parse({{"highway", "residential"}, {"width", "24'"}});
  EXPECT_NEAR(feet.attributes.lane_width_m, 3.6576, 1e-12);

  // 30 m over two lanes is 15 m per lane: implausible, ignored with a warning.
  std::string warnings;
  const ParsedWay wide = parse({{"highway", "residential"}, {"width", "30"}}, &warnings);
  EXPECT_DOUBLE_EQ(wide.attributes.lane_width_m, 3.0);
  EXPECT_FALSE(wide.attributes.width_tagged);
  EXPECT_NE(warnings.find("width='30'"), std::string::npos) << warnings;

  warnings.clear();
  const ParsedWay bad = parse({{"highway", "service"}, {"width", "wide"}}, &warnings);
  EXPECT_DOUBLE_EQ(bad.attributes.lane_width_m, 2.75);
  EXPECT_NE(warnings.find("width='wide'"), std::string::npos) << warnings;
}

TEST(ParseWayTags, MaxspeedMphAndKmh) {
  EXPECT_NEAR(*parse({{"highway", "residential"}, {"maxspeed", "25 mph"}}).attributes.maxspeed_mps, 11.176,
              1e-9);
  EXPECT_NEAR(*parse({{"highway", "residential"}, {"maxspeed", "50"}}).attributes.maxspeed_mps, 50 / 3.6,
              1e-9);
  std::string warnings;
  EXPECT_FALSE(
      parse({{"highway", "residential"}, {"maxspeed", "US:urban"}}, &warnings).attributes.maxspeed_mps);
  EXPECT_TRUE(warnings.empty()) << warnings;
  EXPECT_FALSE(parse({{"highway", "residential"}, {"maxspeed", "fast"}}, &warnings).attributes.maxspeed_mps);
  EXPECT_NE(warnings.find("maxspeed='fast'"), std::string::npos) << warnings;
}

TEST(ParseWayTags, Layer) {
  EXPECT_EQ(parse({{"highway", "residential"}, {"layer", "1"}}).attributes.layer, 1);
  EXPECT_EQ(parse({{"highway", "residential"}, {"layer", "-2"}}).attributes.layer, -2);
  EXPECT_EQ(parse({{"highway", "residential"}, {"layer", "+1"}}).attributes.layer, 1);
  std::string warnings;
  EXPECT_EQ(parse({{"highway", "residential"}, {"layer", "1.5"}}, &warnings).attributes.layer, 0);
  EXPECT_NE(warnings.find("layer='1.5'"), std::string::npos) << warnings;
  warnings.clear();
  EXPECT_EQ(parse({{"highway", "residential"}, {"layer", "high"}}, &warnings).attributes.layer, 0);
  EXPECT_FALSE(warnings.empty());
}

TEST(ParseWayTags, BridgeAndTunnel) {
  EXPECT_TRUE(parse({{"highway", "motorway"}, {"bridge", "yes"}}).attributes.bridge);
  EXPECT_TRUE(parse({{"highway", "motorway"}, {"bridge", "viaduct"}}).attributes.bridge);
  EXPECT_FALSE(parse({{"highway", "motorway"}, {"bridge", "no"}}).attributes.bridge);
  EXPECT_TRUE(parse({{"highway", "primary"}, {"tunnel", "yes"}}).attributes.tunnel);
  EXPECT_TRUE(parse({{"highway", "secondary"}, {"tunnel", "building_passage"}}).attributes.tunnel);
  EXPECT_FALSE(parse({{"highway", "secondary"}, {"tunnel", "no"}}).attributes.tunnel);
  EXPECT_FALSE(parse({{"highway", "secondary"}, {"tunnel", "no"}}).attributes.bridge);
}

TEST(ParseWayTags, Roundabout) {
  EXPECT_TRUE(parse({{"highway", "primary"}, {"junction", "roundabout"}}).attributes.roundabout);
  EXPECT_TRUE(parse({{"highway", "primary"}, {"junction", "circular"}}).attributes.roundabout);
  EXPECT_FALSE(parse({{"highway", "primary"}, {"junction", "yes"}}).attributes.roundabout);
}

TEST(ParseWayTags, GoodTagsGiveNoWarnings) {
  std::string warnings;
  (void)parse({{"highway", "primary"},
               {"lanes", "4"},
               {"width", "14"},
               {"layer", "1"},
               {"maxspeed", "35 mph"},
               {"oneway", "no"},
               {"bridge", "yes"}},
              &warnings);
  EXPECT_TRUE(warnings.empty()) << warnings;
}

}  // namespace
}  // namespace relief

#include "relief/roads/highway_class.h"

#include <gtest/gtest.h>

#include <string>

namespace relief {
namespace {

constexpr double kMph = 0.44704;

TEST(HighwayClass, ParsesEveryModelledValueAndRoundTrips) {
  const char* values[] = {"motorway",     "motorway_link", "trunk",          "trunk_link",    "primary",
                          "primary_link", "secondary",     "secondary_link", "tertiary",      "tertiary_link",
                          "unclassified", "residential",   "service",        "living_street", "pedestrian",
                          "track",        "footway",       "path",           "cycleway",      "steps",
                          "bridleway"};
  int expected = 0;
  for (const char* value : values) {
    const auto cls = parse_highway_class(value);
    ASSERT_TRUE(cls.has_value()) << value;
    EXPECT_EQ(static_cast<int>(*cls), expected++) << value;
    EXPECT_EQ(to_string(*cls), value);
  }
  EXPECT_EQ(parse_highway_class("residential"), HighwayClass::residential);
}

TEST(HighwayClass, UnmodelledValuesAreNullopt) {
  for (const char* value :
       {"construction", "proposed", "platform", "bus_stop", "elevator", "corridor", "raceway", "road",
        "crossing", "traffic_signals", "", "Residential", " residential"}) {
    EXPECT_FALSE(parse_highway_class(value).has_value()) << "'" << value << "'";
  }
}

TEST(HighwayClass, MotorRoadsAreMotorwayToLivingStreet) {
  EXPECT_TRUE(is_motor_road(HighwayClass::motorway));
  EXPECT_TRUE(is_motor_road(HighwayClass::tertiary_link));
  EXPECT_TRUE(is_motor_road(HighwayClass::service));
  EXPECT_TRUE(is_motor_road(HighwayClass::living_street));
  EXPECT_FALSE(is_motor_road(HighwayClass::pedestrian));
  EXPECT_FALSE(is_motor_road(HighwayClass::footway));
  EXPECT_FALSE(is_motor_road(HighwayClass::track));
  EXPECT_FALSE(is_motor_road(HighwayClass::bridleway));
}

struct DefaultsRow {
  HighwayClass cls;
  int lanes;
  double width_m;
  double speed_mps;
};

TEST(HighwayClass, Defaults) {
  const DefaultsRow rows[] = {
      {HighwayClass::motorway, 2, 3.65, 65 * kMph},      {HighwayClass::trunk, 2, 3.5, 45 * kMph},
      {HighwayClass::primary, 2, 3.5, 35 * kMph},        {HighwayClass::secondary, 1, 3.25, 30 * kMph},
      {HighwayClass::tertiary, 1, 3.25, 25 * kMph},      {HighwayClass::motorway_link, 1, 3.5, 25 * kMph},
      {HighwayClass::primary_link, 1, 3.5, 25 * kMph},   {HighwayClass::unclassified, 1, 3.0, 25 * kMph},
      {HighwayClass::residential, 1, 3.0, 25 * kMph},    {HighwayClass::service, 1, 2.75, 15 * kMph},
      {HighwayClass::living_street, 1, 2.75, 10 * kMph}, {HighwayClass::footway, 1, 1.5, 5 / 3.6},
      {HighwayClass::cycleway, 1, 1.5, 5 / 3.6},
  };
  for (const auto& r : rows) {
    SCOPED_TRACE(std::string(to_string(r.cls)));
    EXPECT_EQ(default_lanes_per_direction(r.cls), r.lanes);
    EXPECT_DOUBLE_EQ(default_lane_width_m(r.cls), r.width_m);
    EXPECT_NEAR(default_speed_mps(r.cls), r.speed_mps, 1e-12);
  }
  EXPECT_NEAR(default_speed_mps(HighwayClass::motorway), 29.0576, 1e-9);
}

}  // namespace
}  // namespace relief

// The text forms of BuildOptions' values.
#include "relief/pipeline/option_text.h"

#include <gtest/gtest.h>

#include "relief/core/errors.h"

namespace relief {
namespace {

TEST(OptionText, FiniteNumbersOnly) {
  EXPECT_EQ(parse_finite_number("12"), 12.0);
  EXPECT_EQ(parse_finite_number("-2.5"), -2.5);
  EXPECT_EQ(parse_finite_number("1e3"), 1000.0);
  for (const char* bad : {"", "12 %", "abc", "nan", "inf", "-inf", "1e999"}) {
    EXPECT_FALSE(parse_finite_number(bad)) << bad;
  }
}

TEST(OptionText, ListsSplitLikeGetline) {
  EXPECT_EQ(split_list("a,,b"), (std::vector<std::string>{"a", "", "b"}));
  EXPECT_EQ(split_list("a,"), (std::vector<std::string>{"a"}));
  EXPECT_TRUE(split_list("").empty());
}

TEST(OptionText, Outputs) {
  EXPECT_EQ(parse_outputs("all"), BuildOptions{}.outputs);  // "all" is the library's default
  EXPECT_EQ(parse_outputs("xodr,report"), (std::set<Output>{Output::xodr, Output::report}));
  EXPECT_TRUE(parse_outputs("").empty());
  EXPECT_THROW((void)parse_outputs("xodr,pdf"), OptionError);
  EXPECT_THROW((void)parse_outputs("xodr,all"), OptionError);  // "all" stands alone
  try {
    (void)parse_outputs("xodr,pdf");
  } catch (const OptionError& e) {
    EXPECT_STREQ(e.what(), "'pdf' is not one of xodr, sumo, mesh, sight, view, geojson, report, html, all");
  }
}

TEST(OptionText, MeshFormats) {
  EXPECT_EQ(parse_mesh_formats("glb,obj,fbx"), BuildOptions{}.mesh_formats);
  EXPECT_EQ(parse_mesh_formats("obj"), std::set<MeshFormat>{MeshFormat::obj});
  EXPECT_THROW((void)parse_mesh_formats("glb,stl"), OptionError);
  EXPECT_EQ(parse_mesh_formats("glb,"), std::set<MeshFormat>{MeshFormat::glb});  // as getline splits
}

TEST(OptionText, VclassMaxGrade) {
  std::map<std::string, double> grades = SumoOptions{}.max_grade_percent;
  apply_vclass_max_grade(grades, "truck=12.5");
  apply_vclass_max_grade(grades, "passenger=30");
  apply_vclass_max_grade(grades, "bus=none");
  EXPECT_EQ(grades.at("truck"), 12.5);
  EXPECT_EQ(grades.at("passenger"), 30.0);
  EXPECT_FALSE(grades.contains("bus"));
  EXPECT_EQ(grades.at("trailer"), 10.0);  // untouched default
  const auto before = grades;
  for (const char* bad :
       {"truck", "=15", "truck=abc", "truck=0", "truck=-5", "truck=nan", "truck=inf", "truck="}) {
    EXPECT_THROW(apply_vclass_max_grade(grades, bad), OptionError) << bad;
  }
  EXPECT_EQ(grades, before);
}

TEST(OptionText, GateThresholds) {
  GateThresholds gates;
  apply_gate_threshold(gates, "ground_holes=3");
  apply_gate_threshold(gates, "sumo_lane_z_max_m=0.2");
  EXPECT_EQ(gates.ground_holes, 3.0);
  EXPECT_EQ(gates.sumo_lane_z_max_m, 0.2);
  for (const char* bad : {"ground_holes", "ground_holes=", "ground_holes=nan", "ground_holes=1x", "=1"}) {
    EXPECT_THROW(apply_gate_threshold(gates, bad), OptionError) << bad;
  }
  try {
    apply_gate_threshold(gates, "no_such_gate=1");
    ADD_FAILURE() << "unknown gate accepted";
  } catch (const OptionError& e) {
    EXPECT_STREQ(e.what(), "'no_such_gate' is not a quality gate");
  }
  EXPECT_EQ(gates.ground_holes, 3.0);
}

TEST(OptionText, LonLatBox) {
  const LonLatBox b = parse_lon_lat_box("-122.41,37.75,-122.39,37.76");
  EXPECT_EQ(b.min_lon, -122.41);
  EXPECT_EQ(b.min_lat, 37.75);
  EXPECT_EQ(b.max_lon, -122.39);
  EXPECT_EQ(b.max_lat, 37.76);
  for (const char* bad :
       {"1,2,3", "1,2,3,4,5", "3,2,1,4", "1,4,3,2", "-181,0,0,1", "0,0,1,91", "a,b,c,d", "nan,0,1,1", ""}) {
    EXPECT_THROW((void)parse_lon_lat_box(bad), OptionError) << bad;
  }
}

}  // namespace
}  // namespace relief

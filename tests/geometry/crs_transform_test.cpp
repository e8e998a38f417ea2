#include "relief/geometry/crs_transform.h"

#include <gtest/gtest.h>

#include <cmath>

#include "relief/core/errors.h"

namespace relief {
namespace {

TEST(CrsTransform, Wgs84ToUtmKnownPoint) {
  // lon -123 is the central meridian of zone 10: easting exactly 500 km.
  const CrsTransform t("EPSG:4326", "EPSG:32610");
  const Vec2 p = t.apply(Vec2(-123.0, 37.75));
  EXPECT_NEAR(p.x(), 500000.0, 1e-6);
  EXPECT_NEAR(p.y(), 4178000.0, 2000.0);
  const Vec2 back = t.apply_inverse(p);
  EXPECT_NEAR(back.x(), -123.0, 1e-9);
  EXPECT_NEAR(back.y(), 37.75, 1e-9);
  EXPECT_EQ(t.accuracy_m().value_or(-1.0), 0.0);
}

TEST(CrsTransform, AxisOrderIsLonLatEvenForGeographicCrs) {
  // EPSG:4269 (NAD83) officially has lat/lon order; relief always uses x = lon.
  const CrsTransform t("EPSG:32610", "EPSG:4269");
  const Vec2 p = t.apply(Vec2(552000.0, 4178500.0));
  EXPECT_NEAR(p.x(), -122.40, 0.02);
  EXPECT_NEAR(p.y(), 37.75, 0.02);
}

TEST(CrsTransform, BatchMatchesSinglePoints) {
  const CrsTransform t("EPSG:4326", "EPSG:32610");
  std::vector<Vec2> pts{{-122.40, 37.75}, {-122.41, 37.76}, {-122.39, 37.80}};
  const std::vector<Vec2> original = pts;
  t.apply(pts);
  for (std::size_t i = 0; i < pts.size(); ++i) EXPECT_NEAR((pts[i] - t.apply(original[i])).norm(), 0.0, 1e-9);
}

TEST(CrsTransform, Nad27DatumShiftIsApplied) {
  // NAD27 and WGS84 UTM coordinates of one place differ by ~100 m east and ~200 m north in SF;
  // a transformation that ignored the datum would leave them equal.
  const LonLatBox sf{-122.45, 37.74, -122.38, 37.81};
  const CrsTransform t("EPSG:32610", "EPSG:26710", sf);
  const Vec2 wgs(552000.0, 4178500.0);
  const Vec2 nad27 = t.apply(wgs);
  const Vec2 shift = nad27 - wgs;
  EXPECT_GT(shift.norm(), 150.0);
  EXPECT_LT(shift.norm(), 260.0);
  EXPECT_FALSE(t.operation_name().empty());
  std::cout << "NAD27 shift at Potrero: " << shift.transpose() << " m via '" << t.operation_name()
            << "', accuracy " << t.accuracy_m().value_or(-1) << " m"
            << (t.better_operation_missing_grid() ? ", missing grid " + t.missing_grids() : "") << "\n";
}

TEST(CrsTransform, TransformBoundsContainsCorners) {
  const CrsTransform t("EPSG:4326", "EPSG:32610");
  Aabb2 box;
  box.extend(Vec2(-122.41, 37.75));
  box.extend(Vec2(-122.39, 37.76));
  const Aabb2 out = t.transform_bounds(box);
  for (const Vec2& c : {Vec2(-122.41, 37.75), Vec2(-122.39, 37.76), Vec2(-122.41, 37.76)}) {
    EXPECT_TRUE(out.inflated(1e-6).contains(t.apply(c)));
  }
}

TEST(CrsTransform, Errors) {
  EXPECT_THROW(CrsTransform("EPSG:4326", "not a crs"), ProjectionError);
  const CrsTransform t("EPSG:4326", "EPSG:32610");
  EXPECT_THROW((void)t.apply(Vec2(std::nan(""), 0.0)), ProjectionError);
  EXPECT_EQ(crs_identifier("EPSG:26710"), "EPSG:26710");
}

}  // namespace
}  // namespace relief

#include "relief/geometry/geo_frame.h"

#include <gtest/gtest.h>

#include "relief/core/errors.h"
#include "relief/geometry/crs_transform.h"

namespace relief {
namespace {

TEST(GeoFrame, UtmZoneFromLongitude) {
  EXPECT_EQ(utm_epsg_for({-122.4, 37.75}), 32610);
  EXPECT_EQ(utm_epsg_for({2.35, 48.85}), 32631);
  EXPECT_EQ(utm_epsg_for({151.2, -33.9}), 32756);
  EXPECT_EQ(utm_epsg_for({180.0, 0.0}), 32660);
}

TEST(GeoFrame, OriginIsTheRoundedProjectedCentre) {
  const GeoFrame f = GeoFrame::utm_at({-122.3993, 37.7533});
  EXPECT_EQ(f.crs(), "EPSG:32610");
  // Potrero Hill lies near E 552 km, N 4178 km in UTM 10N.
  EXPECT_NEAR(f.origin().x(), 552000.0, 1500.0);
  EXPECT_NEAR(f.origin().y(), 4178500.0, 1500.0);
  EXPECT_EQ(f.origin().x(), std::round(f.origin().x()));
}

TEST(GeoFrame, ProjStringMapsLocalCoordinatesBackToLonLat) {
  const GeoFrame f = GeoFrame::utm_at({-122.3993, 37.7533});
  const CrsTransform to_local("EPSG:4326", f.proj_string());
  const CrsTransform to_utm("EPSG:4326", f.crs());
  const Vec2 lonlat(-122.40, 37.754);
  const Vec2 via_proj_string = to_local.apply(lonlat);
  const Vec2 via_frame = f.to_local(to_utm.apply(lonlat));
  EXPECT_NEAR(via_proj_string.x(), via_frame.x(), 1e-3);
  EXPECT_NEAR(via_proj_string.y(), via_frame.y(), 1e-3);
  EXPECT_LT(via_frame.norm(), 2000.0);
}

TEST(GeoFrame, ProjStringOfANonUtmCrsShiftsFalseOrigin) {
  // California zone 3 state plane (metres): the origin is folded into x_0 / y_0.
  const GeoFrame f = GeoFrame::in_crs("EPSG:26943", {-122.40, 37.75});
  const CrsTransform to_local("EPSG:4326", f.proj_string());
  const CrsTransform to_crs("EPSG:4326", f.crs());
  const Vec2 lonlat(-122.41, 37.76);
  EXPECT_NEAR((to_local.apply(lonlat) - f.to_local(to_crs.apply(lonlat))).norm(), 0.0, 1e-3);
}

TEST(GeoFrame, ProjStringOfANad83UtmFrameKeepsItsDatumAndOrigin) {
  // PROJ's utm ignores x_0: the frame must come out as tmerc with the origin folded in.
  const GeoFrame f = GeoFrame::in_crs("EPSG:26910", {-122.40, 37.75});
  const std::string text = f.proj_string();
  EXPECT_NE(text.find("+proj=tmerc"), std::string::npos) << text;
  EXPECT_NE(text.find("NAD83"), std::string::npos) << text;
  const CrsTransform to_local("EPSG:4326", text);
  const CrsTransform to_crs("EPSG:4326", f.crs());
  const Vec2 lonlat(-122.41, 37.76);
  EXPECT_NEAR((to_local.apply(lonlat) - f.to_local(to_crs.apply(lonlat))).norm(), 0.0, 1e-3);
}

TEST(GeoFrame, UnknownCrsThrowsProjectionError) {
  EXPECT_THROW((void)GeoFrame::in_crs("EPSG:999999", {-122.4, 37.75}), ProjectionError);
}

}  // namespace
}  // namespace relief

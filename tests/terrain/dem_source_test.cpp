#include "relief/terrain/dem_source.h"

#include <gtest/gtest.h>

#include <fstream>

#include "relief/core/errors.h"
#include "relief/terrain/dem_sampler.h"
#include "relief/terrain/dem_writer.h"
#include "support/test_data.h"

namespace relief {
namespace {

TEST(VerticalUnit, MetresPerUnit) {
  EXPECT_EQ(metres_per_unit(VerticalUnit::metre), 1.0);
  EXPECT_EQ(metres_per_unit(VerticalUnit::foot), 0.3048);
  EXPECT_NEAR(metres_per_unit(VerticalUnit::us_survey_foot), 0.3048006096012192, 1e-15);
}

TEST(VerticalUnit, PrintsAndParses) {
  for (auto unit : {VerticalUnit::metre, VerticalUnit::foot, VerticalUnit::us_survey_foot}) {
    EXPECT_EQ(parse_vertical_unit(to_string(unit)), unit);
  }
  EXPECT_EQ(to_string(VerticalUnit::metre), "m");
  EXPECT_EQ(to_string(VerticalUnit::foot), "ft");
  EXPECT_EQ(to_string(VerticalUnit::us_survey_foot), "us-ft");
  EXPECT_EQ(parse_vertical_unit("Metre"), VerticalUnit::metre);
  EXPECT_EQ(parse_vertical_unit("meter"), VerticalUnit::metre);
  EXPECT_EQ(parse_vertical_unit(" m "), VerticalUnit::metre);
  EXPECT_EQ(parse_vertical_unit("FT"), VerticalUnit::foot);
  EXPECT_EQ(parse_vertical_unit("foot"), VerticalUnit::foot);
  EXPECT_EQ(parse_vertical_unit("feet"), VerticalUnit::foot);
  EXPECT_EQ(parse_vertical_unit("US survey foot"), VerticalUnit::us_survey_foot);
  EXPECT_EQ(parse_vertical_unit("us_survey_foot"), VerticalUnit::us_survey_foot);
  EXPECT_EQ(parse_vertical_unit("US-FT"), VerticalUnit::us_survey_foot);
  EXPECT_FALSE(parse_vertical_unit("furlong"));
  EXPECT_FALSE(parse_vertical_unit(""));
}

TEST(Interpolation, PrintsAndParses) {
  for (auto method : {Interpolation::bilinear, Interpolation::idw, Interpolation::nearest}) {
    EXPECT_EQ(parse_interpolation(to_string(method)), method);
  }
  EXPECT_EQ(to_string(Interpolation::idw), "idw");
  EXPECT_EQ(parse_interpolation("Bilinear"), Interpolation::bilinear);
  EXPECT_FALSE(parse_interpolation("cubic"));
}

TEST(InspectDem, ReportsGridCrsUnitAndNodata) {
  const auto dir = test::scratch_dir("inspect_dem_projected");
  DemGrid grid = make_dem_grid("EPSG:32610", 550000.0, 4180000.0, 10.0, 20.0, 30, 10,
                               [](double, double) { return 1.0; });
  grid.nodata = -9999.0;
  grid.unit_type = "ft";
  const auto path = (dir / "g.tif").string();
  write_geotiff(path, grid);

  const DemInfo info = inspect_dem(path);
  EXPECT_EQ(info.path, path);
  EXPECT_EQ(info.crs, "EPSG:32610");
  EXPECT_NE(info.crs_wkt.find("UTM zone 10N"), std::string::npos);
  EXPECT_EQ(info.width, 30);
  EXPECT_EQ(info.height, 10);
  EXPECT_EQ(info.pixel_size, Vec2(10.0, 20.0));
  EXPECT_EQ(info.extent.min, Vec2(550000.0, 4179800.0));
  EXPECT_EQ(info.extent.max, Vec2(550300.0, 4180000.0));
  ASSERT_TRUE(info.extent_wgs84);
  EXPECT_NEAR(info.extent_wgs84->min_lon, -122.43, 0.01);
  EXPECT_NEAR(info.extent_wgs84->min_lat, 37.77, 0.01);
  EXPECT_EQ(info.nodata, -9999.0);
  EXPECT_EQ(info.unit, VerticalUnit::foot);
  EXPECT_TRUE(info.unit_from_metadata);
  EXPECT_FALSE(info.unit_stated_by_user);
  EXPECT_EQ(info.scale, 1.0);
  EXPECT_EQ(info.offset, 0.0);
  EXPECT_TRUE(info.transform_name.empty());  // depends on a frame: filled by DemSampler

  DemOptions options;
  options.unit = VerticalUnit::metre;
  const DemInfo stated = inspect_dem(path, options);
  EXPECT_EQ(stated.unit, VerticalUnit::metre);
  EXPECT_TRUE(stated.unit_stated_by_user);
  EXPECT_FALSE(stated.unit_from_metadata);
}

TEST(InspectDem, GeographicRaster) {
  const auto dir = test::scratch_dir("inspect_dem_geographic");
  const DemGrid grid =
      make_dem_grid("EPSG:4269", -122.41, 37.76, 0.001, 0.001, 10, 10, [](double, double) { return 1.0; });
  const auto path = (dir / "g.tif").string();
  write_geotiff(path, grid);
  const DemInfo info = inspect_dem(path);
  EXPECT_EQ(info.crs, "EPSG:4269");
  EXPECT_NEAR(info.pixel_size.x(), 0.001, 1e-12);
  EXPECT_NEAR(info.extent.min.x(), -122.41, 1e-9);
  EXPECT_NEAR(info.extent.min.y(), 37.75, 1e-9);
  ASSERT_TRUE(info.extent_wgs84);  // NAD83 ~ WGS84 to within a few metres
  EXPECT_NEAR(info.extent_wgs84->max_lon, -122.40, 1e-4);
  EXPECT_NEAR(info.extent_wgs84->max_lat, 37.76, 1e-4);
  EXPECT_FALSE(info.nodata);
  EXPECT_EQ(info.unit, VerticalUnit::metre);
  EXPECT_FALSE(info.unit_from_metadata);
}

TEST(InspectDem, MissingFileIsIoError) {
  const auto dir = test::scratch_dir("inspect_dem_missing");
  EXPECT_THROW((void)inspect_dem((dir / "absent.tif").string()), IoError);
}

TEST(InspectDem, TextFileIsInvalidInput) {
  const auto dir = test::scratch_dir("inspect_dem_text");
  const auto path = dir / "notes.tif";
  std::ofstream(path) << "not a raster at all\n";
  EXPECT_THROW((void)inspect_dem(path.string()), InvalidInput);
}

TEST(InspectDem, RasterWithoutCrsIsInvalidInput) {
  const auto dir = test::scratch_dir("inspect_dem_no_crs");
  const auto path = dir / "grid.asc";  // ESRI ASCII grid: a geotransform, no CRS without a .prj
  std::ofstream(path) << "ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 2\n3 4\n";
  EXPECT_THROW((void)inspect_dem(path.string()), InvalidInput);
  try {
    (void)inspect_dem(path.string());
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("no coordinate reference system"), std::string::npos) << e.what();
  }
}

TEST(InspectDem, RasterWithoutGeotransformIsInvalidInput) {
  const auto dir = test::scratch_dir("inspect_dem_no_geotransform");
  const auto path = dir / "image.pgm";  // a plain greyscale image
  std::ofstream(path, std::ios::binary) << "P5\n2 2\n255\n" << std::string("\x01\x02\x03\x04", 4);
  EXPECT_THROW((void)inspect_dem(path.string()), InvalidInput);
  try {
    (void)inspect_dem(path.string());
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("not georeferenced"), std::string::npos) << e.what();
  }
}

TEST(InspectDem, UnknownUnitTypeIsInvalidInputUnlessTheUserStatesTheUnit) {
  const auto dir = test::scratch_dir("inspect_dem_unit");
  DemGrid grid =
      make_dem_grid("EPSG:32610", 550000.0, 4180000.0, 10.0, 10.0, 2, 2, [](double, double) { return 1.0; });
  grid.unit_type = "furlong";
  const auto path = (dir / "g.tif").string();
  write_geotiff(path, grid);
  EXPECT_THROW((void)inspect_dem(path), InvalidInput);
  DemOptions options;
  options.unit = VerticalUnit::foot;
  EXPECT_EQ(inspect_dem(path, options).unit, VerticalUnit::foot);
}

TEST(InspectDemRealData, SharedRasters) {
  RELIEF_REQUIRE_SHARED_DATA();
  const DemInfo potrero =
      inspect_dem(test::shared_data("sf-potrero/USGS_13_n38w123-subsection-small-potrero.tif").string());
  EXPECT_EQ(potrero.crs, "EPSG:4269");
  EXPECT_EQ(potrero.width, 99);
  EXPECT_EQ(potrero.height, 49);
  EXPECT_EQ(potrero.nodata, -999999.0);
  EXPECT_NEAR(potrero.extent.min.x(), -122.4039, 1e-4);
  EXPECT_NEAR(potrero.extent.max.y(), 37.7556, 1e-4);

  const DemInfo north =
      inspect_dem(test::shared_data("sf-dem/sf_north_quad_usgs24k_30m_nad27utm10_m.tif").string());
  EXPECT_EQ(north.crs, "EPSG:26710");
  EXPECT_EQ(north.pixel_size, Vec2(30.0, 30.0));
  EXPECT_EQ(north.nodata, -32767.0);
  EXPECT_EQ(north.unit, VerticalUnit::metre);
  EXPECT_TRUE(north.unit_from_metadata);

  // The README says the south quadrangle does not state its unit, but its band does say "ft".
  const DemInfo south =
      inspect_dem(test::shared_data("sf-dem/sf_south_quad_usgs24k_30m_nad27utm10_ft.tif").string());
  EXPECT_EQ(south.unit, VerticalUnit::foot);
  EXPECT_TRUE(south.unit_from_metadata);
}

}  // namespace
}  // namespace relief

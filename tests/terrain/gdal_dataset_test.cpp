#include "terrain/gdal_dataset.h"

#include <gtest/gtest.h>

#include <fstream>

#include "relief/core/errors.h"
#include "relief/terrain/dem_writer.h"
#include "support/test_data.h"

namespace relief::gdal {
namespace {

// 4 x 3 cells of 10 m x 20 m from (500000, 4200000), the central meridian of UTM 10N; the
// value of cell (col, row) is col + 10 * row, cell (3, 2) void, heights in feet.
std::string write_small_dem(const std::string& name, DemDataType type = DemDataType::float64) {
  DemGrid grid;
  grid.x0 = 500000.0;
  grid.y0 = 4200000.0;
  grid.dx = 10.0;
  grid.dy = 20.0;
  grid.width = 4;
  grid.height = 3;
  for (int row = 0; row < grid.height; ++row) {
    for (int col = 0; col < grid.width; ++col) grid.values.push_back(col + 10.0 * row + 0.25);
  }
  grid.values.back() = -9999.0;
  grid.nodata = -9999.0;
  grid.unit_type = "ft";
  grid.data_type = type;
  const std::string path = (test::scratch_dir("gdal_dataset_" + name) / "dem.tif").string();
  write_geotiff(path, grid);
  return path;
}

TEST(GdalDataset, ReadsSizeGeoreferencingBandFactsAndWindows) {
  const Dataset dataset = Dataset::open_raster(write_small_dem("read"));
  EXPECT_EQ(dataset.width(), 4);
  EXPECT_EQ(dataset.height(), 3);
  EXPECT_EQ(dataset.geo_transform(), (GeoTransform{500000.0, 10.0, 0.0, 4200000.0, 0.0, -20.0}));
  EXPECT_EQ(dataset.crs_identifier(), "EPSG:32610");
  EXPECT_NE(dataset.crs_wkt().find("UTM zone 10N"), std::string::npos);
  const BandFacts facts = dataset.band_facts();
  EXPECT_EQ(facts.nodata, -9999.0);
  EXPECT_EQ(facts.scale, 1.0);
  EXPECT_EQ(facts.offset, 0.0);
  EXPECT_EQ(facts.unit_type, "ft");
  // Columns 1..2 of rows 1..2, row-major, raw (the void comes back as its nodata value).
  EXPECT_EQ(dataset.read_window({1, 1, 2, 2}), (std::vector<double>{11.25, 12.25, 21.25, 22.25}));
  EXPECT_EQ(dataset.read_window({2, 2, 2, 1}), (std::vector<double>{22.25, -9999.0}));
  EXPECT_TRUE(dataset.read_window({0, 0, 0, 3}).empty());
  EXPECT_THROW((void)dataset.read_window({3, 0, 2, 1}), IoError);  // past the last column
}

TEST(GdalDataset, Int16BandRoundsToWholeUnits) {
  const Dataset dataset = Dataset::open_raster(write_small_dem("int16", DemDataType::int16));
  EXPECT_EQ(dataset.read_window({0, 1, 4, 1}), (std::vector<double>{10.0, 11.0, 12.0, 13.0}));
}

// describe_dem: extent, pixel size and the unit, from the raster or from the caller.
TEST(GdalDataset, DescribesTheDem) {
  const Dataset dataset = Dataset::open_raster(write_small_dem("describe"));
  const DemInfo info = describe_dem(dataset, std::nullopt);
  EXPECT_EQ(info.crs, "EPSG:32610");
  EXPECT_EQ(info.width, 4);
  EXPECT_EQ(info.pixel_size, Vec2(10.0, 20.0));
  EXPECT_EQ(info.extent.min, Vec2(500000.0, 4199940.0));
  EXPECT_EQ(info.extent.max, Vec2(500040.0, 4200000.0));
  ASSERT_TRUE(info.extent_wgs84);
  EXPECT_NEAR(info.extent_wgs84->min_lon, -123.0, 1e-6);     // easting 500000: the central meridian
  EXPECT_NEAR(info.extent_wgs84->min_lat, 37.947049, 1e-5);  // cs2cs EPSG:32610 EPSG:4326
  EXPECT_EQ(info.unit, VerticalUnit::foot);
  EXPECT_TRUE(info.unit_from_metadata);
  EXPECT_EQ(info.nodata, -9999.0);
  const DemInfo stated = describe_dem(dataset, VerticalUnit::metre);
  EXPECT_EQ(stated.unit, VerticalUnit::metre);
  EXPECT_TRUE(stated.unit_stated_by_user);
  EXPECT_FALSE(stated.unit_from_metadata);
}

// A raster written through the adapter with a rotated geotransform and no unit: read back,
// then refused by describe_dem; one without geotransform or CRS says so.
TEST(GdalDataset, WrittenRastersRoundTripAndRotatedOnesAreRefused) {
  const auto dir = test::scratch_dir("gdal_dataset_write");
  const std::string rotated = (dir / "rotated.tif").string();
  {
    Dataset out = Dataset::create_geotiff(rotated, 2, 2);
    out.set_geo_transform({100.0, 1.0, 0.5, 200.0, 0.0, -1.0});
    out.set_crs("EPSG:32610");
    out.set_nodata(-1.0);
    out.write_band({1.5, 2.5, 3.5, -1.0});
    EXPECT_THROW(out.set_crs("EPSG:999999"), ProjectionError);
    out.close();
    out.close();  // a second close is a no-op
  }
  const Dataset back = Dataset::open_raster(rotated);
  EXPECT_EQ(back.read_window({0, 0, 2, 2}), (std::vector<double>{1.5, 2.5, 3.5, -1.0}));
  EXPECT_EQ(back.band_facts().unit_type, "");
  EXPECT_THROW((void)describe_dem(back, std::nullopt), InvalidInput);

  const std::string bare = (dir / "bare.tif").string();
  Dataset::create_geotiff(bare, 1, 1).close();
  const Dataset plain = Dataset::open_raster(bare);
  EXPECT_THROW((void)plain.geo_transform(), InvalidInput);
  EXPECT_THROW((void)plain.crs_wkt(), InvalidInput);
  EXPECT_THROW((void)plain.crs_identifier(), InvalidInput);
}

TEST(GdalDataset, MissingFileIsIoErrorAndTextIsInvalidInput) {
  const auto dir = test::scratch_dir("gdal_dataset_open");
  EXPECT_THROW((void)Dataset::open_raster((dir / "missing.tif").string()), IoError);
  std::ofstream(dir / "text.tif") << "not a raster\n";
  EXPECT_THROW((void)Dataset::open_raster((dir / "text.tif").string()), InvalidInput);
}

// Moving hands the handle over: the moved-to dataset reads, the moved-from one is closed.
TEST(GdalDataset, MovesTheHandle) {
  Dataset a = Dataset::open_raster(write_small_dem("move"));
  Dataset b = std::move(a);
  EXPECT_EQ(b.width(), 4);
  a = std::move(b);
  EXPECT_EQ(a.read_window({0, 0, 1, 1}), std::vector<double>{0.25});
}

}  // namespace
}  // namespace relief::gdal

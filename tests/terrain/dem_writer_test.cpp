#include "relief/terrain/dem_writer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "relief/core/errors.h"
#include "relief/terrain/dem_sampler.h"
#include "relief/terrain/dem_source.h"
#include "support/test_data.h"

namespace relief {
namespace {

std::vector<std::string> files_in(const std::filesystem::path& dir) {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    names.push_back(entry.path().filename().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

TEST(MakeDemGrid, ValuesAtCellCentresRowZeroNorth) {
  const DemGrid grid = make_dem_grid("EPSG:32610", 1000.0, 2000.0, 10.0, 5.0, 3, 2,
                                     [](double x, double y) { return x + 1000.0 * y; });
  EXPECT_EQ(grid.crs, "EPSG:32610");
  ASSERT_EQ(grid.values.size(), 6U);
  EXPECT_EQ(grid.cell_centre(0, 0), Vec2(1005.0, 1997.5));
  EXPECT_EQ(grid.cell_centre(2, 1), Vec2(1025.0, 1992.5));
  EXPECT_EQ(grid.values[0], 1005.0 + 1997500.0);
  EXPECT_EQ(grid.values[5], 1025.0 + 1992500.0);  // row-major: (2, 1) is the last
  EXPECT_FALSE(grid.nodata);
  EXPECT_TRUE(grid.unit_type.empty());
}

TEST(MakeDemGrid, RejectsDegenerateGrids) {
  const auto f = [](double, double) { return 0.0; };
  EXPECT_THROW((void)make_dem_grid("EPSG:32610", 0, 0, 0.0, 1.0, 2, 2, f), InvalidInput);
  EXPECT_THROW((void)make_dem_grid("EPSG:32610", 0, 0, 1.0, -1.0, 2, 2, f), InvalidInput);
  EXPECT_THROW((void)make_dem_grid("EPSG:32610", 0, 0, 1.0, 1.0, 0, 2, f), InvalidInput);
}

TEST(WriteGeotiff, RoundTripsGridGeoreferencingNodataAndUnit) {
  const auto dir = test::scratch_dir("write_geotiff_round_trip");
  DemGrid grid = make_dem_grid("EPSG:32610", 550000.0, 4180000.0, 10.0, 10.0, 4, 3, [](double x, double y) {
    return 0.001 * (x - 550000.0) + 0.01 * (4180000.0 - y);
  });
  grid.values[5] = -9999.0;  // cell (1, 1) void
  grid.nodata = -9999.0;
  grid.unit_type = "m";
  const auto path = (dir / "dem.tif").string();
  write_geotiff(path, grid);
  EXPECT_EQ(files_in(dir), std::vector<std::string>{"dem.tif"});  // no temporary left behind

  const DemInfo info = inspect_dem(path);
  EXPECT_EQ(info.crs, "EPSG:32610");
  EXPECT_EQ(info.width, 4);
  EXPECT_EQ(info.height, 3);
  EXPECT_EQ(info.extent.min, Vec2(550000.0, 4179970.0));
  EXPECT_EQ(info.extent.max, Vec2(550040.0, 4180000.0));
  EXPECT_EQ(info.nodata, -9999.0);
  EXPECT_TRUE(info.unit_from_metadata);

  // Float64 values come back bit for bit at the cell centres (nearest).
  const GeoFrame frame("EPSG:32610", Vec2(550000.0, 4180000.0));
  DemOptions nearest;
  nearest.interpolation = Interpolation::nearest;
  Aabb2 area;
  area.extend(Vec2(0.0, -30.0));
  area.extend(Vec2(40.0, 0.0));
  const DemSampler sampler({path}, frame, area, nearest);
  for (int row = 0; row < 3; ++row) {
    for (int col = 0; col < 4; ++col) {
      const auto z = sampler.height_at(grid.cell_centre(col, row) - frame.origin());
      if (row == 1 && col == 1) {
        EXPECT_FALSE(z);
      } else {
        ASSERT_TRUE(z);
        EXPECT_EQ(*z, grid.values[static_cast<std::size_t>(row * 4 + col)]);
      }
    }
  }
}

TEST(WriteGeotiff, Int16LikeSrtmRoundsToWholeMetresAndKeepsItsVoids) {
  const auto dir = test::scratch_dir("write_geotiff_int16");
  DemGrid grid =
      make_dem_grid("EPSG:32610", 550000.0, 4180000.0, 30.0, 30.0, 3, 2, [](double, double) { return 0.0; });
  grid.values = {812.4, 812.6, -0.6, -32768.0, 32767.0, -32767.2};
  grid.nodata = -32768.0;
  grid.data_type = DemDataType::int16;
  const auto path = (dir / "srtm.tif").string();
  write_geotiff(path, grid);
  EXPECT_EQ(inspect_dem(path).nodata, -32768.0);

  const GeoFrame frame("EPSG:32610", Vec2(550000.0, 4180000.0));
  DemOptions nearest;
  nearest.interpolation = Interpolation::nearest;
  nearest.plausible_min_m = -40000.0;  // read back the extremes of the type as they are
  nearest.plausible_max_m = 40000.0;
  nearest.spike_min_step_m = std::numeric_limits<double>::infinity();
  Aabb2 area;
  area.extend(Vec2(0.0, -60.0));
  area.extend(Vec2(90.0, 0.0));
  const DemSampler sampler({path}, frame, area, nearest);
  const std::vector<std::optional<double>> expected = {812.0, 813.0, -1.0, std::nullopt, 32767.0, -32767.0};
  for (int row = 0; row < 2; ++row) {
    for (int col = 0; col < 3; ++col) {
      EXPECT_EQ(sampler.height_at(grid.cell_centre(col, row) - frame.origin()),
                expected[static_cast<std::size_t>(row * 3 + col)])
          << col << ", " << row;
    }
  }
}

TEST(WriteGeotiff, Int16RefusesValuesOutsideItsRange) {
  const auto dir = test::scratch_dir("write_geotiff_int16_range");
  DemGrid grid = make_dem_grid("EPSG:32610", 0, 0, 1, 1, 2, 1, [](double, double) { return 1.0; });
  grid.data_type = DemDataType::int16;
  grid.values[1] = 32767.6;
  EXPECT_THROW(write_geotiff((dir / "high.tif").string(), grid), InvalidInput);
  grid.values[1] = std::nan("");
  EXPECT_THROW(write_geotiff((dir / "nan.tif").string(), grid), InvalidInput);
  grid.values[1] = 1.0;
  grid.nodata = -9999999.0;
  EXPECT_THROW(write_geotiff((dir / "nodata.tif").string(), grid), InvalidInput);
  EXPECT_TRUE(files_in(dir).empty());
}

TEST(WriteGeotiff, OverwritesAnExistingFile) {
  const auto dir = test::scratch_dir("write_geotiff_overwrite");
  const auto path = (dir / "dem.tif").string();
  write_geotiff(path, make_dem_grid("EPSG:32610", 0, 0, 1, 1, 2, 2, [](double, double) { return 1.0; }));
  write_geotiff(path, make_dem_grid("EPSG:4326", 0, 0, 1, 1, 5, 7, [](double, double) { return 1.0; }));
  const DemInfo info = inspect_dem(path);
  EXPECT_EQ(info.width, 5);
  EXPECT_EQ(info.crs, "EPSG:4326");
  EXPECT_EQ(files_in(dir), std::vector<std::string>{"dem.tif"});
}

TEST(WriteGeotiff, FailuresThrowAndLeaveNothingBehind) {
  const auto dir = test::scratch_dir("write_geotiff_failures");
  const DemGrid grid = make_dem_grid("EPSG:32610", 0, 0, 1, 1, 2, 2, [](double, double) { return 1.0; });
  EXPECT_THROW(write_geotiff((dir / "no" / "such" / "dir.tif").string(), grid), IoError);

  DemGrid unknown_crs = grid;
  unknown_crs.crs = "EPSG:999999";
  EXPECT_THROW(write_geotiff((dir / "crs.tif").string(), unknown_crs), ProjectionError);

  DemGrid short_values = grid;
  short_values.values.pop_back();
  EXPECT_THROW(write_geotiff((dir / "short.tif").string(), short_values), InvalidInput);

  EXPECT_TRUE(files_in(dir).empty());
}

}  // namespace
}  // namespace relief

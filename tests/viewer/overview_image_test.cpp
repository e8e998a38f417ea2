#include "relief/viewer/overview_image.h"

#include <gtest/gtest.h>
#include <libdeflate.h>

#include <cstdint>
#include <string>
#include <vector>

#include "relief/core/errors.h"

namespace relief {
namespace {

struct Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;
  [[nodiscard]] std::array<int, 3> at(int x, int y) const {
    const std::size_t i = 3 * (static_cast<std::size_t>(y) * width + x);
    return {rgb[i], rgb[i + 1], rgb[i + 2]};
  }
};

std::uint32_t be32(const std::string& s, std::size_t at) {
  std::uint32_t v = 0;
  for (int k = 0; k < 4; ++k) v = v << 8 | static_cast<unsigned char>(s[at + k]);
  return v;
}

/// Decodes relief's PNG (one IDAT, filter 0 rows), checking every chunk's CRC.
Image decode(const std::string& png) {
  EXPECT_EQ(png.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  Image image;
  std::string idat;
  for (std::size_t at = 8; at + 12 <= png.size();) {
    const std::uint32_t length = be32(png, at);
    const std::string type = png.substr(at + 4, 4);
    EXPECT_EQ(be32(png, at + 8 + length), libdeflate_crc32(0, png.data() + at + 4, length + 4)) << type;
    if (type == "IHDR") {
      image.width = static_cast<int>(be32(png, at + 8));
      image.height = static_cast<int>(be32(png, at + 12));
      EXPECT_EQ(png[at + 16], 8);  // bits
      EXPECT_EQ(png[at + 17], 2);  // RGB
    }
    if (type == "IDAT") idat += png.substr(at + 8, length);
    at += 12 + length;
  }
  const std::size_t row = 3 * static_cast<std::size_t>(image.width) + 1;
  std::vector<std::uint8_t> raw(row * image.height);
  libdeflate_decompressor* d = libdeflate_alloc_decompressor();
  std::size_t got = 0;
  EXPECT_EQ(libdeflate_zlib_decompress(d, idat.data(), idat.size(), raw.data(), raw.size(), &got),
            LIBDEFLATE_SUCCESS);
  libdeflate_free_decompressor(d);
  EXPECT_EQ(got, raw.size());
  for (int y = 0; y < image.height; ++y) {
    EXPECT_EQ(raw[y * row], 0);  // filter 0
    image.rgb.insert(image.rgb.end(), raw.begin() + static_cast<std::ptrdiff_t>(y * row + 1),
                     raw.begin() + static_cast<std::ptrdiff_t>((y + 1) * row));
  }
  return image;
}

// A road plane climbing 10 % to the north over a flat terrain wider than it: the picture's
// centre is the road in the 10 % colour (254, 224, 139) shaded, its corners the background.
TEST(OverviewImage, ARoadAtTenPercentIsDrawnInTheTenPercentColour) {
  MeshScene scene;
  TriangleMesh terrain;
  terrain.name = "Terrain";
  terrain.vertices = {{-100, -100, -5}, {100, -100, -5}, {100, 100, -5}, {-100, 100, -5}};
  terrain.triangles = {{0, 1, 2}, {0, 2, 3}};
  TriangleMesh road;
  road.name = "Road_Road";
  road.vertices = {{-20, -50, -5}, {20, -50, -5}, {20, 50, 5}, {-20, 50, 5}};
  road.triangles = {{0, 1, 2}, {0, 2, 3}};
  scene.meshes = {terrain, road};
  OverviewImageOptions o;
  o.width = 200;
  o.height = 120;
  const Image image = decode(render_overview_png(scene, o));
  ASSERT_EQ(image.width, 200);
  ASSERT_EQ(image.height, 120);
  EXPECT_EQ(image.at(0, 0), (std::array<int, 3>{0xcf, 0xd8, 0xe3}));
  EXPECT_EQ(image.at(199, 119), (std::array<int, 3>{0xcf, 0xd8, 0xe3}));
  const auto c = image.at(100, 60);
  // Lambert shading scales all three alike: the hue is the 10 % stop's.
  EXPECT_NEAR(static_cast<double>(c[1]) / c[0], 224.0 / 254.0, 0.02);
  EXPECT_NEAR(static_cast<double>(c[2]) / c[0], 139.0 / 254.0, 0.02);
  EXPECT_GT(c[0], 140);
  // Beside the road: the terrain's tint, not the road's.
  const auto t = image.at(100 - 60, 60);
  EXPECT_LT(t[0], t[1]);
}

TEST(OverviewImage, SizesOutOfRangeThrow) {
  const MeshScene empty;
  OverviewImageOptions o;
  o.width = 8;
  EXPECT_THROW((void)render_overview_png(empty, o), InvalidInput);
  o = {};
  o.supersample = 0;
  EXPECT_THROW((void)render_overview_png(empty, o), InvalidInput);
  // An empty scene is the background only.
  o = {};
  o.width = 32;
  o.height = 16;
  const Image image = decode(render_overview_png(empty, o));
  EXPECT_EQ(image.at(16, 8), (std::array<int, 3>{0xcf, 0xd8, 0xe3}));
}

}  // namespace
}  // namespace relief

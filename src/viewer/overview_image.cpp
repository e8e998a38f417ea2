// A software z-buffer render of the scene for report.html, and its PNG encoding.
#include "relief/viewer/overview_image.h"

#include <libdeflate.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <numbers>
#include <vector>

#include <Eigen/Geometry>

#include "relief/core/errors.h"

namespace relief {
namespace {

using Rgb = std::array<double, 3>;

// The grade ramp of the 3D view (src/viewer/web/src/colors.js, GRADE_STOPS).
constexpr std::array<std::pair<double, Rgb>, 6> kGradeStops = {{{0, {26, 152, 80}},
                                                                {5, {145, 207, 96}},
                                                                {10, {254, 224, 139}},
                                                                {15, {252, 141, 89}},
                                                                {20, {215, 48, 39}},
                                                                {30, {123, 50, 148}}}};

Rgb grade_colour(double grade_percent) {
  if (grade_percent <= kGradeStops.front().first) return kGradeStops.front().second;
  for (std::size_t i = 1; i < kGradeStops.size(); ++i) {
    const auto& [v1, c1] = kGradeStops[i];
    if (grade_percent <= v1) {
      const auto& [v0, c0] = kGradeStops[i - 1];
      const double f = (grade_percent - v0) / (v1 - v0);
      return {c0[0] + f * (c1[0] - c0[0]), c0[1] + f * (c1[1] - c0[1]), c0[2] + f * (c1[2] - c0[2])};
    }
  }
  return kGradeStops.back().second;
}

/// A PNG of 8-bit RGB rows (filter 0 on every row), zlib stream by libdeflate.
std::string encode_png(const std::vector<std::uint8_t>& rgb, int width, int height) {
  std::vector<std::uint8_t> raw;
  raw.reserve(static_cast<std::size_t>(height) * (3 * static_cast<std::size_t>(width) + 1));
  for (int y = 0; y < height; ++y) {
    raw.push_back(0);
    const auto row = rgb.begin() + static_cast<std::ptrdiff_t>(3 * static_cast<std::size_t>(width) * y);
    raw.insert(raw.end(), row, row + 3 * static_cast<std::ptrdiff_t>(width));
  }
  const std::unique_ptr<libdeflate_compressor, decltype(&libdeflate_free_compressor)> compressor(
      libdeflate_alloc_compressor(6), &libdeflate_free_compressor);
  if (!compressor) throw std::bad_alloc();
  std::string z(libdeflate_zlib_compress_bound(compressor.get(), raw.size()), '\0');
  z.resize(libdeflate_zlib_compress(compressor.get(), raw.data(), raw.size(), z.data(), z.size()));

  std::string png("\x89PNG\r\n\x1a\n", 8);
  const auto be32 = [](std::string& out, std::uint32_t v) {
    for (int shift = 24; shift >= 0; shift -= 8) out += static_cast<char>(v >> shift & 0xff);
  };
  const auto chunk = [&](const char* type, const std::string& data) {
    be32(png, static_cast<std::uint32_t>(data.size()));
    const std::string body = std::string(type, 4) + data;
    png += body;
    be32(png, libdeflate_crc32(0, body.data(), body.size()));
  };
  std::string header;
  be32(header, static_cast<std::uint32_t>(width));
  be32(header, static_cast<std::uint32_t>(height));
  header += std::string("\x08\x02\x00\x00\x00", 5);  // 8 bits, RGB, deflate, filter 0, no interlace
  chunk("IHDR", header);
  chunk("IDAT", z);
  chunk("IEND", "");
  return png;
}

}  // namespace

std::string render_overview_png(const MeshScene& scene, const OverviewImageOptions& options) {
  if (options.width < 16 || options.width > 8192 || options.height < 16 || options.height > 8192)
    throw InvalidInput("overview image: width and height must be 16 to 8192 pixels");
  if (options.supersample < 1 || options.supersample > 4)
    throw InvalidInput("overview image: supersample must be 1 to 4");
  const int ss = options.supersample;
  const int W = options.width * ss, H = options.height * ss;

  // The view: from the south, looking north and down at elevation_deg; orthographic.
  const double el = options.elevation_deg * std::numbers::pi / 180.0;
  const Vec3 right(1, 0, 0), up(0, std::sin(el), std::cos(el)), forward(0, std::cos(el), -std::sin(el));
  double u0 = std::numeric_limits<double>::infinity(), u1 = -u0, v0 = u0, v1 = -u0;
  double z_min = u0, z_max = -u0;
  for (const TriangleMesh& m : scene.meshes)
    for (const Vec3& p : m.vertices) {
      u0 = std::min(u0, p.dot(right));
      u1 = std::max(u1, p.dot(right));
      v0 = std::min(v0, p.dot(up));
      v1 = std::max(v1, p.dot(up));
      z_min = std::min(z_min, p.z());
      z_max = std::max(z_max, p.z());
    }
  const Rgb background = {0xcf, 0xd8, 0xe3};  // the 3D view's
  std::vector<double> depth(static_cast<std::size_t>(W) * H, std::numeric_limits<double>::infinity());
  std::vector<float> colour(3 * static_cast<std::size_t>(W) * H);
  for (std::size_t i = 0; i < depth.size(); ++i)
    for (int k = 0; k < 3; ++k) colour[3 * i + k] = static_cast<float>(background[k]);
  if (u1 > u0 || v1 > v0) {
    const double span_u = std::max(u1 - u0, 1.0), span_v = std::max(v1 - v0, 1.0);
    const double scale =
        std::min(W * (1 - 2 * options.margin) / span_u, H * (1 - 2 * options.margin) / span_v);
    const double cu = 0.5 * (u0 + u1), cv = 0.5 * (v0 + v1);
    const Vec3 light = Vec3(-0.4, -0.5, 1.0).normalized();
    const Rgb terrain_low = {120, 150, 100}, terrain_high = {190, 175, 150};
    const double z_span = std::max(1.0, z_max - z_min);

    // Terrain first, then roads, then marks: at equal depth the later one wins (a mark lies 5 mm
    // over its road, less than a pixel's depth step afar).
    std::vector<const TriangleMesh*> order;
    for (const char* name : {"Terrain", "Road_Road", "Road_Sidewalk", "Road_Marking"})
      for (const TriangleMesh& m : scene.meshes)
        if (m.name == name) order.push_back(&m);
    for (const TriangleMesh& m : scene.meshes)
      if (std::find(order.begin(), order.end(), &m) == order.end()) order.push_back(&m);

    for (const TriangleMesh* mesh : order) {
      const bool terrain = mesh->name == "Terrain", marking = mesh->name == "Road_Marking";
      const bool paved = mesh->name == "Road_Road" || mesh->name == "Road_Sidewalk";
      // Roads win depth ties against the terrain they meet by a small bias toward the eye.
      const double bias = terrain ? 0.0 : marking ? 0.2 : 0.1;
      for (const auto& tri : mesh->triangles) {
        const Vec3& a = mesh->vertices[tri[0]];
        const Vec3& b = mesh->vertices[tri[1]];
        const Vec3& c = mesh->vertices[tri[2]];
        Vec3 n = (b - a).cross(c - a);
        const double area = n.norm();
        if (area <= 0.0) continue;
        n /= area;
        if (n.z() < 0) n = -n;
        Rgb base{170, 170, 170};
        if (terrain) {
          const double f = std::clamp(((a.z() + b.z() + c.z()) / 3.0 - z_min) / z_span, 0.0, 1.0);
          for (int k = 0; k < 3; ++k) base[k] = terrain_low[k] + f * (terrain_high[k] - terrain_low[k]);
        } else if (marking) {
          base = {244, 244, 244};
        } else if (paved) {
          const double slope =
              std::abs(n.z()) > 1e-9 ? 100.0 * std::hypot(n.x(), n.y()) / std::abs(n.z()) : 1000.0;
          base = grade_colour(slope);
        }
        const double shade = 0.55 + 0.45 * std::max(0.0, n.dot(light));
        // Screen positions (pixels, y down) and depths of the corners.
        std::array<Eigen::Vector3d, 3> s;
        for (int k = 0; k < 3; ++k) {
          const Vec3& p = mesh->vertices[tri[k]];
          s[k] = {0.5 * W + (p.dot(right) - cu) * scale, 0.5 * H - (p.dot(up) - cv) * scale,
                  p.dot(forward) - bias};
        }
        const double det =
            (s[1].x() - s[0].x()) * (s[2].y() - s[0].y()) - (s[2].x() - s[0].x()) * (s[1].y() - s[0].y());
        if (std::abs(det) < 1e-12) continue;
        const int x0 = std::max(0, static_cast<int>(std::floor(std::min({s[0].x(), s[1].x(), s[2].x()}))));
        const int x1 = std::min(W - 1, static_cast<int>(std::ceil(std::max({s[0].x(), s[1].x(), s[2].x()}))));
        const int y0 = std::max(0, static_cast<int>(std::floor(std::min({s[0].y(), s[1].y(), s[2].y()}))));
        const int y1 = std::min(H - 1, static_cast<int>(std::ceil(std::max({s[0].y(), s[1].y(), s[2].y()}))));
        for (int y = y0; y <= y1; ++y)
          for (int x = x0; x <= x1; ++x) {
            // Barycentric weights of the pixel centre.
            const double px = x + 0.5, py = y + 0.5;
            const double w1 =
                ((px - s[0].x()) * (s[2].y() - s[0].y()) - (s[2].x() - s[0].x()) * (py - s[0].y())) / det;
            const double w2 =
                ((s[1].x() - s[0].x()) * (py - s[0].y()) - (px - s[0].x()) * (s[1].y() - s[0].y())) / det;
            const double w0 = 1.0 - w1 - w2;
            if (w0 < 0 || w1 < 0 || w2 < 0) continue;
            const double d = w0 * s[0].z() + w1 * s[1].z() + w2 * s[2].z();
            const std::size_t i = static_cast<std::size_t>(y) * W + x;
            if (d >= depth[i]) continue;
            depth[i] = d;
            for (int k = 0; k < 3; ++k) colour[3 * i + k] = static_cast<float>(base[k] * shade);
          }
      }
    }
  }
  // Average each ss x ss block into one pixel.
  std::vector<std::uint8_t> rgb(3 * static_cast<std::size_t>(options.width) * options.height);
  for (int y = 0; y < options.height; ++y)
    for (int x = 0; x < options.width; ++x)
      for (int k = 0; k < 3; ++k) {
        double sum = 0.0;
        for (int dy = 0; dy < ss; ++dy)
          for (int dx = 0; dx < ss; ++dx)
            sum += colour[3 * ((static_cast<std::size_t>(y) * ss + dy) * W +
                               static_cast<std::size_t>(x) * ss + dx) +
                          k];
        rgb[3 * (static_cast<std::size_t>(y) * options.width + x) + k] =
            static_cast<std::uint8_t>(std::clamp(std::lround(sum / (ss * ss)), 0L, 255L));
      }
  return encode_png(rgb, options.width, options.height);
}

}  // namespace relief

#include "terrain/dem_ground_filter.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <vector>

namespace relief::terrain_detail {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// `line` with its voids filled and r values beyond each end, for the running extrema: a run of
// voids takes the straight line between the valid values on either side (the nearest valid
// value at an end), and beyond an end the line is reflected through its end value (v(-k) =
// 2 v(0) - v(k)), so that a plane, voids or edges in it, stays a plane and is kept. False when
// the line has no valid value.
bool fill_and_pad(const std::vector<double>& line, std::size_t r, std::vector<double>& out) {
  const std::size_t n = line.size();
  out.assign(n + 2 * r, kNaN);
  std::size_t last = n;  // the last valid index seen
  for (std::size_t i = 0; i < n; ++i) {
    if (std::isnan(line[i])) continue;
    out[r + i] = line[i];
    const std::size_t from = last == n ? 0 : last + 1;
    for (std::size_t k = from; k < i; ++k) {
      out[r + k] = last == n ? line[i]
                             : line[last] + (line[i] - line[last]) * static_cast<double>(k - last) /
                                                static_cast<double>(i - last);
    }
    last = i;
  }
  if (last == n) return false;
  for (std::size_t k = last + 1; k < n; ++k) out[r + k] = line[last];
  for (std::size_t k = 1; k <= r; ++k) {
    const std::size_t inside = std::min(k, n - 1);
    out[r - k] = 2.0 * out[r] - out[r + inside];
    out[r + n - 1 + k] = 2.0 * out[r + n - 1] - out[r + n - 1 - inside];
  }
  return true;
}

// Running extremum of `line` over a centred window of 2 r + 1 (van Herk / Gil-Werman: prefix
// and suffix extrema over blocks of the window's length, then one comparison per value), on the
// line as fill_and_pad gives it. A line without a valid value stays void.
template <typename Pick>
void running_extremum(std::vector<double>& line, int r, Pick pick, std::vector<double>& g,
                      std::vector<double>& h) {
  const auto n = static_cast<std::ptrdiff_t>(line.size());
  const auto k = 2 * static_cast<std::ptrdiff_t>(r) + 1;
  if (!fill_and_pad(line, static_cast<std::size_t>(r), g)) return;
  const auto m = static_cast<std::ptrdiff_t>(g.size());
  // Whole blocks; what lies past the last window counts for nothing.
  g.resize(static_cast<std::size_t>((m + k - 1) / k * k), pick(-kInf, kInf) == -kInf ? kInf : -kInf);
  h = g;
  const auto padded = static_cast<std::ptrdiff_t>(g.size());
  for (std::ptrdiff_t b = 0; b < padded; b += k) {
    for (std::ptrdiff_t j = b + 1; j < b + k; ++j) {
      const auto u = static_cast<std::size_t>(j);
      g[u] = pick(g[u - 1], g[u]);
    }
    for (std::ptrdiff_t j = b + k - 2; j >= b; --j) {
      const auto u = static_cast<std::size_t>(j);
      h[u] = pick(h[u + 1], h[u]);
    }
  }
  // The window of value i spans padded indices i .. i + 2r.
  for (std::ptrdiff_t i = 0; i < n; ++i)
    line[static_cast<std::size_t>(i)] =
        pick(h[static_cast<std::size_t>(i)], g[static_cast<std::size_t>(i + k - 1)]);
}

// A flat rectangular erosion (min) or dilation (max) of a row-major grid, rows then columns.
template <typename Pick>
std::vector<double> extremum_2d(const std::vector<double>& z, int cols, int rc, int rr, Pick pick) {
  const auto w = static_cast<std::size_t>(cols);
  const std::size_t rows = z.size() / w;
  std::vector<double> out = z, line, g, h;
  line.resize(w);
  for (std::size_t r = 0; r < rows; ++r) {
    std::copy_n(out.begin() + static_cast<std::ptrdiff_t>(r * w), w, line.begin());
    running_extremum(line, rc, pick, g, h);
    std::copy_n(line.begin(), w, out.begin() + static_cast<std::ptrdiff_t>(r * w));
  }
  line.resize(rows);
  for (std::size_t c = 0; c < w; ++c) {
    for (std::size_t r = 0; r < rows; ++r) line[r] = out[r * w + c];
    running_extremum(line, rr, pick, g, h);
    for (std::size_t r = 0; r < rows; ++r) out[r * w + c] = line[r];
  }
  return out;
}

std::vector<double> erode(const std::vector<double>& z, int cols, int rc, int rr) {
  return extremum_2d(z, cols, rc, rr, [](double a, double b) { return std::min(a, b); });
}

std::vector<double> dilate(const std::vector<double>& z, int cols, int rc, int rr) {
  return extremum_2d(z, cols, rc, rr, [](double a, double b) { return std::max(a, b); });
}

}  // namespace

GroundFiltered filter_off_ground(std::span<double> z, int cols, int radius_cols, int radius_rows,
                                 double min_height_m) {
  GroundFiltered out;
  if (z.empty() || cols <= 0) return out;
  std::vector<double> grid(z.begin(), z.end());
  for (double& v : grid) {
    if (!std::isfinite(v)) v = kNaN;
  }
  const std::vector<double> opened =
      dilate(erode(grid, cols, radius_cols, radius_rows), cols, radius_cols, radius_rows);
  const std::vector<double> ground =
      erode(dilate(opened, cols, radius_cols, radius_rows), cols, radius_cols, radius_rows);
  for (std::size_t i = 0; i < z.size(); ++i) {
    if (!std::isfinite(z[i]) || std::isnan(ground[i])) continue;
    const double change = std::abs(z[i] - ground[i]);
    if (!(change > min_height_m)) continue;
    ++(z[i] > ground[i] ? out.lowered : out.raised);
    if (change > out.largest_m) {
      out.largest_m = change;
      out.largest_from_m = z[i];
      out.largest_col = static_cast<int>(i % static_cast<std::size_t>(cols));
      out.largest_row = static_cast<int>(i / static_cast<std::size_t>(cols));
    }
    z[i] = ground[i];
  }
  return out;
}

}  // namespace relief::terrain_detail

#include "terrain/dem_sanity.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace relief::terrain_detail {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

void keep_cell(VoidedCells& out, std::size_t keep, int col, int row, double height_m, double around_m) {
  ++out.count;
  if (out.first.size() < keep) out.first.push_back({col, row, height_m, around_m});
}

// Median of the first n values (sorted in place by insertion: n <= 8).
double median(std::array<double, 8>& v, int n) {
  for (int i = 1; i < n; ++i) {
    const double x = v[i];
    int j = i;
    for (; j > 0 && v[j - 1] > x; --j) v[j] = v[j - 1];
    v[j] = x;
  }
  return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace

VoidedCells void_implausible_heights(std::span<double> z, int cols, double min_m, double max_m,
                                     std::size_t keep) {
  VoidedCells out;
  for (std::size_t i = 0; i < z.size(); ++i) {
    if (std::isnan(z[i]) || (z[i] >= min_m && z[i] <= max_m)) continue;
    keep_cell(out, keep, static_cast<int>(i % cols), static_cast<int>(i / cols), z[i], kNaN);
    z[i] = kNaN;
  }
  return out;
}

VoidedCells void_spikes(std::span<double> z, int cols, std::span<const double> cell_m,
                        const SpikeCriteria& criteria, std::size_t keep) {
  VoidedCells out;
  const int rows = static_cast<int>(cell_m.size());
  const auto at = [&](int c, int r) { return z[static_cast<std::size_t>(r) * cols + c]; };
  std::vector<std::size_t> spikes;
  std::array<double, 8> around{};
  for (int r = 0; r < rows; ++r) {
    const double step_m = std::max(criteria.min_step_m, criteria.step_per_cell * cell_m[r]);
    // Quick test first: a peak lies above all its neighbours by more than margin_m (z0 - max >=
    // d - (max - min) > (1 - spread) * d), a pit below them: a cell that does not is neither.
    const double margin_m = (1.0 - criteria.max_neighbour_spread) * step_m;
    for (int c = 0; c < cols; ++c) {
      const double z0 = at(c, r);
      if (std::isnan(z0)) continue;
      int n = 0;
      double lo = std::numeric_limits<double>::infinity();
      double hi = -lo;
      for (int dr = -1; dr <= 1; ++dr) {
        for (int dc = -1; dc <= 1; ++dc) {
          const int cc = c + dc;
          const int rr = r + dr;
          if ((dc == 0 && dr == 0) || cc < 0 || rr < 0 || cc >= cols || rr >= rows) continue;
          const double v = at(cc, rr);
          if (std::isnan(v)) continue;
          around[n++] = v;
          lo = std::min(lo, v);
          hi = std::max(hi, v);
        }
      }
      if (n < 3 || (z0 - hi < margin_m && lo - z0 < margin_m)) continue;
      const double m = median(around, n);
      const double d = std::abs(z0 - m);
      if (d > step_m && hi - lo < criteria.max_neighbour_spread * d) {
        spikes.push_back(static_cast<std::size_t>(r) * cols + c);
        keep_cell(out, keep, c, r, z0, m);
      }
    }
  }
  // Voided only now, so that every cell was judged on the heights as given.
  for (const std::size_t i : spikes) z[i] = kNaN;
  return out;
}

}  // namespace relief::terrain_detail

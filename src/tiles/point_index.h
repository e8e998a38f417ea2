#pragma once
// Points by 1 m cells, for finding the same place in two builds (road ends, junction centres).

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <unordered_map>
#include <utility>
#include <vector>

#include "relief/geometry/types.h"

namespace relief::detail {

/// Points by 1 m cells; a lookup searches the 3 x 3 cells around its point, so tolerances up
/// to 1 m.
template <typename Value>
class PointIndex {
 public:
  void add(const Vec2& p, const Value& value) { cells_[key(cell(p.x()), cell(p.y()))].push_back({p, value}); }

  /// Every value within `tolerance` of `p`, nearest first.
  [[nodiscard]] std::vector<Value> all_near(const Vec2& p, double tolerance) const {
    std::vector<std::pair<double, Value>> found;
    const long long cx = cell(p.x()), cy = cell(p.y());
    for (long long dx = -1; dx <= 1; ++dx) {
      for (long long dy = -1; dy <= 1; ++dy) {
        const auto it = cells_.find(key(cx + dx, cy + dy));
        if (it == cells_.end()) continue;
        for (const auto& [q, value] : it->second) {
          const double d = (q - p).norm();
          if (d <= tolerance) found.emplace_back(d, value);
        }
      }
    }
    std::stable_sort(found.begin(), found.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    std::vector<Value> out;
    out.reserve(found.size());
    for (auto& f : found) out.push_back(std::move(f.second));
    return out;
  }

  /// The value nearest `p` within `tolerance`.
  [[nodiscard]] std::optional<Value> nearest(const Vec2& p, double tolerance) const {
    std::vector<Value> near = all_near(p, tolerance);
    if (near.empty()) return std::nullopt;
    return std::move(near.front());
  }

 private:
  static long long cell(double v) { return static_cast<long long>(std::floor(v)); }
  static std::uint64_t key(long long x, long long y) {
    return (static_cast<std::uint64_t>(x) * 0x9E3779B97F4A7C15ull) ^ static_cast<std::uint64_t>(y);
  }
  std::unordered_map<std::uint64_t, std::vector<std::pair<Vec2, Value>>> cells_;
};

}  // namespace relief::detail

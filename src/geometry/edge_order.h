#pragma once
// Private to the geometry module: edges (or edge uses) ordered by their vertex pair in linear
// time, for the topology passes over whole meshes.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace relief::detail {

/// Sorts `items` by (lo(item), hi(item)), lo below n_vertices: a counting sort on lo, then, per
/// lo, an insertion sort on hi (a vertex has a handful of edges; a stable sort past 32). Stable:
/// items of one vertex pair keep their input order. O(items + n_vertices) where a comparison
/// sort took n log n, and the largest single cost of a mesh's topology figures.
template <class T, class Lo, class Hi>
void sort_by_vertex_pair(std::vector<T>& items, std::size_t n_vertices, Lo lo, Hi hi) {
  std::vector<std::uint32_t> start(n_vertices + 1, 0);
  for (const T& item : items) ++start[lo(item) + 1];
  for (std::size_t v = 0; v < n_vertices; ++v) start[v + 1] += start[v];
  std::vector<T> sorted(items.size());
  std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
  for (const T& item : items) sorted[fill[lo(item)]++] = item;
  const auto by_hi = [&](const T& a, const T& b) { return hi(a) < hi(b); };
  for (std::size_t v = 0; v < n_vertices; ++v) {
    const auto first = sorted.begin() + start[v], last = sorted.begin() + start[v + 1];
    if (last - first > 32) {
      std::stable_sort(first, last, by_hi);
      continue;
    }
    for (auto i = first + 1; i < last; ++i) {
      const T item = *i;
      auto j = i;
      for (; j > first && by_hi(item, *(j - 1)); --j) *j = *(j - 1);
      *j = item;
    }
  }
  items = std::move(sorted);
}

}  // namespace relief::detail

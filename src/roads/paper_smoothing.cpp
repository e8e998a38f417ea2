#include "relief/roads/paper_smoothing.h"

#include <cmath>

namespace relief {
namespace {

bool complies(const RoadProfile& p, double limit_fraction) {
  for (std::size_t i = 0; i + 1 < p.size(); ++i) {
    const double ds = p.s[i + 1] - p.s[i];
    if (std::abs(p.z[i + 1] - p.z[i]) > limit_fraction * ds + 1e-12) return false;
  }
  return true;
}

}  // namespace

PaperSmoothingResult smooth_paper(const RoadNetwork& network, const std::vector<RoadProfile>& raw,
                                  const PaperSmoothingOptions& options) {
  PaperSmoothingResult result;
  result.profiles = raw;
  result.iterations.assign(raw.size(), 0);
  std::vector<double> next;
  for (std::size_t r = 0; r < raw.size(); ++r) {
    RoadProfile& p = result.profiles[r];
    const double limit = options.limits.limit_for(network.roads[r].attributes.highway) / 100.0;
    int k = 0;
    while (!complies(p, limit)) {
      if (k == options.max_iterations) {
        result.not_converged_roads.push_back(network.roads[r].id);
        break;
      }
      // One pass of the three-point moving average over the interior (Jacobi: all from the
      // previous pass).
      next = p.z;
      for (std::size_t i = 1; i + 1 < p.size(); ++i) next[i] = (p.z[i - 1] + p.z[i] + p.z[i + 1]) / 3.0;
      p.z.swap(next);
      ++k;
    }
    result.iterations[r] = k;
    for (std::size_t i = 0; i < p.size(); ++i) {
      const double shift = std::abs(p.z[i] - raw[r].z[i]);
      if (shift > result.max_shift_m) {
        result.max_shift_m = shift;
        result.max_shift_road = network.roads[r].id;
      }
    }
  }
  return result;
}

}  // namespace relief

#include "export/sumo_shapes.h"

#include <algorithm>

#include <cmath>

#include "relief/geometry/plane.h"
#include "relief/geometry/polyline.h"
#include "relief/roads/road_surface.h"

namespace relief {

Polyline3 simplify_3d(const Polyline3& line, double tolerance_m, const std::vector<double>& headings,
                      double max_turn_rad) {
  if (line.size() <= 2) return line;
  const std::vector<std::uint8_t> keep = douglas_peucker(
      line.size(), tolerance_m,
      [&](std::size_t i, std::size_t k, std::size_t j) {
        return point_segment_distance(line[k], line[i], line[j]);
      },
      [&](std::size_t i, std::size_t j) {
        return !headings.empty() && std::abs(wrap_angle(headings[j] - headings[i])) > max_turn_rad;
      });
  Polyline3 out;
  for (std::size_t k = 0; k < line.size(); ++k) {
    if (keep[k]) out.push_back(line[k]);
  }
  return out;
}

Polyline3 sample_road_curve(const ModelRoad& road, const std::function<double(double)>& t_of,
                            double tolerance_m, double s_begin, double s_end, bool lanes_offset_from_it) {
  if (s_end < 0.0) s_end = road.length();
  const double length = s_end - s_begin;
  // Every metre, and closer where the road turns: at most kMaxTurnRad between samples, or an
  // offset lane on a tight bend (a few metres of radius) would be cut short by its chords.
  constexpr double kMaxTurnRad = 2.0 * M_PI / 180.0;
  const double turn = road.plan.total_turn(s_begin, s_end);
  const int n =
      std::max({1, static_cast<int>(std::ceil(length)), static_cast<int>(std::ceil(turn / kMaxTurnRad))});
  Polyline3 line;
  std::vector<double> headings;
  line.reserve(static_cast<std::size_t>(n) + 1);
  for (int i = 0; i <= n; ++i) {
    const double s = s_begin + length * i / n;
    const Pose2 pose = road.plan.at(s);
    const Vec3 p = surface_point(road, pose, s, t_of(s));
    const double h = pose.heading;
    // Where the road bends tighter than the offset t, the offset curve loops back (a cusp):
    // keep only points that advance along the reference line's heading.
    if (!line.empty() && i < n) {
      if ((p - line.back()).head<2>().dot(Vec2(std::cos(h), std::sin(h))) <= 1e-3) continue;
    }
    line.push_back(p);
    headings.push_back(h);
  }
  if (!lanes_offset_from_it) return simplify_3d(line, tolerance_m);
  return simplify_3d(line, tolerance_m, headings, kMaxTurnRad);
}

}  // namespace relief

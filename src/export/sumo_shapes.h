#pragma once
// Polylines of OpenDRIVE curves for SUMO shapes: sampled every metre, then simplified in 3D.

#include <functional>

#include "relief/roads/road_model.h"

namespace relief {

/// The curve s -> surface_point(road, s, t_of(s)) for s in [s_begin, s_end] (s_end < 0: the road's
/// end), as a 3D polyline whose chords stay within `tolerance_m` of samples taken every metre
/// (Douglas-Peucker in 3D). With `lanes_offset_from_it` (an edge's shape, its lanes offset from
/// the chords by SUMO) the chords also turn at most 2 degrees; a lane's own shape (an internal
/// lane) needs only the tolerance, and has about half the points.
[[nodiscard]] Polyline3 sample_road_curve(const ModelRoad& road, const std::function<double(double)>& t_of,
                                          double tolerance_m, double s_begin = 0.0, double s_end = -1.0,
                                          bool lanes_offset_from_it = true);

/// Douglas-Peucker in 3D: the kept points of `line` (both ends always kept). With `headings`
/// (one per point, radians), a chord is also split while the headings at its ends differ by more
/// than `max_turn_rad`: SUMO offsets lanes from the chords, and a lane `t` metres aside lands on
/// the right station only when the chords turn little.
[[nodiscard]] Polyline3 simplify_3d(const Polyline3& line, double tolerance_m,
                                    const std::vector<double>& headings = {}, double max_turn_rad = 0.0);

}  // namespace relief

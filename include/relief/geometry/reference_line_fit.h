#pragma once
// Reference lines fitted to what relief has in plan: an OSM centreline rounded at its vertices
// (lines and arcs within a tolerance, no arc tighter than the lanes allow), and the connectors
// that join two poses inside a junction or across a transition (paramPoly3 Hermite curves,
// corner arcs). The records are plan_view.h's.

#include <vector>

#include "relief/geometry/plan_view.h"
#include "relief/geometry/types.h"

namespace relief {

/// Options for fitting a reference line to a polyline.
struct ReferenceLineOptions {
  double tolerance_m = 0.05;   ///< max distance of the reference line from the polyline
  double min_length_m = 1e-3;  ///< records shorter than this are merged away
  /// Smallest arc radius (m), 0 for none. A road's lane borders at |t| fold back wherever the
  /// radius is below |t|, so a road takes its outermost border |t| plus a margin. Corners that
  /// cannot be rounded that wide within tolerance_m depart from the polyline (see
  /// ReferenceLineReport).
  double min_radius_m = 0.0;
};

/// What ReferenceLineOptions::min_radius_m cost.
struct ReferenceLineReport {
  std::size_t corners_widened = 0;  ///< corners whose radius was raised to min_radius_m
  std::size_t vertices_merged = 0;  ///< polyline vertices dropped or merged to make room for such arcs
  /// Largest distance of a polyline vertex from the reference line when corners were widened
  /// or merged (0 otherwise: the fit then stays within tolerance_m).
  double max_departure_m = 0.0;
};

/// G1 reference line through a polyline: straight segments as `line` records joined by `arc`
/// records that round each corner within the tolerance (never arc with curvature 0, no
/// zero-length records). `station_map` receives, for each polyline vertex, the reference-line
/// s nearest to it, so that quantities given along the polyline (elevation) can be re-mapped
/// (the arc's midpoint for a rounded vertex; the ends map to 0 and length(); vertices merged
/// away are interpolated by polyline length between their neighbours).
/// Vertices closer than 1 mm are merged first. Each corner of turning angle θ gets the radius
/// max(min_radius, min(tolerance / (1/cos(θ/2) - 1), min(half adjacent segment) / tan(|θ|/2)));
/// where two such arcs would overlap on a segment, their corners are merged into one (the
/// intersection of the outer segments' lines for two turns the same way, else the midpoint),
/// and a corner whose arc would overrun the polyline's first or last segment is dropped, so
/// that no arc is tighter than min_radius and both ends keep their position. Lines between two
/// arcs that fill their segment vanish; a line that would be shorter than min_length_m shrinks
/// its neighbouring arcs to reach it (or, when that would go below min_radius, grows them until
/// it vanishes; only a line on a polyline segment that is itself shorter than min_length_m can
/// stay shorter, so that the fit never leaves the polyline).
/// Throws InvalidInput for fewer than two distinct vertices, non-finite vertices, a tolerance
/// that is not positive, or a negative or non-finite min_length_m or min_radius_m.
[[nodiscard]] PlanView fit_reference_line(const Polyline2& polyline, const ReferenceLineOptions& options,
                                          std::vector<double>* station_map = nullptr,
                                          ReferenceLineReport* report = nullptr);

/// A paramPoly3 (normalized) leaving `from` with its heading and arriving at `to` with its
/// heading: the cubic Hermite curve with tangent lengths `tangent_scale` x the chord. Its record
/// length is the curve's arc length. A straight-ahead pair within 1e-9 gives a `line`.
/// Throws InvalidInput when the positions coincide or tangent_scale is not positive.
[[nodiscard]] PlanGeometry hermite_connector(const Pose2& from, const Pose2& to, double tangent_scale = 0.5);

/// A connector from `from` to `to` (both headings kept) made of the roundest circular arc that
/// fits the corner between them, and a line before or after it: the two headings' lines meet at
/// distances a (ahead of `from`) and b (behind `to`); the arc turns with radius
/// min(a, b) / tan(|θ|/2) and a line takes up |a - b|. Its smallest radius is the largest any
/// curve keeping both poses can have where a and b differ (a cubic Hermite between such poses
/// bends far tighter near the nearer end). Where the turn is under 0.001 rad or over 0.9 π it
/// falls back to hermite_connector with arc_tangent_scale, and where the lines do not meet ahead
/// of both poses (an S-bend) to hermite_connector with tangents as long as the chord. Throws
/// InvalidInput as hermite_connector does.
[[nodiscard]] std::vector<PlanGeometry> corner_connector(const Pose2& from, const Pose2& to);

/// The tangent scale (tangent length over chord) at which hermite_connector follows the circular
/// arc through a turn of `turn_rad` radians, 2 tan(θ/4) / sin(θ/2): 1 when straight, about 1.17 at
/// a right angle. Shorter tangents pinch the bend in the middle into a radius well under the
/// arc's (at 0.5 and a right angle, under half of it), which folds the lanes of a tight turn.
/// Turns beyond 0.9 π are taken as 0.9 π (the scale grows without bound towards a U-turn).
[[nodiscard]] double arc_tangent_scale(double turn_rad);

}  // namespace relief

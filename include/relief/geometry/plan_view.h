#pragma once
// Reference lines as OpenDRIVE describes them (planView): a sequence of geometry records, each
// starting at arc length `s` at (x, y) with heading `hdg`, of one of the kinds below. Used by
// relief's road model, its OpenDRIVE writer and reader, and every evaluation of the road surface.

#include <vector>

#include "relief/geometry/types.h"

namespace relief {

/// Position and heading on a reference line.
struct Pose2 {
  Vec2 position = Vec2::Zero();
  double heading = 0.0;    ///< radians, counter-clockwise from +x
  double curvature = 0.0;  ///< 1/m, positive turning left
};

/// Cubic in a parameter p: value(p) = a + b p + c p^2 + d p^3.
struct Poly3 {
  double a = 0.0, b = 0.0, c = 0.0, d = 0.0;
  [[nodiscard]] double value(double p) const { return a + p * (b + p * (c + p * d)); }
  [[nodiscard]] double derivative(double p) const { return b + p * (2.0 * c + 3.0 * d * p); }
  [[nodiscard]] double second_derivative(double p) const { return 2.0 * c + 6.0 * d * p; }
};

struct PlanGeometry {
  enum class Kind { line, arc, spiral, param_poly3 };
  Kind kind = Kind::line;
  double s = 0.0;  ///< start arc length along the reference line (m)
  Vec2 start = Vec2::Zero();
  double heading = 0.0;          ///< at the start (rad)
  double length = 0.0;           ///< arc length (m), > 0
  double curvature = 0.0;        ///< arc
  double curvature_start = 0.0;  ///< spiral (clothoid): curvature varies linearly in s
  double curvature_end = 0.0;
  /// paramPoly3: local u (along the start heading) and v (to its left) as cubics of p;
  /// p in [0, 1] when `normalized` (OpenDRIVE pRange="normalized"), else p in [0, length].
  Poly3 u, v;
  bool normalized = true;
};

/// A reference line: records sorted by s, each starting where the previous ends.
class PlanView {
 public:
  PlanView() = default;
  /// Throws InvalidInput unless every record has a positive, finite length, a finite start, and
  /// the records are strictly increasing in s. Continuity between records is not checked.
  explicit PlanView(std::vector<PlanGeometry> records);

  [[nodiscard]] const std::vector<PlanGeometry>& records() const { return records_; }
  /// End s of the last record (0 when empty).
  [[nodiscard]] double length() const;
  /// Pose at arc length s (clamped to [records().front().s, length()], normally [0, length()]).
  /// Throws InvalidInput when the plan view has no records.
  [[nodiscard]] Pose2 at(double s) const;
  /// Index of the record containing s (binary search; a record's start s belongs to it; s before
  /// the first record gives 0, after the last the last). Throws InvalidInput when empty.
  [[nodiscard]] std::size_t record_at(double s) const;
  /// Angle turned over [s0, s1], both ways counted: the integral of |curvature|. Exact for
  /// lines, arcs and spirals; paramPoly3 records are sampled at the midpoints of steps of at
  /// most 0.25 m. 0 when s1 <= s0 or the plan view is empty.
  [[nodiscard]] double total_turn(double s0, double s1) const;

 private:
  std::vector<PlanGeometry> records_;
  std::vector<std::vector<double>> arc_tables_;  ///< per paramPoly3 record: cumulative arc length
};

/// Cumulative arc length of a paramPoly3 record at 33 evenly spaced parameters (what PlanView
/// caches so that evaluating it does not integrate the whole curve each time).
[[nodiscard]] std::vector<double> param_poly3_arc_table(const PlanGeometry& record);

/// Pose at `ds` metres into one record (ds is clamped to [0, record.length]). Spirals are
/// integrated numerically (error < 1e-9 m); paramPoly3 arc length is mapped to p by a cumulative
/// table (error < 1e-6 m), scaled so that ds = record.length is the end of the parameter range.
[[nodiscard]] Pose2 evaluate(const PlanGeometry& record, double ds);

/// Arc length of a paramPoly3 over its parameter range (Gauss-Legendre, error < 1e-9 m).
[[nodiscard]] double param_poly3_length(const Poly3& u, const Poly3& v, double p_end);

}  // namespace relief

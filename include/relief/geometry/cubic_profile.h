#pragma once
// A function of arc length as OpenDRIVE poly3 records (elevation, superelevation, lane width,
// lane offset): piece i covers [s_i, s_{i+1}) with value a + b ds + c ds^2 + d ds^3, ds = s - s_i.

#include <optional>
#include <utility>
#include <vector>

#include "relief/geometry/plan_view.h"

namespace relief {

struct CubicPiece {
  double s = 0.0;
  Poly3 poly;  ///< in ds = s - this->s
};

class CubicProfile {
 public:
  CubicProfile() = default;
  /// Throws InvalidInput unless the pieces' s are finite and strictly increasing.
  explicit CubicProfile(std::vector<CubicPiece> pieces);
  /// A constant function.
  [[nodiscard]] static CubicProfile constant(double value);

  [[nodiscard]] const std::vector<CubicPiece>& pieces() const { return pieces_; }
  [[nodiscard]] bool empty() const { return pieces_.empty(); }
  /// Value at s (the first piece extends to the left, the last to the right). 0 when empty.
  [[nodiscard]] double value(double s) const;
  [[nodiscard]] double derivative(double s) const;

 private:
  [[nodiscard]] std::size_t piece_at(double s) const;
  std::vector<CubicPiece> pieces_;
};

/// Fits C1 cubic pieces to samples (s_i, z_i), s strictly increasing: cubic Hermite pieces
/// between knots chosen among the samples, with knot slopes from the samples (three-point
/// derivative), extending each piece while every sample it spans stays within `tolerance`.
/// Value and slope are continuous at every knot; the first and last samples are reproduced
/// exactly, as are `end_slopes` when given (slope at s_0 and at s_n). Knots are found greedily
/// (exponential then binary search for the longest piece), O(n log n). One sample gives a
/// constant (or a line with the first end slope). Throws InvalidInput for no samples, sizes that
/// differ, stations not strictly increasing, non-finite values, or a negative tolerance.
[[nodiscard]] CubicProfile fit_cubic_profile(
    const std::vector<double>& s, const std::vector<double>& z, double tolerance,
    const std::optional<std::pair<double, double>>& end_slopes = std::nullopt);

/// Like fit_cubic_profile, with the grade kept within the samples' own: the samples' polyline
/// with each kink rounded by a parabolic vertical curve (within half the tolerance), merged
/// into the longest Hermite pieces whose slope stays within the steepest grade they replace
/// (+0.01 %) and that keep every sample within `tolerance`. The slope never exceeds the largest
/// of the chord grades |z_(i+1) - z_i| / (s_(i+1) - s_i) and the end slopes, except that an end
/// interval's grade rises by at most tolerance / (4 (its length - its ramp / 2)) to pay for the
/// ramp from the end slope. A fitted profile that keeps its grade limits between samples keeps
/// them here too, where a cubic through the samples would overshoot them between (a steep
/// stretch between two flatter ones). First and last samples and the end slopes (three-point
/// estimates when not given) are exact. A tolerance of 0 gives fit_cubic_profile. Throws as
/// fit_cubic_profile.
[[nodiscard]] CubicProfile fit_grade_bounded_profile(
    const std::vector<double>& s, const std::vector<double>& z, double tolerance,
    const std::optional<std::pair<double, double>>& end_slopes = std::nullopt);

/// The cubic on [0, length] with value z0, slope g0 at 0 and value z1, slope g1 at length.
/// Throws InvalidInput unless length is positive and finite.
[[nodiscard]] CubicProfile hermite_profile(double length, double z0, double g0, double z1, double g1);

/// The slope bound of slope_bounded_profile: max(|g0|, |g1|, |z1 - z0| / length + allowance).
[[nodiscard]] double slope_bound(double length, double z0, double g0, double z1, double g1, double allowance);

/// A C1 profile on [0, length] with the ends of hermite_profile whose slope stays within
/// bound = max(|g0|, |g1|, |z1 - z0| / length + `allowance`): the Hermite cubic (the smoothest)
/// where its slope stays within bound + allowance (it overshoots where the end slopes pull
/// against the mean grade, e.g. a short steep connection that leaves downhill and arrives
/// climbing), else a slope that ramps linearly from g0 to a constant c within the bound and from
/// c to g1 over ramps of equal length, as long as the bound allows (parabolic vertical curves
/// joined by a straight grade: two or three pieces). Throws
/// InvalidInput unless length is positive and finite and allowance >= 0.
[[nodiscard]] CubicProfile slope_bounded_profile(double length, double z0, double g0, double z1, double g1,
                                                 double allowance);

}  // namespace relief

#pragma once
// Heights along a line brought within a grade limit, departing from the given ones only where
// they are steeper than the limit.

#include <vector>

namespace relief {

/// Heights z'_i at the stations s_i (strictly increasing) whose chords keep |z'_(i+1) - z'_i| <=
/// limit (s_(i+1) - s_i), the same as z at both ends and wherever z and its neighbours within 2
/// `round_m` already keep the limit. Two steps: the heights nearest z in least squares within the
/// limit (solve_soft_qp: the limit's rows dearest, each end's first chord at z's grade as a cheaper
/// row, and so is every chord within min(round_m, a quarter of the line) of an end, so that the
/// line leaves its ends as z does and the mean below has nothing to round there; then the solver's
/// rounding taken out, so that the limit holds exactly); then, around the stations that moved, a
/// moving mean of that polyline over [s - h, s + h], h(s) = min(round_m, s - s_0, s_n - s, max(0, 2
/// round_m - d(s))), d the distance to the nearest moved station. A window whose half-width changes
/// by at most its own step keeps the limit (the mean's slope is a blend of the window's two half
/// chords), so the result keeps it too, with its corners rounded (no kink where it leaves z).
/// Throws InvalidInput for sizes that differ, fewer than two stations, stations not strictly
/// increasing, non-finite values, a limit or round_m not finite and >= 0, or ends further apart in
/// height than the limit allows; Error when the solver does not converge.
[[nodiscard]] std::vector<double> grade_limited(const std::vector<double>& s, const std::vector<double>& z,
                                                double limit, double round_m);

}  // namespace relief

#pragma once
// A sparse convex quadratic programme whose constraint rows are soft, each with a price per unit
// of violation:
//
//   minimise   1/2 x'Px + q'x + sum_r price_r * v_r
//   subject to lower_r - v_r <= a_r x <= upper_r + v_r,   v_r >= 0
//
// P symmetric positive definite (n x n), A sparse (m x n); a bound may be infinite (a one-sided
// row), every price finite and positive. With every row soft the problem is always feasible and
// its dual bounded (the multiplier of row r lies in [-price_r, price_r]); the L1 price is exact:
// where the rows could all be met and every price exceeds the force its row bears, the soft
// optimum is the hard one (Nocedal & Wright, Numerical Optimization, 2nd ed., 17.2-17.3). Several
// priorities are several price levels: a cheaper row gives way first, and only where it conflicts
// with a dearer one.
//
// Method. A primal-dual interior point (Mehrotra's predictor-corrector, Nocedal & Wright 16.6)
// on the normal equations (P + A'DA) dx = r, kept in the wide neighbourhood of its central path
// (s_i y_i >= gamma c_i mu, c_i how central pair i started, at most 1; Wright, Primal-Dual
// Interior-Point Methods, ch. 5-6). It starts from the unconstrained minimiser after a few rounds
// of quadratic penalties on the rows found violated, stiffened while a row stays beyond its bound
// (a start near feasibility wherever feasibility is possible). Rows far inside their
// bounds are screened out: the interior point runs on the rows near or beyond a bound, every row
// is checked at its solution, and the rows found violated join another round (a point that meets
// every row left out solves the whole problem: those rows carry no multiplier).
// Where rows conflict the interior point can stall (the multipliers of the rows that end violated
// must climb to their prices); then, from its last point, the method of multipliers solves the
// same L1 form (Rockafellar 1976): each round minimises an augmented Lagrangian, convex and
// piecewise quadratic with a Lipschitz gradient, by a semismooth Newton method with an exact line
// search (convergent from any start), then moves the multipliers, which stay within their prices.
// The rounds are the proximal point method on the dual and converge to the L1 optimum; they stop
// when no row's split residual exceeds 1e-7 row units. Either way the priorities hold exactly
// (a conflict falls on the cheapest row alone) and every row left violated is reported by the
// caller, so a conflict is never silent.
// The pattern of P + A'A is analysed once, in the caller's fill-reducing order; each iteration
// of either method factorises it numerically once (sparse LDL').

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace relief {

struct SoftQp {
  Eigen::SparseMatrix<double> P;                   ///< n x n, symmetric (both triangles stored)
  Eigen::VectorXd q;                               ///< n
  Eigen::SparseMatrix<double, Eigen::RowMajor> A;  ///< m x n
  Eigen::VectorXd lower, upper;                    ///< m, -inf / +inf allowed, lower <= upper
  Eigen::VectorXd price;                           ///< m, finite, > 0, per unit of violation
  /// Optional, m entries: rows the screening always takes, from the first round on (rows that
  /// bind over long stretches, which screening by distance finds only over many rounds).
  std::vector<std::uint8_t> always;
  /// Optional, m entries: a group per row (>= 0; -1 for none). When a round finds a row of a
  /// group violated, the whole group joins the next round (rows of one road bind together: a
  /// kink pushed out of one row moves to the next).
  std::vector<int> group;
  /// Optional, n entries: the value a variable is held at (NaN: free). The solver eliminates the
  /// held variables (their terms move into q and into the rows' bounds; a row left without a free
  /// variable is dropped from the solve, its value and violation still reported) and solves for
  /// the others: a hard equality that no price can move.
  std::vector<double> fixed;
};

struct SoftQpOptions {
  /// Relative accuracy of stationarity and of the duality gap, and the absolute accuracy (row
  /// units) to which every row left out is checked.
  double tolerance = 1e-9;
  /// Relative duality gap the interior point closes before it stops (default: `tolerance`).
  /// The gap is what leaves a solution off the optimum by the barrier's pull on the rows near
  /// their bounds; closing it further costs an iteration or two per decade and makes solutions
  /// of overlapping problems (region tiles) agree to well under a millimetre.
  std::optional<double> gap_tolerance;
  int max_iterations = 200;      ///< interior-point iterations per screening round
  int max_rounds = 10;           ///< screening rounds
  int newton_iterations = 2000;  ///< Newton iterations of the method of multipliers (all rounds)
  /// Fill-reducing order of the variables: indices()[old] = new. Without one, AMD on the
  /// pattern of P + A'A.
  std::optional<Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int>> ordering;
  /// Called with one line per iteration (residuals, step) when set: for diagnosis.
  std::function<void(const std::string&)> trace;
};

struct SoftQpResult {
  Eigen::VectorXd x;
  Eigen::VectorXd row_values;  ///< A x
  Eigen::VectorXd violation;   ///< per row: how far A x lies outside [lower, upper] (>= 0)
  Eigen::VectorXd multiplier;  ///< per row: the force it bears (> 0 at its lower bound; 0 if out)
  int iterations = 0;          ///< iterations of both methods
  int rounds = 0;              ///< screening rounds of the interior point, or multiplier rounds
  std::size_t rows_used = 0;   ///< rows in the last round / outside their bounds at the end
  bool converged = false;
  double stationarity = 0.0;  ///< ||Px + q - A'y||_inf relative to the largest of its terms
  double gap = 0.0;           ///< complementarity left, relative to 1 + |objective|
  double objective = 0.0;     ///< including the prices of the violations
  std::string status;         ///< "converged", or why not
  std::string method;         ///< "interior point", or the fallback and why
};

/// Solves the programme. Throws InvalidInput for inconsistent sizes, lower > upper or a price
/// that is not finite and positive; Error when P + A'DA cannot be factorised (P not positive
/// definite).
[[nodiscard]] SoftQpResult solve_soft_qp(const SoftQp& problem, const SoftQpOptions& options = {});

}  // namespace relief

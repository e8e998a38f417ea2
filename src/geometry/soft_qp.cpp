#include "relief/geometry/soft_qp.h"

#include <Eigen/OrderingMethods>
#include <Eigen/SparseCholesky>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "geometry/soft_qp_fixed.h"
#include "relief/core/errors.h"

namespace relief {
namespace {

using SpMat = Eigen::SparseMatrix<double>;
using RowMat = Eigen::SparseMatrix<double, Eigen::RowMajor>;
using Vec = Eigen::VectorXd;
using Permutation = Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int>;

constexpr double kStepFraction = 0.99;   // of the step to the boundary of the positive orthant
constexpr double kNeighbourhood = 1e-3;  // gamma of the neighbourhood s_i y_i >= gamma c_i mu
constexpr double kStartMu = 1.0;
constexpr double kStartForceCap = 1e3;     // complementarity at the start (force x row unit)
constexpr double kStartProductCap = 1e5;   // largest complementarity at the start
constexpr double kStartPriceShare = 0.25;  // w's least share of the price at the start
constexpr double kStartSlackShare = 0.05;  // smallest starting slack, share of the row's scale
constexpr double kMaxCentring = 1.0;       // largest sigma
constexpr std::size_t kStallWindow = 20;
constexpr int kStallIterations = 4;             // without progress once the gap is closed
constexpr double kRoundingStationarity = 1e-4;  // accepted then (relative force imbalance)
constexpr double kRoundingGap = 1e-7;           // and the relative gap accepted with it
constexpr double kFarBound = 1e6;               // a missing bound, this many row scales away
constexpr int kPenaltyRounds = 12;              // of the start's quadratic penalties
constexpr double kPenaltyShare = 1e-3;          // their first weight, a share of the row's price
constexpr double kPenaltyGrowth = 3.0;          // a spring's growth while its row stays beyond
constexpr double kSplitResidual = 1e-7;         // row units: the method of multipliers stops there
constexpr int kMultiplierRounds = 100;
constexpr double kMaxStiffening = 1e6;  // the stiffest envelope, relative to P's diagonal

// The normal matrix M = P + A'DA in the elimination order, upper triangle (the form the LDL'
// factorisation reads without a copy), with a fixed pattern: every P entry and every entry pair
// of every row has its slot in the value array, found once.
class NormalMatrix {
 public:
  NormalMatrix(const SpMat& P, const RowMat& A, const Permutation& order) : A_(A), order_(order) {
    const auto n = static_cast<int>(P.rows());
    const auto perm = [&](Eigen::Index i) { return order.indices()[i]; };
    {
      std::vector<Eigen::Triplet<double>> pattern;
      pattern.reserve(static_cast<std::size_t>(P.nonZeros()) / 2 + static_cast<std::size_t>(n) +
                      static_cast<std::size_t>(A.nonZeros()));
      for (int j = 0; j < n; ++j) {
        pattern.emplace_back(perm(j), perm(j), 0.0);  // every diagonal, also where P has none
        for (SpMat::InnerIterator it(P, j); it; ++it) {
          const int a = perm(it.row()), b = perm(j);
          if (a < b) pattern.emplace_back(a, b, 0.0);
        }
      }
      for (Eigen::Index r = 0; r < A.rows(); ++r) {
        for (RowMat::InnerIterator i(A, r); i; ++i) {
          for (RowMat::InnerIterator k(A, r); k && k.col() < i.col(); ++k) {
            const int a = perm(i.col()), b = perm(k.col());
            pattern.emplace_back(std::min(a, b), std::max(a, b), 0.0);
          }
        }
      }
      M_.resize(n, n);
      M_.setFromTriplets(pattern.begin(), pattern.end());
    }
    M_.makeCompressed();
    if (M_.nonZeros() >= std::numeric_limits<std::uint32_t>::max())
      throw Error("soft QP: the normal matrix has too many entries");

    // Slots of P's upper entries (in the new order) and their values.
    for (int j = 0; j < n; ++j) {
      for (SpMat::InnerIterator it(P, j); it; ++it) {
        const int a = perm(it.row()), b = perm(j);
        if (a > b) continue;
        p_slot_.push_back(slot(a, b));
        p_value_.push_back(it.value());
      }
    }
    // Slots of every row's entry pairs (k <= i), row after row.
    pair_start_.assign(static_cast<std::size_t>(A.rows()) + 1, 0);
    for (Eigen::Index r = 0; r < A.rows(); ++r) {
      for (RowMat::InnerIterator i(A, r); i; ++i) {
        for (RowMat::InnerIterator k(A, r); k && k.col() <= i.col(); ++k) {
          const int a = perm(i.col()), b = perm(k.col());
          pair_slot_.push_back(slot(std::min(a, b), std::max(a, b)));
        }
      }
      pair_start_[static_cast<std::size_t>(r) + 1] = pair_slot_.size();
    }
    ldlt_.analyzePattern(M_);
  }

  /// Factorises M = P + sum over the rows given of d_k a_r a_r'.
  void factorise(const std::vector<int>& rows, const std::vector<double>& d) {
    double* values = M_.valuePtr();
    std::fill(values, values + M_.nonZeros(), 0.0);
    for (std::size_t k = 0; k < p_slot_.size(); ++k) values[p_slot_[k]] += p_value_[k];
    const int* outer = A_.outerIndexPtr();
    const double* a = A_.valuePtr();
    const int* col = A_.innerIndexPtr();
    for (std::size_t k = 0; k < rows.size(); ++k) {
      const double dk = d[k];
      if (dk == 0.0) continue;
      const int r = rows[k];
      std::size_t slot = pair_start_[static_cast<std::size_t>(r)];
      for (int i = outer[r]; i < outer[r + 1]; ++i) {
        for (int j = outer[r]; j < outer[r + 1] && col[j] <= col[i]; ++j)
          values[pair_slot_[slot++]] += dk * a[i] * a[j];
      }
    }
    ldlt_.factorize(M_);
    // Near the end of an interior point D spans many orders of magnitude, and rounding can
    // leave a pivot that is not positive: retry with a growing relative shift of the diagonal
    // (a proximal term, which changes the direction, not the solution it converges to).
    double shift = 1e-14;
    while (ldlt_.info() != Eigen::Success && shift < 1e-6) {
      for (int j = 0; j < M_.outerSize(); ++j) {
        const int last = M_.outerIndexPtr()[j + 1] - 1;  // the diagonal ends each upper column
        values[last] += shift * std::max(1.0, std::abs(values[last]));
      }
      ldlt_.factorize(M_);
      shift *= 100.0;
    }
    if (ldlt_.info() != Eigen::Success)
      throw Error("soft QP: the normal equations could not be factorised (is P positive definite?)");
  }

  /// Solves M x = b in the caller's variable order, with one step of iterative refinement
  /// (D spans many orders of magnitude near the end of an interior point, and the factor's
  /// rounding would otherwise floor the accuracy of the steps).
  void solve(const Vec& b, Vec& x) {
    permuted_ = order_ * b;
    solved_ = ldlt_.solve(permuted_);
    residual_ = permuted_ - M_.selfadjointView<Eigen::Upper>() * solved_;
    solved_ += ldlt_.solve(residual_);
    x = order_.transpose() * solved_;
  }

 private:
  [[nodiscard]] std::uint32_t slot(int row, int col) const {
    const int* begin = M_.innerIndexPtr() + M_.outerIndexPtr()[col];
    const int* end = M_.innerIndexPtr() + M_.outerIndexPtr()[col + 1];
    return static_cast<std::uint32_t>(std::lower_bound(begin, end, row) - M_.innerIndexPtr());
  }

  const RowMat& A_;
  const Permutation& order_;
  SpMat M_;
  std::vector<std::uint32_t> p_slot_;
  std::vector<double> p_value_;
  std::vector<std::size_t> pair_start_;
  std::vector<std::uint32_t> pair_slot_;
  Vec permuted_, solved_, residual_;
  Eigen::SimplicialLDLT<SpMat, Eigen::Upper, Eigen::NaturalOrdering<int>> ldlt_;
};

void validate(const SoftQp& problem) {
  const Eigen::Index n = problem.P.rows();
  const Eigen::Index m = problem.A.rows();
  if (!problem.fixed.empty() && problem.fixed.size() != static_cast<std::size_t>(n))
    throw InvalidInput("soft QP: inconsistent sizes");
  for (const double v : problem.fixed) {
    if (std::isinf(v)) throw InvalidInput("soft QP: a variable is held at an infinite value");
  }
  if (problem.P.cols() != n || problem.q.size() != n || problem.A.cols() != n || problem.lower.size() != m ||
      problem.upper.size() != m || problem.price.size() != m ||
      (!problem.always.empty() && problem.always.size() != static_cast<std::size_t>(m)) ||
      (!problem.group.empty() && problem.group.size() != static_cast<std::size_t>(m))) {
    throw InvalidInput("soft QP: inconsistent sizes");
  }
  for (Eigen::Index r = 0; r < m; ++r) {
    if (!(problem.lower[r] <= problem.upper[r]))
      throw InvalidInput("soft QP: row " + std::to_string(r) + " has lower > upper");
    if (!(problem.price[r] > 0.0) || !std::isfinite(problem.price[r]))
      throw InvalidInput("soft QP: row " + std::to_string(r) + " has no finite positive price");
  }
}

Permutation amd_order(const SpMat& P, const RowMat& A) {
  SpMat pattern = P;
  const SpMat At = SpMat(A.transpose());
  pattern += SpMat(At * A);
  Permutation inverse;
  Eigen::AMDOrdering<int>()(pattern, inverse);
  return inverse.inverse();
}

// a_r . x for row r of A.
inline double row_dot(const RowMat& A, int r, const double* x) {
  const int* outer = A.outerIndexPtr();
  double s = 0.0;
  for (int i = outer[r]; i < outer[r + 1]; ++i) s += A.valuePtr()[i] * x[A.innerIndexPtr()[i]];
  return s;
}

// out += f a_r.
inline void row_scatter(const RowMat& A, int r, double f, double* out) {
  const int* outer = A.outerIndexPtr();
  for (int i = outer[r]; i < outer[r + 1]; ++i) out[A.innerIndexPtr()[i]] += f * A.valuePtr()[i];
}

// The rows in the interior point, each with two finite bounds (a missing one is moved far away)
// and three complementarity pairs: sl yl (lower bound), su yu (upper bound), v w (the violation,
// and what is left of its price), each pair with its centrality c at the start (its product over
// the mean product, at most 1), which the neighbourhood keeps it from falling far below.
// Struct of arrays, indexed by position in the working set.
struct WorkingRows {
  std::vector<int> row;  // index in A
  std::vector<double> scale, l, u, c;
  std::vector<double> sl, yl, su, yu, v, w;
  std::vector<double> tl, tu, tv;  // centralities at the start
  // Per iteration: residuals, scalings, the right-hand side parts and the direction.
  std::vector<double> r1, r2, r3, th_l, th_u, big_w, d, f;
  std::vector<double> dsl, dyl, dsu, dyu, dv, dw;

  [[nodiscard]] std::size_t size() const { return row.size(); }
  void resize() {
    const std::size_t m = row.size();
    for (auto* a : {&sl,   &yl,   &su,    &yu, &v, &w,   &tl,  &tu,  &tv,  &r1, &r2, &r3,
                    &th_l, &th_u, &big_w, &d,  &f, &dsl, &dyl, &dsu, &dyu, &dv, &dw})
      a->resize(m);
  }
  /// Copies the slacks and multipliers of `from`: kept with a point the run may end at, and given
  /// back with it, so that a run ending at an earlier point answers with that point's multipliers.
  void copy_point(const WorkingRows& from) {
    sl = from.sl, yl = from.yl, su = from.su, yu = from.yu, v = from.v, w = from.w;
  }
  [[nodiscard]] double product(std::size_t k, double alpha) const {
    return (sl[k] + alpha * dsl[k]) * (yl[k] + alpha * dyl[k]) +
           (su[k] + alpha * dsu[k]) * (yu[k] + alpha * dyu[k]) +
           (v[k] + alpha * dv[k]) * (w[k] + alpha * dw[k]);
  }
};

// The predictor's row directions, kept for the corrector's second-order term.
struct AffineDirection {
  std::vector<double> dsl, dyl, dsu, dyu, dv, dw;
  void take(WorkingRows& rows) {
    dsl.swap(rows.dsl);
    dyl.swap(rows.dyl);
    dsu.swap(rows.dsu);
    dyu.swap(rows.dyu);
    dv.swap(rows.dv);
    dw.swap(rows.dw);
    rows.resize();
  }
};

class InteriorPoint {
 public:
  InteriorPoint(const SoftQp& qp, NormalMatrix& normal, const SoftQpOptions& options)
      : qp_(qp), A_(qp.A), normal_(normal), options_(options) {}

  [[nodiscard]] const WorkingRows& rows() const { return rows_; }

  /// Takes row r into the working set.
  void add(int r) {
    const double l = qp_.lower[r], u = qp_.upper[r];
    const bool has_l = std::isfinite(l), has_u = std::isfinite(u);
    // A row's scale: its width, or for a one-sided row its bound's size.
    const double scale = has_l && has_u ? u - l : 1.0 + std::abs(has_l ? l : u);
    rows_.row.push_back(r);
    rows_.scale.push_back(scale);
    rows_.l.push_back(has_l ? l : u - kFarBound * scale);
    rows_.u.push_back(has_u ? u : l + kFarBound * scale);
    rows_.c.push_back(qp_.price[r]);
  }

  /// Runs the interior point from `x` on the working rows until the tolerance or the
  /// iteration limit.
  void run(Vec& x, const std::vector<double>& force, SoftQpResult& out) {
    start(x, force);
    const std::size_t m = rows_.size();
    const Eigen::Index n = x.size();
    Vec Px(n), Atz(n), rd(n), rhs(n), dx(n);
    const double tol = options_.tolerance;
    const double gap_tol = options_.gap_tolerance.value_or(tol);
    const double pairs = std::max(3.0 * static_cast<double>(m), 1.0);
    double best_stationarity = std::numeric_limits<double>::infinity();
    Vec best_x;
    WorkingRows best_rows;  // the rows' slacks and multipliers at best_x
    // The best point whose bounds and prices hold and whose gap is closed to kRoundingGap (by its
    // stationarity): where the iteration ends without meeting the tolerance (a step that turns
    // non-finite as mu reaches 1e-10, a stall of rounding), that point is the answer when its
    // stationarity is within kRoundingStationarity. Portland (after a one-road change) reached
    // 2e-8 at iteration 49, and its next steps lost s and y to rounding.
    double acceptable_stationarity = std::numeric_limits<double>::infinity();
    Vec acceptable_x;
    WorkingRows acceptable_rows;
    SoftQpResult acceptable;
    const auto end_without_tolerance = [&](const char* status) {
      if (acceptable_stationarity <= kRoundingStationarity) {
        if (options_.trace)
          options_.trace(std::string(status) +
                         ": the best point within the rounding tolerances is the answer");
        x = acceptable_x;
        rows_.copy_point(acceptable_rows);
        out.stationarity = acceptable.stationarity;
        out.gap = acceptable.gap;
        out.objective = acceptable.objective;
        out.converged = true;
        return;
      }
      out.converged = false;
      out.status = status;
    };
    std::vector<double> merits;
    int stalled = 0;
    for (int iter = 0;; ++iter) {
      // Residuals, the scaling of every row and D.
      Px = qp_.P * x;
      Atz.setZero();
      double gap = 0.0, penalty = 0.0, price_residual = 0.0, primal = 0.0;
      for (std::size_t k = 0; k < m; ++k) {
        const int r = rows_.row[k];
        const double t = row_dot(A_, r, x.data());
        row_scatter(A_, r, rows_.yl[k] - rows_.yu[k], Atz.data());
        rows_.r1[k] = rows_.sl[k] - (t - rows_.l[k] + rows_.v[k]);
        rows_.r2[k] = rows_.su[k] - (rows_.u[k] - t + rows_.v[k]);
        rows_.r3[k] = rows_.yl[k] + rows_.yu[k] + rows_.w[k] - rows_.c[k];
        primal = std::max({primal, std::abs(rows_.r1[k]), std::abs(rows_.r2[k])});
        price_residual = std::max(price_residual, std::abs(rows_.r3[k]) / rows_.c[k]);
        gap += rows_.product(k, 0.0);
        penalty += rows_.c[k] * std::max({0.0, rows_.l[k] - t, t - rows_.u[k]});
        // th = y / s of each bound; W = w + v (th_l + th_u). Nothing divides by v: v is tiny on
        // every row inside its bounds, w of the order of the price.
        const double tl = rows_.yl[k] / rows_.sl[k], tu = rows_.yu[k] / rows_.su[k];
        const double v = rows_.v[k], w = rows_.w[k];
        rows_.th_l[k] = tl;
        rows_.th_u[k] = tu;
        rows_.big_w[k] = w + v * (tl + tu);
        rows_.d[k] = ((tl + tu) * w + 4.0 * v * tl * tu) / rows_.big_w[k];
      }
      rd = Px + qp_.q - Atz;
      const double objective = 0.5 * x.dot(Px) + qp_.q.dot(x) + penalty;
      const double scale = std::max({1.0, Px.lpNorm<Eigen::Infinity>(), qp_.q.lpNorm<Eigen::Infinity>(),
                                     Atz.lpNorm<Eigen::Infinity>()});
      out.stationarity = rd.lpNorm<Eigen::Infinity>() / scale;
      out.gap = gap / (1.0 + std::abs(objective));
      out.objective = objective;
      const double mu = gap / pairs;
      if (out.stationarity <= 10.0 * tol && primal <= tol && price_residual <= tol && out.gap <= gap_tol) {
        out.converged = true;
        return;
      }
      if (!std::isfinite(gap) || !std::isfinite(out.stationarity)) {
        end_without_tolerance("not finite");
        return;
      }
      if (primal <= tol && price_residual <= tol && out.gap <= kRoundingGap &&
          out.stationarity < acceptable_stationarity) {
        acceptable_stationarity = out.stationarity;
        acceptable_x = x;
        acceptable_rows.copy_point(rows_);
        acceptable = out;
      }
      // Complementarity gone and stationarity down to what rounding leaves in the normal
      // equations: no further step can improve the point. Keep the best point seen, and stop
      // there once the gap is closed and stationarity has not improved for a few iterations.
      if (out.gap <= tol && primal <= tol && price_residual <= tol) {
        if (out.stationarity < best_stationarity) {
          best_stationarity = out.stationarity;
          best_x = x;
          best_rows.copy_point(rows_);
          stalled = 0;
        } else if (++stalled >= kStallIterations) {
          if (best_stationarity > kRoundingStationarity) {
            // Rounding spoilt the steps after the gap closed: an earlier point within the
            // rounding tolerances (kRoundingGap), if there is one, is the answer.
            end_without_tolerance("stalled");
            return;
          }
          x = best_x;
          rows_.copy_point(best_rows);
          out.stationarity = best_stationarity;
          out.converged = true;
          return;
        }
      }
      if (iter >= options_.max_iterations) {
        end_without_tolerance("iteration limit");
        return;
      }
      // No progress: the residuals and the gap not down by a tenth over kStallWindow iterations.
      const double merit = std::max({out.stationarity, primal, out.gap});
      merits.push_back(merit);
      if (merits.size() > kStallWindow && merit > 0.9 * merits[merits.size() - 1 - kStallWindow]) {
        end_without_tolerance("stalled");
        return;
      }
      ++out.iterations;
      normal_.factorise(rows_.row, rows_.d);

      // Predictor (affine scaling), then the corrector with centring and the second-order term;
      // the centred direction without that term when the corrector takes a much shorter step.
      direction(rd, rhs, dx, 0.0, nullptr);
      const double alpha_aff = max_step();
      double gap_aff = 0.0;
      for (std::size_t k = 0; k < m; ++k) gap_aff += rows_.product(k, alpha_aff);
      // Mehrotra's centring, capped: when the predictor is blocked (a step of 1e-4), sigma = 1 would
      // only re-centre, iteration after iteration, without closing the gap.
      const double sigma = std::min(kMaxCentring, std::pow(std::clamp(gap_aff / gap, 0.0, 1.0), 3.0));
      affine_.take(rows_);
      direction(rd, rhs, dx, sigma * mu, &affine_);
      double alpha = std::min(1.0, kStepFraction * max_step());
      if (alpha < 0.1 * alpha_aff) {
        direction(rd, rhs, dx, sigma * mu, nullptr);
        alpha = std::min(1.0, kStepFraction * max_step());
      }
      alpha = neighbourhood_step(alpha, pairs);
      if (options_.trace) {
        char line[256];
        std::snprintf(line, sizeof line,
                      "iteration %d rows %zu: stationarity %.2e primal %.2e gap %.2e mu %.2e sigma %.2e "
                      "alpha %.2e (predictor %.2e)",
                      iter, m, out.stationarity, primal, out.gap, mu, sigma, alpha, alpha_aff);
        options_.trace(line);
      }

      x += alpha * dx;
      for (std::size_t k = 0; k < m; ++k) {
        rows_.sl[k] += alpha * rows_.dsl[k];
        rows_.su[k] += alpha * rows_.dsu[k];
        rows_.v[k] += alpha * rows_.dv[k];
        rows_.yl[k] += alpha * rows_.dyl[k];
        rows_.yu[k] += alpha * rows_.dyu[k];
        rows_.w[k] += alpha * rows_.dw[k];
      }
    }
  }

 private:
  // Starts every working row at `x`: the slacks what x leaves (at least a share of the row's
  // scale), the multipliers kStartMu over them, or the force the start's penalty put on the row
  // where that is larger (so that the start is as stationary as the point it came from), the rest
  // of the price in w (dual feasible), v = kStartMu / w. Each pair's centrality is its product
  // over the mean (at most 1): the central path itself is the uniform one (every product the same
  // mu), and the neighbourhood lets a pair that starts far below the mean stay as far below in
  // proportion, no further. (With these products as the path's weights instead, a weighted path,
  // the products spanned ten orders of magnitude and the iterations crawled at steps of 0.2-0.3
  // where rows a millimetre wide bind along whole roads: the generated mountain range's fit took
  // 161 iterations, 115 of them in its first round.) A violated row starts primal infeasible (a
  // positive slack although x lies beyond the bound), a residual the iterations close by moving x
  // or growing v. (Starting it primal feasible instead, v past its violation, puts a
  // complementarity of price x violation on it, and the centring then pushes every other row
  // towards that average.)
  void start(const Vec& x, const std::vector<double>& force) {
    const std::size_t m = rows_.size();
    rows_.resize();
    for (std::size_t k = 0; k < m; ++k) {
      const int r = rows_.row[k];
      const double t = row_dot(A_, r, x.data());
      const double c = rows_.c[k];
      const double floor = std::max(kStartSlackShare * rows_.scale[k], 8.0 * kStartMu / c);
      const double f_given = force.empty() ? 0.0 : force[static_cast<std::size_t>(r)];
      const double f = std::abs(f_given) >= 0.5 * c ? f_given : std::clamp(f_given, -0.25 * c, 0.25 * c);
      const double below = rows_.l[k] - t, above = t - rows_.u[k];
      if (std::abs(f) >= 0.5 * c && std::max(below, above) > 0.0) {
        // A row known to end violated (the quadratic-penalty solution pushed it with at least
        // half its price) starts as it ends: its violation in v, the violated bound's slack ~0
        // and its multiplier the rest of the price, every product kStartMu where that leaves
        // room: w and the far bound's multiplier at most a quarter of the price each, so that
        // the near bound's keeps at least half (a cheap row's kStartMu / v alone can exceed its
        // price: the start had a negative multiplier and the interior point stepped backwards).
        const double tiny = kStartMu / c;
        rows_.v[k] = std::max(below, above) + tiny;
        rows_.sl[k] = t - rows_.l[k] + rows_.v[k];
        rows_.su[k] = rows_.u[k] - t + rows_.v[k];
        rows_.w[k] = std::min(kStartMu / rows_.v[k], kStartPriceShare * c);
        if (below > 0.0) {
          rows_.yu[k] = std::min(kStartMu / rows_.su[k], kStartPriceShare * c);
          rows_.yl[k] = c - rows_.w[k] - rows_.yu[k];
        } else {
          rows_.yl[k] = std::min(kStartMu / rows_.sl[k], kStartPriceShare * c);
          rows_.yu[k] = c - rows_.w[k] - rows_.yl[k];
        }
      } else {
        rows_.sl[k] = std::max(t - rows_.l[k], floor);
        rows_.su[k] = std::max(rows_.u[k] - t, floor);
        double yl = std::max(std::min(kStartMu / rows_.sl[k], kStartForceCap), f);
        double yu = std::max(std::min(kStartMu / rows_.su[k], kStartForceCap), -f);
        // w = c - yl - yu keeps at least a quarter of the price: a row that ended the last
        // round at its bound with a force near its price would otherwise start with w <= 0,
        // v = kStartMu / w negative, outside the positive orthant.
        const double room = (1.0 - kStartPriceShare) * c;
        if (yl + yu > room) {
          const double scale = room / (yl + yu);
          yl *= scale;
          yu *= scale;
        }
        rows_.yl[k] = yl;
        rows_.yu[k] = yu;
        // A bound that bears a large force starts near it: its slack at most kStartProductCap
        // over the force. (A row at its bound with a force of 1e8 and its slack at the floor had
        // a product of 1e7, which set mu, and the centring then pulled every other pair up
        // towards it at steps of 1e-5: three of ProfileFit.RandomNetworksConverge's twelve
        // networks stalled, as they do with a cap of 1e6. With 1-10 some of the generated
        // mountain chains stalled, with 1e3 Liechtenstein; 1e4-3e5 solve all of them, and 1e5
        // lies in the middle.) Where the slack was larger, the row starts primal infeasible by
        // the difference, like a violated row.
        rows_.sl[k] = std::min(rows_.sl[k], kStartProductCap / yl);
        rows_.su[k] = std::min(rows_.su[k], kStartProductCap / yu);
        rows_.w[k] = c - yl - yu;
        rows_.v[k] = kStartMu / rows_.w[k];
      }
      rows_.tl[k] = rows_.sl[k] * rows_.yl[k];
      rows_.tu[k] = rows_.su[k] * rows_.yu[k];
      rows_.tv[k] = rows_.v[k] * rows_.w[k];
    }
    double sum = 0.0;
    for (std::size_t k = 0; k < m; ++k) sum += rows_.tl[k] + rows_.tu[k] + rows_.tv[k];
    const double mean = std::max(sum / std::max(3.0 * static_cast<double>(m), 1.0), 1e-300);
    for (std::size_t k = 0; k < m; ++k) {
      rows_.tl[k] = std::min(1.0, rows_.tl[k] / mean);
      rows_.tu[k] = std::min(1.0, rows_.tu[k] / mean);
      rows_.tv[k] = std::min(1.0, rows_.tv[k] / mean);
    }
  }

  // One Newton direction. The complementarity targets are rho = target - s y (minus the
  // predictor's ds dy when `affine` is given); per row, dz = dyl - dyu = -D g + e with g = a dx,
  // so (P + A'DA) dx = -rd + A'e, then each row's parts follow from g. Eliminating dsl, dsu,
  // dyl, dyu and dw and solving v's complementarity for dv:
  //   dv = (rho6 + v (a + b + r3) + v (th_u - th_l) g) / W,  W = w + v (th_l + th_u),
  //   a = rho4 / sl + th_l r1,  b = rho5 / su + th_u r2,  e = a - b + (th_u - th_l) f / W,
  // with f the part of dv's numerator without g.
  void direction(const Vec& rd, Vec& rhs, Vec& dx, double target, const AffineDirection* affine) {
    const std::size_t m = rows_.size();
    rhs = -rd;
    for (std::size_t k = 0; k < m; ++k) {
      double rho4 = target - rows_.sl[k] * rows_.yl[k];
      double rho5 = target - rows_.su[k] * rows_.yu[k];
      double rho6 = target - rows_.v[k] * rows_.w[k];
      if (affine) {
        rho4 -= affine->dsl[k] * affine->dyl[k];
        rho5 -= affine->dsu[k] * affine->dyu[k];
        rho6 -= affine->dv[k] * affine->dw[k];
      }
      // Keep the targets for the recovery below in the direction's own slots.
      rows_.dyl[k] = rho4;
      rows_.dyu[k] = rho5;
      const double a = rho4 / rows_.sl[k] + rows_.th_l[k] * rows_.r1[k];
      const double b = rho5 / rows_.su[k] + rows_.th_u[k] * rows_.r2[k];
      const double f = rho6 + rows_.v[k] * (a + b + rows_.r3[k]);
      rows_.f[k] = f;
      const double e = (rows_.th_u[k] - rows_.th_l[k]) * f / rows_.big_w[k] + a - b;
      row_scatter(A_, rows_.row[k], e, rhs.data());
    }
    normal_.solve(rhs, dx);
    for (std::size_t k = 0; k < m; ++k) {
      const double g = row_dot(A_, rows_.row[k], dx.data());
      const double rho4 = rows_.dyl[k], rho5 = rows_.dyu[k];
      const double dv = (rows_.f[k] + rows_.v[k] * (rows_.th_u[k] - rows_.th_l[k]) * g) / rows_.big_w[k];
      const double dsl = g + dv - rows_.r1[k];
      const double dsu = -g + dv - rows_.r2[k];
      rows_.dv[k] = dv;
      rows_.dsl[k] = dsl;
      rows_.dsu[k] = dsu;
      rows_.dyl[k] = rho4 / rows_.sl[k] - rows_.th_l[k] * dsl;
      rows_.dyu[k] = rho5 / rows_.su[k] - rows_.th_u[k] * dsu;
      rows_.dw[k] = -rows_.r3[k] - rows_.dyl[k] - rows_.dyu[k];
    }
  }

  // The largest step up to `alpha` (shrunk by 0.8 at a time) that keeps every complementarity
  // pair at least kNeighbourhood times its centrality at the start times the mean product.
  [[nodiscard]] double neighbourhood_step(double alpha, double pairs) const {
    const std::size_t m = rows_.size();
    for (int tries = 0; tries < 60; ++tries, alpha *= 0.8) {
      double sum = 0.0;
      for (std::size_t k = 0; k < m; ++k) sum += rows_.product(k, alpha);
      const double floor = kNeighbourhood * sum / pairs;
      bool inside = true;
      for (std::size_t k = 0; k < m && inside; ++k) {
        inside =
            (rows_.sl[k] + alpha * rows_.dsl[k]) * (rows_.yl[k] + alpha * rows_.dyl[k]) >=
                floor * rows_.tl[k] &&
            (rows_.su[k] + alpha * rows_.dsu[k]) * (rows_.yu[k] + alpha * rows_.dyu[k]) >=
                floor * rows_.tu[k] &&
            (rows_.v[k] + alpha * rows_.dv[k]) * (rows_.w[k] + alpha * rows_.dw[k]) >= floor * rows_.tv[k];
      }
      if (inside) return alpha;
    }
    return alpha;
  }

  // The largest step (<= 1) that keeps every slack and multiplier non-negative.
  [[nodiscard]] double max_step() const {
    double alpha = 1.0;
    const auto limit = [&](double value, double delta) {
      if (delta < 0.0) alpha = std::min(alpha, -value / delta);
    };
    for (std::size_t k = 0; k < rows_.size(); ++k) {
      limit(rows_.sl[k], rows_.dsl[k]);
      limit(rows_.yl[k], rows_.dyl[k]);
      limit(rows_.su[k], rows_.dsu[k]);
      limit(rows_.yu[k], rows_.dyu[k]);
      limit(rows_.v[k], rows_.dv[k]);
      limit(rows_.w[k], rows_.dw[k]);
    }
    return alpha;
  }

  const SoftQp& qp_;
  const RowMat& A_;
  NormalMatrix& normal_;
  const SoftQpOptions& options_;
  WorkingRows rows_;
  AffineDirection affine_;
};

// The L1 form by the interior point, in screening rounds.
SoftQpResult interior_point(const SoftQp& problem, NormalMatrix& normal, const SoftQpOptions& options) {
  const SpMat& P = problem.P;
  const RowMat& A = problem.A;
  const Eigen::Index n = P.rows();
  const Eigen::Index m = A.rows();
  const Vec& l = problem.lower;
  const Vec& u = problem.upper;
  InteriorPoint ipm(problem, normal, options);
  SoftQpResult out;

  // The unconstrained minimiser, then rounds of the interior point: the first on the rows within
  // a quarter of their width of a bound there (a one-sided row: within its bound's size) and the
  // rows the caller marked, each later one adding the rows the last solution violates.
  Vec x;
  normal.factorise({}, {});
  normal.solve(-problem.q, x);
  Vec t = A * x;
  // From there, rounds of one-sided quadratic penalties on the rows found violated, each pulled
  // a little inside its bound (the penalty first a thousandth of its price, so priorities hold,
  // then three times stiffer each round its row stays beyond the bound, up to the price): a start
  // near feasibility wherever feasibility is possible. (Without the growth, rows a millimetre
  // wide stayed several widths beyond their bounds, for the interior point to cross.) Parts of the
  // problem the objective hardly determines (a deck whose only data are its anchors) would
  // otherwise start anywhere, and an interior point needs many short steps to cross a large
  // infeasibility among tight rows.
  // One-sided: a spring whose row ends inside its aim is released in the next round, because it
  // would pull the row back towards the bound with a force no bound bears; the interior point
  // then starts with every remaining spring's force as that row's multiplier, stationary. (With
  // two-sided springs, kept on, Portland's interior point started with force imbalances of 1e6
  // on rows inside their bounds, crawled at steps of 1e-3 and stalled; 223 s for its fit, 17-19 s
  // now.) The rounds end when no spring is added, released or stiffened, after at most
  // kPenaltyRounds.
  std::vector<double> force(static_cast<std::size_t>(m), 0.0);  // the rows' forces at x
  std::vector<int> penalised;
  std::vector<double> rho, aim;
  std::vector<int> side;  // -1: pushed up from the lower bound, 1: down from the upper
  std::vector<std::uint8_t> taken(static_cast<std::size_t>(m), 0);
  Vec rhs(n);
  int penalty_rounds = 0;
  for (int round = 0; round < kPenaltyRounds; ++round) {
    // Release the springs whose rows the last solution left inside their aim; add the rows
    // newly beyond a bound.
    std::size_t changed = 0;
    for (std::size_t k = 0; k < penalised.size();) {
      const int r = penalised[k];
      const bool beyond = side[k] < 0 ? t[r] < aim[k] : t[r] > aim[k];
      if (beyond) {
        // Still beyond the bound itself: a stiffer spring, up to the row's price.
        const bool outside = side[k] < 0 ? t[r] < l[r] : t[r] > u[r];
        if (outside && rho[k] < problem.price[r]) {
          rho[k] = std::min(problem.price[r], kPenaltyGrowth * rho[k]);
          ++changed;
        }
        ++k;
        continue;
      }
      taken[static_cast<std::size_t>(r)] = 0;
      penalised[k] = penalised.back();
      rho[k] = rho.back();
      aim[k] = aim.back();
      side[k] = side.back();
      penalised.pop_back();
      rho.pop_back();
      aim.pop_back();
      side.pop_back();
      ++changed;
    }
    for (Eigen::Index r = 0; r < m; ++r) {
      if (taken[static_cast<std::size_t>(r)]) continue;
      const bool low = std::isfinite(l[r]) && t[r] < l[r], high = std::isfinite(u[r]) && t[r] > u[r];
      if (!low && !high) continue;
      const double width =
          std::isfinite(l[r]) && std::isfinite(u[r]) ? u[r] - l[r] : 1.0 + std::abs(low ? l[r] : u[r]);
      const double inside = std::min(0.1 * width, 0.5 * (std::isfinite(u[r] - l[r]) ? u[r] - l[r] : width));
      taken[static_cast<std::size_t>(r)] = 1;
      penalised.push_back(static_cast<int>(r));
      rho.push_back(kPenaltyShare * problem.price[r]);
      aim.push_back(low ? l[r] + inside : u[r] - inside);
      side.push_back(low ? -1 : 1);
      ++changed;
    }
    if (options.trace) {
      options.trace("start round " + std::to_string(round) + ": " + std::to_string(changed) +
                    " springs changed, " + std::to_string(penalised.size()) + " on");
    }
    if (changed == 0) break;
    normal.factorise(penalised, rho);
    rhs = -problem.q;
    for (std::size_t k = 0; k < penalised.size(); ++k)
      row_scatter(A, penalised[k], rho[k] * aim[k], rhs.data());
    normal.solve(rhs, x);
    t = A * x;
    ++penalty_rounds;
  }
  if (options.trace) {
    options.trace("start: " + std::to_string(penalty_rounds) + " penalty rounds, " +
                  std::to_string(penalised.size()) + " rows on springs");
  }
  // The springs' forces at x, where they push the row towards its bound's inside.
  for (std::size_t k = 0; k < penalised.size(); ++k) {
    const double f = rho[k] * (aim[k] - t[penalised[k]]);
    if (f * side[k] < 0.0) force[static_cast<std::size_t>(penalised[k])] = f;
  }
  std::vector<std::uint8_t> in(static_cast<std::size_t>(m), 0);
  // Rows of each group, for taking a group whole.
  std::vector<std::vector<int>> members;
  if (!problem.group.empty()) {
    int groups = 0;
    for (const int g : problem.group) groups = std::max(groups, g + 1);
    members.resize(static_cast<std::size_t>(groups));
    for (Eigen::Index r = 0; r < m; ++r) {
      const int g = problem.group[static_cast<std::size_t>(r)];
      if (g >= 0) members[static_cast<std::size_t>(g)].push_back(static_cast<int>(r));
    }
  }
  std::vector<std::uint8_t> group_taken(members.size(), 0);
  const auto bounded = [&](Eigen::Index r) { return std::isfinite(l[r]) || std::isfinite(u[r]); };
  for (int round = 1;; ++round) {
    std::size_t added = 0;
    const auto take = [&](Eigen::Index r) {
      const auto k = static_cast<std::size_t>(r);
      if (in[k] || !bounded(r)) return;
      in[k] = 1;
      ipm.add(static_cast<int>(r));
      ++added;
    };
    for (Eigen::Index r = 0; r < m; ++r) {
      const auto k = static_cast<std::size_t>(r);
      if (in[k] || !bounded(r)) continue;
      const bool has_l = std::isfinite(l[r]), has_u = std::isfinite(u[r]);
      const double near = round > 1        ? -options.tolerance
                          : has_l && has_u ? 0.25 * (u[r] - l[r])
                                           : 1.0 + std::abs(has_l ? l[r] : u[r]);
      const bool always = round == 1 && !problem.always.empty() && problem.always[k];
      if (!always && !(has_l && t[r] < l[r] + near) && !(has_u && t[r] > u[r] - near)) continue;
      take(r);
      const int g = problem.group.empty() ? -1 : problem.group[k];
      if (round > 1 && g >= 0 && !group_taken[static_cast<std::size_t>(g)]) {
        group_taken[static_cast<std::size_t>(g)] = 1;
        for (const int other : members[static_cast<std::size_t>(g)]) take(other);
      }
    }
    if (round > 1 && added == 0) break;  // every row left out holds: the whole problem is solved
    if (round > options.max_rounds) {
      out.converged = false;
      out.status = "screening round limit";
      break;
    }
    out.rounds = round;
    ipm.run(x, force, out);
    // A later round starts from the multipliers this one found.
    const WorkingRows& solved = ipm.rows();
    std::fill(force.begin(), force.end(), 0.0);
    for (std::size_t k = 0; k < solved.size(); ++k)
      force[static_cast<std::size_t>(solved.row[k])] = solved.yl[k] - solved.yu[k];
    t = A * x;
    if (!out.converged) break;
  }
  if (out.converged) out.status = "converged";
  out.rows_used = ipm.rows().size();

  out.x = x;
  out.row_values = t;
  out.violation = Vec::Zero(m);
  out.multiplier = Vec::Zero(m);
  for (Eigen::Index r = 0; r < m; ++r) {
    out.violation[r] =
        std::max({0.0, std::isfinite(l[r]) ? l[r] - t[r] : 0.0, std::isfinite(u[r]) ? t[r] - u[r] : 0.0});
  }
  const WorkingRows& rows = ipm.rows();
  for (std::size_t k = 0; k < rows.size(); ++k) out.multiplier[rows.row[k]] = rows.yl[k] - rows.yu[k];
  return out;
}

// The L1 form by the method of multipliers (Rockafellar, "Augmented Lagrangians and applications
// of the proximal point algorithm in convex programming", Math. Oper. Res. 1, 1976). Each round
// minimises the augmented Lagrangian
//   1/2 x'Px + q'x + sum_r H_r(a_r x + y_r / rho_r),
// H_r the Moreau envelope (parameter 1/rho_r) of price_r dist(., [l_r, u_r]): rho_r/2 e^2 for an
// excess e over the bounds of up to price_r / rho_r, linear at the price beyond. Then every y_r
// becomes H_r's slope there, which stays in [-price_r, price_r]. A round's objective is convex
// and piecewise quadratic with a Lipschitz gradient; the semismooth Newton method minimises it
// from any start (the generalised Hessian P + sum over the rows in their quadratic zone of
// rho_r a_r a_r', an exact line search along each step) and is exact once those rows settle. The
// rounds are the proximal point method on the dual, so the multipliers converge to the L1
// optimum's for any rho > 0 that never falls: rho_r starts at price_r and grows 10x for a row
// whose residual does not fall to a quarter in a round. The method stops when a round moves no
// row's split residual |y_new - y_old| / rho_r (the violation of a row not at its price) by more
// than kSplitResidual.
// With y = 0 the first round is the quadratic-penalty form, in which a conflict is shared by
// price; the later rounds give each row back its priority.
SoftQpResult multiplier_method(const SoftQp& problem, NormalMatrix& normal, const SoftQpOptions& options,
                               Vec x) {
  const SpMat& P = problem.P;
  const RowMat& A = problem.A;
  const Eigen::Index n = P.rows();
  const Eigen::Index m = A.rows();
  const Vec& l = problem.lower;
  const Vec& u = problem.upper;
  const Vec& c = problem.price;
  const auto excess = [&](Eigen::Index r, double value) {
    if (value < l[r]) return value - l[r];
    if (value > u[r]) return value - u[r];
    return 0.0;
  };
  // H_r's slope at w, and whether w lies in its quadratic zone (0 < |excess| < c_r / rho_r).
  Vec rho = c;
  const double stiffest = kMaxStiffening * std::max(1.0, P.diagonal().cwiseAbs().maxCoeff());
  // Round 0 takes the pure quadratic penalty instead (no linear zone), whose Newton steps do not
  // overshoot from a start far outside the bounds; its solution is only the rounds' start.
  int round = 0;
  const auto slope = [&](Eigen::Index r, double w, bool& quadratic) {
    const double f = rho[r] * excess(r, w);
    quadratic = f != 0.0 && (round == 0 || std::abs(f) < c[r]);
    return round == 0 ? f : std::clamp(f, -c[r], c[r]);
  };
  SoftQpResult out;
  Vec t = A * x;
  Vec y = Vec::Zero(m);
  Vec moved = Vec::Constant(m, std::numeric_limits<double>::infinity());  // split residuals, last round
  // The last round's minimiser, returned if the iterations run out before the rounds converge.
  Vec x_round = x, t_round = t, y_round = y;
  std::vector<int> active, previous;
  std::vector<double> weight;
  std::vector<int> changing;
  Vec g(n), d(n), td(m), Px(n);
  bool quadratic = false;
  for (int iter = 0;; ++iter) {
    // The gradient and the rows in their quadratic zone (the generalised Hessian's).
    active.clear();
    weight.clear();
    Px = P * x;
    g = Px + problem.q;
    for (Eigen::Index r = 0; r < m; ++r) {
      const double f = slope(r, t[r] + y[r] / rho[r], quadratic);
      if (f != 0.0) row_scatter(A, static_cast<int>(r), f, g.data());
      if (!quadratic) continue;
      active.push_back(static_cast<int>(r));
      weight.push_back(rho[r]);
    }
    const double scale = std::max({1.0, problem.q.lpNorm<Eigen::Infinity>(), Px.lpNorm<Eigen::Infinity>()});
    out.stationarity = g.lpNorm<Eigen::Infinity>() / scale;
    if (options.trace) {
      char line[160];
      std::snprintf(line, sizeof line, "multipliers %d, newton %d: quadratic %zu, gradient %.3e", round, iter,
                    active.size(), out.stationarity);
      options.trace(line);
    }
    const bool settled = iter > 0 && active == previous;
    previous.swap(active);
    if (out.stationarity <= options.tolerance || (settled && out.stationarity <= kRoundingStationarity)) {
      // The round's minimiser: the multiplier step. A row whose residual did not fall to a
      // quarter gets a 10x stiffer envelope (the usual safeguard; rho never falls, so the
      // rounds still converge).
      double residual = 0.0;
      for (Eigen::Index r = 0; r < m; ++r) {
        const double next = std::clamp(slope(r, t[r] + y[r] / rho[r], quadratic), -c[r], c[r]);
        const double split = std::abs(next - y[r]) / rho[r];
        residual = std::max(residual, split);
        y[r] = next;
        if (split > kSplitResidual && split > 0.25 * moved[r])
          rho[r] = std::min(10.0 * rho[r], std::max(c[r], stiffest));
        moved[r] = split;
      }
      x_round = x;
      t_round = t;
      y_round = y;
      ++round;
      if (options.trace) {
        char line[120];
        std::snprintf(line, sizeof line, "multipliers %d: split residual %.3e", round, residual);
        options.trace(line);
      }
      if (residual <= kSplitResidual) {
        out.converged = true;
        out.status = "converged";
        break;
      }
      if (round >= kMultiplierRounds) break;
      iter = -1;  // a new round: its first iteration is not "settled"
      continue;
    }
    if (out.iterations >= options.newton_iterations) break;
    ++out.iterations;
    normal.factorise(previous, weight);
    normal.solve(-g, d);
    td = A * d;
    // Exact line search on the convex piecewise quadratic phi(alpha): the root of its increasing
    // derivative in [0, 1], by bisection over the rows with a slope at either end (a row without
    // one at both ends is inside its bounds all along).
    const double d_pd = d.dot(P * d), g_d = (Px + problem.q).dot(d);
    changing.clear();
    for (Eigen::Index r = 0; r < m; ++r) {
      const double w = t[r] + y[r] / rho[r];
      if (excess(r, w) != 0.0 || excess(r, w + td[r]) != 0.0) changing.push_back(static_cast<int>(r));
    }
    const auto dphi = [&](double a) {
      double v = g_d + a * d_pd;
      bool unused = false;
      for (const int r : changing) v += slope(r, t[r] + y[r] / rho[r] + a * td[r], unused) * td[r];
      return v;
    };
    double alpha = 1.0;
    if (dphi(1.0) > 0.0) {
      double lo = 0.0, hi = 1.0;
      for (int k = 0; k < 50; ++k) {
        const double mid = 0.5 * (lo + hi);
        (dphi(mid) > 0.0 ? hi : lo) = mid;
      }
      alpha = 0.5 * (lo + hi);
    }
    x += alpha * d;
    t += alpha * td;
  }
  if (!out.converged && round > 0) {
    // Out of iterations or rounds: the last round's minimiser, that of the quadratic-penalty
    // form with bounds shifted by the multipliers, in which a conflict is shared by price. Its
    // violations are what the caller reports.
    x = x_round;
    t = t_round;
    y = y_round;
    out.converged = true;
    out.status = "converged";
    out.method = "; stopped after " + std::to_string(round) + " rounds at the " +
                 (round >= kMultiplierRounds ? "round" : "iteration") +
                 " limit, at the last round's quadratic-penalty form";
  } else if (!out.converged) {
    out.status = "iteration limit";
  }
  out.rounds = round;
  out.rows_used = 0;
  out.x = x;
  out.row_values = t;
  out.violation = Vec::Zero(m);
  out.multiplier = -y;
  out.objective = 0.5 * x.dot(P * x) + problem.q.dot(x);
  for (Eigen::Index r = 0; r < m; ++r) {
    out.violation[r] = std::abs(excess(r, t[r]));
    out.rows_used += out.violation[r] > 0.0 ? 1 : 0;
    out.objective += c[r] * out.violation[r];
  }
  return out;
}

}  // namespace

SoftQpResult solve_soft_qp(const SoftQp& problem, const SoftQpOptions& options) {
  validate(problem);
  if (std::any_of(problem.fixed.begin(), problem.fixed.end(), [](double v) { return !std::isnan(v); }))
    return detail::solve_with_fixed_variables(problem, options);
  const Permutation order = options.ordering ? *options.ordering : amd_order(problem.P, problem.A);
  if (order.size() != problem.P.rows()) throw InvalidInput("soft QP: the ordering has the wrong size");
  NormalMatrix normal(problem.P, problem.A, order);
  SoftQpResult ipm = interior_point(problem, normal, options);
  if (ipm.converged) {
    ipm.method = "interior point";
    return ipm;
  }
  SoftQpResult multipliers = multiplier_method(problem, normal, options, ipm.x);
  multipliers.iterations += ipm.iterations;
  multipliers.method = "method of multipliers after the interior point " + ipm.status + multipliers.method;
  return multipliers;
}

}  // namespace relief

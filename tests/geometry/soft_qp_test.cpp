#include "relief/geometry/soft_qp.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <random>

#include "relief/core/errors.h"

namespace relief {
namespace {

using Vec = Eigen::VectorXd;
using RowMat = Eigen::SparseMatrix<double, Eigen::RowMajor>;
constexpr double kInf = std::numeric_limits<double>::infinity();

// min sum_i (x_i - target_i)^2 (P = 2 I, q = -2 target) with the rows given.
SoftQp separable(const std::vector<double>& target, const std::vector<Eigen::Triplet<double>>& rows,
                 std::vector<double> lower, std::vector<double> upper, std::vector<double> price) {
  const auto n = static_cast<Eigen::Index>(target.size());
  SoftQp qp;
  qp.P.resize(n, n);
  qp.P.setIdentity();
  qp.P *= 2.0;
  qp.q = -2.0 * Eigen::Map<const Vec>(target.data(), n);
  const auto m = static_cast<Eigen::Index>(lower.size());
  qp.A.resize(m, n);
  qp.A.setFromTriplets(rows.begin(), rows.end());
  qp.lower = Eigen::Map<const Vec>(lower.data(), m);
  qp.upper = Eigen::Map<const Vec>(upper.data(), m);
  qp.price = Eigen::Map<const Vec>(price.data(), m);
  return qp;
}

TEST(SoftQp, WithoutRowsIsTheUnconstrainedMinimiser) {
  const SoftQp qp = separable({1.5, -2.0, 7.25}, {}, {}, {}, {});
  const SoftQpResult r = solve_soft_qp(qp);
  ASSERT_TRUE(r.converged) << r.status;
  EXPECT_NEAR(r.x[0], 1.5, 1e-12);
  EXPECT_NEAR(r.x[1], -2.0, 1e-12);
  EXPECT_NEAR(r.x[2], 7.25, 1e-12);
}

TEST(SoftQp, ARowDearerThanItsForceHoldsExactly) {
  // min (x - 3)^2 subject to x <= 1: the force at the bound is 2 (3 - 1) = 4 < price 10.
  const SoftQp qp = separable({3.0}, {{0, 0, 1.0}}, {-kInf}, {1.0}, {10.0});
  const SoftQpResult r = solve_soft_qp(qp);
  ASSERT_TRUE(r.converged) << r.status;
  EXPECT_NEAR(r.x[0], 1.0, 1e-8);
  EXPECT_NEAR(r.multiplier[0], -4.0, 1e-5);  // pushes x down: negative at an upper bound
  EXPECT_LT(r.violation[0], 1e-8);
}

TEST(SoftQp, ARowCheaperThanItsForceGivesWayByThePriceBalance) {
  // Same with price 1: the optimum is where the pull 2 (3 - x) equals the price, x = 2.5.
  const SoftQp qp = separable({3.0}, {{0, 0, 1.0}}, {-kInf}, {1.0}, {1.0});
  const SoftQpResult r = solve_soft_qp(qp);
  ASSERT_TRUE(r.converged) << r.status;
  EXPECT_NEAR(r.x[0], 2.5, 1e-7);
  EXPECT_NEAR(r.violation[0], 1.5, 1e-7);
  EXPECT_NEAR(r.multiplier[0], -1.0, 1e-6);
}

TEST(SoftQp, ConflictingRowsTheCheaperOneGivesWay) {
  // x >= 2 (price 100) and x <= 1 (price 10), data at 0: the cheaper row is violated by 1.
  const SoftQp qp = separable({0.0}, {{0, 0, 1.0}, {1, 0, 1.0}}, {2.0, -kInf}, {kInf, 1.0}, {100.0, 10.0});
  const SoftQpResult r = solve_soft_qp(qp);
  ASSERT_TRUE(r.converged) << r.status;
  EXPECT_NEAR(r.x[0], 2.0, 1e-7);
  EXPECT_LT(r.violation[0], 1e-7);
  EXPECT_NEAR(r.violation[1], 1.0, 1e-7);
}

TEST(SoftQp, TwoSidedRowOnADifference) {
  // min (x0 - 0)^2 + (x1 - 10)^2 with |x1 - x0| <= 2: x0 = 4, x1 = 6.
  const SoftQp qp = separable({0.0, 10.0}, {{0, 1, 1.0}, {0, 0, -1.0}}, {-2.0}, {2.0}, {1e6});
  const SoftQpResult r = solve_soft_qp(qp);
  ASSERT_TRUE(r.converged) << r.status;
  EXPECT_NEAR(r.x[0], 4.0, 1e-7);
  EXPECT_NEAR(r.x[1], 6.0, 1e-7);
  EXPECT_NEAR(r.multiplier[0], -8.0, 1e-4);
}

// KKT conditions of the L1-soft programme, checked independently of the solver:
//   P x + q = A' y,  and per row: y = 0 strictly inside, y in [0, c] at the lower bound,
//   y = c below it, y in [-c, 0] at the upper bound, y = -c above it.
// `by_terms`: stationarity relative to the largest of its terms (Px, q, the rows' forces A'y), as
// the solver measures it: where dear rows bear large opposing forces, the residual left is a
// share of those forces, not of their small sum.
void expect_kkt(const SoftQp& qp, const SoftQpResult& r, double tol, bool by_terms = false) {
  const Vec t = qp.A * r.x;
  // Multipliers implied by the row positions where they are determined.
  const Vec grad = qp.P * r.x + qp.q;
  const Vec forces = qp.A.transpose() * r.multiplier;
  const Vec residual = grad - forces;
  const double terms = by_terms ? std::max({Vec(qp.P * r.x).lpNorm<Eigen::Infinity>(),
                                            qp.q.lpNorm<Eigen::Infinity>(), forces.lpNorm<Eigen::Infinity>()})
                                : 0.0;
  const double scale = std::max({1.0, grad.lpNorm<Eigen::Infinity>(), terms});
  EXPECT_LT(residual.lpNorm<Eigen::Infinity>() / scale, tol);
  for (Eigen::Index k = 0; k < t.size(); ++k) {
    const double y = r.multiplier[k], c = qp.price[k];
    const double width = std::max(1.0, std::abs(t[k]));
    // Classified with a margin well above the solver's: it stops when every complementarity
    // product is ~1e-9 of the objective, so a row 1e-6 beyond its bound is at it.
    if (t[k] < qp.lower[k] - 1e-3 * width) {
      EXPECT_NEAR(y, c, 1e-4 * c) << "row " << k << " below its bound";
    } else if (t[k] > qp.upper[k] + 1e-3 * width) {
      EXPECT_NEAR(y, -c, 1e-4 * c) << "row " << k << " above its bound";
    } else {
      EXPECT_GE(y, -c * (1 + 1e-6));
      EXPECT_LE(y, c * (1 + 1e-6));
      if (t[k] > qp.lower[k] + 1e-3 * width && t[k] < qp.upper[k] - 1e-3 * width) {
        EXPECT_NEAR(y, 0.0, 1e-4 * scale) << "row " << k << " strictly inside";
      }
    }
  }
}

// Rows on a chain of heights: first differences (grades) and second differences (curvatures).
struct ChainRows {
  std::vector<Eigen::Triplet<double>> entries;
  std::vector<double> lower, upper, price;
  void grade(int i, double lo, double hi, double cost) {  // x[i + 1] - x[i]
    const auto r = static_cast<int>(lower.size());
    entries.emplace_back(r, i + 1, 1.0);
    entries.emplace_back(r, i, -1.0);
    add(lo, hi, cost);
  }
  void curvature(int i, double lo, double hi, double cost) {  // x[i - 1] - 2 x[i] + x[i + 1]
    const auto r = static_cast<int>(lower.size());
    entries.emplace_back(r, i - 1, 1.0);
    entries.emplace_back(r, i, -2.0);
    entries.emplace_back(r, i + 1, 1.0);
    add(lo, hi, cost);
  }
  void into(SoftQp& qp, int n) const {
    const auto m = static_cast<Eigen::Index>(lower.size());
    qp.A.resize(m, n);
    qp.A.setFromTriplets(entries.begin(), entries.end());
    qp.lower = Eigen::Map<const Vec>(lower.data(), m);
    qp.upper = Eigen::Map<const Vec>(upper.data(), m);
    qp.price = Eigen::Map<const Vec>(price.data(), m);
  }

 private:
  void add(double lo, double hi, double cost) {
    lower.push_back(lo);
    upper.push_back(hi);
    price.push_back(cost);
  }
};

// A chain like a road profile: data, second-difference smoothing, grade and curvature rows.
SoftQp random_chain(std::mt19937& rng, int n) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Eigen::Triplet<double>> p;
  Vec q(n);
  double z = 0.0, g = 0.0;
  for (int i = 0; i < n; ++i) {
    g += 0.3 * (unit(rng) - 0.5);
    z += g + 2.0 * (unit(rng) - 0.5);
    p.emplace_back(i, i, 1.0);
    q[i] = -z;
  }
  const double lambda = 5.0 + 50.0 * unit(rng);
  for (int i = 1; i + 1 < n; ++i) {
    const int idx[3] = {i - 1, i, i + 1};
    const double c[3] = {1.0, -2.0, 1.0};
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) p.emplace_back(idx[a], idx[b], lambda * c[a] * c[b]);
  }
  SoftQp qp;
  qp.P.resize(n, n);
  qp.P.setFromTriplets(p.begin(), p.end());
  qp.q = q;
  ChainRows rows;
  const double cap = 0.2 + 0.6 * unit(rng);
  for (int i = 0; i + 1 < n; ++i)  // a few cheap ones give way
    rows.grade(i, -cap, cap, unit(rng) < 0.1 ? 0.5 + unit(rng) : 1e4);
  for (int i = 1; i + 1 < n; ++i) {  // one-sided curvature rows on some stations
    if (unit(rng) < 0.7) continue;
    rows.curvature(i, -0.05, kInf, 1e3);
  }
  rows.into(qp, n);
  return qp;
}

TEST(SoftQp, RandomChainsMeetTheKktConditions) {
  // Both methods solve the L1 form itself: the same conditions, whichever one ended. The
  // interior point solves every chain alone (29 of 40 fell back to the method of multipliers
  // while a later screening round could start a row with w = price - yl - yu <= 0); the method
  // of multipliers is made to take over by an interior point held to 3 iterations.
  int rounds_over_one = 0;
  for (int seed = 1; seed <= 40; ++seed) {
    std::mt19937 rng(static_cast<unsigned>(seed));
    const SoftQp qp = random_chain(rng, 60 + seed * 7);
    const SoftQpResult r = solve_soft_qp(qp);
    SCOPED_TRACE("seed " + std::to_string(seed) + ", " + r.method);
    ASSERT_TRUE(r.converged) << r.status;
    EXPECT_EQ(r.method, "interior point");
    EXPECT_LT(r.iterations, 60);
    rounds_over_one += r.rounds > 1 ? 1 : 0;
    expect_kkt(qp, r, 1e-6);
    SoftQpOptions short_ipm;
    short_ipm.max_iterations = 3;
    const SoftQpResult m = solve_soft_qp(qp, short_ipm);
    ASSERT_TRUE(m.converged) << m.status;
    EXPECT_EQ(m.method.rfind("method of multipliers after the interior point iteration limit", 0), 0u)
        << m.method;
    expect_kkt(qp, m, 1e-6);
    // The one optimum (P is positive definite) within 1 mm (measured: at most 0.26 mm, each
    // method stopping at its own tolerance).
    EXPECT_NEAR((m.x - r.x).lpNorm<Eigen::Infinity>(), 0.0, 1e-3);
  }
  std::cout << "random chains: " << rounds_over_one << " of 40 needed more than one screening round\n";
}

// A mountain road's profile as the fit sees it: a height per metre pulled towards a steep, rough
// terrain, a grade cap on every step and a two-sided vertical-curve band on every station as
// tight as a fast road's (|z''| <= 5e-4 /m, about a millimetre wide), dear rows bound over most
// of the road. Steep stretches start several band widths outside, so the interior point must
// cross a large infeasibility among nearly equal rows: the case that made its first round crawl.
SoftQp mountain_chain(std::mt19937& rng, int n) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double a1 = 20.0 + 40.0 * unit(rng), a2 = 5.0 + 10.0 * unit(rng);
  const double w1 = 80.0 + 150.0 * unit(rng), w2 = 20.0 + 30.0 * unit(rng);
  std::vector<Eigen::Triplet<double>> p;
  Vec q(n);
  for (int i = 0; i < n; ++i) {
    const double z = 0.15 * i + a1 * std::sin(i / w1) + a2 * std::sin(i / w2) + 2.0 * (unit(rng) - 0.5);
    p.emplace_back(i, i, 1.0);
    q[i] = -z;
  }
  SoftQp qp;
  qp.P.resize(n, n);
  qp.P.setFromTriplets(p.begin(), p.end());
  qp.q = q;
  ChainRows rows;
  for (int i = 0; i + 1 < n; ++i) rows.grade(i, -0.12, 0.12, 1e9);
  for (int i = 1; i + 1 < n; ++i) rows.curvature(i, -5e-4, 4e-4, 1e7);
  rows.into(qp, n);
  qp.group.assign(rows.lower.size(), 0);  // one road: its rows bind together, as in the fit
  return qp;
}

TEST(SoftQp, MountainChainsWithTightCurveBandsConvergeInFewIterations) {
  int most = 0;
  for (int seed = 1; seed <= 12; ++seed) {
    std::mt19937 rng(static_cast<unsigned>(seed));
    const SoftQp qp = mountain_chain(rng, 1500 + 100 * seed);
    const SoftQpResult r = solve_soft_qp(qp);
    SCOPED_TRACE("seed " + std::to_string(seed) + ", " + r.method);
    ASSERT_TRUE(r.converged) << r.status;
    EXPECT_EQ(r.method, "interior point");
    expect_kkt(qp, r, 1e-5, true);
    EXPECT_LT(r.violation.lpNorm<Eigen::Infinity>(), 1e-6);  // every row can hold, and does
    most = std::max(most, r.iterations);
  }
  // Measured: at most 78 (before the uniform central path and the stiffening start: 93-118 on
  // most seeds, and seed 4's interior point stalled into the method of multipliers).
  std::cout << "mountain chains: at most " << most << " interior-point iterations\n";
  EXPECT_LE(most, 100);
}

// A held variable is a constant: x0 wants 10 but a dear row keeps it within 1 of x1, held at 5;
// a row over held variables alone is not solved but its violation is reported.
TEST(SoftQp, HeldVariablesAreConstantsTheRowsAroundThemRespect) {
  SoftQp qp = separable({10.0, 0.0, -3.0}, {{0, 0, 1.0}, {0, 1, -1.0}, {1, 1, 1.0}}, {-kInf, -kInf},
                        {1.0, 2.0}, {1e6, 1.0});
  qp.fixed = {std::nan(""), 5.0, std::nan("")};
  const SoftQpResult r = solve_soft_qp(qp);
  ASSERT_TRUE(r.converged) << r.status;
  EXPECT_EQ(r.x[1], 5.0);  // exactly
  EXPECT_NEAR(r.x[0], 6.0, 1e-7);
  EXPECT_NEAR(r.x[2], -3.0, 1e-9);
  EXPECT_NEAR(r.violation[0], 0.0, 1e-7);
  EXPECT_NEAR(r.multiplier[0], -8.0, 1e-5);  // the force 2 (x0 - 10) the row bears, at its upper bound
  EXPECT_NEAR(r.violation[1], 3.0, 1e-12);
  EXPECT_EQ(r.multiplier[1], 0.0);
  EXPECT_NEAR(r.row_values[1], 5.0, 1e-12);
  // Every variable held: nothing to solve.
  qp.fixed = {1.0, 2.0, 3.0};
  const SoftQpResult all = solve_soft_qp(qp);
  EXPECT_TRUE(all.converged);
  EXPECT_EQ(all.x, Vec((Vec(3) << 1.0, 2.0, 3.0).finished()));
  qp.fixed = {1.0, std::numeric_limits<double>::infinity(), 3.0};
  EXPECT_THROW((void)solve_soft_qp(qp), InvalidInput);
  qp.fixed = {1.0};
  EXPECT_THROW((void)solve_soft_qp(qp), InvalidInput);
}

// Holding variables at the optimum's own values leaves the optimum where it was: on random
// road-like chains with every seventh station held, in the caller's ordering (reversed).
TEST(SoftQp, HoldingVariablesAtTheOptimumKeepsIt) {
  for (int seed = 1; seed <= 10; ++seed) {
    std::mt19937 rng(static_cast<unsigned>(seed));
    SoftQp qp = random_chain(rng, 80 + seed * 5);
    const SoftQpResult free = solve_soft_qp(qp);
    ASSERT_TRUE(free.converged);
    const auto n = static_cast<int>(qp.P.rows());
    qp.fixed.assign(static_cast<std::size_t>(n), std::nan(""));
    for (int v = 0; v < n; v += 7) qp.fixed[static_cast<std::size_t>(v)] = free.x[v];
    SoftQpOptions options;
    Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> reversed(n);
    for (int v = 0; v < n; ++v) reversed.indices()[v] = n - 1 - v;
    options.ordering = reversed;
    const SoftQpResult held = solve_soft_qp(qp, options);
    SCOPED_TRACE("seed " + std::to_string(seed));
    ASSERT_TRUE(held.converged) << held.status;
    EXPECT_LE((held.x - free.x).lpNorm<Eigen::Infinity>(), 1e-4);
    EXPECT_NEAR(held.objective, free.objective, 1e-6 * (1.0 + std::abs(free.objective)));
    for (int v = 0; v < n; v += 7) EXPECT_EQ(held.x[v], free.x[v]);
  }
}

TEST(SoftQp, AMethodOfMultipliersOutOfIterationsSaysSoAndKeepsItsLastRound) {
  // A random chain whose interior point is held to 3 iterations, with too few Newton steps for
  // the method of multipliers to converge: it returns the minimiser of its last whole round,
  // whose forces stay within the prices, and says where it stopped.
  std::mt19937 rng(7U);
  const SoftQp qp = random_chain(rng, 109);
  bool stopped = false;
  for (int budget = 1; budget <= 400 && !stopped; budget *= 2) {
    SoftQpOptions few;
    few.max_iterations = 3;
    few.newton_iterations = budget;
    const SoftQpResult r = solve_soft_qp(qp, few);
    if (!r.converged) {
      EXPECT_EQ(r.status, "iteration limit");  // not even the first round finished
      continue;
    }
    if (r.method.find("stopped after") == std::string::npos) break;  // converged within the budget
    stopped = true;
    EXPECT_NE(r.method.find("iteration limit"), std::string::npos) << r.method;
    for (Eigen::Index k = 0; k < r.multiplier.size(); ++k)
      EXPECT_LE(std::abs(r.multiplier[k]), qp.price[k] * (1.0 + 1e-12));
    // The reported violations are those of the point returned.
    const Vec t = qp.A * r.x;
    for (Eigen::Index k = 0; k < t.size(); ++k) {
      const double e = std::max({qp.lower[k] - t[k], t[k] - qp.upper[k], 0.0});
      EXPECT_NEAR(r.violation[k], e, 1e-9);
    }
  }
  EXPECT_TRUE(stopped);
}

TEST(SoftQp, RowsLeftOutAreCheckedAtTheEnd) {
  // min x0^2 + x1^2 + (x2 - 10)^2, |x2 - x1| <= 1, |x1 - x0| <= 3. At the unconstrained
  // minimiser (0, 0, 10) the second row is far inside and left out; the first pulls x1 up to 4.5,
  // beyond the second, which joins in a second round. Optimum (1, 4, 5).
  const SoftQp qp = separable({0.0, 0.0, 10.0}, {{0, 2, 1.0}, {0, 1, -1.0}, {1, 1, 1.0}, {1, 0, -1.0}},
                              {-1.0, -3.0}, {1.0, 3.0}, {1e6, 1e6});
  const SoftQpResult r = solve_soft_qp(qp);
  ASSERT_TRUE(r.converged) << r.status;
  EXPECT_NEAR(r.x[0], 1.0, 1e-7);
  EXPECT_NEAR(r.x[1], 4.0, 1e-7);
  EXPECT_NEAR(r.x[2], 5.0, 1e-7);
  expect_kkt(qp, r, 1e-7);
}

TEST(SoftQp, GroupsAndAlwaysRowsDoNotChangeTheOptimum) {
  // The same with a third row far inside, the rows grouped and marked.
  SoftQp qp = separable({0.0, 0.0, 10.0}, {{0, 2, 1.0}, {0, 1, -1.0}, {1, 1, 1.0}, {1, 0, -1.0}, {2, 0, 1.0}},
                        {-1.0, -3.0, -100.0}, {1.0, 3.0, 100.0}, {1e6, 1e6, 1e6});
  qp.group = {-1, 7, 7};
  qp.always = {0, 0, 1};
  const SoftQpResult r = solve_soft_qp(qp);
  ASSERT_TRUE(r.converged) << r.status;
  EXPECT_EQ(r.rows_used, 3u);  // the marked row is in although far inside
  EXPECT_NEAR(r.x[0], 1.0, 1e-7);
  EXPECT_NEAR(r.x[1], 4.0, 1e-7);
  EXPECT_NEAR(r.x[2], 5.0, 1e-7);
}

TEST(SoftQp, RefusesInconsistentInput) {
  SoftQp qp = separable({0.0}, {{0, 0, 1.0}}, {1.0}, {0.0}, {1.0});
  EXPECT_THROW((void)solve_soft_qp(qp), InvalidInput);  // lower > upper
  qp = separable({0.0}, {{0, 0, 1.0}}, {0.0}, {1.0}, {0.0});
  EXPECT_THROW((void)solve_soft_qp(qp), InvalidInput);  // no positive price
  qp = separable({0.0}, {{0, 0, 1.0}}, {0.0}, {1.0}, {kInf});
  EXPECT_THROW((void)solve_soft_qp(qp), InvalidInput);  // infinite price
  qp = separable({0.0}, {{0, 0, 1.0}}, {0.0}, {1.0}, {1.0});
  qp.q.resize(2);
  EXPECT_THROW((void)solve_soft_qp(qp), InvalidInput);
  qp = separable({0.0}, {{0, 0, 1.0}}, {0.0}, {1.0}, {1.0});
  qp.always = {1, 1};
  EXPECT_THROW((void)solve_soft_qp(qp), InvalidInput);
}

}  // namespace
}  // namespace relief

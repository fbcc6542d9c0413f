// Single-precision panels of a simplicial LDLᵀ factor (solver/panel_factor.hpp): they solve the
// factor they hold exactly (to double round-off), refuse what is not such a factor, and, used by
// the linear solver as a preconditioner, leave every solution within the solver's tolerance.
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <numeric>
#include <random>

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include "ddaslope/assembly/block_sparse_matrix.hpp"
#include "ddaslope/solver/linear_solver.hpp"
#include "ddaslope/solver/panel_factor.hpp"
#include "ddaslope/solver/sparse_cholesky.hpp"

using namespace ddaslope;

namespace {

/// A factor in CHOLMOD's simplicial layout: column j holds D(j,j), then L's rows below.
struct OwnedFactor {
  std::vector<int> perm, start, count, rows;
  std::vector<double> values;
  solver::SimplicialFactorView view() const {
    return {static_cast<int>(start.size()), perm.data(), start.data(), count.data(), rows.data(), values.data()};
  }
};

/// The LDLᵀ factor of a lower triangle (natural order) in that layout, with L's entries rounded
/// to single precision before it is handed over (so the panels hold it without loss) and the
/// factor's rows permuted at random; also returns L and D as Eigen holds them.
struct RoundedFactor {
  OwnedFactor owned;
  Eigen::SparseMatrix<double> l;
  Eigen::VectorXd d;
};
RoundedFactor roundedFactorOf(const Eigen::SparseMatrix<double>& lowerA, std::mt19937& rng) {
  const int n = static_cast<int>(lowerA.rows());
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::NaturalOrdering<int>> ldlt(lowerA);
  EXPECT_EQ(ldlt.info(), Eigen::Success);
  RoundedFactor r;
  r.l = ldlt.matrixL();
  for (int k = 0; k < r.l.outerSize(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(r.l, k); it; ++it)
      if (it.row() != it.col()) it.valueRef() = static_cast<double>(static_cast<float>(it.value()));
  r.d = ldlt.vectorD();
  OwnedFactor& f = r.owned;
  for (int j = 0; j < n; ++j) {
    f.start.push_back(static_cast<int>(f.rows.size()));
    f.rows.push_back(j);
    f.values.push_back(r.d[j]);
    for (Eigen::SparseMatrix<double>::InnerIterator it(r.l, j); it; ++it)
      if (it.row() > j) f.rows.push_back(static_cast<int>(it.row())), f.values.push_back(it.value());
    f.count.push_back(static_cast<int>(f.rows.size()) - f.start.back());
  }
  f.perm.resize(n);
  std::iota(f.perm.begin(), f.perm.end(), 0);
  std::shuffle(f.perm.begin(), f.perm.end(), rng);
  return r;
}

/// |x − solve(b)| / |x| for b = Pᵀ (L D Lᵀ) P x with a known x: y = P x in the factor's order,
/// c = L D Lᵀ y, b = Pᵀ c.
double relativeSolveError(const RoundedFactor& r, const solver::PanelFactor& panels) {
  const int n = static_cast<int>(r.d.size());
  const std::vector<int>& perm = r.owned.perm;
  const Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(n, -3, 4);
  Eigen::VectorXd y(n), b(n);
  for (int k = 0; k < n; ++k) y[k] = x[perm[k]];
  const Eigen::VectorXd c = r.l * (r.d.asDiagonal() * (r.l.transpose() * y));
  for (int k = 0; k < n; ++k) b[perm[k]] = c[k];
  Eigen::VectorXd solved;
  panels.solve(b, solved);
  return (solved - x).norm() / x.norm();
}

/// The panel substitution written out in scalar code, in the summation order the kernels
/// promise (src/solver/panel_kernels.inc): a row's dot product in four lanes (entry c into lane
/// c mod 4 while whole groups of four remain), combined as (l0 + l2) + (l1 + l3), then the rest
/// in order; the back pass's column sums in row order; the back triangle four rows at a time.
/// L's entries are taken as the panels hold them (rounded to single precision if `single`).
Eigen::VectorXd referenceSubstitution(const OwnedFactor& f, bool single, const Eigen::VectorXd& b) {
  const int n = static_cast<int>(f.start.size());
  const auto entry = [&](long at) { return single ? double(static_cast<float>(f.values[at])) : f.values[at]; };
  // L(f.rows[at], j) for the entry of column j at position q of its list (q = 0: D(j,j)).
  const auto at = [&](int j, int q) { return static_cast<long>(f.start[j]) + q; };
  const auto laneDot = [](const std::vector<double>& v, const std::vector<double>& y, int m) {
    double lane[4] = {0, 0, 0, 0};
    int c = 0;
    for (; c + 4 <= m; c += 4)
      for (int k = 0; k < 4; ++k) lane[k] += v[c + k] * y[c + k];
    double t = (lane[0] + lane[2]) + (lane[1] + lane[3]);
    for (; c < m; ++c) t += v[c] * y[c];
    return t;
  };
  // The panels: column k + 1 continues column k's when it is k's first row below and has k's
  // other rows below it (PanelFactor::build).
  std::vector<std::pair<int, int>> panels;  // first column, width
  for (int j = 0; j < n;) {
    int w = 1;
    for (; j + w < n; ++w) {
      const int k = j + w - 1;
      if (f.count[k] != f.count[k + 1] + 1 || f.rows[at(k, 1)] != k + 1) break;
      if (!std::equal(f.rows.begin() + at(k, 2), f.rows.begin() + at(k, f.count[k]), f.rows.begin() + at(k + 1, 1)))
        break;
    }
    panels.emplace_back(j, w);
    j += w;
  }
  Eigen::VectorXd y(n);
  for (int k = 0; k < n; ++k) y[k] = b[f.perm[k]];
  // T(r, c) = L(first + r, first + c); B(i, c) = L(row i below the panel, first + c).
  const auto T = [&](int first, int r, int c) { return entry(at(first + c, r - c)); };
  const auto B = [&](int first, int w, int i, int c) { return entry(at(first + c, w - c + i)); };
  for (const auto& [first, w] : panels) {
    std::vector<double> yc(static_cast<size_t>(w)), v;
    for (int r = 0; r < w; ++r) {
      v.assign(static_cast<size_t>(r), 0.0);
      for (int c = 0; c < r; ++c) v[c] = T(first, r, c);
      yc[r] = y[first + r] = y[first + r] - laneDot(v, yc, r);
    }
    const int below = f.count[first] - w;
    for (int i = 0; i < below; ++i) {
      v.assign(static_cast<size_t>(w), 0.0);
      for (int c = 0; c < w; ++c) v[c] = B(first, w, i, c);
      y[f.rows[at(first, w + i)]] -= laneDot(v, yc, w);
    }
  }
  for (int k = 0; k < n; ++k) y[k] /= f.values[at(k, 0)];
  for (auto p = panels.rbegin(); p != panels.rend(); ++p) {
    const auto [first, w] = *p;
    const int below = f.count[first] - w;
    std::vector<double> yc(static_cast<size_t>(w));
    for (int c = 0; c < w; ++c) {
      double sum = 0;
      for (int i = 0; i < below; ++i) sum += B(first, w, i, c) * y[f.rows[at(first, w + i)]];
      yc[c] = y[first + c] - sum;
    }
    int r = w - 1;
    for (; r >= 4; r -= 4) {
      const auto t = [&](int row, int c) { return T(first, row, c); };
      const double z0 = yc[r];
      const double z1 = yc[r - 1] -= t(r, r - 1) * z0;
      const double z2 = yc[r - 2] -= t(r, r - 2) * z0 + t(r - 1, r - 2) * z1;
      const double z3 = yc[r - 3] -= t(r, r - 3) * z0 + t(r - 1, r - 3) * z1 + t(r - 2, r - 3) * z2;
      for (int c = 0; c < r - 3; ++c)
        yc[c] -= (t(r, c) * z0 + t(r - 1, c) * z1) + (t(r - 2, c) * z2 + t(r - 3, c) * z3);
    }
    for (; r >= 1; --r)
      for (int c = 0; c < r; ++c) yc[c] -= T(first, r, c) * yc[r];
    for (int c = 0; c < w; ++c) y[first + c] = yc[c];
  }
  Eigen::VectorXd x(n);
  for (int k = 0; k < n; ++k) x[f.perm[k]] = y[k];
  return x;
}

}  // namespace

// Exact algebra: the panels hold the rounded factor without loss, so solving
// P^T L D L^T P x = b must return x up to double round-off. The matrix is a chain of 6×6 blocks
// with couplings two blocks ahead (so each block's six columns share their rows below: panels),
// ordered by a random permutation.
TEST(PanelFactor, SolvesTheFactorItHoldsToDoubleRoundOff) {
  constexpr int kBlocks = 40, n = 6 * kBlocks;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Eigen::Triplet<double>> t;
  for (int b = 0; b < kBlocks; ++b)
    for (int e = 0; e < 6; ++e) {
      t.emplace_back(6 * b + e, 6 * b + e, 40.0 + u(rng));
      for (int f = 0; f < e; ++f) t.emplace_back(6 * b + e, 6 * b + f, u(rng));
      for (int ahead = 1; ahead <= 2; ++ahead)
        if (b + ahead < kBlocks)
          for (int f = 0; f < 6; ++f) t.emplace_back(6 * (b + ahead) + f, 6 * b + e, u(rng));
    }
  Eigen::SparseMatrix<double> lowerA(n, n);
  lowerA.setFromTriplets(t.begin(), t.end());
  const RoundedFactor r = roundedFactorOf(lowerA, rng);
  solver::PanelFactor panels;
  ASSERT_TRUE(panels.build(r.owned.view()));
  EXPECT_LE(panels.panelCount(), n / 3) << "a block's columns share their rows below: they make one panel";
  // Diagonally dominant blocks: the condition number is small, so round-off stays near 1e-15.
  EXPECT_LE(relativeSolveError(r, panels), 1e-12);
}

// The same exactness for panels of every width class the solve's kernels distinguish: sixteen
// columns per pass over the rows below, then 12, 8 or 4, then 3, 2 or 1; rows four at a time and
// the rest (of 1, 2 or 3), in chunks of 16 and the rest; triangles four rows at a time and the
// rest. An arrow matrix: dense heads of 37, 27, 31, 18, 3, 20 and 8 columns (37 = 32 + 4 + 1,
// 27 = 16 + 8 + 3, 31 = 16 + 12 + 3, 18 = 16 + 2, 3, 20 = 16 + 4, 8), each coupled to the last
// 45, 45, 45, 45, 45, 14 and 7 rows and not to each other, then 6 uncoupled columns, then the 45.
// The factor's panels: each head (its width, its rows below), 6 single columns, and the 45 last
// columns, which the heads fill completely (45 wide, a triangle only). Entries random in
// (−1, 1), the diagonal dominant (300 against at most 161 + 44 off-diagonal entries a row).
TEST(PanelFactor, SolvesPanelsOfEveryWidthClassToDoubleRoundOff) {
  const std::vector<int> heads = {37, 27, 31, 18, 3, 20, 8};
  const std::vector<int> coupled = {45, 45, 45, 45, 45, 14, 7};
  constexpr int kGap = 6, kTail = 45;
  int n = kGap + kTail;
  for (const int h : heads) n += h;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Eigen::Triplet<double>> t;
  for (int j = 0; j < n; ++j) t.emplace_back(j, j, 300.0 + u(rng));
  int first = 0;
  for (size_t k = 0; k < heads.size(); ++k) {
    const int h = heads[k];
    for (int j = first; j < first + h; ++j) {
      for (int i = j + 1; i < first + h; ++i) t.emplace_back(i, j, u(rng));
      for (int i = n - coupled[k]; i < n; ++i) t.emplace_back(i, j, u(rng));
    }
    first += h;
  }
  Eigen::SparseMatrix<double> lowerA(n, n);
  lowerA.setFromTriplets(t.begin(), t.end());
  const RoundedFactor r = roundedFactorOf(lowerA, rng);
  const int expectedPanels = static_cast<int>(heads.size()) + kGap + 1;
  solver::PanelFactor panels;
  ASSERT_TRUE(panels.build(r.owned.view()));
  EXPECT_EQ(panels.panelCount(), expectedPanels) << "the heads, the single columns between, the filled tail";
  EXPECT_LE(relativeSolveError(r, panels), 1e-12);
  // Exact panels (double entries) run the same kernels on the same layout.
  solver::PanelFactor exact;
  ASSERT_TRUE(exact.build(r.owned.view(), solver::PanelFactor::Precision::Double));
  EXPECT_FALSE(exact.rounded());
  EXPECT_EQ(exact.panelCount(), expectedPanels);
  EXPECT_LE(relativeSolveError(r, exact), 1e-12);

  // Asking for the entries' cache lines ahead (a factor larger than the cache) is only a hint:
  // the substitutions return the same bits with it as without, in both precisions and kernels.
  const Eigen::VectorXd probe = Eigen::VectorXd::LinSpaced(n, -1, 3);
  for (solver::PanelFactor* p : {&panels, &exact})
    for (const auto kernel : {solver::PanelFactor::Kernel::Best, solver::PanelFactor::Kernel::Portable}) {
      Eigen::VectorXd ahead, plain;
      p->setKernel(kernel);
      p->setPrefetch(solver::PanelFactor::Prefetch::Always);
      p->solve(probe, ahead);
      p->setPrefetch(solver::PanelFactor::Prefetch::Never);
      p->solve(probe, plain);
      ASSERT_TRUE(ahead.allFinite());
      for (int k = 0; k < n; ++k) EXPECT_EQ(ahead[k], plain[k]) << "entry " << k;
      EXPECT_LE(relativeSolveError(r, *p), 1e-12) << "with the prefetch off";
    }

  // The AVX and the portable kernels split every sum into the same four lanes: the same bits
  // (panel_kernels.inc), so a run does not depend on the processor it ran on. Compared on this
  // pattern with entries of order one (L in (−1, 1), D in (1, 2)), in both precisions: the small
  // entries of a diagonally dominant factor would hide a different rounding of their sums.
  if (!solver::PanelFactor::avxAvailable()) GTEST_SKIP() << "no AVX here: one kernel only";
  OwnedFactor rough = r.owned;
  for (int j = 0; j < n; ++j)
    for (int q = 0; q < rough.count[j]; ++q)
      rough.values[rough.start[j] + q] = q == 0 ? 1.5 + u(rng) / 2 : static_cast<float>(u(rng));
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(n, 1, 2).array().sin();
  for (const auto precision : {solver::PanelFactor::Precision::Single, solver::PanelFactor::Precision::Double}) {
    solver::PanelFactor p;
    ASSERT_TRUE(p.build(rough.view(), precision));
    Eigen::VectorXd best, portable;
    p.solve(b, best);
    p.setKernel(solver::PanelFactor::Kernel::Portable);
    p.solve(b, portable);
    ASSERT_TRUE(best.allFinite());
    for (int k = 0; k < n; ++k) EXPECT_EQ(best[k], portable[k]) << "entry " << k;
    // And both the bits of the substitution written out in scalar code in the promised order:
    // a layout or kernel that adds in another order (a different rounding) fails here.
    const Eigen::VectorXd reference =
        referenceSubstitution(rough, precision == solver::PanelFactor::Precision::Single, b);
    for (int k = 0; k < n; ++k) EXPECT_EQ(best[k], reference[k]) << "entry " << k;
  }
}

// What is not a simplicial LDLᵀ factor with D > 0 is refused, not solved wrongly.
TEST(PanelFactor, RefusesWhatIsNotSuchAFactor) {
  // 2 × 2: column 0 = [D0; L10], column 1 = [D1].
  OwnedFactor f{{0, 1}, {0, 2}, {2, 1}, {0, 1, 1}, {2.0, 0.5, 3.0}};
  solver::PanelFactor panels;
  ASSERT_TRUE(panels.build(f.view()));
  OwnedFactor negative = f;
  negative.values[2] = -3.0;  // D1 < 0: not positive definite
  EXPECT_FALSE(panels.build(negative.view()));
  EXPECT_TRUE(panels.empty());
  OwnedFactor notLed = f;
  notLed.rows[0] = 1;  // column 0 not led by its diagonal
  EXPECT_FALSE(panels.build(notLed.view()));
  OwnedFactor huge = f;
  huge.values[1] = 1e300;  // beyond single precision
  EXPECT_FALSE(panels.build(huge.view()));
  EXPECT_TRUE(panels.build(huge.view(), solver::PanelFactor::Precision::Double)) << "within double precision";
  for (const double bad : {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    OwnedFactor d = f;
    d.values[0] = bad;  // D0 not a finite positive number
    EXPECT_FALSE(panels.build(d.view()));
  }
  // 3 × 3 with column 0's rows below out of order.
  OwnedFactor unsorted{{0, 1, 2}, {0, 3, 4}, {3, 1, 1}, {0, 2, 1, 1, 2}, {2.0, 0.1, 0.2, 3.0, 4.0}};
  ASSERT_TRUE(solver::PanelFactor().build(OwnedFactor{{0, 1, 2}, {0, 3, 4}, {3, 1, 1}, {0, 1, 2, 1, 2},
                                                      {2.0, 0.1, 0.2, 3.0, 4.0}}.view()));
  EXPECT_FALSE(panels.build(unsorted.view()));
}

namespace {

/// A 2-D grid of 6×6 blocks coupled to their eight neighbours (by default 46 × 46 = 2116 blocks,
/// 12 696 unknowns): the wall's pattern, large enough for rounded panels (about 1.6 million
/// entries of L under nested dissection), and diagonally dominant (Gershgorin: condition below
/// 3.2).
struct Grid {
  static constexpr int kDefaultSide = 46;
  const int side;
  std::vector<std::pair<int, int>> couplings;
  assembly::BlockSparseMatrix k;
  explicit Grid(int sideBlocks = kDefaultSide) : side(sideBlocks) {
    for (int r = 0; r < side; ++r)
      for (int c = 0; c < side; ++c) {
        const int b = r * side + c;
        if (c + 1 < side) couplings.emplace_back(b, b + 1);
        if (r + 1 < side) couplings.emplace_back(b, b + side);
        if (r + 1 < side && c + 1 < side) couplings.emplace_back(b, b + side + 1);
        if (r + 1 < side && c > 0) couplings.emplace_back(b, b + side - 1);
      }
    k.setPattern(side * side, assembly::BlockSparseMatrix::normalise(couplings));
    fill(0);
  }
  /// `drift` scales the diagonal blocks: a change of K a factor has not seen, as a step makes.
  void fill(double drift) {
    k.setZero();
    for (int b = 0; b < side * side; ++b) {
      Mat6 d = Mat6::Identity() * (60.0 + 0.01 * b) * (1 + drift * (b % 5));
      for (int e = 0; e < 6; ++e) d(e, (e + 2) % 6) = d((e + 2) % 6, e) = 1.0;
      k.addDiagonal(b, d);
    }
    for (const auto& [i, j] : couplings) k.addCoupling(i, j, Mat6::Constant(-0.5));
  }
};

/// Large-system settings: nested dissection, simplicial copy, and the panels if asked.
void largeSystem(solver::LinearSolver& s, bool panels) {
  s.setOrdering(solver::FillOrdering::NestedDissection);
  s.setSimplicialSolves(true);
  s.setPanelSolves(panels);
}

}  // namespace

// In the linear solver, a factor in long use is solved through its panels, and conjugate
// gradients still bring every solution to the solver's tolerance on K itself: 1e-12 of ‖b‖, as
// with the double factor alone, whose solutions the panels' then match to that tolerance over
// K's condition (below 3.2: 1e-11).
TEST(LinearSolver, PanelsLeaveEverySolutionWithinTheTolerance) {
  Grid g;
  solver::LinearSolver withPanels, doubleOnly;
  largeSystem(withPanels, true);
  largeSystem(doubleOnly, false);
  const Eigen::VectorXd b0 = Eigen::VectorXd::LinSpaced(g.k.size(), -2, 7);
  Eigen::VectorXd xp, xd;
  ASSERT_TRUE(withPanels.solve(g.k, b0, xp));
  ASSERT_TRUE(doubleOnly.solve(g.k, b0, xd));
  ASSERT_GE(withPanels.factorEntries(), solver::SparseCholesky::kPanelMinEntries) << "the panels' size class";
  g.fill(1e-6);
  withPanels.matrixChanged();
  doubleOnly.matrixChanged();
  for (int s = 0; s < 2 * solver::SparseCholesky::kSolvesBeforePanels; ++s) {
    const Eigen::VectorXd b = b0 + 0.1 * s * Eigen::VectorXd::Ones(g.k.size());
    ASSERT_TRUE(withPanels.solve(g.k, b, xp));
    ASSERT_TRUE(doubleOnly.solve(g.k, b, xd));
    EXPECT_LE((b - g.k.multiply(xp)).norm(), 1e-12 * b.norm()) << "solve " << s;
    EXPECT_LE((xp - xd).norm(), 1e-11 * xd.norm()) << "solve " << s;
  }
  EXPECT_GT(withPanels.panelSubstitutions(), 0) << "the panels must have been used";
  EXPECT_EQ(doubleOnly.panelSubstitutions(), 0);
  EXPECT_EQ(withPanels.stats().factorisations, 1) << "CG with the panels converged within its budget";
}

// A factor of K itself solves K exactly in double precision, without CG; through its panels it
// no longer does, so those solutions too must go through CG to the tolerance.
TEST(LinearSolver, PanelsOfAFactorOfKItselfAreCheckedToo) {
  Grid g;
  solver::LinearSolver s;
  largeSystem(s, true);
  Eigen::VectorXd x;
  for (int n = 0; n < 2 * solver::SparseCholesky::kSolvesBeforePanels; ++n) {
    const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(g.k.size(), -2 - n, 7);
    ASSERT_TRUE(s.solve(g.k, b, x));  // K unchanged: its own factor throughout
    EXPECT_LE((b - g.k.multiply(x)).norm(), 1e-12 * b.norm()) << "solve " << n;
  }
  EXPECT_GT(s.panelSubstitutions(), 0);
  EXPECT_EQ(s.stats().factorisations, 1);
}

// A factor under kPanelMinEntries gets exact panels (double entries): they solve as the factor
// does, so a factor of K itself needs no CG iteration through them, and their solutions match
// CHOLMOD's substitution to round-off (condition below 3.2: 1e-13 leaves a factor of 300 over
// double precision's 3e-16 and none for the rounded panels' 1e-7).
TEST(LinearSolver, ExactPanelsOfASmallerFactorSolveAsTheFactorDoes) {
  Grid g(20);  // 400 blocks, 2400 unknowns
  solver::LinearSolver withPanels, doubleOnly;
  largeSystem(withPanels, true);
  largeSystem(doubleOnly, false);
  Eigen::VectorXd xp, xd;
  for (int n = 0; n < 2 * solver::SparseCholesky::kSolvesBeforePanels; ++n) {
    const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(g.k.size(), -2 - n, 7);
    ASSERT_TRUE(withPanels.solve(g.k, b, xp));
    ASSERT_TRUE(doubleOnly.solve(g.k, b, xd));
    EXPECT_LE((xp - xd).norm(), 1e-13 * xd.norm()) << "solve " << n;
  }
  ASSERT_LT(withPanels.factorEntries(), solver::SparseCholesky::kPanelMinEntries) << "the exact panels' size class";
  EXPECT_GT(withPanels.panelSubstitutions(), 0) << "the panels must have been used";
  EXPECT_EQ(withPanels.stats().cgIterations, 0) << "exact panels of K's own factor need no CG iteration";
  EXPECT_EQ(withPanels.stats().factorisations, 1);
}

// The panels are rebuilt from the factor as CHOLMOD's update/downdate leaves it (columns it may
// have grown and moved): after rank-one changes, a solve through them agrees with the double
// factor's to the rounding of L's entries to single precision (about 6e-8 relative) times K's
// condition (below 3.2) and the factor's growth: within 1e-5.
TEST(SparseCholesky, PanelsFollowTheFactorThroughUpdates) {
  Grid g;
  solver::SparseCholesky panelled, exact;
  for (solver::SparseCholesky* c : {&panelled, &exact}) {
    c->setOrdering(solver::FillOrdering::NestedDissection);
    c->setSimplicialSolves(true);
    ASSERT_TRUE(c->factorise(g.k));
  }
  panelled.setPanelSolves(true);
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> block(0, g.side * g.side - 1);
  std::uniform_real_distribution<double> u(-0.3, 0.3);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(g.k.size(), -1, 3);
  for (int round = 0; round < 3; ++round) {
    // Springs between distant blocks: long paths through the factor's tree, columns that grow.
    std::vector<solver::SparseCholesky::Column> added;
    for (int q = 0; q < 40; ++q) {
      solver::SparseCholesky::Column c;
      const int i = block(rng), j = block(rng);
      if (i == j) continue;
      for (const int blk : {std::min(i, j), std::max(i, j)})
        for (int e = 0; e < 6; ++e) {
          c.rows[c.count] = 6 * blk + e;
          c.values[c.count++] = u(rng);
        }
      added.push_back(c);
    }
    ASSERT_TRUE(panelled.modify(added, true));
    ASSERT_TRUE(exact.modify(added, true));
    // A factor of this size (rounded panels) serves its first kSolvesBeforeRoundedPanels solves
    // itself, then through its panels.
    ASSERT_GE(panelled.factorEntries(), solver::SparseCholesky::kPanelMinEntries);
    for (int s = 0; s < solver::SparseCholesky::kSolvesBeforeRoundedPanels; ++s) {
      panelled.beginSolve();
      ASSERT_FALSE(panelled.solvingWithPanels()) << "round " << round << ", solve " << s;
    }
    panelled.beginSolve();
    ASSERT_TRUE(panelled.solvingWithPanels()) << "round " << round;
    Eigen::VectorXd xp, xd;
    panelled.solve(b, xp);
    exact.solve(b, xd);
    EXPECT_LE((xp - xd).norm(), 1e-5 * xd.norm()) << "round " << round;
    EXPECT_GT((xp - xd).norm(), 0.0) << "the panels, not the double factor, solved it";
  }
}

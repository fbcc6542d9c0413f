// The linear solver's stopping and refactorising rules (solver/linear_solver.hpp), on a chain of
// coupled 6×6 blocks whose factor is made stale by a change of K, as a step's geometry does.
#include <gtest/gtest.h>

#include <Eigen/Dense>

#include "ddaslope/assembly/block_sparse_matrix.hpp"
#include "ddaslope/solver/linear_solver.hpp"
#include "ddaslope/solver/sparse_cholesky.hpp"

using namespace ddaslope;

namespace {
constexpr int kBlocks = 60;

/// A chain of blocks, each coupled to the next: SPD by diagonal dominance. `drift` scales the
/// diagonal blocks, standing for the change of K the factor has not seen.
void chain(assembly::BlockSparseMatrix& k, double drift) {
  std::vector<std::pair<int, int>> couplings;
  for (int b = 0; b + 1 < kBlocks; ++b) couplings.emplace_back(b, b + 1);
  if (k.patternVersion() == 0) k.setPattern(kBlocks, assembly::BlockSparseMatrix::normalise(couplings));
  k.setZero();
  for (int b = 0; b < kBlocks; ++b) {
    Mat6 d = Mat6::Identity() * 40.0;
    for (int e = 0; e < 6; ++e) d(e, (e + 1) % 6) = d((e + 1) % 6, e) = 3.0 + 0.1 * b;
    k.addDiagonal(b, (1.0 + drift * (b % 7)) * d);
  }
  for (int b = 0; b + 1 < kBlocks; ++b) k.addCoupling(b, b + 1, Mat6::Constant(-1.5));
}

Eigen::VectorXd load() { return Eigen::VectorXd::LinSpaced(6 * kBlocks, -3, 5); }
}  // namespace

// The stopping rule: CG ends once ‖b − Kx‖ ≤ max(tolerance·‖b‖, floor). A floor above the
// residual of the stale factor's own solve accepts that solve (no CG iteration); without a floor
// CG iterates down to tolerance·‖b‖.
TEST(LinearSolver, StopsAtTheResidualFloor) {
  assembly::BlockSparseMatrix k;
  chain(k, 0.0);
  solver::LinearSolver solver;
  const Eigen::VectorXd b = load();
  Eigen::VectorXd x;
  ASSERT_TRUE(solver.solve(k, b, x));  // factorises K0
  chain(k, 1e-3);
  solver.matrixChanged();
  // The residual of one solve with K0's factor, found independently.
  assembly::BlockSparseMatrix k0;
  chain(k0, 0.0);
  solver::SparseCholesky stale;
  ASSERT_TRUE(stale.factorise(k0));
  Eigen::VectorXd first;
  stale.solve(b, first);
  const double r0 = (b - k.multiply(first)).norm();
  ASSERT_GT(r0, 1e-12 * b.norm()) << "the drift must leave work for CG";

  const long before = solver.stats().cgIterations;
  ASSERT_TRUE(solver.solve(k, b, x, 2 * r0));
  EXPECT_EQ(solver.stats().cgIterations, before);
  EXPECT_LE((b - k.multiply(x)).norm(), 2 * r0);
  // The open-close iteration asks whether such a solution is also within the strict target
  // (Simulation::solveIterate solves loosely while contact states change): it is not.
  EXPECT_FALSE(solver.lastSolveWithin(0.0));
  EXPECT_TRUE(solver.lastSolveWithin(2 * r0));

  ASSERT_TRUE(solver.solve(k, b, x));
  EXPECT_GT(solver.stats().cgIterations, before);
  EXPECT_LE((b - k.multiply(x)).norm(), 1e-12 * b.norm());
  EXPECT_TRUE(solver.lastSolveWithin(0.0));
  EXPECT_EQ(solver.stats().factorisations, 1);  // CG converged: no new factor
}

// The iteration budget: a stale factor whose CG needs more iterations than the budget is redone
// (large systems use 4 of the default 8: Simulation::configureSolver), and the fresh factor then solves K
// without iterating.
TEST(LinearSolver, RedoesAFactorThatNeedsMoreThanItsBudget) {
  for (const int budget : {8, 4}) {
    assembly::BlockSparseMatrix k;
    chain(k, 0.0);
    solver::LinearSolver solver;
    solver.setMaxIterations(budget);
    const Eigen::VectorXd b = load();
    Eigen::VectorXd x;
    ASSERT_TRUE(solver.solve(k, b, x));
    chain(k, 0.01);
    solver.matrixChanged();
    ASSERT_TRUE(solver.solve(k, b, x));
    EXPECT_LE((b - k.multiply(x)).norm(), 1e-12 * b.norm());
    const long iterations = solver.stats().cgIterations;
    if (budget == 8) {
      // The drift takes CG more than 4 iterations but fewer than 8 to absorb.
      EXPECT_GT(iterations, 4);
      EXPECT_EQ(solver.stats().factorisations, 1);
      continue;
    }
    EXPECT_EQ(solver.stats().factorisations, 2);
    ASSERT_TRUE(solver.solve(k, b, x));
    EXPECT_EQ(solver.stats().cgIterations, iterations) << "a fresh factor of K solves it directly";
  }
}

// The fill-reducing ordering and the factor's form change the factor, not the solution: a 2-D
// grid of coupled blocks (the wall's pattern, where large systems order by nested dissection and
// solve with a simplicial copy) solved with AMD, NESDIS and NESDIS simplicial gives the same x to
// round-off (all are exact Cholesky solves of one K), and switching the ordering of a solver
// redoes its symbolic analysis.
TEST(SparseCholesky, EitherFillOrderingSolvesTheSameSystem) {
  constexpr int kSide = 14;  // 196 blocks, 1176 unknowns
  std::vector<std::pair<int, int>> couplings;
  for (int r = 0; r < kSide; ++r)
    for (int c = 0; c < kSide; ++c) {
      const int b = r * kSide + c;
      if (c + 1 < kSide) couplings.emplace_back(b, b + 1);
      if (r + 1 < kSide) couplings.emplace_back(b, b + kSide);
    }
  assembly::BlockSparseMatrix k;
  k.setPattern(kSide * kSide, assembly::BlockSparseMatrix::normalise(couplings));
  k.setZero();
  for (int b = 0; b < kSide * kSide; ++b) {
    Mat6 d = Mat6::Identity() * (30.0 + 0.01 * b);
    for (int e = 0; e < 6; ++e) d(e, (e + 2) % 6) = d((e + 2) % 6, e) = 1.0;
    k.addDiagonal(b, d);
  }
  for (const auto& [i, j] : couplings) k.addCoupling(i, j, Mat6::Constant(-0.5));
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(k.size(), -2, 7);

  solver::SparseCholesky amd, nd;
  nd.setOrdering(solver::FillOrdering::NestedDissection);
  ASSERT_TRUE(amd.factorise(k));
  ASSERT_TRUE(nd.factorise(k));
  Eigen::VectorXd xa, xn;
  amd.solve(b, xa);
  nd.solve(b, xn);
  // Both residuals at round-off of K's diagonally dominant terms; the two solutions agree to it.
  EXPECT_LE((b - k.multiply(xa)).norm(), 1e-13 * b.norm());
  EXPECT_LE((b - k.multiply(xn)).norm(), 1e-13 * b.norm());
  EXPECT_LE((xa - xn).norm(), 1e-13 * xa.norm());

  // Large systems solve with a simplicial LDLᵀ copy of the supernodal factor: the same solution.
  solver::SparseCholesky simplicial;
  simplicial.setOrdering(solver::FillOrdering::NestedDissection);
  simplicial.setSimplicialSolves(true);
  ASSERT_TRUE(simplicial.factorise(k));
  Eigen::VectorXd xs;
  simplicial.solve(b, xs);
  EXPECT_LE((b - k.multiply(xs)).norm(), 1e-13 * b.norm());
  EXPECT_LE((xs - xn).norm(), 1e-13 * xn.norm());

  ASSERT_EQ(amd.symbolicAnalyses(), 1);
  amd.setOrdering(solver::FillOrdering::NestedDissection);
  ASSERT_TRUE(amd.factorise(k));
  EXPECT_EQ(amd.symbolicAnalyses(), 2) << "a new ordering needs a new symbolic analysis";
  Eigen::VectorXd again;
  amd.solve(b, again);
  EXPECT_EQ(again, xn) << "the same ordering gives the same factor, bit for bit";
}

#pragma once
// Solves the sequence of slowly changing systems K x = b of a run. The last Cholesky factor
// preconditions conjugate gradients; K is refactorised only when CG is slow, the pattern
// changed, or K lost positive definiteness. Between steps K changes by geometry (small) and
// within the open-close loop by a few contact springs (low rank): CG with the old factor then
// converges in a handful of iterations, each far cheaper than a factorisation.
#include <Eigen/Core>

#include "ddaslope/assembly/block_sparse_matrix.hpp"
#include "ddaslope/solver/sparse_cholesky.hpp"

namespace ddaslope::solver {

struct LinearSolverSettings {
  /// Relative residual ‖b − Kx‖/‖b‖ at which CG stops. Smaller: closer to a direct solve.
  double tolerance = 1e-12;
  /// CG iterations tried with a stale factor before refactorising.
  int maxIterations = 8;
};

struct LinearSolverStats {
  long factorisations = 0;
  long solves = 0;
  long cgIterations = 0;
  long factorModifications = 0;  ///< low-rank updates/downdates applied instead of refactorising
};

class LinearSolver {
 public:
  explicit LinearSolver(LinearSolverSettings s = {}) : settings_(s) {}
  /// When on, a stale factor is redone once the conjugate-gradient iterations it has cost since
  /// it was made add up to the flops of a factorisation (rent or buy: never more than twice the
  /// better of the two). Counted in flops, not seconds, so that a run does not depend on the
  /// machine's speed. Off: the factor is redone only when CG fails.
  void amortiseRefactorisation(bool on) { amortise_ = on; }
  /// K changed since the last call (values; the pattern is tracked by its version).
  void matrixChanged() { factorCurrent_ = false; }
  /// Returns false if K is not positive definite. CG stops at a residual of tolerance·‖b‖ or
  /// `residualFloor`, whichever is larger: b is known only to the round-off of the terms summed
  /// into it, and iterating below that refines noise.
  bool solve(const assembly::BlockSparseMatrix& k, const Eigen::VectorXd& b, Eigen::VectorXd& x,
             double residualFloor = 0);
  /// K changed by these rank-one terms since the factor was made (or last modified): the factor
  /// follows them by update/downdate, and CG then converges as if it were fresh. Returns false
  /// (and drops the factor, so the next solve refactorises) if the result lost positive
  /// definiteness; does nothing without a factor of K's pattern.
  bool modifyFactor(const assembly::BlockSparseMatrix& k, const std::vector<SparseCholesky::Column>& added,
                    const std::vector<SparseCholesky::Column>& removed);
  bool hasFactor() const { return haveFactor_; }
  const LinearSolverStats& stats() const { return stats_; }
  int symbolicAnalyses() const { return cholesky_.symbolicAnalyses(); }

 private:
  bool refactorise(const assembly::BlockSparseMatrix& k);
  /// Preconditioned CG from the factor's solution; false if it did not reach the tolerance.
  bool conjugateGradients(const assembly::BlockSparseMatrix& k, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                          double residualFloor);

  LinearSolverSettings settings_;
  SparseCholesky cholesky_;
  bool haveFactor_ = false;
  bool factorCurrent_ = false;
  long patternVersion_ = -1;
  bool amortise_ = false;
  double staleFlops_ = 0;  ///< CG work done with the current factor since it was made
  LinearSolverStats stats_;
};

}  // namespace ddaslope::solver

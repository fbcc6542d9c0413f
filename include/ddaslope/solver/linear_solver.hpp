#pragma once
// Solves the sequence of slowly changing systems K x = b of a run. The last Cholesky factor
// preconditions conjugate gradients; K is refactorised only when CG is slow, the pattern
// changed, or K lost positive definiteness. Between steps K changes by geometry (small) and
// within the open-close loop by a few contact springs (low rank): CG with the old factor then
// converges in a handful of iterations, each far cheaper than a factorisation.
#include <algorithm>

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
  /// The cache probe (LinearSolver::setCacheProbe): first substitutions timed, their seconds,
  /// and the seconds of the same substitution repeated at once, with the factor still in cache.
  long probedSubstitutions = 0;
  double probeFirstSeconds = 0, probeRepeatSeconds = 0;
};

/// K as the solver uses it: products with K for conjugate gradients, and K's entries when a
/// factorisation needs them (K kept as its terms assembles them only then: assembly/system_terms).
class SystemOperator {
 public:
  virtual ~SystemOperator() = default;
  virtual void multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const = 0;
  virtual const assembly::BlockSparseMatrix& matrix() const = 0;
  /// The version of K's pattern (known without its entries): a factor's symbolic analysis holds
  /// while it is the same.
  virtual long patternVersion() const = 0;
};

/// An assembled K.
class AssembledSystem final : public SystemOperator {
 public:
  explicit AssembledSystem(const assembly::BlockSparseMatrix& k) : k_(k) {}
  void multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const override { y = k_.multiply(x); }
  const assembly::BlockSparseMatrix& matrix() const override { return k_; }
  long patternVersion() const override { return k_.patternVersion(); }

 private:
  const assembly::BlockSparseMatrix& k_;
};

class LinearSolver {
 public:
  explicit LinearSolver(LinearSolverSettings s = {}) : settings_(s) {}
  /// CG iterations tried with a stale factor before refactorising (settings' maxIterations).
  void setMaxIterations(int n) { settings_.maxIterations = n; }
  /// Diagnostics (the bench's --probe-solve-cache): times the first substitution of each solve,
  /// then repeats it at once into a scratch vector and times that too. The difference is what
  /// reading the factor from memory instead of the cache costs. Results are unchanged.
  void setCacheProbe(bool on) { probe_ = on; }
  /// K changed since the last call (values; the pattern is tracked by its version).
  void matrixChanged() { factorCurrent_ = false; }
  /// Returns false if K is not positive definite. CG stops at a residual of tolerance·‖b‖ or
  /// `residualFloor`, whichever is larger: b is known only to the round-off of the terms summed
  /// into it, and iterating below that refines noise.
  bool solve(const SystemOperator& k, const Eigen::VectorXd& b, Eigen::VectorXd& x, double residualFloor = 0);
  bool solve(const assembly::BlockSparseMatrix& k, const Eigen::VectorXd& b, Eigen::VectorXd& x,
             double residualFloor = 0) {
    return solve(AssembledSystem(k), b, x, residualFloor);
  }
  /// K changed by these rank-one terms since the factor was made (or last modified): the factor
  /// follows them by update/downdate, and CG then converges as if it were fresh. Returns false
  /// (and drops the factor, so the next solve refactorises) if the result lost positive
  /// definiteness; does nothing without a factor of K's pattern.
  bool modifyFactor(const assembly::BlockSparseMatrix& k, const std::vector<SparseCholesky::Column>& added,
                    const std::vector<SparseCholesky::Column>& removed);
  bool hasFactor() const { return haveFactor_; }
  /// Whether the last solution met the solver's own tolerance (or `residualFloor`) on b, where
  /// it was asked for less. A solve with a factor of the current K counts as exact.
  bool lastSolveWithin(double residualFloor) const {
    return lastResidual_ <= std::max(settings_.tolerance * lastRhsNorm_, residualFloor);
  }
  /// Drops the factor: the next solve refactorises (K's block terms changed in a way CG would
  /// absorb at a few iterations per step, for ever).
  void discardFactor() { haveFactor_ = false; }
  const LinearSolverStats& stats() const { return stats_; }
  int symbolicAnalyses() const { return cholesky_.symbolicAnalyses(); }
  double factorEntries() const { return cholesky_.factorEntries(); }
  /// The factor's fill-reducing ordering from the next symbolic analysis on.
  void setOrdering(FillOrdering o) { cholesky_.setOrdering(o); }
  /// Solves with a simplicial copy of each new factor (SparseCholesky::setSimplicialSolves).
  void setSimplicialSolves(bool on) { cholesky_.setSimplicialSolves(on); }
  /// Substitutions with panels of a factor in long use (SparseCholesky::setPanelSolves). Through
  /// rounded panels every solution is checked against K by CG, and a CG run that misses its budget
  /// through them is tried again with the double factor; exact panels solve as the factor does.
  void setPanelSolves(bool on) { cholesky_.setPanelSolves(on); }
  long panelSubstitutions() const { return cholesky_.panelSubstitutions(); }
  double panelBytes() const { return cholesky_.panelBytes(); }

 private:
  bool refactorise(const SystemOperator& k);
  /// x := K⁻¹ b with the factor, probed if asked (setCacheProbe).
  void firstSubstitution(const Eigen::VectorXd& b, Eigen::VectorXd& x);
  /// Preconditioned CG from the factor's solution; false if it did not reach the tolerance.
  bool conjugateGradients(const SystemOperator& k, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                          double residualFloor);

  LinearSolverSettings settings_;
  SparseCholesky cholesky_;
  bool haveFactor_ = false;
  bool factorCurrent_ = false;
  bool probe_ = false;
  long patternVersion_ = -1;
  double lastResidual_ = 0;  ///< ‖b − Kx‖ of the last solution checked against K (0 if exact)
  double lastRhsNorm_ = 0;   ///< ‖b‖ of the last solve
  LinearSolverStats stats_;
};

}  // namespace ddaslope::solver

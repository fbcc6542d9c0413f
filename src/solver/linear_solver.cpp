#include "ddaslope/solver/linear_solver.hpp"

#include <algorithm>
#include <chrono>

namespace ddaslope::solver {

bool LinearSolver::refactorise(const SystemOperator& k) {
  ++stats_.factorisations;
  haveFactor_ = cholesky_.factorise(k.matrix());
  factorCurrent_ = haveFactor_;
  patternVersion_ = k.patternVersion();
  return haveFactor_;
}

void LinearSolver::firstSubstitution(const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  if (!probe_) {
    cholesky_.solve(b, x);
    return;
  }
  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  cholesky_.solve(b, x);
  const auto t1 = Clock::now();
  Eigen::VectorXd repeat;
  cholesky_.solve(b, repeat);
  const auto t2 = Clock::now();
  ++stats_.probedSubstitutions;
  stats_.probeFirstSeconds += std::chrono::duration<double>(t1 - t0).count();
  stats_.probeRepeatSeconds += std::chrono::duration<double>(t2 - t1).count();
}

bool LinearSolver::conjugateGradients(const SystemOperator& k, const Eigen::VectorXd& b,
                                      Eigen::VectorXd& x, double residualFloor) {
  const double target = std::max(settings_.tolerance * b.norm(), residualFloor);
  firstSubstitution(b, x);
  Eigen::VectorXd q;
  k.multiply(x, q);
  Eigen::VectorXd r = b - q;
  lastResidual_ = r.norm();
  if (lastResidual_ <= target) return true;
  Eigen::VectorXd z, p;
  cholesky_.solve(r, z);
  p = z;
  double rz = r.dot(z);
  for (int it = 0; it < settings_.maxIterations; ++it) {
    ++stats_.cgIterations;
    k.multiply(p, q);
    const double pq = p.dot(q);
    if (!(pq > 0)) return false;  // K no longer positive definite along p: refactorise
    const double alpha = rz / pq;
    x += alpha * p;
    r -= alpha * q;
    lastResidual_ = r.norm();
    if (lastResidual_ <= target) return true;
    cholesky_.solve(r, z);
    const double rzNext = r.dot(z);
    p = z + (rzNext / rz) * p;
    rz = rzNext;
  }
  return false;
}

bool LinearSolver::solve(const SystemOperator& k, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                         double residualFloor) {
  ++stats_.solves;
  lastResidual_ = 0;
  lastRhsNorm_ = b.norm();
  if (b.squaredNorm() == 0) {
    x = Eigen::VectorXd::Zero(b.size());
    return true;
  }
  if (haveFactor_ && patternVersion_ == k.patternVersion()) {
    cholesky_.beginSolve();
    // A factor of this very K solves exactly, unless through its single-precision panels.
    if (factorCurrent_ && !cholesky_.solvingWithPanels()) {
      firstSubstitution(b, x);
      return true;
    }
    if (conjugateGradients(k, b, x, residualFloor)) return true;
    if (cholesky_.solvingWithPanels()) {
      // The panels' rounding, not the factor's age, may have cost the budget: the double factor
      // gets its own chance (and exact, if it is K's) before a factorisation.
      cholesky_.dropPanels();
      lastResidual_ = 0;
      if (factorCurrent_) {
        firstSubstitution(b, x);
        return true;
      }
      if (conjugateGradients(k, b, x, residualFloor)) return true;
    }
  }
  lastResidual_ = 0;
  if (!refactorise(k)) return false;
  cholesky_.solve(b, x);
  return true;
}

bool LinearSolver::modifyFactor(const assembly::BlockSparseMatrix& k, const std::vector<SparseCholesky::Column>& added,
                                const std::vector<SparseCholesky::Column>& removed) {
  if (!haveFactor_ || patternVersion_ != k.patternVersion()) return false;
  if (added.empty() && removed.empty()) return true;
  ++stats_.factorModifications;
  factorCurrent_ = false;  // CG checks the modified factor against the true K
  // Updates first: a downdate applied before its matching update could pass through an
  // indefinite matrix.
  if (cholesky_.modify(added, true) && cholesky_.modify(removed, false)) return true;
  haveFactor_ = false;
  return false;
}

}  // namespace ddaslope::solver

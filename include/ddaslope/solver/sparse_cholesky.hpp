#pragma once
// Sparse Cholesky through CHOLMOD: analyse once per pattern, factorise per matrix, solve.
// Only sparse_cholesky.cpp includes CHOLMOD.
#include <memory>

#include <Eigen/Core>

#include "ddaslope/assembly/block_sparse_matrix.hpp"

namespace ddaslope::solver {

class SparseCholesky {
 public:
  SparseCholesky();
  ~SparseCholesky();
  SparseCholesky(const SparseCholesky&) = delete;
  SparseCholesky& operator=(const SparseCholesky&) = delete;

  /// Numeric factorisation; the symbolic analysis is redone only when the pattern changed.
  /// Returns false if the matrix is not positive definite.
  bool factorise(const assembly::BlockSparseMatrix& k);
  /// Solves K x = b with the last factorisation.
  void solve(const Eigen::VectorXd& b, Eigen::VectorXd& x);
  int symbolicAnalyses() const { return analyses_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  int analyses_ = 0;
};

}  // namespace ddaslope::solver

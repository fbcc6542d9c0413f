#pragma once
// Symmetric matrix of 6×6 blocks stored as the upper triangle in compressed columns (CSC),
// the layout CHOLMOD reads without a copy. The pattern is fixed between setPattern calls.
// With dof = 3 (rigid blocks) each block keeps only u0, v0, r0: the leading 3×3 of every term.
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "ddaslope/core/types.hpp"

namespace ddaslope::assembly {

class BlockSparseMatrix {
 public:
  /// nBlocks block rows/columns; couplings: unordered block pairs (any order, duplicates allowed).
  void setPattern(int nBlocks, std::vector<std::pair<int, int>> couplings, int dof = 6);
  /// True if this pattern equals the current one (so the symbolic factorisation can be kept).
  bool hasPattern(int nBlocks, const std::vector<std::pair<int, int>>& sortedUniqueCouplings, int dof = 6) const;
  static std::vector<std::pair<int, int>> normalise(std::vector<std::pair<int, int>> couplings);

  void setZero();
  void addDiagonal(int b, const Mat6& k);
  /// Adds K_rc, the block coupling row block r to column block c (r ≠ c).
  void addCoupling(int r, int c, const Mat6& krc);
  /// Adds (k·u)·uᵀ to diagonal block b and (k·u)·wᵀ to the coupling of r to c: a spring's
  /// terms, each stored entry computed as the full outer product would (k·u_i first, then
  /// times the other factor), but only the entries stored (the upper triangle, and for dof < 6
  /// the leading dof×dof).
  void addDiagonalOuter(int b, double k, const Vec6& u);
  void addCouplingOuter(int r, int c, double k, const Vec6& u, const Vec6& w);
  Eigen::VectorXd multiply(const Eigen::VectorXd& x) const;

  int size() const { return dof_ * nBlocks_; }
  int blockSize() const { return dof_; }
  int nonZeros() const { return static_cast<int>(values_.size()); }
  const std::vector<int>& columnPointers() const { return colPtr_; }
  const std::vector<int>& rowIndices() const { return rowIdx_; }
  std::vector<double>& values() { return values_; }
  const std::vector<double>& values() const { return values_; }
  /// Bumped each time the pattern changes.
  long patternVersion() const { return patternVersion_; }

 private:
  int slot(int r, int c) const;  ///< position of row block r in column block c's list (r < c)

  int nBlocks_ = 0;
  int dof_ = 6;
  std::vector<std::pair<int, int>> couplings_;   ///< sorted (r < c)
  std::vector<std::vector<int>> columnRows_;     ///< per column block: row blocks r < c, sorted
  std::vector<int> blockBase_;                   ///< first value index of each column block
  std::vector<int> colPtr_, rowIdx_;
  std::vector<double> values_;
  long patternVersion_ = 0;
};

}  // namespace ddaslope::assembly

#include "ddaslope/assembly/block_sparse_matrix.hpp"

#include <algorithm>

#include "ddaslope/core/errors.hpp"

namespace ddaslope::assembly {

std::vector<std::pair<int, int>> BlockSparseMatrix::normalise(std::vector<std::pair<int, int>> c) {
  for (auto& [r, k] : c)
    if (r > k) std::swap(r, k);
  std::sort(c.begin(), c.end());
  c.erase(std::unique(c.begin(), c.end()), c.end());
  return c;
}

bool BlockSparseMatrix::hasPattern(int nBlocks, const std::vector<std::pair<int, int>>& c) const {
  return nBlocks == nBlocks_ && c == couplings_ && patternVersion_ > 0;
}

void BlockSparseMatrix::setPattern(int nBlocks, std::vector<std::pair<int, int>> couplings) {
  couplings_ = normalise(std::move(couplings));
  nBlocks_ = nBlocks;
  columnRows_.assign(nBlocks, {});
  for (const auto& [r, c] : couplings_) {
    DDASLOPE_ASSERT(r != c && c < nBlocks, "bad block coupling");
    columnRows_[c].push_back(r);  // couplings are sorted by r, so each list is sorted
  }
  blockBase_.assign(nBlocks + 1, 0);
  colPtr_.assign(6 * nBlocks + 1, 0);
  rowIdx_.clear();
  int nz = 0;
  for (int c = 0; c < nBlocks; ++c) {
    blockBase_[c] = nz;
    for (int k = 0; k < 6; ++k) {
      colPtr_[6 * c + k] = nz;
      for (int r : columnRows_[c])
        for (int i = 0; i < 6; ++i) rowIdx_.push_back(6 * r + i);
      for (int i = 0; i <= k; ++i) rowIdx_.push_back(6 * c + i);
      nz += 6 * static_cast<int>(columnRows_[c].size()) + k + 1;
    }
  }
  blockBase_[nBlocks] = nz;
  colPtr_[6 * nBlocks] = nz;
  values_.assign(nz, 0.0);
  ++patternVersion_;
}

void BlockSparseMatrix::setZero() { std::fill(values_.begin(), values_.end(), 0.0); }

void BlockSparseMatrix::addDiagonal(int b, const Mat6& k) {
  const int off = 6 * static_cast<int>(columnRows_[b].size());
  for (int col = 0; col < 6; ++col) {
    double* v = &values_[colPtr_[6 * b + col] + off];
    for (int row = 0; row <= col; ++row) v[row] += k(row, col);
  }
}

int BlockSparseMatrix::slot(int r, int c) const {
  const auto& rows = columnRows_[c];
  const auto it = std::lower_bound(rows.begin(), rows.end(), r);
  DDASLOPE_ASSERT(it != rows.end() && *it == r, "block coupling not in the pattern");
  return static_cast<int>(it - rows.begin());
}

void BlockSparseMatrix::addCoupling(int r, int c, const Mat6& krc) {
  if (r > c) {
    addCoupling(c, r, krc.transpose());
    return;
  }
  const int s = 6 * slot(r, c);
  for (int col = 0; col < 6; ++col) {
    double* v = &values_[colPtr_[6 * c + col] + s];
    for (int row = 0; row < 6; ++row) v[row] += krc(row, col);
  }
}

Eigen::VectorXd BlockSparseMatrix::multiply(const Eigen::VectorXd& x) const {
  Eigen::VectorXd y = Eigen::VectorXd::Zero(size());
  for (int col = 0; col < size(); ++col) {
    for (int k = colPtr_[col]; k < colPtr_[col + 1]; ++k) {
      const int row = rowIdx_[k];
      y[row] += values_[k] * x[col];
      if (row != col) y[col] += values_[k] * x[row];
    }
  }
  return y;
}

}  // namespace ddaslope::assembly

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

bool BlockSparseMatrix::hasPattern(int nBlocks, const std::vector<std::pair<int, int>>& c, int dof) const {
  return nBlocks == nBlocks_ && dof == dof_ && c == couplings_ && patternVersion_ > 0;
}

void BlockSparseMatrix::setPattern(int nBlocks, std::vector<std::pair<int, int>> couplings, int dof) {
  DDASLOPE_ASSERT(dof >= 1 && dof <= 6, "a block has 1 to 6 unknowns");
  couplings_ = normalise(std::move(couplings));
  nBlocks_ = nBlocks;
  dof_ = dof;
  columnRows_.assign(nBlocks, {});
  for (const auto& [r, c] : couplings_) {
    DDASLOPE_ASSERT(r != c && c < nBlocks, "bad block coupling");
    columnRows_[c].push_back(r);  // couplings are sorted by r, so each list is sorted
  }
  blockBase_.assign(nBlocks + 1, 0);
  colPtr_.assign(dof_ * nBlocks + 1, 0);
  rowIdx_.clear();
  int nz = 0;
  for (int c = 0; c < nBlocks; ++c) {
    blockBase_[c] = nz;
    for (int k = 0; k < dof_; ++k) {
      colPtr_[dof_ * c + k] = nz;
      for (int r : columnRows_[c])
        for (int i = 0; i < dof_; ++i) rowIdx_.push_back(dof_ * r + i);
      for (int i = 0; i <= k; ++i) rowIdx_.push_back(dof_ * c + i);
      nz += dof_ * static_cast<int>(columnRows_[c].size()) + k + 1;
    }
  }
  blockBase_[nBlocks] = nz;
  colPtr_[dof_ * nBlocks] = nz;
  values_.assign(nz, 0.0);
  ++patternVersion_;
}

void BlockSparseMatrix::setZero() { std::fill(values_.begin(), values_.end(), 0.0); }

void BlockSparseMatrix::addDiagonal(int b, const Mat6& k) {
  // Only the first dof_ unknowns (u0, v0, r0 for a rigid block) take part.
  const int off = dof_ * static_cast<int>(columnRows_[b].size());
  for (int col = 0; col < dof_; ++col) {
    double* v = &values_[colPtr_[dof_ * b + col] + off];
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
  const int s = dof_ * slot(r, c);
  for (int col = 0; col < dof_; ++col) {
    double* v = &values_[colPtr_[dof_ * c + col] + s];
    for (int row = 0; row < dof_; ++row) v[row] += krc(row, col);
  }
}

void BlockSparseMatrix::addDiagonalOuter(int b, double k, const Vec6& u) {
  const int off = dof_ * static_cast<int>(columnRows_[b].size());
  for (int col = 0; col < dof_; ++col) {
    double* v = &values_[colPtr_[dof_ * b + col] + off];
    for (int row = 0; row <= col; ++row) v[row] += (k * u[row]) * u[col];
  }
}

void BlockSparseMatrix::addCouplingOuter(int r, int c, double k, const Vec6& u, const Vec6& w) {
  // Stored as the block of the lower-numbered block's rows: for r > c that is the transpose,
  // whose entry (row, col) is (k·u_col)·w_row.
  const bool transposed = r > c;
  const int s = dof_ * (transposed ? slot(c, r) : slot(r, c));
  const int column = transposed ? r : c;
  for (int col = 0; col < dof_; ++col) {
    double* v = &values_[colPtr_[dof_ * column + col] + s];
    if (transposed)
      for (int row = 0; row < dof_; ++row) v[row] += (k * u[col]) * w[row];
    else
      for (int row = 0; row < dof_; ++row) v[row] += (k * u[row]) * w[col];
  }
}

Eigen::VectorXd BlockSparseMatrix::multiply(const Eigen::VectorXd& x) const {
  // Column by column of the stored upper triangle: an entry (row, col) adds to y[row] and, off
  // the diagonal, its mirror to y[col]. The rows of a coupling are the dof_ consecutive unknowns
  // of one block, so both run over short contiguous ranges the compiler vectorises; the mirror
  // terms of a column are summed before they join y[col]. This product is the inner loop of the
  // conjugate-gradient iterations that a small slope's steps make on a stale factor.
  Eigen::VectorXd y = Eigen::VectorXd::Zero(size());
  const int dof = dof_;
  for (int c = 0; c < nBlocks_; ++c) {
    const std::vector<int>& rows = columnRows_[c];
    for (int k = 0; k < dof; ++k) {
      const int col = dof * c + k;
      const double xc = x[col];
      const double* v = values_.data() + colPtr_[col];
      double mirror = 0;
      for (const int r : rows) {
        double* yr = y.data() + dof * r;
        const double* xr = x.data() + dof * r;
        for (int i = 0; i < dof; ++i) {
          yr[i] += v[i] * xc;
          mirror += v[i] * xr[i];
        }
        v += dof;
      }
      double* yc = y.data() + dof * c;
      const double* xd = x.data() + dof * c;
      for (int i = 0; i < k; ++i) {
        yc[i] += v[i] * xc;
        mirror += v[i] * xd[i];
      }
      y[col] += v[k] * xc + mirror;
    }
  }
  return y;
}

}  // namespace ddaslope::assembly

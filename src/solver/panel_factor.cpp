#include "ddaslope/solver/panel_factor.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ddaslope::solver {

void PanelFactor::clear() {
  panels_.clear();
  rows_.clear();
  values_.clear();
  diagonal_.clear();
  perm_.clear();
  widest_ = 0;
}

bool PanelFactor::build(const SimplicialFactorView& f) {
  clear();
  const int n = f.n;
  const auto start = [&](int j) { return static_cast<long>(f.colStart[j]); };
  // The layout the solve relies on: each column led by its diagonal, rows ascending, D > 0.
  for (int j = 0; j < n; ++j) {
    const long p = start(j);
    const int count = f.colCount[j];
    if (count < 1 || f.rows[p] != j || !(f.values[p] > 0) || !std::isfinite(f.values[p])) return false;
    for (int q = 1; q < count; ++q)
      if (f.rows[p + q] <= f.rows[p + q - 1] || f.rows[p + q] >= n) return false;
  }
  // Entries beyond single precision's range would become infinite (a factor of a sane K holds
  // ratios of its entries, near 1); the solve then stays with the double factor.
  constexpr double kLargest = 1e30;
  diagonal_.resize(static_cast<size_t>(n));
  perm_.assign(f.perm, f.perm + n);
  // Column k + 1 continues column k's panel when it is k's parent (k's first row below the
  // diagonal) and has k's rows below it. In a Cholesky pattern, one entry fewer implies it; the
  // rows are compared anyway (O(entries)), so that a factor whose pattern was pruned (CHOLMOD's
  // resymbol) or edited can only make narrower panels, never wrong ones.
  const auto sharesRows = [&](int k) {
    const long p = start(k), q = start(k + 1);
    return f.colCount[k] == f.colCount[k + 1] + 1 && f.rows[p + 1] == k + 1 &&
           std::equal(f.rows + p + 2, f.rows + p + f.colCount[k], f.rows + q + 1);
  };
  for (int j = 0; j < n;) {
    int w = 1;
    while (j + w < n && sharesRows(j + w - 1)) ++w;
    Panel panel{j, w, static_cast<int>(rows_.size()), f.colCount[j] - w, static_cast<long>(values_.size())};
    const long below = start(j) + w;
    rows_.insert(rows_.end(), f.rows + below, f.rows + below + panel.rowCount);
    for (int r = 1; r < w; ++r)
      for (int c = 0; c < r; ++c) {
        const double v = f.values[start(j + c) + (r - c)];
        if (!(std::abs(v) < kLargest)) {
          clear();
          return false;
        }
        values_.push_back(static_cast<float>(v));
      }
    for (int i = 0; i < panel.rowCount; ++i)
      for (int c = 0; c < w; ++c) {
        const double v = f.values[start(j + c) + (w - c) + i];
        if (!(std::abs(v) < kLargest)) {
          clear();
          return false;
        }
        values_.push_back(static_cast<float>(v));
      }
    for (int c = 0; c < w; ++c) diagonal_[static_cast<size_t>(j + c)] = f.values[start(j + c)];
    panels_.push_back(panel);
    widest_ = std::max(widest_, w);
    j += w;
  }
  return true;
}

void PanelFactor::solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) const {
  const int n = static_cast<int>(diagonal_.size());
  y_.resize(n);
  for (int k = 0; k < n; ++k) y_[k] = b[perm_[static_cast<size_t>(k)]];
  local_.resize(static_cast<size_t>(widest_));
  double* yc = local_.data();
  // L y = P b, panel by panel: the panel's own rows through its triangle, then every row below
  // takes the panel's contribution at once.
  for (const Panel& p : panels_) {
    const float* v = values_.data() + p.valueStart;
    for (int r = 0; r < p.width; ++r) {
      double s = y_[p.first + r];
      for (int c = 0; c < r; ++c) s -= double(v[c]) * yc[c];
      yc[r] = s;
      y_[p.first + r] = s;
      v += r;
    }
    const int* rows = rows_.data() + p.rowStart;
    for (int i = 0; i < p.rowCount; ++i, v += p.width) {
      double s = 0;
      for (int c = 0; c < p.width; ++c) s += double(v[c]) * yc[c];
      y_[rows[i]] -= s;
    }
  }
  for (int k = 0; k < n; ++k) y_[k] /= diagonal_[static_cast<size_t>(k)];
  // Lᵀ z = y, panels in reverse: the rows below first (each column's sum over them), then the
  // triangle from the panel's last column back.
  for (auto it = panels_.rbegin(); it != panels_.rend(); ++it) {
    const Panel& p = *it;
    for (int c = 0; c < p.width; ++c) yc[c] = 0;
    const float* below = values_.data() + p.valueStart + static_cast<long>(p.width) * (p.width - 1) / 2;
    const int* rows = rows_.data() + p.rowStart;
    for (int i = 0; i < p.rowCount; ++i, below += p.width) {
      const double xi = y_[rows[i]];
      for (int c = 0; c < p.width; ++c) yc[c] += double(below[c]) * xi;
    }
    const float* tri = values_.data() + p.valueStart;
    for (int c = p.width - 1; c >= 0; --c) {
      double s = y_[p.first + c] - yc[c];
      for (int r = c + 1; r < p.width; ++r) s -= double(tri[static_cast<long>(r) * (r - 1) / 2 + c]) * y_[p.first + r];
      y_[p.first + c] = s;
    }
  }
  x.resize(n);
  for (int k = 0; k < n; ++k) x[perm_[static_cast<size_t>(k)]] = y_[k];
}

double PanelFactor::bytes() const {
  return sizeof(float) * double(values_.size()) + sizeof(int) * double(rows_.size() + perm_.size()) +
         sizeof(double) * double(diagonal_.size()) + sizeof(Panel) * double(panels_.size());
}

}  // namespace ddaslope::solver

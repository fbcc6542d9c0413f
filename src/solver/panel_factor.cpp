#include "ddaslope/solver/panel_factor.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace ddaslope::solver {

void PanelFactor::clear() {
  panels_.clear();
  rows_.clear();
  values_.clear();
  diagonal_.clear();
  perm_.clear();
  widest_ = 0;
  mostRows_ = 0;
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
    mostRows_ = std::max(mostRows_, panel.rowCount);
    j += w;
  }
  return true;
}

namespace {

// Pairs of doubles as one SSE2 register (GCC and Clang vector extensions; any target): the
// substitutions multiply single-precision entries, widened two at a time, by double-precision
// unknowns. Written out because strict IEEE order (no -ffast-math) keeps the compiler from
// vectorising a sum by itself; the sums below are split into lanes on purpose, and each split is
// fixed, so a solve is deterministic (the same bits on every run and thread count).
using Double2 = double __attribute__((vector_size(16)));
using Float2 = float __attribute__((vector_size(8)));

inline Double2 widen(const float* p) {
#if defined(__SSE2__)
  // One cvtps2pd; GCC 12 lowers the generic conversion below to two scalar ones and a shuffle.
  return _mm_cvtps_pd(_mm_castsi128_ps(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(p))));
#else
  Float2 f;
  std::memcpy(&f, p, sizeof f);
  return __builtin_convertvector(f, Double2);
#endif
}
inline Double2 load(const double* p) {
  Double2 d;
  std::memcpy(&d, p, sizeof d);
  return d;
}
inline void store(double* p, Double2 d) { std::memcpy(p, &d, sizeof d); }
inline double sum(Double2 d) { return d[0] + d[1]; }

/// Σ v[c] y[c] over c < n, in four lanes (two independent additions in flight per step).
inline double dot(const float* v, const double* y, int n) {
  Double2 a = {0, 0}, b = {0, 0};
  int c = 0;
  for (; c + 4 <= n; c += 4) {
    a += widen(v + c) * load(y + c);
    b += widen(v + c + 2) * load(y + c + 2);
  }
  if (c + 2 <= n) a += widen(v + c) * load(y + c), c += 2;
  double s = sum(a + b);
  if (c < n) s += double(v[c]) * y[c];
  return s;
}

/// y[rows[i]] −= Σ_c B(i, c) yc[c] for the rows of B (row-major, w entries each), four rows at a
/// time so that their sums overlap.
inline void subtractRows(const float* b, int w, int rowCount, const int* rows, const double* yc, double* y) {
  int i = 0;
  for (; i + 4 <= rowCount; i += 4, b += 4 * w) {
    const float *b1 = b + w, *b2 = b1 + w, *b3 = b2 + w;
    Double2 s0 = {0, 0}, s1 = s0, s2 = s0, s3 = s0;
    int c = 0;
    for (; c + 2 <= w; c += 2) {
      const Double2 yv = load(yc + c);
      s0 += widen(b + c) * yv;
      s1 += widen(b1 + c) * yv;
      s2 += widen(b2 + c) * yv;
      s3 += widen(b3 + c) * yv;
    }
    double t0 = sum(s0), t1 = sum(s1), t2 = sum(s2), t3 = sum(s3);
    if (c < w) t0 += double(b[c]) * yc[c], t1 += double(b1[c]) * yc[c], t2 += double(b2[c]) * yc[c], t3 += double(b3[c]) * yc[c];
    y[rows[i]] -= t0;
    y[rows[i + 1]] -= t1;
    y[rows[i + 2]] -= t2;
    y[rows[i + 3]] -= t3;
  }
  for (; i < rowCount; ++i, b += w) y[rows[i]] -= dot(b, yc, w);
}

/// out[k] = Σ_i B(i, k) x[i] for 2P adjacent columns of B (row-major, stride w): the 2P sums
/// stay in registers while the rows stream past.
template <int P>
inline void columnSums(const float* b, int w, int rowCount, const double* x, double* out) {
  Double2 acc[P];
  for (int k = 0; k < P; ++k) acc[k] = Double2{0, 0};
  for (int i = 0; i < rowCount; ++i, b += w) {
    const Double2 xi = {x[i], x[i]};
    for (int k = 0; k < P; ++k) acc[k] += widen(b + 2 * k) * xi;
  }
  for (int k = 0; k < P; ++k) store(out + 2 * k, acc[k]);
}

/// yc[c] = Σ_i B(i, c) x[i] for every column c of B (rowCount × w, row-major): sixteen columns
/// (a cache line of entries) per pass over the rows, then the rest in one pass.
inline void transposedProduct(const float* b, int w, int rowCount, const double* x, double* yc) {
  int c = 0;
  for (; c + 16 <= w; c += 16) columnSums<8>(b + c, w, rowCount, x, yc + c);
  switch ((w - c) / 2) {
    case 7: columnSums<7>(b + c, w, rowCount, x, yc + c); break;
    case 6: columnSums<6>(b + c, w, rowCount, x, yc + c); break;
    case 5: columnSums<5>(b + c, w, rowCount, x, yc + c); break;
    case 4: columnSums<4>(b + c, w, rowCount, x, yc + c); break;
    case 3: columnSums<3>(b + c, w, rowCount, x, yc + c); break;
    case 2: columnSums<2>(b + c, w, rowCount, x, yc + c); break;
    case 1: columnSums<1>(b + c, w, rowCount, x, yc + c); break;
    default: break;
  }
  c += (w - c) & ~1;
  if (c < w) {
    double s = 0;
    for (int i = 0; i < rowCount; ++i) s += double(b[static_cast<long>(i) * w + c]) * x[i];
    yc[c] = s;
  }
}

/// Solves Tᵀ z = yc in place for the panel's unit lower triangle T (row r at r(r − 1)/2, its
/// entries T(r, c < r)): from the last unknown back, each known z(r) leaves the columns c < r its
/// term from row r at once (a contiguous update), four rows per update of the columns below.
inline void backTriangle(const float* tri, int w, double* yc) {
  const auto row = [tri](int r) { return tri + static_cast<long>(r) * (r - 1) / 2; };
  int r = w - 1;
  for (; r >= 4; r -= 4) {
    const float *t0 = row(r), *t1 = row(r - 1), *t2 = row(r - 2), *t3 = row(r - 3);
    const double z0 = yc[r];
    const double z1 = yc[r - 1] -= double(t0[r - 1]) * z0;
    const double z2 = yc[r - 2] -= double(t0[r - 2]) * z0 + double(t1[r - 2]) * z1;
    const double z3 = yc[r - 3] -= double(t0[r - 3]) * z0 + double(t1[r - 3]) * z1 + double(t2[r - 3]) * z2;
    const Double2 v0 = {z0, z0}, v1 = {z1, z1}, v2 = {z2, z2}, v3 = {z3, z3};
    const int below = r - 3;
    int c = 0;
    for (; c + 2 <= below; c += 2)
      store(yc + c, load(yc + c) - (widen(t0 + c) * v0 + widen(t1 + c) * v1 + (widen(t2 + c) * v2 + widen(t3 + c) * v3)));
    if (c < below)
      yc[c] -= double(t0[c]) * z0 + double(t1[c]) * z1 + (double(t2[c]) * z2 + double(t3[c]) * z3);
  }
  for (; r >= 1; --r) {
    const float* t = row(r);
    const double z = yc[r];
    for (int c = 0; c < r; ++c) yc[c] -= double(t[c]) * z;
  }
}

}  // namespace

void PanelFactor::solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) const {
  const int n = static_cast<int>(diagonal_.size());
  y_.resize(n);
  for (int k = 0; k < n; ++k) y_[k] = b[perm_[static_cast<size_t>(k)]];
  local_.resize(static_cast<size_t>(widest_));
  gathered_.resize(static_cast<size_t>(mostRows_));
  double* yc = local_.data();
  double* y = y_.data();
  // L y = P b, panel by panel: the panel's own rows through its triangle (row r of the
  // triangle, contiguous, against the unknowns solved before it), then every row below takes the
  // panel's contribution at once.
  for (const Panel& p : panels_) {
    const float* v = values_.data() + p.valueStart;
    double* yp = y + p.first;
    for (int r = 0; r < p.width; v += r, ++r) yc[r] = yp[r] = yp[r] - dot(v, yc, r);
    subtractRows(v, p.width, p.rowCount, rows_.data() + p.rowStart, yc, y);
  }
  for (int k = 0; k < n; ++k) y[k] /= diagonal_[static_cast<size_t>(k)];
  // Lᵀ z = y, panels in reverse: each column's sum over the rows below (their unknowns gathered
  // once), then the triangle from the panel's last column back: once z(first + r) is known, every
  // column c < r takes its term from row r of the triangle (contiguous) at once.
  double* xs = gathered_.data();
  for (auto it = panels_.rbegin(); it != panels_.rend(); ++it) {
    const Panel& p = *it;
    const int* rows = rows_.data() + p.rowStart;
    for (int i = 0; i < p.rowCount; ++i) xs[i] = y[rows[i]];
    const float* tri = values_.data() + p.valueStart;
    const long triangle = static_cast<long>(p.width) * (p.width - 1) / 2;
    transposedProduct(tri + triangle, p.width, p.rowCount, xs, yc);
    double* yp = y + p.first;
    for (int c = 0; c < p.width; ++c) yc[c] = yp[c] - yc[c];
    backTriangle(tri, p.width, yc);
    for (int c = 0; c < p.width; ++c) yp[c] = yc[c];
  }
  x.resize(n);
  for (int k = 0; k < n; ++k) x[perm_[static_cast<size_t>(k)]] = y[k];
}

double PanelFactor::bytes() const {
  return sizeof(float) * double(values_.size()) + sizeof(int) * double(rows_.size() + perm_.size()) +
         sizeof(double) * double(diagonal_.size()) + sizeof(Panel) * double(panels_.size());
}

}  // namespace ddaslope::solver

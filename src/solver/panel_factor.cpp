#include "ddaslope/solver/panel_factor.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "ddaslope/core/prefetch.hpp"

#if defined(__x86_64__)
#include <immintrin.h>
#elif defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace ddaslope::solver {

void PanelFactor::clear() {
  panels_.clear();
  rows_.clear();
  // Their memory too (up to a hundred megabytes), not only their contents: a build that fails
  // leaves no panels to hold it for.
  std::vector<float>().swap(values_);
  std::vector<double>().swap(exactValues_);
  diagonal_.clear();
  perm_.clear();
  widest_ = 0;
  mostRows_ = 0;
}

bool PanelFactor::build(const SimplicialFactorView& f, Precision precision) {
  clear();
  precision_ = precision;
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
  const double largest = precision == Precision::Single ? 1e30 : std::numeric_limits<double>::infinity();
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
  // The panels first, their entries then, last panel first (detail::PanelArrays): the back
  // substitution, which reads them last to first, then streams the entries in order.
  long entries = 0;
  for (int j = 0; j < n;) {
    int w = 1;
    while (j + w < n && sharesRows(j + w - 1)) ++w;
    Panel panel{j, w, static_cast<int>(rows_.size()), f.colCount[j] - w, 0};
    const long below = start(j) + w;
    rows_.insert(rows_.end(), f.rows + below, f.rows + below + panel.rowCount);
    entries += panel.entries();
    for (int c = 0; c < w; ++c) diagonal_[static_cast<size_t>(j + c)] = f.values[start(j + c)];
    panels_.push_back(panel);
    widest_ = std::max(widest_, w);
    mostRows_ = std::max(mostRows_, panel.rowCount);
    j += w;
  }
  long end = entries;
  for (Panel& panel : panels_) {
    end -= panel.entries();
    panel.valueStart = end;
  }
  // Sized at once: growing by doubling would hold up to half again as much memory while it
  // copies (and keep it); the other precision's array is freed.
  if (precision == Precision::Single) {
    values_.assign(static_cast<size_t>(entries), 0.0f);
    std::vector<double>().swap(exactValues_);
  } else {
    exactValues_.assign(static_cast<size_t>(entries), 0.0);
    std::vector<float>().swap(values_);
  }
  const auto keep = [&](long at, double v) {
    if (!(std::abs(v) < largest)) return false;
    if (precision == Precision::Single)
      values_[static_cast<size_t>(at)] = static_cast<float>(v);
    else
      exactValues_[static_cast<size_t>(at)] = v;
    return true;
  };
  for (const Panel& panel : panels_) {
    const int j = panel.first, w = panel.width;
    bool fits = true;
    for (int i = 0; i < panel.rowCount; ++i)
      for (int c = 0; c < w; ++c)
        fits = keep(panel.valueStart + static_cast<long>(i) * w + c, f.values[start(j + c) + (w - c) + i]) && fits;
    for (int r = 1; r < w; ++r)
      for (int c = 0; c < r; ++c)
        fits = keep(panel.triangleStart() + detail::triangleRowOffset(w, r) + c, f.values[start(j + c) + (r - c)]) &&
               fits;
    if (!fits) {
      clear();
      return false;
    }
  }
  return true;
}

// The kernels, compiled once for the instruction set every x86-64 processor has (SSE2: two
// lanes per register, so V is a pair of registers) and, with GCC on x86-64, once more for AVX
// (four lanes in one register), which solve() chooses where the processor has it. Both split
// every sum into the same four lanes: the same bits either way.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define DDASLOPE_PANEL_AVX 1
#else
#define DDASLOPE_PANEL_AVX 0
#endif

namespace {

using detail::PanelArrays;
using detail::triangleRowOffset;

/// How far ahead of the substitutions' reading a large factor's entries are asked for
/// (Prefetch). Look-aheads of 1, 2 and 4 KB timed within each other's spread on a factor many
/// times the cache; the largest is kept (the most time for a miss to arrive; docs/performance.md,
/// "Measurements behind the solver's constants"). The kernels tell the prefetcher where they are
/// once per four rows forward and once per chunk backward, so a wide panel's look-ahead runs up
/// to a group or chunk further.
constexpr std::size_t kPrefetchAheadBytes = 4096;
/// Rows per chunk of the back substitution's column sums (transposedProduct): a chunk of a wide
/// panel is read from memory once and then from L1 for each sixteen columns, where a whole panel
/// (up to megabytes in a large factor) would be read from L2 or memory once per sixteen columns.
/// Chunks of 8 and 16 rows timed within each other's spread, ahead of 32 rows and of no chunks
/// (docs/performance.md): 16 carries the sums through memory half as often as 8.
constexpr int kBackChunkRows = 16;

namespace portable {
#if defined(__SSE2__)
struct Lanes {
  struct V {
    __m128d lo, hi;
  };
  static V zero() { return {_mm_setzero_pd(), _mm_setzero_pd()}; }
  static V splat(double a) { return {_mm_set1_pd(a), _mm_set1_pd(a)}; }
  static V widen(const float* p) {
    const __m128 f = _mm_loadu_ps(p);
    return {_mm_cvtps_pd(f), _mm_cvtps_pd(_mm_movehl_ps(f, f))};
  }
  static V widen(const double* p) { return load(p); }
  static V load(const double* p) { return {_mm_loadu_pd(p), _mm_loadu_pd(p + 2)}; }
  static void store(double* p, V v) { _mm_storeu_pd(p, v.lo), _mm_storeu_pd(p + 2, v.hi); }
  static V add(V a, V b) { return {_mm_add_pd(a.lo, b.lo), _mm_add_pd(a.hi, b.hi)}; }
  static V sub(V a, V b) { return {_mm_sub_pd(a.lo, b.lo), _mm_sub_pd(a.hi, b.hi)}; }
  static V mul(V a, V b) { return {_mm_mul_pd(a.lo, b.lo), _mm_mul_pd(a.hi, b.hi)}; }
  static double reduce(V v) {
    const __m128d t = _mm_add_pd(v.lo, v.hi);
    return _mm_cvtsd_f64(t) + _mm_cvtsd_f64(_mm_unpackhi_pd(t, t));
  }
};
#else
struct Lanes {
  struct V {
    double l[4];
  };
  static V zero() { return {{0, 0, 0, 0}}; }
  static V splat(double a) { return {{a, a, a, a}}; }
  static V widen(const float* p) { return {{double(p[0]), double(p[1]), double(p[2]), double(p[3])}}; }
  static V widen(const double* p) { return {{p[0], p[1], p[2], p[3]}}; }
  static V load(const double* p) { return {{p[0], p[1], p[2], p[3]}}; }
  static void store(double* p, V v) { std::memcpy(p, v.l, sizeof v.l); }
  static V add(V a, V b) { return {{a.l[0] + b.l[0], a.l[1] + b.l[1], a.l[2] + b.l[2], a.l[3] + b.l[3]}}; }
  static V sub(V a, V b) { return {{a.l[0] - b.l[0], a.l[1] - b.l[1], a.l[2] - b.l[2], a.l[3] - b.l[3]}}; }
  static V mul(V a, V b) { return {{a.l[0] * b.l[0], a.l[1] * b.l[1], a.l[2] * b.l[2], a.l[3] * b.l[3]}}; }
  static double reduce(V v) { return (v.l[0] + v.l[2]) + (v.l[1] + v.l[3]); }
};
#endif
#include "panel_kernels.inc"
}  // namespace portable

#if DDASLOPE_PANEL_AVX
#pragma GCC push_options
#pragma GCC target("avx")
namespace avx {
// AVX without FMA: a fused multiply-add would round differently from the portable kernel.
struct Lanes {
  using V = __m256d;
  static V zero() { return _mm256_setzero_pd(); }
  static V splat(double a) { return _mm256_set1_pd(a); }
  static V widen(const float* p) { return _mm256_cvtps_pd(_mm_loadu_ps(p)); }
  static V widen(const double* p) { return _mm256_loadu_pd(p); }
  static V load(const double* p) { return _mm256_loadu_pd(p); }
  static void store(double* p, V v) { _mm256_storeu_pd(p, v); }
  static V add(V a, V b) { return _mm256_add_pd(a, b); }
  static V sub(V a, V b) { return _mm256_sub_pd(a, b); }
  static V mul(V a, V b) { return _mm256_mul_pd(a, b); }
  static double reduce(V v) {
    const __m128d t = _mm_add_pd(_mm256_castpd256_pd128(v), _mm256_extractf128_pd(v, 1));
    return _mm_cvtsd_f64(t) + _mm_cvtsd_f64(_mm_unpackhi_pd(t, t));
  }
};
#include "panel_kernels.inc"
}  // namespace avx
#pragma GCC pop_options
#endif

/// The substitution with the AVX kernels where asked (and built), else the portable ones.
template <class T>
void substituteWith(bool useAvx, const PanelArrays& f, const T* values, double* y, double* yc, double* xs,
                    bool prefetch) {
#if DDASLOPE_PANEL_AVX
  if (useAvx) return avx::substitute(f, values, y, yc, xs, prefetch);
#else
  (void)useAvx;
#endif
  portable::substitute(f, values, y, yc, xs, prefetch);
}

}  // namespace

bool PanelFactor::avxAvailable() {
#if DDASLOPE_PANEL_AVX
  static const bool has = __builtin_cpu_supports("avx");
  return has;
#else
  return false;
#endif
}

void PanelFactor::solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) const {
  const int n = static_cast<int>(diagonal_.size());
  y_.resize(n);
  for (int k = 0; k < n; ++k) y_[k] = b[perm_[static_cast<size_t>(k)]];
  local_.resize(static_cast<size_t>(widest_));
  gathered_.resize(static_cast<size_t>(mostRows_));
  const auto valueCount = static_cast<long>(values_.size() + exactValues_.size());
  const PanelArrays f{n, valueCount, panels_.data(), static_cast<int>(panels_.size()), rows_.data(), diagonal_.data()};
  const bool useAvx = kernel_ == Kernel::Best && avxAvailable();
  const bool prefetch =
      prefetch_ == Prefetch::Always || (prefetch_ == Prefetch::Auto && entryBytes() >= kPrefetchMinBytes);
  if (precision_ == Precision::Single)
    substituteWith(useAvx, f, values_.data(), y_.data(), local_.data(), gathered_.data(), prefetch);
  else
    substituteWith(useAvx, f, exactValues_.data(), y_.data(), local_.data(), gathered_.data(), prefetch);
  x.resize(n);
  for (int k = 0; k < n; ++k) x[perm_[static_cast<size_t>(k)]] = y_[k];
}

double PanelFactor::entryBytes() const {
  return sizeof(float) * double(values_.size()) + sizeof(double) * double(exactValues_.size());
}

double PanelFactor::bytes() const {
  return entryBytes() + sizeof(int) * double(rows_.size() + perm_.size()) + sizeof(double) * double(diagonal_.size()) +
         sizeof(Panel) * double(panels_.size());
}

}  // namespace ddaslope::solver

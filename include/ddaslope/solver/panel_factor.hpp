#pragma once
// A simplicial LDLᵀ factor regrouped into panels (single-precision entries, or exact), for the many
// solves a large quiet run makes with one factor.
//
// Why: a large system's step is one forward and back substitution, which streams the whole
// factor, and from about a million entries (12 bytes each with CHOLMOD's row indices) the rest of
// a step pushes the factor out of the cache before the next one: a substitution as the steps run
// then takes markedly longer than one repeated at once (the bench's --probe-solve-cache times
// both; docs/performance.md). A panel stores one row pattern for a run of columns that share it
// (a block's unknowns are coupled to the same blocks) and the run's entries in single precision:
// 4 bytes per entry instead of 12: a third of the bytes to stream, so that a factor just too
// large for the cache fits it again. The solve accumulates in double precision; D stays in
// double. The factor is then that of a matrix within about 1e-7 of K, which makes it a
// preconditioner, not a solver: conjugate gradients (linear_solver.hpp) check every solution
// against K itself and iterate to the same tolerance as with the exact factor. On a large factor
// that costs a CG iteration now and then; on a smaller one, which stays in the cache anyway, one
// per step: hence the size threshold, SparseCholesky::kPanelMinEntries.
//
// The substitutions (src/solver/panel_kernels.inc) sum in four double-precision lanes with
// several sums in flight: four rows at a time forward, sixteen columns per pass over a panel's
// rows backward, four triangle rows per update. A sum split into lanes rounds differently from one
// summed in order, but the split is fixed, so the solve is deterministic. The kernels are compiled
// twice, for SSE2 (every x86-64 processor) and for AVX (chosen where the processor has it, without
// FMA): both split the same way and return the same bits (tests/test_panel_factor.cpp). Lanes
// make a substitution faster than one summed in order, AVX faster than SSE2 (docs/performance.md,
// "Measurements behind the solver's constants"); the rest is waiting for memory. A factor larger
// than the cache is laid out so that each pass reads its entries as one run (PanelArrays: the
// back substitution forward through them, the forward substitution back) and asked for a few
// kilobytes ahead of the reading (Prefetch): the hardware prefetcher alone followed neither the
// back substitution's panels, read back to front (the back pass then cost well over the forward
// one), nor a wide panel's rows. build/ddaslope_substitution_bench times one substitution of the
// wall's factor.

#include <vector>

#include <Eigen/Core>

namespace ddaslope::solver {

/// The arrays of a simplicial LDLᵀ factor of P A Pᵀ in CHOLMOD's layout (int indices): column
/// j starts at colStart[j] and holds colCount[j] entries, D(j,j) first, then the unit lower L
/// below the diagonal, rows ascending.
struct SimplicialFactorView {
  int n = 0;
  const int* perm = nullptr;  ///< perm[k]: the row of A at row k of the factor
  const int* colStart = nullptr;
  const int* colCount = nullptr;
  const int* rows = nullptr;
  const double* values = nullptr;
};

namespace detail {
/// Where row r of a panel's unit lower triangle (width w; entries T(r, c < r)) starts within the
/// triangle: rows stored last first, so that the back substitution, which takes them from the
/// last, reads forward (PanelArrays).
inline long triangleRowOffset(int w, int r) {
  return (static_cast<long>(w) * (w - 1) - static_cast<long>(r) * (r + 1)) / 2;
}

/// The arrays one substitution reads (src/solver/panel_kernels.inc).
struct PanelArrays {
  /// Columns first … first + width − 1 share the rows rows[rowStart …] below them. The entries
  /// of those rows, L(rows[rowStart + i], first + c), are at values[valueStart + i·width + c]
  /// (row by row); then the triangle, L(first + r, first + c) for r > c at
  /// values[triangleStart() + triangleRowOffset(width, r) + c].
  ///
  /// The last panel's entries come first in `values`, the first panel's last. The back
  /// substitution, which takes the panels last to first, each's rows first to last and its
  /// triangle last row first, then reads one ascending run, and the forward substitution one
  /// descending run (it takes a panel's rows from the last; they are independent there, so the
  /// order changes no bit). The hardware prefetcher follows neither well when a panel is wide, so
  /// large factors are also prefetched in software (PanelFactor::Prefetch).
  struct Panel {
    int first = 0;
    int width = 0;
    int rowStart = 0;
    int rowCount = 0;
    long valueStart = 0;
    long entries() const { return static_cast<long>(width) * rowCount + static_cast<long>(width) * (width - 1) / 2; }
    long triangleStart() const { return valueStart + static_cast<long>(width) * rowCount; }
  };
  int n = 0;
  long valueCount = 0;  ///< entries of all panels: values[0 … valueCount)
  const Panel* panels = nullptr;
  int panelCount = 0;
  const int* rows = nullptr;
  const double* diagonal = nullptr;
};
}  // namespace detail

class PanelFactor {
 public:
  /// Single: L's entries rounded to single precision (a preconditioner within about 1e-7 of the
  /// factor, for factors too large for the cache); Double: kept exact (the factor itself, whose
  /// substitution streams the entries without CHOLMOD's row index per entry).
  enum class Precision { Single, Double };
  /// Regroups (and rounds, if Single) the factor: a copy, the view may change afterwards.
  /// Returns false, and leaves the panels empty, if the view is not a factor of that layout (a
  /// column not led by its diagonal or not sorted, a D(j,j) not positive) or an entry does not fit
  /// single precision where asked for.
  bool build(const SimplicialFactorView& f, Precision precision = Precision::Single);
  /// Whether the panels hold L rounded (Single): a preconditioner, not the factor.
  bool rounded() const { return precision_ == Precision::Single; }
  bool empty() const { return panels_.empty(); }
  /// Panels: runs of columns that share their rows below (fewer than the columns where any do).
  int panelCount() const { return static_cast<int>(panels_.size()); }
  void clear();
  /// x := A⁻¹ b for A = Pᵀ L D Lᵀ P with L's entries as the panels hold them.
  void solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) const;
  /// Bytes the panels hold (entries, row patterns, D), for the bench.
  double bytes() const;
  /// The substitutions' instructions: AVX where the processor has it (Best, the default), or
  /// the portable kernel (SSE2 on x86-64). Both return the same bits.
  enum class Kernel { Best, Portable };
  void setKernel(Kernel k) { kernel_ = k; }
  /// Whether Best means AVX here (GCC on x86-64, a processor with AVX).
  static bool avxAvailable();
  /// Whether the substitutions ask for the entries' cache lines ahead of reading them (a few
  /// kilobytes ahead, in the direction each pass reads): Auto from kPrefetchMinBytes of entries up.
  /// The same bits either way.
  enum class Prefetch { Auto, Always, Never };
  void setPrefetch(Prefetch p) { prefetch_ = p; }
  /// Bytes of entries from which a factor is taken to be read from memory in a step, not from
  /// the cache. Asking ahead slows a factor well within the cache; one about half the cache breaks
  /// even in back-to-back solves (which find a factor smaller than the cache warm) and gains in a
  /// step, where the contacts' arrays share the cache; one many times the cache gains most
  /// (build/ddaslope_substitution_bench times each with and without; docs/performance.md,
  /// "Measurements behind the solver's constants"). The threshold lies between the first two, at
  /// half the 32 MB last-level cache of the machine measured.
  static constexpr double kPrefetchMinBytes = 16e6;
  /// Bytes of L's entries.
  double entryBytes() const;

 private:
  using Panel = detail::PanelArrays::Panel;
  std::vector<Panel> panels_;
  std::vector<int> rows_;
  std::vector<float> values_;         ///< L's entries, Single
  std::vector<double> exactValues_;   ///< L's entries, Double
  Precision precision_ = Precision::Single;
  std::vector<double> diagonal_;
  std::vector<int> perm_;
  int widest_ = 0;
  Kernel kernel_ = Kernel::Best;
  Prefetch prefetch_ = Prefetch::Auto;
  int mostRows_ = 0;  ///< the most rows below any panel
  mutable Eigen::VectorXd y_;
  mutable std::vector<double> local_;     ///< one panel's unknowns
  mutable std::vector<double> gathered_;  ///< the back substitution's unknowns of one panel's rows
};

}  // namespace ddaslope::solver

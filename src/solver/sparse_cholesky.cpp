#include "ddaslope/solver/sparse_cholesky.hpp"

#include <array>

#include <cholmod.h>
#include <omp.h>

#include <algorithm>
#include <cstring>

#include "ddaslope/core/errors.hpp"
#include "ddaslope/model/analysis_settings.hpp"
#include "ddaslope/solver/panel_factor.hpp"

namespace ddaslope::solver {

struct SparseCholesky::Impl {
  cholmod_common common{};
  cholmod_factor* factor = nullptr;
  /// Simplicial LDLᵀ copy of `factor` with low-rank changes applied; null when none were.
  cholmod_factor* modified = nullptr;
  std::vector<int> inversePerm;  ///< original row → row of the factor
  long patternVersion = -1;
  const void* patternOwner = nullptr;
  FillOrdering ordering = FillOrdering::MinimumDegree;
  int defaultFirstOrdering = 0;
  /// The factor as it is now (a new factorisation or a modification makes a new generation), and
  /// the panels of one of its generations.
  long generation = 0;
  int solvesWithGeneration = 0;
  bool usePanels = false;  ///< this solve's choice (beginSolve)
  PanelFactor panels;
  long panelGeneration = -1;
  long unpanelledGeneration = -1;  ///< a generation whose panels failed to build or to converge
  double lnz = 0;                  ///< entries of L, from the last symbolic analysis
  void changed() {
    ++generation;
    solvesWithGeneration = 0;
    usePanels = false;
  }
  /// Rounded panels pay for themselves sooner than exact ones (SparseCholesky::kSolvesBeforeRoundedPanels).
  int solvesBeforePanels() const {
    return lnz >= SparseCholesky::kPanelMinEntries ? SparseCholesky::kSolvesBeforeRoundedPanels
                                                   : SparseCholesky::kSolvesBeforePanels;
  }
  /// Whether this generation substitutes through panels (built, or to be built for its next
  /// solve): a factor in use long enough, whose panels did not fail or fall short.
  bool panelsEarned() const {
    return panelGeneration == generation ||
           (modified && unpanelledGeneration != generation &&
            solvesWithGeneration >= solvesBeforePanels());
  }
  /// Panels of `modified` for this generation, if it has earned them and they can be built.
  bool panelsReady() {
    if (panelGeneration == generation) return true;
    if (!panelsEarned()) return false;
    SimplicialFactorView view;
    view.n = static_cast<int>(modified->n);
    view.perm = static_cast<const int*>(modified->Perm);
    view.colStart = static_cast<const int*>(modified->p);
    view.colCount = static_cast<const int*>(modified->nz);
    view.rows = static_cast<const int*>(modified->i);
    view.values = static_cast<const double*>(modified->x);
    const auto precision =
        lnz >= SparseCholesky::kPanelMinEntries ? PanelFactor::Precision::Single : PanelFactor::Precision::Double;
    if (modified->is_super || modified->is_ll || !panels.build(view, precision)) {
      unpanelledGeneration = generation;
      return false;
    }
    panelGeneration = generation;
    return true;
  }

  Impl() {
    cholmod_start(&common);
    common.print = 0;
    common.error_handler = nullptr;
    // LLᵀ (supernodal; simplicial for small systems, factorise()): an LDLᵀ would factorise an
    // indefinite matrix silently, and a lost positive definiteness is a failure the step control
    // must see.
    common.supernodal = CHOLMOD_SUPERNODAL;
    defaultFirstOrdering = common.method[0].ordering;
  }
  /// CHOLMOD's default choice (AMD, METIS only where AMD fills badly) for minimum degree; for
  /// nested dissection NESDIS alone.
  void chooseOrdering() {
    if (ordering == FillOrdering::NestedDissection) {
      common.nmethods = 1;
      common.method[0].ordering = CHOLMOD_NESDIS;
    } else {
      common.nmethods = 0;
      common.method[0].ordering = defaultFirstOrdering;
    }
  }
  /// `modified` := a simplicial LDLᵀ copy of `factor`, packed and monotonic: the form
  /// update/downdate works on.
  void copySimplicial() {
    modified = cholmod_copy_factor(factor, &common);
    DDASLOPE_ASSERT(modified != nullptr, "CHOLMOD could not copy the factor");
    cholmod_change_factor(CHOLMOD_REAL, false, false, true, true, modified, &common);
  }
  ~Impl() {
    if (modified) cholmod_free_factor(&modified, &common);
    if (factor) cholmod_free_factor(&factor, &common);
    cholmod_finish(&common);
  }
  /// A view of the block matrix's arrays: CHOLMOD reads them in place.
  static cholmod_sparse view(const assembly::BlockSparseMatrix& k) {
    cholmod_sparse a{};
    a.nrow = a.ncol = static_cast<size_t>(k.size());
    a.nzmax = static_cast<size_t>(k.nonZeros());
    a.p = const_cast<int*>(k.columnPointers().data());
    a.i = const_cast<int*>(k.rowIndices().data());
    a.x = const_cast<double*>(k.values().data());
    a.stype = 1;  // upper triangle stored
    a.itype = CHOLMOD_INT;
    a.xtype = CHOLMOD_REAL;
    a.dtype = CHOLMOD_DOUBLE;
    a.sorted = 1;
    a.packed = 1;
    return a;
  }
};

SparseCholesky::SparseCholesky() : impl_(std::make_unique<Impl>()) {}
SparseCholesky::~SparseCholesky() = default;

bool SparseCholesky::factorise(const assembly::BlockSparseMatrix& k) {
  cholmod_sparse a = Impl::view(k);
  // Debian's CHOLMOD opens an OpenMP team in every factorisation, whatever OMP_NUM_THREADS says.
  // On a small system (a real slope's search) the work is too small to share and the team's
  // wake-ups cost more than they save; a large one gains a little (docs/performance.md).
  // The setting is the process's: searches' threads factorising side by side agree on it.
  omp_set_max_active_levels(a.nrow < static_cast<size_t>(model::kLargeSystemMinUnknowns) ? 0 : 1);
  if (!impl_->factor || impl_->patternVersion != k.patternVersion() || impl_->patternOwner != &k) {
    if (impl_->factor) cholmod_free_factor(&impl_->factor, &impl_->common);
    impl_->chooseOrdering();
    // A small system's supernodes are a few columns wide: a supernodal factorisation spends more
    // on its BLAS calls and OpenMP regions than on arithmetic. It is factorised simplicially, LLᵀ
    // so that a lost positive definiteness still fails (an LDLᵀ would go on silently).
    const bool small = a.nrow < static_cast<size_t>(model::kLargeSystemMinUnknowns);
    impl_->common.supernodal = small ? CHOLMOD_SIMPLICIAL : CHOLMOD_SUPERNODAL;
    impl_->common.final_ll = small;
    impl_->factor = cholmod_analyze(&a, &impl_->common);
    DDASLOPE_ASSERT(impl_->factor != nullptr, "CHOLMOD symbolic analysis failed");
    impl_->patternVersion = k.patternVersion();
    impl_->patternOwner = &k;
    ++analyses_;
    impl_->lnz = impl_->common.lnz;
  }
  if (impl_->modified) cholmod_free_factor(&impl_->modified, &impl_->common);
  impl_->inversePerm.clear();
  impl_->changed();
  cholmod_factorize(&a, impl_->factor, &impl_->common);
  const bool ok = impl_->common.status == CHOLMOD_OK && impl_->factor->minor == a.nrow;
  if (ok && simplicialSolves_) impl_->copySimplicial();
  return ok;
}

void SparseCholesky::setOrdering(FillOrdering o) {
  if (o == impl_->ordering) return;
  impl_->ordering = o;
  impl_->patternVersion = -1;  // analyse again at the next factorisation
}

void SparseCholesky::beginSolve() {
  impl_->usePanels = panelSolves_ && impl_->panelsReady();
  ++impl_->solvesWithGeneration;
}

bool SparseCholesky::solvingWithPanels() const { return impl_->usePanels && impl_->panels.rounded(); }

void SparseCholesky::dropPanels() {
  impl_->usePanels = false;
  impl_->unpanelledGeneration = impl_->generation;
  impl_->panelGeneration = -1;  // not rebuilt for this generation: panelsEarned() sees it dropped
}

double SparseCholesky::panelBytes() const { return impl_->panels.bytes(); }

double SparseCholesky::factorEntries() const { return impl_->lnz; }

void SparseCholesky::solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  if (impl_->usePanels) {
    impl_->panels.solve(b, x);
    ++panelSubstitutions_;
    return;
  }
  cholmod_dense rhs{};
  rhs.nrow = static_cast<size_t>(b.size());
  rhs.ncol = 1;
  rhs.nzmax = rhs.nrow;
  rhs.d = rhs.nrow;
  rhs.x = const_cast<double*>(b.data());
  rhs.xtype = CHOLMOD_REAL;
  rhs.dtype = CHOLMOD_DOUBLE;
  cholmod_factor* f = impl_->modified ? impl_->modified : impl_->factor;
  cholmod_dense* sol = cholmod_solve(CHOLMOD_A, f, &rhs, &impl_->common);
  DDASLOPE_ASSERT(sol != nullptr, "CHOLMOD solve failed");
  x.resize(b.size());
  std::memcpy(x.data(), sol->x, sizeof(double) * static_cast<size_t>(b.size()));
  cholmod_free_dense(&sol, &impl_->common);
}

bool SparseCholesky::modify(const std::vector<Column>& columns, bool add) {
  if (columns.empty()) return true;
  Impl& m = *impl_;
  if (!m.modified) m.copySimplicial();
  m.changed();
  // The factor is of P K Pᵀ (fill-reducing order): C's rows go through the same permutation.
  const int* perm = static_cast<const int*>(m.modified->Perm);
  if (m.inversePerm.size() != m.modified->n) {
    m.inversePerm.resize(m.modified->n);
    for (size_t k = 0; k < m.modified->n; ++k) m.inversePerm[static_cast<size_t>(perm[k])] = static_cast<int>(k);
  }
  size_t nz = 0;
  for (const Column& c : columns) nz += static_cast<size_t>(c.count);
  cholmod_sparse* cs = cholmod_allocate_sparse(m.modified->n, columns.size(), nz, true, true, 0, CHOLMOD_REAL, &m.common);
  DDASLOPE_ASSERT(cs != nullptr, "CHOLMOD could not allocate the update");
  int* p = static_cast<int*>(cs->p);
  int* i = static_cast<int*>(cs->i);
  double* x = static_cast<double*>(cs->x);
  size_t k = 0;
  for (size_t j = 0; j < columns.size(); ++j) {
    p[j] = static_cast<int>(k);
    const Column& c = columns[j];
    // A column holds a contact spring's entries: two blocks of at most 6 unknowns each, sorted by
    // row. Insertion sort over at most 12: std::sort's introsort made GCC 12 warn (-Warray-bounds)
    // about heap indices it cannot reach, since it did not know the bound.
    DDASLOPE_ASSERT(c.count >= 0 && c.count <= 12, "a spring column has at most 12 entries");
    const int n = std::clamp(c.count, 0, 12);
    std::array<int, 12> order{};
    const auto row = [&](int e) { return m.inversePerm[static_cast<size_t>(c.rows[e])]; };
    for (int e = 0; e < n; ++e) {
      int at = e;
      for (; at > 0 && row(order[static_cast<size_t>(at - 1)]) > row(e); --at)
        order[static_cast<size_t>(at)] = order[static_cast<size_t>(at - 1)];
      order[static_cast<size_t>(at)] = e;
    }
    for (int e = 0; e < n; ++e, ++k) {
      i[k] = row(order[e]);
      x[k] = c.values[order[e]];
    }
  }
  p[columns.size()] = static_cast<int>(k);
  const int ok = cholmod_updown(add, cs, m.modified, &m.common);
  cholmod_free_sparse(&cs, &m.common);
  if (!ok || m.common.status != CHOLMOD_OK) return false;
  // D is on the diagonal of the simplicial LDLᵀ: positive definite iff every D(j,j) > 0.
  const int* lp = static_cast<const int*>(m.modified->p);
  const double* lx = static_cast<const double*>(m.modified->x);
  for (size_t j = 0; j < m.modified->n; ++j)
    if (!(lx[lp[j]] > 0)) return false;
  return true;
}

}  // namespace ddaslope::solver

#include "ddaslope/solver/sparse_cholesky.hpp"

#include <cholmod.h>

#include <cstring>

#include "ddaslope/core/errors.hpp"

namespace ddaslope::solver {

struct SparseCholesky::Impl {
  cholmod_common common{};
  cholmod_factor* factor = nullptr;
  long patternVersion = -1;
  const void* patternOwner = nullptr;

  Impl() {
    cholmod_start(&common);
    common.print = 0;
    common.error_handler = nullptr;
    // Supernodal LLᵀ: a simplicial LDLᵀ would factorise an indefinite matrix silently, and a
    // lost positive definiteness is a failure the step control must see.
    common.supernodal = CHOLMOD_SUPERNODAL;
  }
  ~Impl() {
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
  if (!impl_->factor || impl_->patternVersion != k.patternVersion() || impl_->patternOwner != &k) {
    if (impl_->factor) cholmod_free_factor(&impl_->factor, &impl_->common);
    impl_->factor = cholmod_analyze(&a, &impl_->common);
    DDASLOPE_ASSERT(impl_->factor != nullptr, "CHOLMOD symbolic analysis failed");
    impl_->patternVersion = k.patternVersion();
    impl_->patternOwner = &k;
    ++analyses_;
  }
  cholmod_factorize(&a, impl_->factor, &impl_->common);
  return impl_->common.status == CHOLMOD_OK && impl_->factor->minor == a.nrow;
}

void SparseCholesky::solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  cholmod_dense rhs{};
  rhs.nrow = static_cast<size_t>(b.size());
  rhs.ncol = 1;
  rhs.nzmax = rhs.nrow;
  rhs.d = rhs.nrow;
  rhs.x = const_cast<double*>(b.data());
  rhs.xtype = CHOLMOD_REAL;
  rhs.dtype = CHOLMOD_DOUBLE;
  cholmod_dense* sol = cholmod_solve(CHOLMOD_A, impl_->factor, &rhs, &impl_->common);
  DDASLOPE_ASSERT(sol != nullptr, "CHOLMOD solve failed");
  x.resize(b.size());
  std::memcpy(x.data(), sol->x, sizeof(double) * static_cast<size_t>(b.size()));
  cholmod_free_dense(&sol, &impl_->common);
}

}  // namespace ddaslope::solver

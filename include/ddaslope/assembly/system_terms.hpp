#pragma once
// The global stiffness K of one open-close iteration kept as its terms: a block term per block
// (mass, elasticity, damping, fixed points) and a rank-one spring k·v·vᵀ per contact spring.
// A product K·x then costs a gather, a dot product and a scatter per spring (24 multiply-adds
// with six unknowns per block), where assembling K's entries costs 78 per spring plus the search
// for their place. A large system needs K's entries only to factorise it; between
// factorisations, conjugate gradients and the residual check need only products.
#include <vector>

#include <Eigen/Core>

#include "ddaslope/assembly/block_sparse_matrix.hpp"
#include "ddaslope/core/types.hpp"

namespace ddaslope::assembly {

class SystemTerms {
 public:
  /// Starts a new K of blocks.size() blocks with `dof` unknowns each (6; 3 for rigid blocks:
  /// u0, v0, r0, the leading entries of every term). `blocks` must outlive the terms.
  void reset(int dof, const std::vector<Mat6>& blocks);
  /// Adds the spring k·v·vᵀ between blocks i and j (−1: a fixed block, whose half of v is
  /// dropped). v holds block i's six entries, then block j's; it must outlive the terms.
  void addSpring(int i, int j, double k, const Vec12& v);
  /// y = K·x, with dof unknowns per block.
  void multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const;
  /// Writes K's entries into m (its pattern set for these blocks and springs): block terms first,
  /// then the springs in the order added, each entry computed as BlockSparseMatrix's
  /// add*Outer compute it, so the values equal those of an assembly done term by term.
  void assembleInto(BlockSparseMatrix& m) const;
  int size() const { return dof_ * static_cast<int>(blocks_ ? blocks_->size() : 0); }

 private:
  struct Spring {
    int i, j;
    double k;
    const Vec12* v;
  };
  template <int Dof>
  void multiplyWith(const Eigen::VectorXd& x, Eigen::VectorXd& y) const;

  int dof_ = 6;
  const std::vector<Mat6>* blocks_ = nullptr;
  std::vector<Spring> springs_;
};

}  // namespace ddaslope::assembly

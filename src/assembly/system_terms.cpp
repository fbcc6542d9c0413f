#include "ddaslope/assembly/system_terms.hpp"

#include "ddaslope/core/errors.hpp"

namespace ddaslope::assembly {

void SystemTerms::reset(int dof, const std::vector<Mat6>& blocks) {
  DDASLOPE_ASSERT(dof == 3 || dof == 6, "a block has 3 (rigid) or 6 unknowns");
  dof_ = dof;
  blocks_ = &blocks;
  springs_.clear();
}

void SystemTerms::addSpring(int i, int j, double k, const Vec12& v) { springs_.push_back({i, j, k, &v}); }

template <int Dof>
void SystemTerms::multiplyWith(const Eigen::VectorXd& x, Eigen::VectorXd& y) const {
  const std::vector<Mat6>& blocks = *blocks_;
  y.resize(x.size());
  for (size_t b = 0; b < blocks.size(); ++b)
    y.segment<Dof>(Dof * b).noalias() = blocks[b].topLeftCorner<Dof, Dof>() * x.segment<Dof>(Dof * b);
  for (const Spring& s : springs_) {
    const auto vi = s.v->head<Dof>();
    const auto vj = s.v->segment<Dof>(6);
    double stretch = 0;
    if (s.i >= 0) stretch += vi.dot(x.segment<Dof>(Dof * s.i));
    if (s.j >= 0) stretch += vj.dot(x.segment<Dof>(Dof * s.j));
    const double force = s.k * stretch;
    if (s.i >= 0) y.segment<Dof>(Dof * s.i) += force * vi;
    if (s.j >= 0) y.segment<Dof>(Dof * s.j) += force * vj;
  }
}

void SystemTerms::multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const {
  DDASLOPE_ASSERT(x.size() == size(), "K·x: x has the wrong size");
  if (dof_ == 6)
    multiplyWith<6>(x, y);
  else
    multiplyWith<3>(x, y);
}

void SystemTerms::assembleInto(BlockSparseMatrix& m) const {
  DDASLOPE_ASSERT(m.size() == size() && m.blockSize() == dof_, "K's pattern does not match its terms");
  m.setZero();
  const std::vector<Mat6>& blocks = *blocks_;
  for (size_t b = 0; b < blocks.size(); ++b) m.addDiagonal(static_cast<int>(b), blocks[b]);
  for (const Spring& s : springs_) {
    const Vec6 vi = s.v->head<6>(), vj = s.v->tail<6>();
    if (s.i >= 0) m.addDiagonalOuter(s.i, s.k, vi);
    if (s.j >= 0) m.addDiagonalOuter(s.j, s.k, vj);
    if (s.i >= 0 && s.j >= 0) m.addCouplingOuter(s.i, s.j, s.k, vi, vj);
  }
}

}  // namespace ddaslope::assembly

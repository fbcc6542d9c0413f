// Block-sparse assembly and the CHOLMOD solve against a dense Eigen reference.
#include <gtest/gtest.h>

#include <tuple>
#include <vector>

#include <Eigen/Dense>

#include "ddaslope/assembly/block_sparse_matrix.hpp"
#include "ddaslope/assembly/system_terms.hpp"
#include "ddaslope/solver/sparse_cholesky.hpp"

using namespace ddaslope;

namespace {
/// The block-sparse matrix multiplies and solves like its dense reference (round-off only).
void expectMatchesDense(const assembly::BlockSparseMatrix& k, const Eigen::MatrixXd& dense, solver::SparseCholesky& chol) {
  const Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(dense.rows(), -1, 2);
  EXPECT_LT((k.multiply(x) - dense * x).norm(), 1e-12 * (dense * x).norm());
  ASSERT_TRUE(chol.factorise(k));
  Eigen::VectorXd sol;
  chol.solve(dense * x, sol);
  EXPECT_LT((sol - x).norm(), 1e-10 * x.norm());
}
}  // namespace

TEST(SparseSolve, MatchesDenseCholesky) {
  // Three blocks in a chain: 0–1 and 1–2 coupled. Build an SPD dense matrix with that pattern.
  const int n = 3;
  Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(18, 18);
  std::srand(7);
  const auto rnd = [] { return Mat6(Mat6::Random()); };
  assembly::BlockSparseMatrix k;
  k.setPattern(n, {{1, 0}, {1, 2}});
  k.setZero();
  for (int b = 0; b < n; ++b) {
    Mat6 a = rnd();
    a = a * a.transpose() + 20 * Mat6::Identity();
    k.addDiagonal(b, a);
    dense.block<6, 6>(6 * b, 6 * b) += a;
  }
  for (auto [r, c] : {std::pair{0, 1}, std::pair{2, 1}}) {
    const Mat6 krc = rnd();
    k.addCoupling(r, c, krc);
    dense.block<6, 6>(6 * r, 6 * c) += krc;
    dense.block<6, 6>(6 * c, 6 * r) += krc.transpose();
  }
  solver::SparseCholesky chol;
  expectMatchesDense(k, dense, chol);
  // Same pattern: no second symbolic analysis.
  ASSERT_TRUE(chol.factorise(k));
  EXPECT_EQ(chol.symbolicAnalyses(), 1);
}

TEST(SparseSolve, ReportsIndefiniteMatrix) {
  assembly::BlockSparseMatrix k;
  k.setPattern(1, {});
  k.setZero();
  k.addDiagonal(0, -Mat6::Identity());
  solver::SparseCholesky chol;
  EXPECT_FALSE(chol.factorise(k));
}

// Positive pivots first, then a negative one: [[I, 2I], [2I, I]] has eigenvalues −1 and 3. A small
// system's simplicial factorisation must refuse it as the supernodal one does.
TEST(SparseSolve, ReportsIndefiniteMatrixPastItsFirstPivots) {
  assembly::BlockSparseMatrix k;
  k.setPattern(2, {{0, 1}});
  k.setZero();
  k.addDiagonal(0, Mat6::Identity());
  k.addDiagonal(1, Mat6::Identity());
  k.addCoupling(0, 1, 2 * Mat6::Identity());
  solver::SparseCholesky chol;
  EXPECT_FALSE(chol.factorise(k));
  k.setZero();
  k.addDiagonal(0, Mat6::Identity());
  k.addDiagonal(1, Mat6::Identity());
  k.addCoupling(0, 1, 0.5 * Mat6::Identity());  // eigenvalues 0.5 and 1.5: definite
  EXPECT_TRUE(chol.factorise(k));
}

// Rigid blocks (three unknowns): the matrix keeps the leading 3×3 of every 6×6 term and solves
// that system exactly (dense reference: the same sub-blocks).
TEST(SparseSolve, RigidBlocksKeepTheLeadingThreeUnknowns) {
  const int n = 3;
  Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(9, 9);
  std::srand(11);
  assembly::BlockSparseMatrix k;
  k.setPattern(n, {{0, 1}, {1, 2}}, 3);
  EXPECT_EQ(k.size(), 9);
  k.setZero();
  for (int b = 0; b < n; ++b) {
    Mat6 a = Mat6::Random();
    a = a * a.transpose() + 20 * Mat6::Identity();
    k.addDiagonal(b, a);
    dense.block<3, 3>(3 * b, 3 * b) += a.topLeftCorner<3, 3>();
  }
  for (auto [r, c] : {std::pair{0, 1}, std::pair{2, 1}}) {
    const Mat6 krc = Mat6::Random();
    k.addCoupling(r, c, krc);
    dense.block<3, 3>(3 * r, 3 * c) += krc.topLeftCorner<3, 3>();
    dense.block<3, 3>(3 * c, 3 * r) += krc.topLeftCorner<3, 3>().transpose();
  }
  solver::SparseCholesky chol;
  expectMatchesDense(k, dense, chol);
}

// Low-rank update/downdate of the factor (what a contact spring switched on or off does to K):
// after K + c cᵀ the solve must match a dense solve of that matrix, and after the downdate a
// solve of K again (linear algebra identity; round-off tolerance 1e-9 relative). A downdate
// that would leave an indefinite matrix is refused.
TEST(SparseSolve, FactorFollowsRankOneChanges) {
  const int n = 3;
  Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(18, 18);
  std::srand(11);
  assembly::BlockSparseMatrix k;
  k.setPattern(n, {{1, 0}, {1, 2}});
  k.setZero();
  for (int b = 0; b < n; ++b) {
    Mat6 a = Mat6::Random();
    a = a * a.transpose() + 20 * Mat6::Identity();
    k.addDiagonal(b, a);
    dense.block<6, 6>(6 * b, 6 * b) += a;
  }
  const Mat6 k01 = Mat6::Random();
  k.addCoupling(0, 1, k01);
  dense.block<6, 6>(0, 6) += k01;
  dense.block<6, 6>(6, 0) += k01.transpose();
  solver::SparseCholesky chol;
  ASSERT_TRUE(chol.factorise(k));
  // A stiff spring between blocks 0 and 2 (rows 0..5 and 12..17), scaled like a contact penalty.
  solver::SparseCholesky::Column c;
  Eigen::VectorXd cv = Eigen::VectorXd::Zero(18);
  for (int e = 0; e < 6; ++e) {
    c.rows[c.count] = e, c.values[c.count++] = cv[e] = 30.0 * (e + 1);
    c.rows[c.count] = 12 + e, c.values[c.count++] = cv[12 + e] = -25.0 * (6 - e);
  }
  const Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(18, -1, 2);
  Eigen::VectorXd sol;
  ASSERT_TRUE(chol.modify({c}, true));
  chol.solve((dense + cv * cv.transpose()) * x, sol);
  EXPECT_LT((sol - x).norm(), 1e-9 * x.norm());
  ASSERT_TRUE(chol.modify({c}, false));
  chol.solve(dense * x, sol);
  EXPECT_LT((sol - x).norm(), 1e-9 * x.norm());
  // Removing the spring a second time would take away stiffness K never had.
  EXPECT_FALSE(chol.modify({c}, false));
}

TEST(SystemTerms, ProductsEqualTheAssembledMatrixAndItsDenseReference) {
  // K kept as terms (issue #16) must be the same operator as K assembled: three blocks, springs
  // between 0–1 and 1–2 and one to a fixed block (−1). Dense reference: Σ blocks + Σ k·v·vᵀ,
  // exact linear algebra; the products agree to round-off (1e-13 of |K·x|).
  for (int dof : {6, 3}) {
    std::srand(11);
    std::vector<Mat6> blocks(3);
    for (Mat6& b : blocks) {
      const Mat6 a = Mat6::Random();
      b = a * a.transpose() + 10 * Mat6::Identity();
    }
    std::vector<Vec12> v(4);
    for (Vec12& x : v) x = Vec12::Random();
    const std::vector<std::tuple<int, int, double>> springs{{0, 1, 3.0}, {1, 2, 0.4}, {2, 1, 5.0}, {1, -1, 2.0}};
    assembly::SystemTerms terms;
    terms.reset(dof, blocks);
    Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(3 * dof, 3 * dof);
    for (int b = 0; b < 3; ++b) dense.block(dof * b, dof * b, dof, dof) = blocks[b].topLeftCorner(dof, dof);
    for (size_t s = 0; s < springs.size(); ++s) {
      const auto [i, j, k] = springs[s];
      terms.addSpring(i, j, k, v[s]);
      Eigen::VectorXd u = Eigen::VectorXd::Zero(3 * dof);
      if (i >= 0) u.segment(dof * i, dof) = v[s].head(dof);
      if (j >= 0) u.segment(dof * j, dof) = v[s].segment(6, dof);
      dense += k * u * u.transpose();
    }
    assembly::BlockSparseMatrix m;
    m.setPattern(3, {{0, 1}, {1, 2}}, dof);
    terms.assembleInto(m);
    const Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(3 * dof, -1, 2);
    Eigen::VectorXd y;
    terms.multiply(x, y);
    const double scale = (dense * x).norm();
    EXPECT_LT((y - dense * x).norm(), 1e-13 * scale) << "dof " << dof;
    EXPECT_LT((m.multiply(x) - dense * x).norm(), 1e-13 * scale) << "dof " << dof;
  }
}

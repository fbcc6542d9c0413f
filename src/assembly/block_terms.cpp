#include "ddaslope/assembly/block_terms.hpp"

#include "ddaslope/model/block.hpp"

#include <Eigen/Eigenvalues>

namespace ddaslope::assembly {

Mat6 unitMassMatrix(const geometry::PolygonMoments& m) {
  // T = T0 + X·Tx + Y·Ty with X, Y about the centroid; the first moments vanish, so
  // ∫TᵀT = S T0ᵀT0 + Sxx TxᵀTx + Syy TyᵀTy + Sxy (TxᵀTy + TyᵀTx).
  Mat26 t0 = Mat26::Zero(), tx = Mat26::Zero(), ty = Mat26::Zero();
  t0(0, 0) = 1;  t0(1, 1) = 1;
  tx(1, 2) = 1;  tx(0, 3) = 1;  tx(1, 5) = 0.5;
  ty(0, 2) = -1; ty(1, 4) = 1;  ty(0, 5) = 0.5;
  return m.area * t0.transpose() * t0 + m.sxx * tx.transpose() * tx + m.syy * ty.transpose() * ty +
         m.sxy * (tx.transpose() * ty + ty.transpose() * tx);
}

Eigen::Matrix3d elasticityMatrix(double e, double nu, model::PlaneMode plane) {
  if (plane == model::PlaneMode::Strain) {
    e = e / (1 - nu * nu);
    nu = nu / (1 - nu);
  }
  Eigen::Matrix3d em;
  em << 1, nu, 0, nu, 1, 0, 0, 0, (1 - nu) / 2;
  return em * (e / (1 - nu * nu));
}

Mat6 elasticStiffness(double area, const Eigen::Matrix3d& em) {
  Mat6 k = Mat6::Zero();
  k.bottomRightCorner<3, 3>() = area * em;
  return k;
}

double lowestStrainFrequency(const Mat6& mass, const Mat6& elastic) {
  // M is positive definite and K_e positive semi-definite: three zero eigenvalues (u0, v0, r0),
  // zero to round-off of the largest, then the strain modes.
  const Eigen::GeneralizedSelfAdjointEigenSolver<Mat6> modes(elastic, mass, Eigen::EigenvaluesOnly);
  const Vec6& w2 = modes.eigenvalues();
  for (int k = 0; k < 6; ++k)
    if (w2[k] > 1e-9 * w2[5]) return std::sqrt(w2[k]);
  return 0;
}

Vec6 bodyForce(double area, const Vec2& f) {
  Vec6 r = Vec6::Zero();
  r.head<2>() = area * f;
  return r;
}

Vec6 initialStressForce(double area, const Vec3& stress) {
  Vec6 r = Vec6::Zero();
  r.tail<3>() = -area * stress;
  return r;
}

Vec6 pointForce(const Vec2& centroid, const Vec2& p, const Vec2& force) {
  return model::displacementMatrix(centroid, p).transpose() * force;
}

}  // namespace ddaslope::assembly

// Block sub-matrices against direct quadrature and closed forms.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "ddaslope/assembly/block_terms.hpp"
#include "ddaslope/model/block.hpp"

using namespace ddaslope;

// M/ρ = ∫TᵀT dA, checked against a 20×20 Gauss-free midpoint-refined quadrature would be
// approximate; instead a 2-point Gauss rule per cell is exact for the quadratic integrand.
TEST(BlockTerms, MassMatrixEqualsQuadratureOfTtT) {
  const std::vector<Vec2> rect{{1, 2}, {4, 2}, {4, 3.5}, {1, 3.5}};
  const auto m = geometry::computeMoments(rect);
  const Mat6 analytic = assembly::unitMassMatrix(m);
  Mat6 quad = Mat6::Zero();
  const double g = 1 / std::sqrt(3.0);
  for (double sx : {-g, g})
    for (double sy : {-g, g}) {
      const Vec2 p(2.5 + 1.5 * sx, 2.75 + 0.75 * sy);
      const Mat26 t = model::displacementMatrix(m.centroid, p);
      quad += t.transpose() * t * (3.0 * 1.5 / 4);
    }
  EXPECT_LT((analytic - quad).norm(), 1e-12 * quad.norm());
}

// Plane strain: E/((1+ν)(1−2ν)) [[1−ν, ν, 0], [ν, 1−ν, 0], [0, 0, (1−2ν)/2]] (Timoshenko).
TEST(BlockTerms, PlaneStrainElasticity) {
  const double e = 10e9, nu = 0.3;
  const Eigen::Matrix3d em = assembly::elasticityMatrix(e, nu, model::PlaneMode::Strain);
  const double f = e / ((1 + nu) * (1 - 2 * nu));
  EXPECT_NEAR(em(0, 0), f * (1 - nu), 1e-6);
  EXPECT_NEAR(em(0, 1), f * nu, 1e-6);
  EXPECT_NEAR(em(2, 2), e / (2 * (1 + nu)), 1e-6);  // shear modulus G
  const Eigen::Matrix3d es = assembly::elasticityMatrix(e, nu, model::PlaneMode::Stress);
  EXPECT_NEAR(es(0, 0), e / (1 - nu * nu), 1e-6);
  EXPECT_NEAR(es(2, 2), e / (2 * (1 + nu)), 1e-6);
}

// The exact rotation update keeps a rigid block's area: a quarter turn in one step changes
// the area by round-off only (the linear T would scale it by 1 + r0²).
TEST(BlockTerms, ExactRotationKeepsArea) {
  model::Block b;
  b.vertices = {{0, 0}, {2, 0}, {2, 1}, {0, 1}};
  b.moments = geometry::computeMoments(b.vertices);
  Vec6 d = Vec6::Zero();
  d[2] = M_PI / 2;
  b.applyDisplacement(d);
  EXPECT_NEAR(b.moments.area, 2.0, 1e-13);
  EXPECT_NEAR(b.moments.centroid.x(), 1.0, 1e-13);
  EXPECT_NEAR(b.moments.centroid.y(), 0.5, 1e-13);
  EXPECT_NEAR(b.vertices[0].x(), 1.5, 1e-13);  // (0,0) about (1,0.5) by +90° → (1.5,−0.5)
  EXPECT_NEAR(b.vertices[0].y(), -0.5, 1e-13);
}

// A point load P at p does work P·u = Dᵀ(TᵀP): the generalised force is Tᵀ(p)P.
TEST(BlockTerms, PointForceMoment) {
  const Vec6 f = assembly::pointForce({0, 0}, {2, 0}, {0, 10});
  EXPECT_DOUBLE_EQ(f[1], 10);
  EXPECT_DOUBLE_EQ(f[2], 20);  // moment = x·Fy
}

// A square block's two lowest strain modes are degenerate: the stretch εx = −εy, stiffness
// S E/(1+ν), and the shear γ, stiffness S G = S E/(2(1+ν)) against its mass ρ (Sxx+Syy)/4;
// both give ω₁² = 12 E / (ρ b² (1+ν)) in plane stress, and the same in plane strain, whose
// E' = E/(1−ν²) and ν' = ν/(1−ν) have E'/(1+ν') = E/(1+ν). 10 m, 5 GPa, ρ 2000, ν 0.25:
// 489.9 rad/s. Round-off tolerance (the generalized eigensolver).
TEST(BlockTerms, LowestStrainFrequencyOfASquare) {
  const double b = 10, e = 5e9, rho = 2000, nu = 0.25;
  const std::vector<Vec2> square{{0, 0}, {b, 0}, {b, b}, {0, b}};
  const auto m = geometry::computeMoments(square);
  const double expected = std::sqrt(12 * e / (rho * b * b * (1 + nu)));
  for (const model::PlaneMode plane : {model::PlaneMode::Stress, model::PlaneMode::Strain}) {
    const double w1 = assembly::lowestStrainFrequency(
        rho * assembly::unitMassMatrix(m), assembly::elasticStiffness(m.area, assembly::elasticityMatrix(e, nu, plane)));
    EXPECT_NEAR(w1, expected, 1e-9 * expected);
  }
}

// The step limit's cheap bound (model/block.hpp) is never below the exact largest vertex
// displacement |T(v) D| it stands in for (the triangle inequality on T D's components), and is
// tight for a pure translation (every vertex moves by |(d0, d1)|): random polygons and D, with
// displacements from 1e-12 to 10 m, including pure rotations and strains.
TEST(BlockTerms, VertexDisplacementBoundIsNeverBelowTheExactValue) {
  std::mt19937 rng(16);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int k = 0; k < 2000; ++k) {
    model::Block b;
    const int n = 3 + k % 5;
    const Vec2 centre(100 * u(rng), 100 * u(rng));
    for (int i = 0; i < n; ++i) {
      const double angle = 2 * M_PI * i / n, radius = 0.5 + std::abs(u(rng)) * (1 + k % 7);
      b.vertices.push_back(centre + radius * Vec2(std::cos(angle), std::sin(angle)));
    }
    b.moments = geometry::computeMoments(b.vertices);
    Vec6 d;
    for (int i = 0; i < 6; ++i) d[i] = u(rng) * std::pow(10.0, -12 + (k % 13));
    if (k % 5 == 1) d.head<2>().setZero(), d.tail<3>().setZero();  // pure rotation
    if (k % 5 == 2) d.head<3>().setZero();                         // pure strain
    EXPECT_GE(b.vertexDisplacementBound(d), b.maxVertexDisplacement(d)) << "case " << k;
  }
  model::Block square;
  square.vertices = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  square.moments = geometry::computeMoments(square.vertices);
  Vec6 shift = Vec6::Zero();
  shift[0] = 3e-3, shift[1] = -4e-3;
  EXPECT_NEAR(square.vertexDisplacementBound(shift), 5e-3, 1e-12);
  EXPECT_NEAR(square.maxVertexDisplacement(shift), 5e-3, 1e-15);
}

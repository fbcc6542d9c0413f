// The time integrator alone (solver/newmark.hpp): one free body, K = 0, stepped by solving
// (M/(βΔt²)) D = F + M V/(βΔt) for D as the step does. Newmark's β = 1/2, γ = 1 integrates a
// constant acceleration exactly (dda-method.md §3), so x(t) = v0 t + a t²/2 and v(t) = v0 + a t
// hold at every step up to round-off, at any Δt.
#include <gtest/gtest.h>

#include <cmath>
#include <utility>

#include <Eigen/Cholesky>

#include "ddaslope/solver/newmark.hpp"

using namespace ddaslope;
using solver::NewmarkIntegrator;

namespace {

/// The block's position after `steps` steps of dt from velocity v0 under the acceleration a
/// (the six generalised unknowns at once, each with its own v0 and a), and its velocity.
std::pair<Vec6, Vec6> integrate(const NewmarkIntegrator& integrator, const Mat6& mass, const Vec6& v0,
                                const Vec6& a, double dt, int steps) {
  Vec6 x = Vec6::Zero(), v = v0;
  for (int n = 0; n < steps; ++n) {
    const Mat6 k = integrator.inertiaStiffness(mass, dt);
    Vec6 f = mass * a;
    if (integrator.dynamic()) f += integrator.inertiaForce(mass, v, dt);
    const Vec6 d = k.ldlt().solve(f);
    v = integrator.velocityAfter(d, v, dt);
    x += d;
  }
  return {x, v};
}

}  // namespace

TEST(Newmark, ShisParametersIntegrateAConstantAccelerationExactly) {
  const NewmarkIntegrator integrator(true);
  // A mass matrix with coupling, as a block's about its centroid has none but strains do.
  Mat6 mass = Mat6::Identity() * 2.5;
  mass(3, 4) = mass(4, 3) = 0.3;
  Vec6 v0, a;
  v0 << 1.0, -2.0, 0.1, 0.0, 1e-3, -1e-3;
  a << 0.0, -9.81, 0.5, 1e-2, 0.0, 2e-2;
  for (const double dt : {1e-3, 1e-2, 0.1}) {
    const int steps = static_cast<int>(std::lround(1.0 / dt));
    const auto [x, v] = integrate(integrator, mass, v0, a, dt, steps);
    const Vec6 xExact = v0 + 0.5 * a, vExact = v0 + a;  // at t = 1 s
    for (int e = 0; e < 6; ++e) {
      EXPECT_NEAR(x(e), xExact(e), 1e-11 * (1 + std::abs(xExact(e)))) << "dt " << dt << ", unknown " << e;
      EXPECT_NEAR(v(e), vExact(e), 1e-10 * (1 + std::abs(vExact(e)))) << "dt " << dt << ", unknown " << e;
    }
  }
}

TEST(Newmark, AStaticAnalysisStartsEveryStepFromRest) {
  // Without the carried velocity each step is the static answer D = F/(2M/Δt²) = aΔt²/2, and the
  // velocity after it 2D/Δt = aΔt whatever the velocity before.
  const NewmarkIntegrator integrator(false);
  const Mat6 mass = Mat6::Identity();
  const Vec6 a = Vec6::Constant(-9.81), v0 = Vec6::Constant(3.0);
  const double dt = 0.01;
  const auto [x, v] = integrate(integrator, mass, v0, a, dt, 1);
  for (int e = 0; e < 6; ++e) {
    EXPECT_NEAR(x(e), 0.5 * a(e) * dt * dt, 1e-15);
    EXPECT_NEAR(v(e), a(e) * dt, 1e-14);
  }
}

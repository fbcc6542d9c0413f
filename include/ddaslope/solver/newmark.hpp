#pragma once
// The time integrator of the block motion: Newmark's scheme with Shi's parameters (dda-method.md
// §2-3). A step solves (K + M/(βΔt²)) D = F + M V_n/(βΔt) for the step's displacement D, and the
// velocity follows as V_{n+1} = (γ/(βΔt)) D + (1 − γ/β) V_n. The step never sees β or γ; it asks
// the integrator for the inertia's terms and for the velocity after the step.
#include "ddaslope/core/types.hpp"

namespace ddaslope::solver {

class NewmarkIntegrator {
 public:
  /// Shi's β = 1/2, γ = 1: a constant acceleration is integrated exactly (free fall, a block
  /// sliding on a plane), and γ > 1/2 damps oscillations at a rate that depends on Δt.
  static constexpr double kBeta = 0.5;
  static constexpr double kGamma = 1.0;
  // The general scheme also carries the acceleration A_n: into the force through
  // M (1/(2β) − 1) A_n and into the velocity through Δt (1 − γ/(2β)) A_n. Both vanish for Shi's
  // pair, which is why the blocks carry a velocity and no acceleration.
  static_assert(1 / (2 * kBeta) - 1 == 0 && 1 - kGamma / (2 * kBeta) == 0,
                "other parameters would need the acceleration carried between steps");
  static_assert(1 - kGamma / kBeta == -1, "velocityAfter subtracts V_n once");

  /// `dynamic`: the analysis carries velocity from step to step (analysis.mode); a static
  /// analysis starts every step from rest.
  explicit NewmarkIntegrator(bool dynamic) : dynamic_(dynamic) {}
  bool dynamic() const { return dynamic_; }

  /// The inertia's share of a block's stiffness: M/(βΔt²) = 2M/Δt².
  static Mat6 inertiaStiffness(const Mat6& mass, double dt) { return (1 / kBeta / (dt * dt)) * mass; }
  /// The force of the velocity a block carries into the step: M V_n/(βΔt) = 2M V_n/Δt.
  static Vec6 inertiaForce(const Mat6& mass, const Vec6& velocity, double dt) {
    return (1 / kBeta / dt) * mass * velocity;
  }
  /// Velocity after a step of displacement d from velocity v: V_{n+1} = 2D/Δt − V_n (γ = 1); in
  /// a static analysis the step started from rest (V_n = 0).
  Vec6 velocityAfter(const Vec6& d, const Vec6& velocity, double dt) const {
    return kGamma / kBeta * d / dt - (dynamic_ ? velocity : Vec6::Zero());
  }

 private:
  bool dynamic_;
};

}  // namespace ddaslope::solver

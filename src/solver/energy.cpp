#include "ddaslope/solver/energy.hpp"

#include <Eigen/Cholesky>

#include "ddaslope/assembly/block_terms.hpp"

namespace ddaslope::solver {

EnergyBudget storedEnergy(const model::Scene& scene, const std::vector<double>& mass,
                          const std::vector<Eigen::Matrix3d>& elasticity,
                          const std::vector<contact::Contact>& contacts, double normalStiffness,
                          double shearStiffness) {
  EnergyBudget e;
  for (size_t k = 0; k < scene.blocks.size(); ++k) {
    const model::Block& b = scene.blocks[k];
    if (b.fixed) continue;
    const Mat6 m = (mass[k] / b.moments.area) * assembly::unitMassMatrix(b.moments);
    e.kinetic += 0.5 * b.velocity.dot(m * b.velocity);
    e.potential -= mass[k] * scene.gravity.dot(b.moments.centroid);
    // σ = E ε accumulated from zero, so the strain energy is ½ σᵀ E⁻¹ σ per unit area.
    e.elastic += 0.5 * b.moments.area * b.stress.dot(elasticity[b.material].ldlt().solve(b.stress));
  }
  for (const model::FixedPoint& f : scene.fixedPoints)
    e.elastic += 0.5 * normalStiffness * (f.point.current - f.point.initial).squaredNorm();
  for (const contact::Contact& c : contacts) {
    if (!c.closed()) continue;
    e.elastic += 0.5 * c.normalForce * c.normalForce / normalStiffness;
    if (c.state == contact::ContactState::Locked)
      e.elastic += 0.5 * c.shearForce * c.shearForce / shearStiffness;
  }
  return e;
}

}  // namespace ddaslope::solver

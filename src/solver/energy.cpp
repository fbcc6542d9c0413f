#include "ddaslope/solver/energy.hpp"

#include <cmath>

#include <Eigen/Cholesky>

#include "ddaslope/assembly/block_terms.hpp"
#include "ddaslope/contact/contact_law.hpp"

namespace ddaslope::solver {

double kineticEnergy(const model::Block& b, double mass) {
  const Mat6 m = (mass / b.moments.area) * assembly::unitMassMatrix(b.moments);
  return 0.5 * b.velocity.dot(m * b.velocity);
}

EnergyBudget storedEnergy(const model::Scene& scene, const std::vector<double>& mass,
                          const std::vector<Eigen::Matrix3d>& elasticity,
                          const std::vector<contact::Contact>& contacts, double pointStiffness,
                          const ContactStiffness& stiffness) {
  EnergyBudget e;
  for (size_t k = 0; k < scene.blocks.size(); ++k) {
    const model::Block& b = scene.blocks[k];
    if (b.fixed) continue;
    e.kinetic += kineticEnergy(b, mass[k]);
    e.potential -= mass[k] * scene.gravity.dot(b.moments.centroid);
    // σ = E ε accumulated from zero, so the strain energy is ½ σᵀ E⁻¹ σ per unit area.
    e.elastic += 0.5 * b.moments.area * b.stress.dot(elasticity[b.material].ldlt().solve(b.stress));
  }
  for (const model::FixedPoint& f : scene.fixedPoints)
    e.elastic += 0.5 * pointStiffness * (f.point.current - f.point.initial).squaredNorm();
  // A support's work: stored while it is elastic, dissipated once it yields (counted either way:
  // the budget then only misses a gain, never invents one).
  for (const model::Support& s : scene.supports) e.elastic += s.work;
  for (const contact::Contact& c : contacts) {
    if (!c.closed()) continue;
    const auto [normalStiffness, shearStiffness] = stiffness(c);
    e.elastic += 0.5 * c.normalForce * c.normalForce / normalStiffness;
    // The shear spring is elastic-plastic: locked, it holds S; sliding, it stays stretched to
    // the friction it slides against (Simulation::slidingFriction: N tan φ plus c·L while a
    // softening bond lasts, shared by the ends of an edge; a contact that sticks again keeps that
    // force), so it stores ½ S² / p_s either way.
    const double shear = c.shearForce;
    e.elastic += 0.5 * shear * shear / shearStiffness;
  }
  return e;
}

}  // namespace ddaslope::solver

#pragma once
// The mechanical energy of a scene, for the energy-balance check: no spurious gain.
// Friction, the open-close law and the γ = 1 integrator only dissipate, so
// kinetic + gravity potential + elastic − work of the other loads never rises in a correct run.
#include <functional>
#include <utility>
#include <vector>

#include "ddaslope/contact/contact_set.hpp"
#include "ddaslope/model/scene.hpp"

namespace ddaslope::solver {

/// Energies per unit thickness (J/m).
struct EnergyBudget {
  double kinetic = 0;    ///< ½ Vᵀ M V summed over free blocks
  double potential = 0;  ///< −Σ m g·x_c of free blocks (gravity; zero level at the origin)
  double elastic = 0;    ///< block strain energy + contact springs (½ N²/p + ½ S²/p_s; sliding: S = N tan φ)
  double loadWork = 0;   ///< work done on the blocks by water pressure, point loads and seismic loading
  double groundMotionWork = 0;  ///< the share of loadWork done by a ground-motion record's inertial force
  /// Kinetic + potential + elastic − load work: non-increasing in a dissipative run.
  double mechanical() const { return kinetic + potential + elastic - loadWork; }
};

/// ½ Vᵀ M V of one block of mass `mass` (kg/m).
double kineticEnergy(const model::Block& b, double mass);

/// The stored energies of the scene's current state; `loadWork` is left 0 (the caller sums it).
/// `mass[b]`: block b's mass (kg/m); `pointStiffness` the fixed points' springs (N/m), and
/// `stiffness(c)` a contact's normal and shear springs (N/m).
using ContactStiffness = std::function<std::pair<double, double>(const contact::Contact&)>;
EnergyBudget storedEnergy(const model::Scene& scene, const std::vector<double>& mass,
                          const std::vector<Eigen::Matrix3d>& elasticity,
                          const std::vector<contact::Contact>& contacts, double pointStiffness,
                          const ContactStiffness& stiffness);

}  // namespace ddaslope::solver

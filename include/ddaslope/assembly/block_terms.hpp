#pragma once
// Sub-matrices of a single block (Shi 1988, ch. 2): pure functions of its geometry.
#include "ddaslope/core/types.hpp"
#include "ddaslope/geometry/polygon.hpp"
#include "ddaslope/model/analysis_settings.hpp"

namespace ddaslope::assembly {

/// M/ρ = ∫ TᵀT dA about the centroid, from the polygon moments.
Mat6 unitMassMatrix(const geometry::PolygonMoments& m);
/// 3×3 elasticity matrix E_m (plane stress; plane strain by E' = E/(1−ν²), ν' = ν/(1−ν)).
Eigen::Matrix3d elasticityMatrix(double e, double nu, model::PlaneMode plane);
/// Elastic stiffness: S·E_m on the strain unknowns.
Mat6 elasticStiffness(double area, const Eigen::Matrix3d& em);
/// Lowest angular frequency (rad/s) of a free block's own strain modes, K_e φ = ω² M φ with the
/// three rigid modes left out; 0 when K_e is zero.
double lowestStrainFrequency(const Mat6& mass, const Mat6& elastic);
/// Body force per unit volume f acting on the block: F[u0, v0] = S f.
Vec6 bodyForce(double area, const Vec2& f);
/// Force of the accumulated stress σ on the next step: F[ε] = −S σ.
Vec6 initialStressForce(double area, const Vec3& stress);
/// Point force P at p: Tᵀ(p) P.
Vec6 pointForce(const Vec2& centroid, const Vec2& p, const Vec2& force);

}  // namespace ddaslope::assembly

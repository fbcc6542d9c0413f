#pragma once
#include <optional>
#include <string>

namespace ddaslope::model {

/// Rock material of a block (SI units).
struct Material {
  std::string name;
  double density = 0;       ///< kg/m³
  double youngModulus = 0;  ///< Pa
  double poissonRatio = 0;  ///< −
};

/// Which contacts of a joint are intact (carry c and σt) when they form.
enum class BondPolicy {
  Initial,  ///< contacts touching at t = 0 are intact; contacts formed later are not
  None,     ///< never intact: friction only
  Always,   ///< contacts formed later are intact too (a cementing joint)
};

/// How a joint's strength falls from peak to residual with accumulated slip δ (docs/contact-model.md).
enum class WeakeningLaw {
  Linear,       ///< remaining fraction 1 − δ/δw, residual from δ = δw on
  Exponential,  ///< remaining fraction exp(−δ/δw): 63 % lost at δw, 95 % at 3 δw
};

/// The automatic weakening distance as a fraction of w0 (half the model's larger side): half the
/// searches' default failure displacement, so a trial judged failing has lost its peak strength,
/// and five times the slip of the elastic load transfer between the blocks of a long slide
/// (2.5 cm on the 300 m planar multi-block slide, 1e-4 w0: at 1e-4 w0 that slide's upper blocks
/// soften while passing their load down and its critical c is 6 % high; docs/contact-model.md).
constexpr double kAutomaticWeakeningRatio = 5e-4;

/// Mohr-Coulomb joint with tension cut-off, softening from peak (c, φ, σt) to residual
/// (c_r, φ_r, 0) with slip. Angles are radians inside the code.
struct JointProperties {
  std::string name;
  double frictionAngle = 0;    ///< peak φ (rad)
  double cohesion = 0;         ///< peak c (Pa)
  double tensileStrength = 0;  ///< σt (Pa), residual 0
  BondPolicy bond = BondPolicy::Initial;
  /// Residual φ_r (rad); unset: the peak φ (friction does not soften). Used as min(φ_r, φ), so a
  /// search that lowers the peak below it softens nothing.
  std::optional<double> residualFrictionAngle;
  double residualCohesion = 0;  ///< c_r (Pa), used as min(c_r, c); acts only on intact contacts
  /// Slip δw (m) over which peak falls to residual. 0: brittle, the bond (c, σt) and the peak φ
  /// are lost the moment a contact slides (original DDA). Unset: automatic,
  /// kAutomaticWeakeningRatio × w0, resolved when a simulation starts (docs/contact-model.md).
  std::optional<double> weakeningDistance;
  WeakeningLaw weakeningLaw = WeakeningLaw::Linear;
  /// Barton–Bandis (Barton & Choubey 1977): τ = σn tan(φr + JRC log10(JCS/σn)), φr the
  /// frictionAngle, no cohesion (docs/contact-model.md, "Barton–Bandis joints"). With a weakening
  /// distance JRC falls to 0 with slip. Strength reduction divides tan of the whole mobilised angle
  /// by F (`reduction`), as RS2 and UDEC reduce a nonlinear joint.
  struct BartonBandis {
    double jrc = 0;        ///< joint roughness coefficient (as used: scale-corrected if asked)
    double jcs = 0;        ///< joint wall compressive strength (Pa, as used)
    double reduction = 1;  ///< F of a strength reduction
    bool wears = false;    ///< JRC falls to 0 over the weakening distance (given one)
  };
  std::optional<BartonBandis> bartonBandis;
  /// Joint stiffness per unit joint length, normal and shear (Pa/m), as RS2 and UDEC take it;
  /// 0: the model's penalty. A contact's spring is kn·L (ks·L) over the share L of an
  /// edge-to-edge contact it stands for (half the overlap); a corner touching an edge, which has
  /// no length, keeps the penalty (docs/contact-model.md, "Joint stiffness").
  double normalStiffness = 0, shearStiffness = 0;

  /// A joint of constant strength (no softening besides the brittle bond).
  static JointProperties coulomb(std::string name, double frictionAngle, double cohesion = 0, double tensileStrength = 0);
  /// φ_r as used: the residual friction, never above the peak.
  double residualFriction() const;
  /// δw as used in a model of half-size w0: the set distance, or the automatic one.
  double weakeningDistanceIn(double w0) const { return weakeningDistance.value_or(kAutomaticWeakeningRatio * w0); }
  /// c_r as used, never above the peak.
  double residualCohesionUsed() const;
  /// Strength reduction by F (Dawson et al. 1999, for peak and residual alike): c/F, σt/F,
  /// atan(tan φ/F), c_r/F and atan(tan φ_r/F); the weakening distance is kept.
  JointProperties reducedBy(double factor) const;
};

}  // namespace ddaslope::model

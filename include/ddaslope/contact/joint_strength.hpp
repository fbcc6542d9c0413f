#pragma once
// A joint's strength as a contact sees it: peak softening to residual with slip (Mohr-Coulomb with
// tension cut-off). Apart from the contact-state rules, which only compare forces with it.
#include "ddaslope/model/materials.hpp"

namespace ddaslope::contact {

/// Strength of one contact (or one half of an edge-to-edge contact) as forces per metre of
/// thickness over its share L of the contact length.
struct ContactStrength {
  double tanPhi = 0;
  double cohesionForce = 0;   ///< c·L (N/m), acts only while bonded
  double tensileForce = 0;    ///< σt·L (N/m), acts only while bonded
  /// A joint with a weakening distance keeps its bond while it slides (the strength falls with
  /// the slip instead); a brittle one loses it the moment it slides.
  bool bondSurvivesSlip = false;
  /// The joint has tensile strength (σt > 0): pulled open, its bond cracks, whatever share of it
  /// this contact carries.
  bool cracks = false;
  /// Barton–Bandis (bartonBandis): the friction of a normal force N over the share `length` is
  /// N tan(φr + jrc·log10(jcs·length/N)) / reduction, the angle held within [φr, 70°] (Barton's
  /// cap at low stress; above JCS the law has no roughness left). tanPhi is tan φr.
  bool bartonBandis = false;
  double jrc = 0, jcs = 0, length = 0, reduction = 1;
  /// The friction a normal force N mobilises (N/m; N ≤ 0 gives N tan φ, which only a bond offsets).
  double friction(double normalForce) const;
};

/// Fraction w ∈ [0, 1] of the peak-above-residual strength left after an accumulated slip δ (m):
/// 1 − δ/δw (linear) or exp(−δ/δw) (exponential). A brittle joint (δw = 0) has 1 until it slides;
/// the state rules then set 0 at once. The joint's distance must be resolved (set).
double remainingStrength(const model::JointProperties& j, double slip);

/// A joint's strength in the form the contact rules use, computed once per run (the open-close
/// loop asks for it for every contact in every iteration).
struct JointStrength {
  double tanPeak = 0, tanResidual = 0;  ///< tan φ, tan φ_r as used (φ_r ≤ φ)
  double cohesion = 0, residualCohesion = 0, tensileStrength = 0;  ///< Pa
  bool softens = false;                 ///< weakening distance > 0: the bond survives slip
  bool bartonBandis = false, jrcWears = false;
  double jrc = 0, jcs = 0, reduction = 1;
};
/// The joint's distance must be resolved (set).
JointStrength jointStrength(const model::JointProperties& j);

/// The strength of a contact share of length `length` whose remaining fraction is `intact`:
/// tanφ = tanφ_r + (tanφ − tanφ_r)·w, c = c_r + (c − c_r)·w, σt·w.
ContactStrength contactStrength(const JointStrength& j, double intact, double length);
inline ContactStrength contactStrength(const model::JointProperties& j, double intact, double length) {
  return contactStrength(jointStrength(j), intact, length);
}

}  // namespace ddaslope::contact

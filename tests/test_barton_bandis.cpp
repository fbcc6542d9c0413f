// Barton–Bandis joints against closed forms: the critical angle of a block on an incline and its
// strength-reduction factor, with σn from the block's weight (docs/contact-model.md).
#include <gtest/gtest.h>

#include <cmath>

#include "ddaslope/calibration/strength_search.hpp"
#include "ddaslope/calibration/verdict.hpp"
#include "ddaslope/contact/joint_strength.hpp"
#include "scene_builders.hpp"

using namespace ddaslope;
using scenes::InclineSpec;

namespace {

// φr 25°, JRC 5, JCS 20 MPa; a 2 × 0.5 m block of 2600 kg/m³: σn = ρ g h cos α ≈ 12.8 kPa, so
// φr + JRC log10(JCS/σn) ≈ 41°, below Barton's 70° cap.
constexpr double kPhiR = 25, kJrc = 5, kJcs = 20e6;

InclineSpec thinBlock(double alphaDeg) {
  InclineSpec spec;
  spec.alphaDeg = alphaDeg;
  spec.b = 2;
  spec.h = 0.5;  // thin: the normal force is shared almost evenly between the base's two ends
  spec.phiDeg = kPhiR;
  spec.duration = 1.0;
  return spec;
}

model::Scene bartonBandisIncline(double alphaDeg) {
  model::Scene s = scenes::makeIncline(thinBlock(alphaDeg));
  model::JointProperties::BartonBandis bb;
  bb.jrc = kJrc;
  bb.jcs = kJcs;
  s.joints[0].bartonBandis = bb;
  return s;
}

/// The mobilised angle at the block's base: φr + JRC log10(JCS/σn), σn = ρ g h cos α.
double mobilisedDeg(double alphaDeg) {
  const InclineSpec spec = thinBlock(alphaDeg);
  const double sigma = spec.density * spec.g * spec.h * std::cos(degToRad(alphaDeg));
  return kPhiR + kJrc * std::log10(kJcs / sigma);
}

/// The closed-form critical angle: α = φr + JRC log10(JCS/(ρ g h cos α)), by bisection.
double criticalAngleDeg() {
  double lo = 0, hi = 80;
  for (int k = 0; k < 200; ++k) {
    const double mid = 0.5 * (lo + hi);
    (mobilisedDeg(mid) > mid ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace

// The law itself: the friction of N over a share L is N tan(φr + JRC log10(JCS L/N)), held within
// [φr, 70°]; a reduction F divides that tangent (Barton & Choubey 1977).
TEST(BartonBandis, FrictionFollowsTheLawWithinItsCaps) {
  contact::ContactStrength s;
  s.bartonBandis = true;
  s.tanPhi = std::tan(degToRad(kPhiR));
  s.jrc = kJrc;
  s.jcs = kJcs;
  s.length = 1;
  const double n = 1e4;  // σn = 10 kPa
  EXPECT_NEAR(s.friction(n), n * std::tan(degToRad(kPhiR + kJrc * std::log10(kJcs / n))), 1e-9 * n);
  EXPECT_NEAR(s.friction(1e-3), 1e-3 * std::tan(degToRad(70)), 1e-15);   // near no load: the 70° cap
  EXPECT_NEAR(s.friction(1e8), 1e8 * std::tan(degToRad(kPhiR)), 1e-6);   // above JCS: φr
  s.reduction = 1.5;
  EXPECT_NEAR(s.friction(n), n * std::tan(degToRad(kPhiR + kJrc * std::log10(kJcs / n))) / 1.5, 1e-9 * n);
}

// The block holds 0.5 % below the closed-form critical angle and slides 0.5 % above it.
TEST(BartonBandis, BlockOnAnInclineSlidesAtTheClosedFormCriticalAngle) {
  const double critical = criticalAngleDeg();
  ASSERT_GT(critical, 35);
  ASSERT_LT(critical, 45);
  EXPECT_TRUE(calibration::judgeStability(bartonBandisIncline(critical * 0.995)).stable) << critical;
  EXPECT_FALSE(calibration::judgeStability(bartonBandisIncline(critical * 1.005)).stable) << critical;
}

// Strength reduction of the nonlinear law divides the tangent of the mobilised angle by F
// (as RS2 and UDEC reduce a Barton–Bandis joint): on a 30° incline F = tan(φ_mob(σn))/tan 30°,
// within 1 %.
TEST(BartonBandis, FactorOfSafetyReducesTheTangentOfTheMobilisedAngle) {
  const double alpha = 30;
  const double expected = std::tan(degToRad(mobilisedDeg(alpha))) / std::tan(degToRad(alpha));
  const calibration::FactorOfSafetyResult r = calibration::factorOfSafety(bartonBandisIncline(alpha), {}, 1e-3);
  ASSERT_TRUE(r.found) << r.message;
  EXPECT_NEAR(r.factor, expected, 0.01 * expected);
}

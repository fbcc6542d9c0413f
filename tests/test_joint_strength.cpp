// Joints that soften from peak to residual with slip (contact/joint_strength.hpp, issue #14).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "ddaslope/calibration/strength_search.hpp"
#include "ddaslope/calibration/trial_report.hpp"
#include "ddaslope/contact/joint_strength.hpp"
#include "ddaslope/io/case_reader.hpp"
#include "ddaslope/solver/simulation.hpp"
#include "scene_builders.hpp"

using namespace ddaslope;
using scenes::InclineSpec;

namespace {

model::JointProperties softening(double phiDeg, double c, double phiResidualDeg, double distance,
                                 model::WeakeningLaw law = model::WeakeningLaw::Linear) {
  model::JointProperties j = model::JointProperties::coulomb("j", degToRad(phiDeg), c);
  j.residualFrictionAngle = degToRad(phiResidualDeg);
  j.weakeningDistance = distance;
  j.weakeningLaw = law;
  return j;
}

/// The centre monitor's displacement and speed when its displacement first reaches `d`
/// (linear between the two rows around it).
std::pair<double, double> speedWhenDisplaced(const io::Trace& t, double d) {
  const int m = t.monitorIndex("centre");
  const auto dist = [&](size_t row) { return std::hypot(t.samples[row][m].ux, t.samples[row][m].uy); };
  const auto speed = [&](size_t row) { return std::hypot(t.samples[row][m].vx, t.samples[row][m].vy); };
  for (size_t r = 1; r < t.samples.size(); ++r)
    if (dist(r) >= d) {
      const double f = (d - dist(r - 1)) / (dist(r) - dist(r - 1));
      const double time = (r >= 2 ? t.steps[r - 2].time : 0.0) * (1 - f) + t.steps[r - 1].time * f;
      return {time, speed(r - 1) * (1 - f) + speed(r) * f};
    }
  ADD_FAILURE() << "never displaced by " << d << " m";
  return {0, 0};
}

/// The critical cohesion (Pa) of the joint named `joint` at φ = 18° to a bracket of `width` Pa;
/// a search that brackets nothing fails the test.
double criticalCohesionAt18(const model::Scene& scene, const std::string& joint, double width) {
  int j = 0;
  while (scene.joints[j].name != joint) ++j;
  const calibration::CriticalResult r = calibration::criticalCohesion(scene, j, 18, width, {});
  EXPECT_TRUE(r.found) << r.message;
  return r.critical;
}

/// The scene with the joint named `joint` brittle (weakening_distance 0: original DDA's bond).
model::Scene withBrittleJoint(model::Scene scene, const std::string& joint) {
  for (model::JointProperties& j : scene.joints)
    if (j.name == joint) j.weakeningDistance = 0;
  return scene;
}

}  // namespace

// The remaining fraction w(δ) and the strength it gives, exactly (definitions in
// contact/joint_strength.hpp: linear 1 − δ/δw, exponential exp(−δ/δw); tanφ and c interpolated).
TEST(JointStrength, SoftensFromPeakToResidual) {
  model::JointProperties j = softening(40, 100e3, 20, 0.1);
  j.residualCohesion = 10e3;
  j.tensileStrength = 50e3;
  EXPECT_DOUBLE_EQ(contact::remainingStrength(j, 0), 1);
  EXPECT_DOUBLE_EQ(contact::remainingStrength(j, 0.025), 0.75);
  EXPECT_DOUBLE_EQ(contact::remainingStrength(j, 0.1), 0);
  EXPECT_DOUBLE_EQ(contact::remainingStrength(j, 3), 0);
  const contact::ContactStrength s = contact::contactStrength(j, 0.75, 2.0);  // over L = 2 m
  EXPECT_NEAR(s.tanPhi, std::tan(degToRad(20)) + 0.75 * (std::tan(degToRad(40)) - std::tan(degToRad(20))), 1e-15);
  EXPECT_NEAR(s.cohesionForce, 2.0 * (10e3 + 0.75 * 90e3), 1e-9);
  EXPECT_NEAR(s.tensileForce, 2.0 * 0.75 * 50e3, 1e-9);
  EXPECT_TRUE(s.bondSurvivesSlip);
  j.weakeningLaw = model::WeakeningLaw::Exponential;
  EXPECT_NEAR(contact::remainingStrength(j, 0.1), std::exp(-1.0), 1e-15);
  EXPECT_NEAR(contact::remainingStrength(j, 0.3), std::exp(-3.0), 1e-15);
  // Brittle (δw = 0): full strength until any slip, residual after; the bond does not survive.
  j.weakeningDistance = 0;
  EXPECT_DOUBLE_EQ(contact::remainingStrength(j, 0), 1);
  EXPECT_DOUBLE_EQ(contact::remainingStrength(j, 1e-12), 0);
  EXPECT_FALSE(contact::contactStrength(j, 1, 1).bondSurvivesSlip);
  // A residual above the peak (a search lowering the peak) is used as the peak.
  const model::JointProperties low = softening(10, 5e3, 20, 0.1);
  EXPECT_DOUBLE_EQ(contact::contactStrength(low, 0, 1).tanPhi, std::tan(degToRad(10)));
}

// Strength reduction divides peak and residual alike: c/F, c_r/F, σt/F, tan φ/F, tan φ_r/F.
TEST(JointStrength, StrengthReductionReducesPeakAndResidual) {
  model::JointProperties j = softening(40, 100e3, 20, 0.1);
  j.residualCohesion = 10e3;
  j.tensileStrength = 50e3;
  const model::JointProperties r = j.reducedBy(2);
  EXPECT_NEAR(std::tan(r.frictionAngle), std::tan(j.frictionAngle) / 2, 1e-15);
  EXPECT_NEAR(std::tan(r.residualFriction()), std::tan(degToRad(20)) / 2, 1e-15);
  EXPECT_DOUBLE_EQ(r.cohesion, 50e3);
  EXPECT_DOUBLE_EQ(r.residualCohesion, 5e3);
  EXPECT_DOUBLE_EQ(r.tensileStrength, 25e3);
  EXPECT_DOUBLE_EQ(*r.weakeningDistance, 0.1);
}

// A block on a 30° incline whose joint softens over δw = 5 cm from peak (φ 25°, c = 1 kPa) to
// residual (φ_r 15°, c_r = 0). Closed forms (rigid block, benchmarks.md A2 with the strength a
// function of slip δ): the acceleration is a(δ) = a_r + (a_p − a_r) w(δ), a_p = g (sin α − cos α
// tan φ) − c b/m, a_r = g (sin α − cos α tan φ_r), so by the work-energy theorem
// v(δ)² = 2∫a dδ: linear law δw (a_p + a_r) at δ = δw; exponential 2 [a_r δ + (a_p − a_r) δw
// (1 − e^{−δ/δw})]. Past δw (linear) the acceleration is a_r. Tolerance 1 % (issue #14). The
// strength of a step is that at its start, so the speed lags by about half a step's slip.
TEST(JointStrength, SofteningBlockMatchesTheWorkEnergyClosedForm) {
  InclineSpec s;  // α 30°, b 2 m, h 1 m, ρ 2600, g 9.81
  s.duration = 1.0;
  const double mass = s.density * s.b * s.h, alpha = degToRad(s.alphaDeg), dw = 0.05;
  const double aResidual = s.g * (std::sin(alpha) - std::cos(alpha) * std::tan(degToRad(15)));
  const double aPeak = s.g * (std::sin(alpha) - std::cos(alpha) * std::tan(degToRad(25))) - 1e3 * s.b / mass;
  ASSERT_GT(aPeak, 0);  // the peak is exceeded at once
  const double vLinear = std::sqrt(dw * (aPeak + aResidual));
  const double vExponential = std::sqrt(2 * (aResidual * 3 * dw + (aPeak - aResidual) * dw * (1 - std::exp(-3.0))));
  for (double dt : {1e-3, 4e-3}) {
    s.timeStep = dt;
    model::Scene sc = scenes::makeIncline(s);
    sc.joints[0] = softening(25, 1e3, 15, dw);
    io::Trace t = scenes::runTrace(sc);
    const auto [when, v] = speedWhenDisplaced(t, dw);
    EXPECT_NEAR(v, vLinear, 0.01 * vLinear) << "dt = " << dt;
    // Past δw: the second difference of displacement over 0.2 s steps is the acceleration.
    const auto d = [&](double time) { return scenes::measureAt(t, "centre", "displacement", time); };
    const double a = (d(1.0) - 2 * d(0.8) + d(0.6)) / (0.2 * 0.2);
    EXPECT_GT(0.6, when);
    EXPECT_NEAR(a, aResidual, 0.01 * aResidual) << "dt = " << dt;

    sc.joints[0] = softening(25, 1e3, 15, dw, model::WeakeningLaw::Exponential);
    t = scenes::runTrace(sc);
    EXPECT_NEAR(speedWhenDisplaced(t, 3 * dw).second, vExponential, 0.01 * vExponential) << "dt = " << dt;
  }
}

// The brittle limit (δw = 0) is original DDA's bond: c and the peak φ are lost the moment the
// contact slides, so the block slides at the residual closed form from the start.
TEST(JointStrength, BrittleJointSlidesAtResidualFromTheStart) {
  InclineSpec s;
  const double alpha = degToRad(s.alphaDeg);
  const double aResidual = s.g * (std::sin(alpha) - std::cos(alpha) * std::tan(degToRad(15)));
  model::Scene sc = scenes::makeIncline(s);
  sc.joints[0] = softening(25, 1e3, 15, 0);
  const io::Trace t = scenes::runTrace(sc);
  // d(1 s) = a_r/2: 0.5 % as benchmark A2.
  EXPECT_NEAR(scenes::measureAt(t, "centre", "displacement", 1.0), aResidual / 2, 0.005 * aResidual / 2);
}

// The chair-shaped slide (cases/chair_slide.json: 50 m blocks on a 30° segment buttressed by an 8°
// toe, a 3 m kink block above the kink): critical cohesion of the sliding surface at φ = 18°.
// - Brittle bonds (original DDA, the first-failure answer): each upper block loses its bond as it
//   slips before the toe can take its load, so the answer is that of one block of the 30° segment
//   standing alone, γ'h·cosα(sinα − cosα tanφ) = 268.07 kPa (scripts/chair_slide.py le); within
//   10 %, measured 260.8.
// - Default (softening) joints: the slide's cohesion acts as a whole, the toe buttressing the
//   upper blocks. Issue #14 asks for limit equilibrium on the same slices within 10 %: the
//   multi-wedge method with the joints' 40° on the vertical interfaces (Sarma-type, the slices'
//   equilibrium with the strength the DDA joints have) needs 48.50 kPa (scripts/chair_slide.py le;
//   Spencer's constant interslice inclination, 21.6°, asks 66.24: docs/calibration.md says why
//   the joints' friction is the referee). Without the kink block a 50 m block's corner on the
//   kink holds the slide at about a third of that (docs/calibration.md has the figures).
// - Nor can it lie below 44.12 kPa, the least cohesion for which any set of contact forces holds
//   these blocks (scripts/block_equilibrium.py cases/chair_slide.json --joint sliding_surface
//   --friction 18: Livesley's rigid-block limit equilibrium): a block model at rest is such a set
//   (the static theorem), so below it DDA would hold the slide with strength it does not have.
//   Tolerance: the search's 500 Pa bracket.
TEST(ChairSlide, SofteningJointsKeepTheButtressThatBrittleBondsLose) {
  const model::Scene scene = io::readCase(std::string(DDASLOPE_SOURCE_DIR) + "/cases/chair_slide.json");
  const auto critical = [](const model::Scene& s) { return criticalCohesionAt18(s, "sliding_surface", 500); };
  constexpr double kWedgesAtJointFriction = 48.50e3, kSingleBlock = 268.07e3, kBlocksStaticBound = 44.123e3,
                   kBracket = 500;
  const double edge = critical(scene);
  EXPECT_NEAR(edge, kWedgesAtJointFriction, 0.1 * kWedgesAtJointFriction);
  EXPECT_GE(edge, kBlocksStaticBound - kBracket);
  model::Scene vertex = scene;
  vertex.settings.contactTreatment = model::ContactTreatment::Vertex;
  const double original = critical(vertex);
  EXPECT_NEAR(original, kWedgesAtJointFriction, 0.1 * kWedgesAtJointFriction);
  EXPECT_GE(original, kBlocksStaticBound - kBracket);
  EXPECT_NEAR(critical(withBrittleJoint(scene, "sliding_surface")), kSingleBlock, 0.1 * kSingleBlock);
}

// A softening joint without tensile strength keeps its bond through a separation smaller than its
// weakening distance and loses it at one that large. A 2 × 1 m block on a 30° incline, bonded
// (c = 2 c_cr, φ = 20°: benchmarks B1), is thrown off it at v = 0.5 m/s along the outward normal
// (with 2 v tan α up the slope, so that it comes down where it left). Its contacts record the
// largest opening, the hop's height v²/(2 g cos α) = 14.7 mm (within 2 %: the springs' penetration
// at rest and the first step's share), and at the top of the hop, before it lands, a weakening
// distance of 1 km has kept the bond and one of 8 mm has lost it. (A rule that drops the bond at
// any opening loses both.)
TEST(SofteningJoints, ASeparationBreaksTheBondAtTheWeakeningDistance) {
  InclineSpec spec{30, 2, 1, 20, 0, 2600, 9.81};
  spec.cohesion = 2 * model::criticalCohesion(spec);
  const double a = 30 * M_PI / 180, v = 0.5, hop = v * v / (2 * 9.81 * std::cos(a));
  const auto thrown = [&](double weakeningDistance) {
    model::Scene scene = scenes::makeIncline(spec);
    scene.joints[0].weakeningDistance = weakeningDistance;
    scene.blocks[1].velocity.head<2>() =
        v * Vec2(-std::sin(a), std::cos(a)) + 2 * v * std::tan(a) * Vec2(std::cos(a), std::sin(a));
    solver::Simulation sim(scene);
    sim.bringToEquilibrium(nullptr);
    while (sim.time() < 1.1 * v / (9.81 * std::cos(a))) sim.advance();  // just past the top
    return sim.contacts().contacts();
  };
  const auto kept = thrown(1000), lost = thrown(8e-3);
  ASSERT_FALSE(kept.empty());
  ASSERT_FALSE(lost.empty());
  for (const contact::Contact& c : kept) {
    EXPECT_FALSE(c.closed());
    EXPECT_TRUE(c.bonded);
    EXPECT_NEAR(c.opening, hop, 0.02 * hop);
  }
  for (const contact::Contact& c : lost) EXPECT_FALSE(c.bonded);
}

// Stage 3 that stalls hands the analysis its quietest state. The chair slide at c = 55.6 kPa and
// Δt 1 ms settles into a slow cycle of switching contacts and stops nearing rest; stage 2's state
// implies 3.1 g in one step from rest at that Δt (`ddaslope run cases/chair_slide.json --at-fos 1
// --time-step 0.001 --set joints.sliding_surface.cohesion=55556 --verbose`, the first settling
// step), and started from it the first analysis step gives a block's centroid 0.57 g. The start
// must be the quietest state found, a hundredth of that at most, reported as stalled, not at rest.
TEST(SofteningJoints, AStalledSettlingStartsFromItsQuietestState) {
  model::Scene scene = io::readCase(std::string(DDASLOPE_SOURCE_DIR) + "/cases/chair_slide.json",
                                    {io::CaseOverride("analysis.time_step", 0.001),
                                     io::CaseOverride("joints.sliding_surface.cohesion", 55556)});
  solver::Simulation sim(scene);
  sim.bringToEquilibrium(nullptr);
  const auto& st = sim.statistics();
  EXPECT_STREQ(st.settling, "stalled");
  EXPECT_FALSE(st.startedAtRest);
  EXPECT_LT(st.equilibriumResidual, 0.031) << "g";
  EXPECT_GT(st.equilibriumResidual, 1e-6) << "g: a stall is not a rest";
  // The first analysis step from that start: no block's centroid gathers more than 0.031 g.
  const double dt = scene.settings.timeStep;
  sim.advance();
  double fastest = 0;
  for (const model::Block& b : sim.scene().blocks) fastest = std::max(fastest, b.velocity.head<2>().norm());
  EXPECT_LT(fastest / dt / 9.81, 0.031) << "g";
}

// The chair slide's critical cohesion is the slope's, not the time step's: a search at Δt 0.5, 1
// and 3 ms (the case's own step is 4.2 ms), on the shipped 50 m blocks and on 40 m blocks, lands
// within issue #14's 10 % of the slices' limit equilibrium with the joints' 40° (48.50 kPa for
// 50 m blocks, 49.0 for 40 m: scripts/chair_slide.py le) and above the blocks' static bound (44.12
// and 46.0 kPa, scripts/block_equilibrium.py; tolerance the search's 500 Pa bracket). Smaller
// steps leave the ringing that follows the release of the held start undamped: a kick from a
// settling that found no rest, or bonds broken at every edge-contact end the ringing lifts, make
// the answer follow Δt (docs/contact-model.md, "Separation without tensile strength").
TEST(ChairSlide, CriticalCohesionDoesNotFollowTheTimeStep) {
  const std::string path = std::string(DDASLOPE_SOURCE_DIR) + "/cases/chair_slide.json";
  constexpr double kBracket = 500;
  struct Layout {
    double spacing, wedges, bound;
  };
  for (const Layout& l : {Layout{50, 48.50e3, 44.123e3}, Layout{40, 49.0e3, 46.0e3}}) {
    double least = INFINITY, most = -INFINITY;
    for (double dt : {0.0005, 0.001, 0.003}) {
      const model::Scene scene =
          io::readCase(path, {io::CaseOverride("section.joint_sets[0].spacing", l.spacing),
                              io::CaseOverride("analysis.time_step", dt)});
      const double c = criticalCohesionAt18(scene, "sliding_surface", kBracket);
      EXPECT_NEAR(c, l.wedges, 0.1 * l.wedges) << l.spacing << " m blocks, Δt " << dt;
      EXPECT_GE(c, l.bound - kBracket) << l.spacing << " m blocks, Δt " << dt;
      least = std::min(least, c), most = std::max(most, c);
    }
    // And no trend with Δt beyond half of that tolerance.
    EXPECT_LE(most - least, 0.05 * l.wedges) << l.spacing << " m blocks";
  }
}

// Stiff contacts (analysis.penalty_factor 2000 against the case's 40) make the chair's settling
// chatter: trials start from settlings that found no rest, and the verdict stops being monotone
// in c (`run` stands at 55-66 kPa, fails at c = 200000/3 Pa, stands at 66 667). A search on two
// threads lands on such a failure and answers 66.9 kPa (one thread: 51.7, where `run` puts the
// change from failing to standing). It must say that its failing end did not start from rest;
// at the case's own stiffness it has nothing to say.
TEST(ChairSlide, AFailingEndThatDidNotStartFromRestIsReported) {
  const std::string path = std::string(DDASLOPE_SOURCE_DIR) + "/cases/chair_slide.json";
  for (const double penalty : {40.0, 2000.0}) {
    const model::Scene scene = io::readCase(path, {io::CaseOverride("analysis.penalty_factor", penalty)});
    int j = 0;
    while (scene.joints[j].name != "sliding_surface") ++j;
    calibration::SearchSettings s;
    s.threads = 2;
    const calibration::CriticalResult r = calibration::criticalCohesion(scene, j, 18, 500, s);
    ASSERT_TRUE(r.found) << r.message;
    const std::string w = calibration::unrestedEndWarning(r.trials, r.found, r.failingEnd, "c", "chair_slide.json");
    if (penalty == 40)
      EXPECT_EQ(w, "") << "critical c " << r.critical;
    else
      EXPECT_NE(w.find("did not start from rest"), std::string::npos) << "critical c " << r.critical << ": " << w;
  }
}

// A planar multi-block slide (cases/planar_multiblock_slide.json: a wedge on one 30° plane, thick
// at the crown, joints normal to the plane) is a rigid mechanism, so limit equilibrium is exact:
// c_cr = γA(sinα − cosα tanφ)/L = 24525 × 10000 × 0.218616 / 461.880 = 116.08 kPa at φ = 18°.
// With the scene settled at rest before t = 0 (analysis.settle_dynamically) and the default
// weakening distance, DDA's critical cohesion must match it within 2 %: issue #14 asks 10 %, and
// 2 % is what separates it from the two defects this slide exposes (+6.1 % from an unsettled
// start, +6.1 % from a distance shorter than the load transfer; the presets and time steps measured
// are in docs/calibration.md). The thick crown blocks need up to twice the mean alone, so brittle
// bonds (original DDA, the first-failure answer) must lie well above it: the crown blocks fail one
// after another.
TEST(PlanarMultiBlockSlide, CriticalCohesionMatchesTheClosedFormWhenSettledAtRest) {
  const model::Scene scene = io::readCase(std::string(DDASLOPE_SOURCE_DIR) + "/cases/planar_multiblock_slide.json");
  ASSERT_TRUE(scene.settings.settleDynamically);
  const auto critical = [](const model::Scene& s) { return criticalCohesionAt18(s, "sliding_surface", 300); };
  const double tanPhi = std::tan(18 * M_PI / 180), alpha = 30 * M_PI / 180;
  const double closedForm = 2500 * 9.81 * (0.5 * 50 * 400) * (std::sin(alpha) - std::cos(alpha) * tanPhi) /
                            (400 / std::cos(alpha));
  EXPECT_NEAR(critical(scene), closedForm, 0.02 * closedForm);
  model::Scene vertex = scene;
  vertex.settings.contactTreatment = model::ContactTreatment::Vertex;
  EXPECT_NEAR(critical(vertex), closedForm, 0.02 * closedForm);
  EXPECT_GT(critical(withBrittleJoint(scene, "sliding_surface")), 1.5 * closedForm);
}

// Vajont from trigger to deposit in one run (calibration/vajont_trigger/case.json): one law for
// the sliding surface, peak φ 19.3° (0.1° below the 19.41° critical at the failure level of the
// layout with 10 m kink blocks, so the slope fails) softening over 1 m of slip to the run-out
// study's residual 5.54° (calibration/vajont_runout; docs/vajont.md). The crown must travel
// and move as observed (300–400 m horizontal, 17–30 m/s; ../shared/data/vajont/README.md, S8 p46,
// S1 p147) and come to rest within the run (the collapse lasted under 45 s), and the energy budget
// must only dissipate (largest rise below 1e-3 of the energy scale, as for the run-out table).
TEST(VajontTrigger, FailsAndRunsOutInOneRun) {
  const model::Scene scene = io::readCase(std::string(DDASLOPE_SOURCE_DIR) + "/calibration/vajont_trigger/case.json");
  const io::Trace t = scenes::runTrace(scene);
  EXPECT_GE(scenes::measureAt(t, "crown", "ux", std::nullopt), 300);
  EXPECT_LE(scenes::measureAt(t, "crown", "ux", std::nullopt), 400);
  EXPECT_GE(scenes::measureAt(t, "crown", "speed", std::nullopt), 17);
  EXPECT_LE(scenes::measureAt(t, "crown", "speed", std::nullopt), 30);
  EXPECT_LT(scenes::measureAt(t, "crown", "speed", 45.0), 0.1);
  EXPECT_LE(t.largestEnergyGain(), 1e-3 * t.energyScale());
  EXPECT_LE(t.largestStepGain(), 1e-3 * t.energyScale());  // issue #14: no step gains 0.1 % of the scale
}

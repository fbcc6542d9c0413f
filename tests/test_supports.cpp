// Supports (bolts, anchors) and edge loads against closed forms: a passive bolt on a sliding
// block (Hooke's law, its capacity, the slide after it gives), the Hoek & Bray planar failure
// with an anchor, and the equivalence of an edge load with its resultant.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include <nlohmann/json.hpp>

#include "ddaslope/calibration/strength_search.hpp"
#include "ddaslope/calibration/verdict.hpp"
#include "ddaslope/core/errors.hpp"
#include "ddaslope/io/case_reader.hpp"
#include "ddaslope/solver/simulation.hpp"

#include "scene_builders.hpp"
#include "test_io.hpp"

using namespace ddaslope;
using scenes::InclineSpec;

namespace {

/// The A4 incline (30°, φ 20°: the block slides at g (sin α − cos α tan φ) = 1.813 m/s²) with a
/// fixed anchor block 1 m upslope of it and a bolt parallel to the slope from the middle of the
/// block's upslope face into the anchor block: its elongation is the block's slip.
model::Scene boltedIncline(double stiffness, double capacity, model::SupportFailure failure) {
  InclineSpec spec;
  spec.duration = 0.6;
  model::Scene s = scenes::makeIncline(spec);
  const double a = degToRad(spec.alphaDeg);
  const Vec2 u(std::cos(a), std::sin(a)), n(-std::sin(a), std::cos(a));
  const auto p = [&](double along, double up) -> Vec2 { return along * u + up * n; };
  model::Block anchor;
  anchor.id = "anchor";
  anchor.fixed = true;
  anchor.vertices = {p(13, 0), p(15, 0), p(15, 1), p(13, 1)};
  anchor.moments = geometry::computeMoments(anchor.vertices);
  s.blocks.push_back(anchor);
  model::Support b;
  b.id = "bolt";
  b.head = {1, p(12, 0.5), p(12, 0.5)};
  b.end = {2, p(14, 0.5), p(14, 0.5)};
  b.initialLength = 2;
  b.stiffness = stiffness;
  b.capacity = capacity;
  b.failure = failure;
  s.supports.push_back(b);
  s.settings.initialEquilibrium = false;  // the block starts at rest on the ramp and slides
  // Rigid, so that the block's slip is one number (a deformable block's face and centre differ by
  // its strain under the base friction, a micrometre here).
  s.settings.rigidBlocks = true;
  return s;
}

Vec2 downslopeUnit() {
  const double a = degToRad(InclineSpec{}.alphaDeg);
  return {-std::cos(a), -std::sin(a)};
}

struct BoltRecord {
  std::vector<double> time, slip, force, speed;
  std::vector<model::SupportState> state;
};

BoltRecord runBolt(const model::Scene& scene) {
  solver::Simulation sim(scene);
  sim.bringToEquilibrium();
  BoltRecord r;
  while (!sim.finished()) {
    sim.advance();
    const model::Monitor& m = sim.scene().monitors[0];
    r.time.push_back(sim.time());
    // Down the slope (the block also settles into the ramp by a micrometre: not slip).
    r.slip.push_back((m.point.current - m.point.initial).dot(downslopeUnit()));
    r.force.push_back(sim.scene().supports[0].force);
    r.state.push_back(sim.scene().supports[0].state);
    r.speed.push_back(sim.monitorVelocity(0).norm());
  }
  return r;
}

/// The acceleration over the last 0.2 s of the run (m/s²), from the monitor's speed.
double lateAcceleration(const BoltRecord& r) {
  const size_t end = r.time.size() - 1;
  size_t start = end;
  while (start > 0 && r.time[end] - r.time[start] < 0.2) --start;
  return (r.speed[end] - r.speed[start]) / (r.time[end] - r.time[start]);
}

constexpr double kMass = 2600 * 2.0;  // the 2 × 1 m block (kg/m)

}  // namespace

// Early rest (calibration/verdict.hpp) with a support: a bolt's law does not depend on time, so a
// block it holds stops early with the verdict of its whole run. The A4 block pulls 9.43 kN/m down
// the slope beyond its friction (m a, a = 1.813 m/s²). A bolt of 20 kN/m capacity holds it at the
// static stretch m a / k = 9.4 mm, where the initial equilibrium brings it: the run stops as rest
// before its duration, as stable as the whole run. One of 5 kN/m yields: from rest, the block
// stretches it elastically, s = s0 (1 − cos ωt) with s0 = m a / k and ω = √(k/m), until k s
// reaches the capacity, then slides on at (9.43 − 5) kN/m / m = 0.85 m/s² under its constant
// pull. Both runs pass the 0.1 m failure displacement at that closed form's 0.434 s, and neither
// stops as rest.
TEST(EarlyRest, ABoltedBlockStopsEarlyWithTheWholeRunsVerdict) {
  const double pull = kMass * scenes::slidingAcceleration(InclineSpec{});
  ASSERT_NEAR(pull, 9428, 10);
  for (const double capacity : {2e4, 5e3}) {
    model::Scene s = boltedIncline(1e6, capacity, model::SupportFailure::Yield);
    s.settings.duration = 2;
    const bool holds = capacity > pull;
    // Brought to rest first only where it holds: the yielding bolt's block would pass the
    // threshold while the scene settles (rule (0)), before any run could stop early.
    s.settings.initialEquilibrium = holds;
    calibration::VerdictSettings v;
    v.failureDisplacement = 0.1;
    s.settings.earlyRest = false;
    const calibration::TrialResult whole = calibration::judgeStability(s, v);
    s.settings.earlyRest = true;
    const calibration::TrialResult early = calibration::judgeStability(s, v);
    EXPECT_EQ(whole.stable, holds) << capacity << ": " << whole.reason;
    EXPECT_EQ(early.stable, holds) << capacity << ": " << early.reason;
    EXPECT_EQ(early.rule, whole.rule) << capacity;
    EXPECT_EQ(early.earlyRest, holds) << capacity;
    EXPECT_FALSE(whole.earlyRest);
    if (holds) {
      EXPECT_LT(early.timeReached, 0.5 * s.settings.duration);
    } else {
      const double k = 1e6, w = std::sqrt(k / kMass), s0 = pull / k;
      const double t1 = std::acos(1 - capacity / k / s0) / w, v1 = s0 * w * std::sin(w * t1);
      const double a2 = (pull - capacity) / kMass;
      const double passes = t1 + (-v1 + std::sqrt(v1 * v1 + 2 * a2 * (0.1 - capacity / k))) / a2;
      ASSERT_NEAR(passes, 0.434, 0.001);
      EXPECT_EQ(early.rule, calibration::VerdictRule::PassedDisplacement);
      // Within 1 %: steps of 1 ms, and the threshold is met by the block's farthest point, which
      // its slight rotation carries ahead of its centre.
      EXPECT_NEAR(early.timeReached, passes, 0.01 * passes);
    }
  }
}

// A passive bolt's force is k × elongation while it holds (Hooke's law; the elongation is the
// slip, the bolt lying along it), stays at its capacity once reached (perfectly plastic), and the
// block then slides at (W sin α − W cos α tan φ − C)/m: the closed form with the bolt's constant
// pull. Tolerances: 1e-3 for the force (the bolt turns by the block's rotation, ~1e-5 rad); 1 %
// for the acceleration (Newmark γ = 1 loses a little of a transient that has not quite died).
TEST(Supports, PassiveBoltFollowsHookesLawThenYieldsAtItsCapacity) {
  const double k = 1e6, capacity = 5000;
  const BoltRecord r = runBolt(boltedIncline(k, capacity, model::SupportFailure::Yield));
  int elastic = 0, yielded = 0;
  for (size_t i = 0; i < r.time.size(); ++i) {
    EXPECT_LE(r.force[i], capacity * (1 + 1e-12)) << "at t = " << r.time[i];
    if (r.state[i] == model::SupportState::Elastic && r.slip[i] > 1e-4) {
      ++elastic;
      EXPECT_NEAR(r.force[i], k * r.slip[i], 1e-3 * k * r.slip[i]) << "at t = " << r.time[i];
    }
    if (r.state[i] == model::SupportState::Yielded) {
      ++yielded;
      EXPECT_DOUBLE_EQ(r.force[i], capacity);
    }
  }
  EXPECT_GT(elastic, 20);
  EXPECT_GT(yielded, 100);
  const InclineSpec spec;
  const double expected = scenes::slidingAcceleration(spec) - capacity / kMass;
  EXPECT_NEAR(lateAcceleration(r), expected, 0.01 * expected);
}

// A brittle bolt breaks at its capacity and the block then slides as the closed form without
// it, g (sin α − cos α tan φ) (benchmarks.md A2), within 1 %.
TEST(Supports, BrittleBoltBreaksAndTheBlockSlidesAsWithoutIt) {
  const double k = 1e6, capacity = 5000;
  const BoltRecord r = runBolt(boltedIncline(k, capacity, model::SupportFailure::Rupture));
  double largest = 0;
  for (double f : r.force) largest = std::max(largest, f);
  EXPECT_LE(largest, capacity);
  EXPECT_GT(largest, 0.9 * capacity);  // it did carry load up to near its capacity before breaking
  EXPECT_EQ(r.state.back(), model::SupportState::Broken);
  EXPECT_EQ(r.force.back(), 0);
  const double expected = scenes::slidingAcceleration(InclineSpec{});
  EXPECT_NEAR(lateAcceleration(r), expected, 0.01 * expected);
}

// A bolt strong enough stops the block. From rest under the constant net force m·a (gravity less
// friction) the slip obeys m s'' = m a − k s while it slides down, so it stops at s = 2 m a / k;
// there the bolt's pull less the weight's downslope part (6.6 kN/m) is within the friction
// W cos α tan φ (16.1 kN/m), so it stays. Within 2 %: Newmark's γ = 1 damps the half swing
// (ζ ≈ ωΔt/4 = 0.35 %, about 1 % of the amplitude).
TEST(Supports, StrongBoltStopsTheBlockAtTwiceItsStaticStretch) {
  const double k = 1e6;
  model::Scene s = boltedIncline(k, 1e9, model::SupportFailure::Yield);
  s.settings.duration = 1;
  const BoltRecord r = runBolt(s);
  const double swing = 2 * kMass * scenes::slidingAcceleration(InclineSpec{}) / k;
  EXPECT_NEAR(r.slip.back(), swing, 0.02 * swing);
  EXPECT_LT(r.speed.back(), 1e-6);
  EXPECT_NEAR(r.force.back(), k * r.slip.back(), 1e-3 * k * r.slip.back());
}

namespace {

/// Hoek & Bray's planar failure (cases/planar_failure.json): W = 3685.3 kN/m, A = 24.415 m,
/// ψ = 35°, c = 25 kPa, φ = 30°. With an anchor force T at θ below the horizontal (Wyllie & Mah
/// 2004, eq. 6.24) and a vertical surcharge Q on the crest:
/// F = (cA + ((W + Q) cos ψ + T sin(θ + ψ)) tan φ) / ((W + Q) sin ψ − T cos(θ + ψ)).
double planarFactor(double anchor, double thetaDeg, double surcharge = 0) {
  const double w = 3685.3e3 + surcharge, a = 24.415, c = 25e3;
  const double psi = degToRad(35), phi = degToRad(30), theta = degToRad(thetaDeg);
  return (c * a + (w * std::cos(psi) + anchor * std::sin(theta + psi)) * std::tan(phi)) /
         (w * std::sin(psi) - anchor * std::cos(theta + psi));
}

model::Scene planarCase(const std::string& name) {
  return io::readCase(std::string(DDASLOPE_SOURCE_DIR) + "/cases/" + name);
}

/// The shipped anchor re-aimed at θ below the horizontal from its head, 15 m long, holding T.
void aimAnchor(model::Scene& s, double thetaDeg, double force) {
  model::Support& b = s.supports.at(0);
  const Vec2 dir(std::cos(degToRad(thetaDeg)), -std::sin(degToRad(thetaDeg)));
  b.end.initial = b.end.current = b.head.initial + 15 * dir;
  b.initialLength = 15;
  b.end.block = 0;  // the rock mass below the sliding plane
  s.setSupportQuantity("anchor", force);
}

/// A vertical surcharge q (Pa) on the planar wedge's crest, from the face's top to the crack, as
/// the point loads of an edge load named "surcharge".
model::EdgeLoad addCrestSurcharge(model::Scene& s, double q) {
  model::EdgeLoad l;
  l.id = "surcharge";
  l.block = 1;
  l.from = {11.547005383793, 20};
  l.to = {20, 20};
  l.q0 = l.q1 = {0, -q};
  for (const model::PointLoad& p : model::equivalentPointLoads(l)) s.pointLoads.push_back(p);
  return l;
}

}  // namespace

// The anchored planar failure: F by strength reduction within 1 % of the closed form for three
// anchor forces at two angles (the search brackets F to 1e-3).
TEST(Supports, AnchoredPlanarFailureMatchesTheClosedForm) {
  const model::Scene base = planarCase("planar_failure_anchor.json");
  for (double theta : {20.0, 45.0})
    for (double force : {500e3, 1000e3, 2000e3}) {
      model::Scene s = base;
      aimAnchor(s, theta, force);
      const calibration::FactorOfSafetyResult r = calibration::factorOfSafety(s, {}, 1e-3);
      ASSERT_TRUE(r.found) << r.message;
      const double expected = planarFactor(force, theta);
      EXPECT_NEAR(r.factor, expected, 0.01 * expected) << "θ = " << theta << "°, T = " << force << " N/m";
    }
}

// critical --solve support: the anchor force for F = 1.5 within 1 % of the closed form's root
// (613.07 kN/m at 20°, 985.96 kN/m at 45°: planarFactor(T, θ) = 1.5, solved by bisection here).
TEST(Supports, AnchorForceForATargetFactorOfSafetyMatchesTheClosedForm) {
  const model::Scene base = planarCase("planar_failure_anchor.json");
  for (double theta : {20.0, 45.0}) {
    model::Scene s = base;
    aimAnchor(s, theta, 1000e3);
    double lo = 0, hi = 3e6;
    for (int k = 0; k < 100; ++k) ((planarFactor(0.5 * (lo + hi), theta) < 1.5) ? lo : hi) = 0.5 * (lo + hi);
    const calibration::CriticalResult r = calibration::criticalSupport(s, "anchor", 1.5, 0);
    ASSERT_TRUE(r.found) << r.message;
    EXPECT_NEAR(r.critical, lo, 0.01 * lo) << "θ = " << theta << "°";
  }
}

// An edge load is its resultant: a 100 kPa surcharge on the wedge's crest adds Q = q × 8.453 m to
// the weight, F = (cA + (W + Q) cos ψ tan φ)/((W + Q) sin ψ), within 1 %.
TEST(Supports, SurchargeOnTheCrestActsAsItsResultant) {
  model::Scene s = planarCase("planar_failure.json");
  const model::EdgeLoad l = addCrestSurcharge(s, 100e3);
  const double q = 100e3 * (20 - 11.547005383793);
  EXPECT_NEAR(l.resultant().y(), -q, 1e-9 * q);
  const calibration::FactorOfSafetyResult r = calibration::factorOfSafety(s, {}, 1e-3);
  ASSERT_TRUE(r.found) << r.message;
  EXPECT_NEAR(r.factor, planarFactor(0, 0, q), 0.01 * planarFactor(0, 0, q));
}

/// The support search on a shipped case for F = 1, on two threads; expects an answer.
double supportForLimitingEquilibrium(const std::string& caseName, const std::string& id) {
  calibration::SearchSettings settings;
  settings.threads = 2;
  const calibration::CriticalResult r = calibration::criticalSupport(planarCase(caseName), id, 1.0, 0, settings);
  EXPECT_TRUE(r.found) << r.message;
  return r.critical;
}

// The Goodman & Bray toppling slope at φ = 33.02° (cases/goodman_bray_toppling.json): the toe
// force for F = 1 found by the support search, within 5 % of the published 2013 kN/m (horizontal;
// the Goodman–Bray chain of scripts/goodman_bray_toppling.py gives 1997 kN/m).
TEST(Supports, GoodmanBrayToeForceForLimitingEquilibrium) {
  EXPECT_NEAR(supportForLimitingEquilibrium("goodman_bray_toppling.json", "toe_force"), 2013e3, 0.05 * 2013e3);
}

// The same slope held by a toe anchor, a support element 20° below the horizontal into the rock
// (cases/goodman_bray_toppling_anchor.json): the anchor force for F = 1 within 5 % of Goodman &
// Bray's chain for a pure toe force in that direction, 2085.5 kN/m
// (python3 scripts/goodman_bray_toppling.py --theta 50).
TEST(Supports, GoodmanBrayToeAnchorForLimitingEquilibrium) {
  EXPECT_NEAR(supportForLimitingEquilibrium("goodman_bray_toppling_anchor.json", "toe_anchor"), 2085.5e3,
              0.05 * 2085.5e3);
}

// RS2's rigid stand-in (E = 2e14 Pa) is accepted: the contact penalty is that of the stiffest rock
// (2e11 Pa), and Hoek & Bray's planar failure keeps its factor of safety (1.1133 closed form),
// the same as with E = 2e11 Pa to the search's bracket.
TEST(Supports, RigidStandInModulusKeepsThePlanarFactorOfSafety) {
  model::Scene stiffest = planarCase("planar_failure.json");
  stiffest.materials[0].youngModulus = 2e11;
  model::Scene standIn = stiffest;
  standIn.materials[0].youngModulus = 2e14;
  EXPECT_DOUBLE_EQ(standIn.normalPenalty(), stiffest.normalPenalty());
  const calibration::FactorOfSafetyResult a = calibration::factorOfSafety(stiffest, {}, 1e-3);
  const calibration::FactorOfSafetyResult b = calibration::factorOfSafety(standIn, {}, 1e-3);
  ASSERT_TRUE(a.found && b.found);
  EXPECT_NEAR(b.factor, a.factor, 2e-3);
  EXPECT_NEAR(b.factor, 1.1133, 0.01 * 1.1133);
}

// A load the slope stands without is sized the other way: the largest crest surcharge that holds
// at a target F. With Q on the planar wedge, F = cA/((W + Q) sin ψ) + tan φ/tan ψ, so for F = 1.05
// Q = cA/((1.05 − tan φ/tan ψ) sin ψ) − W (closed form), within 1 %.
TEST(Supports, LargestSurchargeForATargetFactorOfSafety) {
  model::Scene s = planarCase("planar_failure.json");
  addCrestSurcharge(s, 10e3);
  const double psi = std::atan2(14.004150764194, 20.0), target = 1.05;
  const double w = s.blocks[1].moments.area * 2600 * 9.81, ca = 25e3 * 20 / std::cos(psi);
  const double expected = ca / ((target - std::tan(degToRad(30)) / std::tan(psi)) * std::sin(psi)) - w;
  const calibration::CriticalResult r = calibration::criticalSupport(s, "surcharge", target, 0);
  ASSERT_TRUE(r.found) << r.message;
  EXPECT_TRUE(r.largestThatHolds);
  EXPECT_NEAR(r.critical, expected, 0.01 * expected);
}

// history.png shows motions; a case with supports also gets supports.png, each support's axial
// force against time, drawn from the same rows as history.csv's <id>_force columns: the
// prestressed anchor of cases/planar_failure_anchor.json holds its force. A case without supports
// gets none (issue #43).
TEST(Supports, RunDrawsTheSupportForcesBesideTheHistory) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("ddaslope_supports_png_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  std::string err;
  const std::string src = DDASLOPE_SOURCE_DIR;
  const std::string out =
      clitest::captureCli("run " + src + "/cases/planar_failure_anchor.json --duration 0.1 --quiet --out " + dir.string(), &err);
  EXPECT_NE(out.find("supports.png"), std::string::npos) << out;
  EXPECT_GT(fs::file_size(dir / "supports.png"), 1000u);
  clitest::captureCli("run " + src + "/cases/planar_failure.json --duration 0.1 --quiet --out " + dir.string(), &err);
  EXPECT_FALSE(fs::exists(dir / "supports.png")) << "a case without supports keeps no stale picture";
  fs::remove_all(dir);
}

// A planar wedge (plane 32°, c 15 kPa, φ 35°) cut in two by a vertical joint at x = −8, an
// anchor of 600 kN/m whose head is drawn on that joint, as a user might draw it. Which
// block carries the head decides the answer, the whole wedge held or the toe block sliding alone
// (F 2.17 against 1.47), so the file's block order must not: such a head must name its block.
// Named, the wedge gets Hoek & Bray's F with an anchor, within 1 %, in either order:
// F = (cA + (W cos ψ − T u·n) tan φ)/(W sin ψ + T u·d), d down the plane, n out of it, u the
// anchor's pull on the wedge. A monitor on the same joint follows the block whose centroid lies
// highest, in either order.
TEST(Supports, AHeadOnTheJointBetweenTwoFreeBlocksMustNameItsBlock) {
  const nlohmann::json rock = {{-46.25, -15}, {12, -15}, {12, -7.4984}, {0, 0}, {-16.2976, 10.1839}, {-16.2976, 18}, {-46.25, 18}};
  const nlohmann::json lower = {{0, 0}, {-8, 12.8030}, {-8, 4.9990}};
  const nlohmann::json upper = {{-8, 4.9990}, {-8, 12.8030}, {-11.2476, 18}, {-16.2476, 18}, {-16.2476, 10.1527}};
  const Vec2 head(-8, 9), end(-21.5230, 5.3765);
  const double tension = 600e3;
  const auto caseWith = [&](bool lowerFirst, const char* headBlock) {
    nlohmann::json blocks = {{{"id", "rock_mass"}, {"material", "rock"}, {"fixed", true}, {"vertices", rock}}};
    const nlohmann::json l = {{"id", "lower"}, {"material", "rock"}, {"vertices", lower}};
    const nlohmann::json u = {{"id", "upper"}, {"material", "rock"}, {"vertices", upper}};
    blocks.push_back(lowerFirst ? l : u);
    blocks.push_back(lowerFirst ? u : l);
    nlohmann::json anchor = {{"id", "anchor"}, {"head", {head.x(), head.y()}}, {"end", {end.x(), end.y()}}, {"pretension", tension}};
    if (headBlock) anchor["head_block"] = headBlock;
    return nlohmann::json{{"gravity", {0, -9.81}},
                          {"materials", {{"rock", {{"density", 2500}, {"young_modulus", 1e10}, {"poisson_ratio", 0.25}}}}},
                          {"joints", {{"plane", {{"friction_angle", 35}, {"cohesion", 15e3}}}}},
                          {"default_joint", "plane"},
                          {"blocks", blocks},
                          {"supports", {anchor}},
                          {"monitors", {{{"id", "on_joint"}, {"point", {-8, 9}}}}},
                          {"analysis", {{"duration", 1.0}, {"time_step", 0.001}}}}
        .dump();
  };
  for (const bool lowerFirst : {true, false}) {
    SCOPED_TRACE(lowerFirst ? "lower block first" : "upper block first");
    try {
      io::parseCase(caseWith(lowerFirst, nullptr), "wedge.json");
      ADD_FAILURE() << "a head on the joint between two free blocks was given a block";
    } catch (const InputError& e) {
      EXPECT_EQ(e.jsonPath(), "supports[0].head");
      EXPECT_NE(e.message().find("head_block"), std::string::npos) << e.message();
    }
    // A point load there is refused alike; named, it is taken.
    nlohmann::json loaded = nlohmann::json::parse(caseWith(lowerFirst, "lower"));
    loaded["point_loads"] = {{{"point", {-8, 9}}, {"force", {1e4, 0}}}};
    try {
      io::parseCase(loaded.dump(), "wedge.json");
      ADD_FAILURE() << "a load on the joint between two free blocks was given a block";
    } catch (const InputError& e) {
      EXPECT_EQ(e.jsonPath(), "point_loads[0].point");
    }
    loaded["point_loads"][0]["block"] = "upper";
    EXPECT_NO_THROW(io::parseCase(loaded.dump(), "wedge.json"));
    const model::Scene s = io::parseCase(caseWith(lowerFirst, "lower"), "wedge.json");
    EXPECT_EQ(s.blocks[s.monitors.at(0).point.block].id, "upper");
    const calibration::FactorOfSafetyResult r = calibration::factorOfSafety(s, {}, 1e-3);
    ASSERT_TRUE(r.found) << r.message;
    const auto area = [](const nlohmann::json& poly) {
      double a = 0;
      for (size_t k = 0; k < poly.size(); ++k) {
        const auto& p = poly[k];
        const auto& q = poly[(k + 1) % poly.size()];
        a += p[0].get<double>() * q[1].get<double>() - q[0].get<double>() * p[1].get<double>();
      }
      return 0.5 * std::abs(a);
    };
    const double psi = std::atan2(10.1527, 16.2476), w = 2500 * 9.81 * (area(lower) + area(upper));
    const double length = std::hypot(16.2476, 10.1527);
    const Vec2 d(std::cos(psi), -std::sin(psi)), n(std::sin(psi), std::cos(psi)), u = (end - head).normalized();
    const double expected = (15e3 * length + (w * std::cos(psi) - tension * u.dot(n)) * std::tan(degToRad(35))) /
                            (w * std::sin(psi) + tension * u.dot(d));
    EXPECT_NEAR(r.factor, expected, 0.01 * expected);
  }
}

// A load sized for a target F the slope misses without it, and which only burdens it: a crest
// surcharge Q gives F = (cA + (W + Q) cos ψ tan φ)/((W + Q) sin ψ), falling from 1.114 towards
// tan φ / tan ψ = 0.82 as Q grows, never 1.5. The search says so of the load, not of a support
// that 1e12 N/m could not make hold.
TEST(Supports, ALoadThatOnlyBurdensASlopeMissingItsTargetIsSaidToBeOne) {
  model::Scene s = planarCase("planar_failure.json");
  addCrestSurcharge(s, 10e3);
  ASSERT_LT(planarFactor(0, 0), 1.5);
  const calibration::CriticalResult r = calibration::criticalSupport(s, "surcharge", 1.5, 0);
  EXPECT_FALSE(r.found);
  EXPECT_NE(r.message.find("fails without the load"), std::string::npos) << r.message;
  EXPECT_GE(r.runs, 20) << r.message;
}

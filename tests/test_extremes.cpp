// Numerical stability at the extremes (issue #6, fast variants): the A4 sliding block (α = 30°)
// taken to extreme sizes, a 1e-3 sliver, stiffnesses, densities, strengths and time steps. Every run must
// complete with finite numbers, gain no energy (its speed never exceeds the frictional closed
// form a t by more than 1 %, and its mechanical energy never rises), and match the closed form
// where one applies.
#include <gtest/gtest.h>

#include <cmath>

#include <cctype>
#include <filesystem>
#include <fstream>
#include <ostream>

#include "ddaslope/io/case_reader.hpp"
#include "ddaslope/io/extremes.hpp"
#include "ddaslope/model/wall_scene.hpp"
#include "ddaslope/solver/simulation.hpp"
#include "test_io.hpp"

using namespace ddaslope;

namespace ddaslope::io {
// GoogleTest names a parameter by this instead of its bytes.
void PrintTo(const ExtremeIncline& x, std::ostream* os) { *os << x.name; }
}  // namespace ddaslope::io

namespace {

class ExtremeCase : public ::testing::TestWithParam<io::ExtremeIncline> {};

TEST_P(ExtremeCase, FiniteBoundedAndClosedForm) {
  const io::ExtremeResult r = io::runExtreme(GetParam());
  ASSERT_TRUE(r.completed) << r.failure;
  ASSERT_TRUE(r.finite);
  // The frictional closed form a t bounds the speed (1 %, and 1e-6 of the block's size).
  EXPECT_LE(r.peakSpeed, 1.01 * r.closedFormPeakSpeed + 1e-6 * GetParam().spec.b) << "energy gained";
  // Sliding: a t²/2 within 1 % plus the shear springs' elastic elongation W sin α / p_s, released
  // when the contact starts to slide (a compliance of the penalty model; it matters only for
  // micrometre slides). Held: less than 1e-3 b.
  if (GetParam().slides)
    EXPECT_NEAR(r.slide, r.closedFormSlide, r.slideTolerance);
  else
    EXPECT_LT(r.slide, r.slideTolerance);
  // Energy (conservation law): friction and the γ = 1 integrator only dissipate, so the mechanical
  // energy (kinetic + potential + elastic) never rises above its start by more than round-off,
  // 1e-9 of the potential energy the block holds above the origin. Before block masses were held
  // at ρ·S₀ the soft block gained 11 % of its energy scale: its area, and so Shi's mass ρ·S, swelled.
  EXPECT_LE(r.energyGain, 1e-9 * r.heldPotential) << "energy gained";
  // A near-rigid sliding block loses at least the work of friction, tan φ · W cos α · d
  // (1 % and the shear springs' released energy aside); more only by the integrator's damping of
  // its elastic vibration (the kilometre block at Δt = 10 ms: +4.5 %) and by the strain damping of
  // the elastic energy a micrometre slide releases (Δt = 1e-6 s: +26 %). A soft block's base slips
  // less than its centre travels, so d does not measure its slip.
  if (GetParam().slides && GetParam().spec.young >= 1e9) {
    EXPECT_GE(r.energyLost, 0.99 * r.frictionWork - r.elasticRelease - 1e-9 * r.heldPotential);
  }
}

INSTANTIATE_TEST_SUITE_P(Extremes, ExtremeCase, ::testing::ValuesIn(io::extremeInclines()), [](const auto& info) {
  std::string name = info.param.name;
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return name;
});

}  // namespace

// 2000 blocks (issue #6 extremes): a 2000-brick wall with rigid blocks (the deformable one is
// slower to settle; the benchmark measures it). Closed form: a wall standing on a fixed base
// does not move, so its equilibrium ends at rest, after which no brick moves more than a
// micrometre in 20 steps, every number stays finite, and the mechanical energy does not rise
// beyond round-off (1e-12 of the total). A large system: it settles dynamically from its held
// state (the test above).
namespace {

/// What a wall at rest must keep over `steps` steps: the largest centroid travel, the largest
/// rise of the mechanical energy, the Δt cuts, and whether every block stayed finite.
struct StandingStill {
  double moved = 0, energyRise = 0, energyScale = 0;
  int cuts = 0;
  bool finite = true;
};

StandingStill standStill(solver::Simulation& sim, int steps) {
  StandingStill r;
  std::vector<Vec2> start;
  for (const auto& b : sim.scene().blocks) start.push_back(b.moments.centroid);
  const double e0 = sim.energy().mechanical();
  r.energyScale = std::abs(e0);
  for (int k = 0; k < steps; ++k) {
    r.cuts += sim.advance().cuts;
    r.energyRise = std::max(r.energyRise, sim.energy().mechanical() - e0);
  }
  for (size_t b = 0; b < start.size(); ++b) {
    const model::Block& blk = sim.scene().blocks[b];
    r.finite = r.finite && blk.velocity.allFinite() && blk.moments.centroid.allFinite();
    r.moved = std::max(r.moved, (blk.moments.centroid - start[b]).norm());
  }
  return r;
}

}  // namespace

TEST(Extremes, TwoThousandBlockWallStandsStill) {
  model::Scene scene = model::makeBrickWall(2000);
  scene.settings.rigidBlocks = true;
  solver::Simulation sim(scene);
  sim.bringToEquilibrium();
  ASSERT_TRUE(sim.statistics().equilibriumConverged);
  ASSERT_TRUE(sim.statistics().startedAtRest);
  const StandingStill r = standStill(sim, 20);
  ASSERT_TRUE(r.finite);
  EXPECT_LT(r.moved, 1e-6);
  EXPECT_LE(r.energyRise, 1e-12 * r.energyScale);
}

// A large system settles dynamically straight from the state with every contact held, then
// steps once statically to the equilibrium of its settled contact states (issue #16: the static
// relaxation of a 20 000-brick wall crept for an hour instead). Closed form: a wall on a fixed
// base is at rest, so the equilibrium must end confirmed at rest (a step from rest implying less
// than 1e-6 g). A residual acceleration a below that moves a brick at most a t²/2 = 2e-9 m in the
// 20 steps (t = 20 ms) that follow: no brick may move 1e-8 m. No step may cut Δt, and the
// mechanical energy may not rise beyond round-off (1e-12 of the total). Measured: 1e-14 m, and
// 8e-12 m without the static step. The 495-brick side-by-side wall (2970 unknowns) is a large
// system, and deformable.
TEST(Extremes, LargeDeformableWallSettlesFromItsHeldStateAndStandsStill) {
  solver::Simulation sim(model::makeAnchorWall(22, false));
  ASSERT_FALSE(sim.scene().settings.rigidBlocks);
  sim.bringToEquilibrium();
  ASSERT_TRUE(sim.statistics().startedAtRest);
  EXPECT_GT(sim.statistics().settlingSteps, 0);
  const StandingStill r = standStill(sim, 20);
  ASSERT_TRUE(r.finite);
  EXPECT_LT(r.moved, 1e-8);
  EXPECT_EQ(r.cuts, 0);
  EXPECT_LE(r.energyRise, 1e-12 * r.energyScale);
}

// A run does not depend on its thread count (issue #16): the contact search, linearisation and
// judgement split their items into chunks in index order (core/parallel.hpp), so one and two
// threads must give the same state bit for bit. The side-by-side wall started with gravity
// switched on at once (203 bricks, ~1100 contacts: above the parallel threshold of 512 items)
// changes many contact states per step.
TEST(Extremes, ThreadsLeaveTheRunUnchanged) {
  std::vector<std::vector<double>> finals;
  for (int threads : {1, 2}) {
    solver::Simulation sim(model::makeAnchorWall(14, true));
    sim.setThreads(threads);
    sim.bringToEquilibrium();
    for (int k = 0; k < 8; ++k) sim.advance();
    std::vector<double> state;
    for (const auto& b : sim.scene().blocks) {
      for (const Vec2& v : b.vertices) state.insert(state.end(), {v.x(), v.y()});
      for (int i = 0; i < 6; ++i) state.push_back(b.velocity[i]);
    }
    for (const auto& c : sim.contacts().contacts()) state.insert(state.end(), {double(c.state), c.normalForce});
    finals.push_back(state);
  }
  ASSERT_EQ(finals[0].size(), finals[1].size());
  size_t differing = 0;
  for (size_t i = 0; i < finals[0].size(); ++i) differing += finals[0][i] != finals[1][i];
  EXPECT_EQ(differing, 0u) << "values that differ between one and two threads";
}

// A large system's factor follows contact state changes by update/downdate instead of being
// redone (solver/factor_springs.hpp), is ordered by nested dissection, and solves loosely (1e-8)
// while contact states still change. The factor only preconditions conjugate gradients, and the
// solution that ends each step's open-close iteration is solved to 1e-12 of the load either way,
// so the run must be the same: a 600-brick deformable wall (3600 unknowns, above the 1000 from
// which the factor follows) brought to equilibrium, where stage 2 slips and sticks many contacts,
// ends in the same state to 1e-9 m with fewer factorisations. Stage 2's static steps: without
// settle_dynamically, as a large system now settles dynamically from stage 1 instead, whose
// kinetic damping ends at a rest defined only to 1e-6 g (the two runs then end 4e-9 m apart).
TEST(Extremes, FollowingTheFactorLeavesTheRunUnchanged) {
  std::vector<std::vector<Vec2>> finals;
  std::vector<long> factorisations;
  for (bool follow : {true, false}) {
    model::Scene scene = model::makeBrickWall(600);
    scene.settings.settleDynamically = false;
    solver::Simulation sim(scene);
    sim.setFactorFollowing(follow);
    sim.bringToEquilibrium();
    for (int k = 0; k < 5; ++k) sim.advance();
    std::vector<Vec2> c;
    for (const auto& b : sim.scene().blocks) c.push_back(b.moments.centroid);
    finals.push_back(c);
    factorisations.push_back(sim.statistics().factorisations);
  }
  double worst = 0;
  for (size_t b = 0; b < finals[0].size(); ++b) worst = std::max(worst, (finals[0][b] - finals[1][b]).norm());
  EXPECT_LT(worst, 1e-9);
  EXPECT_LT(factorisations[0], factorisations[1]);
}

// Stage 3 gives up on a settling that has stopped approaching rest (docs/performance.md, "Stalled
// equilibria handed on"), and only then. The chair slide's F is 1.1265 (its search; the slices of
// scripts/chair_slide.py give 1.13 with the joints' friction): reduced by 1.12, 0.6 % within it,
// it must still settle to a confirmed rest (measured: 800-1000 settling steps after stalls of up
// to 25 peaks); reduced by 1.13, beyond it, it cycled for the whole budget of 4000 steps
// (20 × equilibrium_max_steps) and must now give up within three quarters of it (measured: 2364
// steps, the 10th stalled peak after the least implied acceleration last halved at step 178).
TEST(Extremes, SettlingGivesUpOnAStalledCycleButNotOnASlowRest) {
  const model::Scene chair = io::readCase(std::string(DDASLOPE_SOURCE_DIR) + "/cases/chair_slide.json");
  const auto reduced = [&](double f) {
    model::Scene s = chair;
    for (model::JointProperties& j : s.joints) j = j.reducedBy(f);
    return s;
  };
  solver::Simulation within(reduced(1.12));
  within.bringToEquilibrium();
  EXPECT_TRUE(within.statistics().startedAtRest);
  solver::Simulation beyond(reduced(1.13));
  beyond.bringToEquilibrium();
  EXPECT_FALSE(beyond.statistics().startedAtRest);
  EXPECT_GT(beyond.statistics().settlingSteps, 0);
  EXPECT_LT(beyond.statistics().settlingSteps, 15 * chair.settings.equilibriumMaxSteps);
}

// Beyond t* = √(2 d/|g|), the time in which a block falling freely from rest moves the step limit
// d, every step of a moving block is cut and a search's F stops following the strengths (Vajont's
// F 1.12 at Δt ≤ 0.36 t*, 1.50 at 1.07 t*, 3.92 at 36 t*: docs/accuracy.md, "Δt beyond the step
// limit"). Vajont's step limit is 0.384 m, so t* = √(2 · 0.384 / 9.81) = 0.280 s.
TEST(TimeStepWarning, SaidBeyondTheStepLimitsFallTimeAndNotBelowIt) {
  const std::string vajont = std::string(DDASLOPE_SOURCE_DIR) + "/cases/vajont.json";
  std::string err;
  const std::string beyond = clitest::captureCli("check " + vajont + " --set analysis.time_step=0.3", &err);
  EXPECT_NE(beyond.find("warning: analysis.time_step 0.3 s is longer than the 0.28 s"), std::string::npos) << beyond;
  EXPECT_NE(beyond.find("step limit (0.384 m)"), std::string::npos) << beyond;
  const std::string below = clitest::captureCli("check " + vajont + " --set analysis.time_step=0.27", &err);
  EXPECT_EQ(below.find("moves the step limit"), std::string::npos) << below;
  // run says it on stderr before it starts.
  const std::filesystem::path out = std::filesystem::temp_directory_path() / "ddaslope_dt_warning_run";
  std::filesystem::remove_all(out);
  EXPECT_EQ(clitest::runCli("run " + vajont + " --set analysis.time_step=0.3 --duration 0.3 --quiet --out " + out.string(), &err), 0) << err;
  EXPECT_NE(err.find("is longer than the 0.28 s"), std::string::npos) << err;
  std::filesystem::remove_all(out);
}

// The presets scale Δt with √(w0/g) and stay below t* for every free block thicker than about
// 1e-5 of w0: none of the shipped cases is warned, at its own Δt or at the coarsest preset.
TEST(TimeStepWarning, NotSaidOnTheShippedCasesAtTheirOwnOrTheFastPreset) {
  const std::filesystem::path cases = std::filesystem::path(DDASLOPE_SOURCE_DIR) / "cases";
  int checked = 0;
  for (const auto& f : std::filesystem::directory_iterator(cases)) {
    if (f.path().extension() != ".json") continue;
    for (const std::string preset : {"", " --preset fast"}) {
      std::string err;
      const std::string out = clitest::captureCli("check " + f.path().string() + preset, &err);
      EXPECT_EQ(out.find("moves the step limit"), std::string::npos) << f.path() << preset << "\n" << out;
      ++checked;
    }
  }
  EXPECT_GE(checked, 40);
}

// fos keeps the warning in fos.json, where the report finds it. Planar failure: the block's step
// limit is 0.125 m, t* = 0.16 s.
TEST(TimeStepWarning, KeptInTheSearchResult) {
  const std::string planar = std::string(DDASLOPE_SOURCE_DIR) + "/cases/planar_failure.json";
  const std::filesystem::path out = std::filesystem::temp_directory_path() / "ddaslope_dt_warning_fos";
  std::filesystem::remove_all(out);
  std::string err;
  clitest::runCli("fos " + planar + " --set analysis.time_step=0.5 --out " + out.string(), &err);
  EXPECT_NE(err.find("is longer than the"), std::string::npos) << err;
  std::ifstream in(out / "fos.json");
  ASSERT_TRUE(in) << err;
  const std::string text((std::istreambuf_iterator<char>(in)), {});
  EXPECT_NE(text.find("is longer than the"), std::string::npos) << text;
  std::filesystem::remove_all(out);
}

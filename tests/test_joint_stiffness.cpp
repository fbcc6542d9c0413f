// Per-joint normal and shear stiffness (kn, ks in Pa/m, issue #41) against the closure the
// springs imply: a block of weight W resting on a joint of length L closes it by W/(kn L), and a
// shear force T below the friction slips it by T/(ks L) (Goodman's joint element; UDEC's and RS2's
// joint stiffness per unit length).
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "ddaslope/io/case_reader.hpp"
#include "ddaslope/solver/simulation.hpp"
#include "test_io.hpp"

using namespace ddaslope;

namespace {

/// A w × 1 m block (ρ 2600) on a fixed base, the joint between them with kn and ks.
nlohmann::json restingBlock(double width, double kn, double ks, const std::string& blocks) {
  return {{"gravity", {0, -9.81}},
          {"materials", {{"rock", {{"density", 2600}, {"young_modulus", 1e10}, {"poisson_ratio", 0.25}}}}},
          {"joints", {{"j", {{"friction_angle", 30}, {"normal_stiffness", kn}, {"shear_stiffness", ks}}}}},
          {"blocks",
           {{{"id", "base"}, {"material", "rock"}, {"fixed", true}, {"vertices", {{-2, -1}, {width + 2, -1}, {width + 2, 0}, {-2, 0}}}},
            {{"id", "b"}, {"material", "rock"}, {"vertices", {{0, 0}, {width, 0}, {width, 1}, {0, 1}}}}}},
          {"monitors", {{{"id", "foot"}, {"block", "b"}, {"point", {width / 2, 0.001}}}}},
          {"analysis", {{"duration", 0.5}, {"time_step", 0.001}, {"blocks", blocks}}}};
}

/// The foot's displacement (x, y) at the end of a run.
Vec2 footDisplacement(const nlohmann::json& doc) {
  solver::Simulation sim(io::parseCase(doc.dump(), "stiffness.json"));
  solver::runAnalysis(sim, [](const solver::Simulation&, const solver::StepRecord&) {});
  const auto& m = sim.scene().monitors[0].point;
  return m.current - m.initial;
}

}  // namespace

// Closure W/(kn L) and slip T/(ks L) within 0.1 % on rigid blocks, for two joint lengths and two
// stiffnesses (a deformable block adds its own compression: within 2 %).
TEST(JointStiffness, ClosureAndSlipAreTheSpringsOwn) {
  const double gamma = 2600 * 9.81, t = 1e4;
  for (const double width : {2.0, 4.0})
    for (const double kn : {1e9, 1e10}) {
      const double ks = 0.4 * kn;
      nlohmann::json doc = restingBlock(width, kn, ks, "rigid");
      const double w = gamma * width;
      EXPECT_NEAR(footDisplacement(doc).y(), -w / (kn * width), 1e-3 * w / (kn * width)) << width << " m, kn " << kn;
      doc["point_loads"] = {{{"id", "t"}, {"block", "b"}, {"point", {width / 2, 0.001}}, {"force", {t, 0}}}};
      EXPECT_NEAR(footDisplacement(doc).x(), t / (ks * width), 1e-3 * t / (ks * width)) << width << " m, ks " << ks;
      const nlohmann::json deformable = restingBlock(width, kn, ks, "deformable");
      EXPECT_NEAR(footDisplacement(deformable).y(), -w / (kn * width), 0.02 * w / (kn * width));
    }
}

// Without kn and ks the model's penalty acts (4e11 N/m per contact here, 40 × E): the closure
// of the same block is W/(2 p), far smaller.
TEST(JointStiffness, WithoutThemThePenaltyActs) {
  nlohmann::json doc = restingBlock(2, 1e9, 4e8, "rigid");
  doc["joints"]["j"].erase("normal_stiffness");
  doc["joints"]["j"].erase("shear_stiffness");
  const double w = 2600 * 9.81 * 2;
  EXPECT_NEAR(footDisplacement(doc).y(), -w / (2 * 40 * 1e10), 1e-3 * w / (2 * 40 * 1e10));
}

// Bad stiffnesses are refused with the file and their JSON path.
TEST(JointStiffness, BadValuesAreRefusedWithTheirPath) {
  for (const auto& [key, value] : std::vector<std::pair<std::string, nlohmann::json>>{
           {"normal_stiffness", 0}, {"normal_stiffness", -1e9}, {"shear_stiffness", 1e16}, {"shear_stiffness", "stiff"}}) {
    nlohmann::json doc = restingBlock(2, 1e9, 4e8, "rigid");
    doc["joints"]["j"][key] = value;
    clitest::expectInputError([&] { io::parseCase(doc.dump(), "bad.json"); }, "bad.json", "joints.j." + key, "");
  }
}

// `check` warns of joint springs far stiffer than the penalty, where docs/contact-model.md
// ("Joint stiffness") measured the drift: on the planar wedge's 24.4 m plane kn = 1e12 Pa/m gives
// kn·L/2 = 1.22e13 N/m, 31 times its penalty of 4e11 N/m (F 0.8 % off the closed form); 1e11, 3
// times, gave F within 0.2 %, and is not warned of.
TEST(JointStiffness, CheckWarnsOfSpringsFarStifferThanThePenalty) {
  const std::string wedge = std::string(DDASLOPE_SOURCE_DIR) + "/cases/planar_failure.json";
  std::string err;
  const std::string stiff =
      clitest::captureCli("check " + wedge + " --set joints.sliding_plane.normal_stiffness=1e12", &err);
  EXPECT_NE(stiff.find("warning: joint sliding_plane: kn·L/2 = 1.22077e+13 N/m"), std::string::npos) << stiff;
  EXPECT_NE(stiff.find("is 31 times the penalty 4e+11 N/m"), std::string::npos) << stiff;
  const std::string fine =
      clitest::captureCli("check " + wedge + " --set joints.sliding_plane.normal_stiffness=1e11", &err);
  EXPECT_EQ(fine.find("kn·L/2"), std::string::npos) << fine;
}

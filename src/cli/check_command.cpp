#include "check_command.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <vector>

#include "ddaslope/calibration/contact_comparison.hpp"
#include "ddaslope/calibration/probability.hpp"
#include "ddaslope/core/errors.hpp"
#include "ddaslope/io/case_reader.hpp"
#include "ddaslope/io/probability_reader.hpp"
#include "ddaslope/io/scene_picture.hpp"
#include "ddaslope/model/input_limits.hpp"
#include "ddaslope/solver/simulation.hpp"
#include "scene_notes.hpp"

namespace ddaslope::cli {

namespace {
/// kn·L/2 above this many penalties: `check` warns (docs/contact-model.md, "Joint stiffness").
constexpr double kStiffJointSpring = 10;
}  // namespace

int checkCommand(const std::string& casePath, const Overrides& o) {
  ddaslope::model::Scene scene = loadCase(casePath, o);
  const ddaslope::solver::Simulation sim(scene);
  int closed = 0;
  for (const auto& c : sim.contacts().contacts()) closed += c.closed();
  const auto count = [](size_t n, const char* word) { return std::to_string(n) + " " + word + (n == 1 ? "" : "s"); };
  std::printf("%s: valid. %s, %s, %s, %s; %s found at t = 0 (%d touching); w0 = %g m, penalty = %g N/m\n",
              casePath.c_str(), count(scene.blocks.size(), "block").c_str(), count(scene.materials.size(), "material").c_str(),
              count(scene.joints.size(), "joint").c_str(), count(scene.monitors.size(), "monitor").c_str(),
              count(sim.contacts().contacts().size(), "contact").c_str(), closed, sim.modelHalfSize(), scene.normalPenalty());
  const double g2w0 = scene.settings.maxDisplacementRatio * sim.modelHalfSize();
  std::printf("  step limit %g m per step (g2·w0 = %g m%s), contact search distance %g m\n", sim.stepLimit(), g2w0,
              sim.stepLimit() < g2w0 ? ", held to a tenth of the thinnest block" : "", sim.searchDistance());
  std::printf("  %s\n", settingsLine(scene).c_str());
  if (const std::string drawn = ddaslope::io::sectionDrawingSummary(casePath); !drawn.empty())
    std::printf("  %s\n", drawn.c_str());
  if (!scene.origin.isZero())
    std::printf("  coordinates: far from (0, 0) for the scene's size; computed relative to (%.17g, %.17g), written back "
                "in the case's coordinates\n",
                scene.origin.x(), scene.origin.y());
  if (const std::string w = timeStepWarning(scene); !w.empty()) std::printf("  warning: %s\n", w.c_str());
  if (const std::string w = unitsWarning(scene); !w.empty()) std::printf("  warning: %s\n", w.c_str());
  if (const std::string w = closedGapWarning(scene, sim.statistics()); !w.empty()) std::printf("  note: %s\n", w.c_str());
  // A free block that touches nothing falls: a misplaced block, not a mechanism.
  std::vector<char> touches(scene.blocks.size(), 0);
  for (const auto& c : sim.contacts().contacts())
    touches[static_cast<size_t>(c.key().vertexBlock)] = touches[static_cast<size_t>(c.key().edgeBlock)] = 1;
  for (size_t b = 0; b < scene.blocks.size(); ++b) {
    if (scene.blocks[b].fixed) continue;
    if (!touches[b])
      std::printf("  warning: block %s touches no other block at t = 0 (no contact within the search distance): it "
                  "falls freely, and every search reads that as failure\n", scene.blocks[b].id.c_str());
  }
  printOutlineNotes(scene);
  printSeismicNote(scene);
  printKinkNotes(scene);
  printSupportNotes(scene);
  printWaterNotes(scene);
  if (scene.water.ru > 0)
    std::printf("  pore pressure: r_u = %g, u = r_u·γ·h on every block face, γ = %g N/m³, h the depth below the "
                "ground surface (the blocks' upper envelope, %zu points)\n",
                scene.water.ru, scene.water.unitWeight / scene.water.ru, scene.water.line.size());
  for (const auto& j : scene.joints)
    if (j.normalStiffness > 0 || j.shearStiffness > 0) {
      const auto stiffness = [](double k, const char* otherwise) {
        char text[64];
        std::snprintf(text, sizeof text, "%g GPa/m", k / 1e9);
        return k > 0 ? std::string(text) : std::string(otherwise);
      };
      std::printf("  joint %s: kn = %s, ks = %s (a contact's spring is k·L over its share L of an edge-to-edge contact; "
                  "the penalty %g N/m stands in for what is not given, and at corners)\n",
                  j.name.c_str(), stiffness(j.normalStiffness, "the penalty").c_str(),
                  stiffness(j.shearStiffness, "the penalty's share").c_str(), scene.normalPenalty());
    }
  // A joint spring far stiffer than the penalty: the open-close tolerances and the step limit are
  // set from the penalty, and such a spring turns a step's round-off into contact force
  // (docs/contact-model.md, "Joint stiffness": the planar wedge's F drifts 0.8 % at 30 times).
  for (size_t j = 0; j < scene.joints.size(); ++j) {
    const double kn = scene.joints[j].normalStiffness;
    double longest = 0;
    for (const auto& c : sim.contacts().contacts())
      if (c.joint == static_cast<int>(j)) longest = std::max(longest, c.geometry.overlap);
    const double spring = kn * 0.5 * longest;
    if (kn > 0 && spring > kStiffJointSpring * scene.normalPenalty())
      std::printf("  warning: joint %s: kn·L/2 = %g N/m on its longest edge-to-edge contact at t = 0 (L = %g m) is "
                  "%.0f times the penalty %g N/m; beyond about %.0f times the results drift (docs/contact-model.md, "
                  "\"Joint stiffness\"): lower kn or raise analysis.penalty with it\n",
                  scene.joints[j].name.c_str(), spring, longest, spring / scene.normalPenalty(), scene.normalPenalty(),
                  kStiffJointSpring);
  }
  if (scene.water.grid)
    std::printf("  pore pressure: a grid of %zu points, interpolated by a thin-plate spline (exact at the points, an "
                "affine field exactly; suction taken as 0), on every block face\n",
                scene.water.grid->points().size());
  for (const auto& m : scene.materials)
    if (m.youngModulus > ddaslope::model::limits::kStiffestRock)
      std::printf("  note: material %s: E = %g Pa is stiffer than any rock: a rigid stand-in (as in RS2 and UDEC). "
                  "Its blocks barely strain; --blocks rigid (analysis.blocks: rigid) is the exact form, at half "
                  "the unknowns\n",
                  m.name.c_str(), m.youngModulus);
  if (ddaslope::io::hasProbabilitySection(casePath)) {
    const ddaslope::io::ProbabilityJob job = ddaslope::io::readProbabilityJob(casePath);
    std::printf("  probability section: %zu uncertain inputs, %d samples (%s, %s, measure %s): valid; run it with "
                "ddaslope probability\n",
                job.spec.inputs.size(), job.spec.samples, ddaslope::calibration::name(job.spec.method),
                ddaslope::calibration::name(job.spec.sampling), ddaslope::calibration::name(job.spec.measure));
  }
  return kExitOk;
}

}  // namespace ddaslope::cli

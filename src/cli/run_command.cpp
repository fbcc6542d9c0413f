#include "run_command.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <optional>

#include "ddaslope/calibration/strength_search.hpp"
#include "ddaslope/io/run_case.hpp"
#include "ddaslope/solver/simulation.hpp"
#include "ddaslope/model/input_limits.hpp"
#include "scene_notes.hpp"

namespace ddaslope::cli {

void addRunOptions(CLI::App* run, std::string& casePath, Overrides& overrides, RunCommandOptions& opt) {
  run->add_option("case", casePath, "case file (JSON)")->required();
  run->add_option("--out", opt.outDir, "output directory")->capture_default_str();
  addModelOptions(run, overrides);
  run->add_option("--duration", overrides.duration, "override analysis.duration (s)")
      ->check(finiteIn(1e-9, model::limits::kMaxDuration, "a duration in (0, 1e6] s"));
  run->add_flag("--quiet", opt.quiet, "no progress on stderr");
  run->add_flag("--verbose", opt.verbose, "log equilibrium steps and time-step cuts on stderr");
  run->add_option("--snapshots", opt.snapshots, "times (s) of PNG pictures snapshot_NN.png in --out, e.g. 0,0.5,1")
      ->delimiter(',')
      ->check(finiteIn(0, model::limits::kMaxDuration, "times in [0, 1e6] s"));
  CLI::Option* vtk = run->add_flag(
      "--vtk", opt.vtk, "write a VTK series for ParaView in --out/vtk: blocks.pvd, contacts.pvd (water.pvd)");
  run->add_option("--vtk-every", opt.vtkEvery, "simulated seconds between VTK frames (default: a hundredth of the run)")
      ->needs(vtk)
      ->check(finiteIn(1e-9, model::limits::kMaxDuration, "an interval in (0, 1e6] s"));
  CLI::Option* atFos = run->add_option(
      "--at-fos", opt.atFactor,
      "run with the joints' strengths reduced by this factor as `fos` reduces them (c/F, tan φ/F): the mechanism at a "
      "factor of safety")
      ->check(finiteIn(0.01, 100, "a factor in [0.01, 100]"));
  run->add_option("--joints", opt.reducedJoints, "the joints --at-fos reduces (default: all), e.g. a,b")
      ->delimiter(',')
      ->needs(atFos);
  addTrialStartOption(run, opt.trialStart)->needs(atFos);
  // One run's contact search and judgement may share the cores (the result does not change). One
  // by default: with the pair cache the work they share is small, and on large walls two threads
  // did not make a step measurably cheaper (docs/performance.md, "Threads").
  run->add_option("--threads", opt.threads, "threads of the run's contact search and judgement (same result for any)")
      ->capture_default_str()
      ->check(CLI::Range(1, 256));
}

namespace {

/// --at-fos: every named joint (all by default) reduced as a `fos` trial at that factor reduces it
/// (model::JointProperties::reducedBy), and what changed, printed.
std::vector<std::string> reduceStrengths(model::Scene& scene, const std::string& casePath, const RunCommandOptions& c) {
  std::vector<int> joints;
  for (const auto& name : c.reducedJoints) joints.push_back(jointIndex(scene, name, casePath));
  if (joints.empty())
    for (size_t j = 0; j < scene.joints.size(); ++j) joints.push_back(static_cast<int>(j));
  std::printf("strengths reduced by F = %.6g, as `ddaslope fos` reduces them:\n", c.atFactor);
  for (int j : joints) {
    model::JointProperties& joint = scene.joints[static_cast<size_t>(j)];
    const model::JointProperties reduced = joint.reducedBy(c.atFactor);
    if (joint.bartonBandis)
      std::printf("  %s: Barton-Bandis, tan of the mobilised angle / %.6g, tensile strength %.4g -> %.4g Pa\n",
                  joint.name.c_str(), c.atFactor, joint.tensileStrength, reduced.tensileStrength);
    else
      std::printf("  %s: cohesion %.6g -> %.6g Pa, friction angle %.4f -> %.4f deg\n", joint.name.c_str(),
                  joint.cohesion, reduced.cohesion, joint.frictionAngle * 180 / M_PI, reduced.frictionAngle * 180 / M_PI);
    joint = reduced;
  }
  std::vector<std::string> names;
  for (int j : joints) names.push_back(scene.joints[static_cast<size_t>(j)].name);
  return names;
}

}  // namespace

int runCommand(const std::string& casePath, const Overrides& o, const RunCommandOptions& c) {
  model::Scene scene = loadCase(casePath, o);
  warnAboutTrials(casePath, timeStepWarning(scene));
  warnAboutTrials(casePath, movedJointWarning(scene));
  warnAboutTrials(casePath, unitsWarning(scene));
  std::vector<std::string> reduced;
  // --at-fos starts where fos's trials start: from the rest at the case's own strengths, when
  // the case stands there.
  std::optional<solver::HeldEquilibrium> settled;
  if (c.atFactor > 0 && scene.settings.initialEquilibrium && trialStartOf(c.trialStart) == calibration::TrialStart::Settled) {
    const solver::HeldEquilibrium held = solver::Simulation(scene).holdEquilibrium();
    settled = calibration::settledStart(scene, held, {});
  }
  if (c.atFactor > 0) {
    reduced = reduceStrengths(scene, casePath, c);
    // The trial of the search, step for step: its quiet steps grow as a trial's do.
    scene.settings.timeStepGrowth = calibration::trialStepGrowth(scene.settings);
    if (scene.settings.initialEquilibrium)
      std::printf("  %s\n", trialStartNote("the run", settled ? calibration::TrialStart::Settled : calibration::TrialStart::Held,
                                             c.trialStart).c_str());
    // The case's expectations are claims about its own strengths, not about reduced ones.
    if (!scene.expectations.empty())
      std::printf("  the case's expectations are for its own strengths: not checked at F = %.6g\n", c.atFactor);
    scene.expectations.clear();
  }
  const std::string& outDir = c.outDir;
  io::RunOptions opt;
  opt.outputDir = outDir;
  opt.casePath = casePath;
  opt.progress = !c.quiet && !c.verbose && isatty(STDERR_FILENO);
  opt.verbose = c.verbose;
  opt.announce = !c.quiet;
  opt.snapshotTimes = c.snapshots;
  opt.threads = c.threads;
  opt.vtk = c.vtk;
  opt.vtkEvery = c.vtkEvery;
  opt.strengthReduction = c.atFactor;
  opt.reducedJoints = reduced;
  opt.sharedEquilibrium = settled ? &*settled : nullptr;
  const io::RunOutcome r = io::runScene(scene, opt);
  warnAboutTrials(casePath, closedGapWarning(scene, r.statistics));  // the run's own contacts at t = 0
  if (!r.completed) {
    std::cerr << "ddaslope: " << casePath << (r.budgetStop ? ": budget exceeded: " : ": non-convergence: ") << r.failure << "\n"
              << "  partial history: " << outDir << "/history.partial.csv\n";
    if (r.vtkFrames > 0)
      std::cerr << "  VTK series to the last state reached: " << outDir << "/vtk (" << r.vtkFrames << " frames)\n";
    return kExitNonConvergence;
  }
  const auto& st = r.statistics;
  std::printf("%s: %d steps, %d Δt cuts, %ld open-close iterations, %.3f s wall\n", casePath.c_str(), st.steps,
              st.cuts, st.iterations, r.wallTime);
  for (const auto& e : r.expectations) std::printf("  %s\n", e.describe().c_str());
  // The energy check a user should see: a correct run only dissipates (docs/case-format.md).
  const auto& first = r.trace.energy.front();
  const auto& last = r.trace.energy.back();
  double stepTime = 0;
  const double gain = r.trace.largestEnergyGain(), stepGain = r.trace.largestStepGain(&stepTime);
  const double scale = r.trace.energyInPlay(), floor = 1e-12 * std::abs(first.mechanical());
  std::printf("  energy: %.4g J/m released (potential and load work), %.4g J/m dissipated; largest rise %.3g J/m "
              "since t = 0, %.3g J/m in one step\n",
              first.potential - last.potential + last.loadWork, first.mechanical() - last.mechanical(), gain, stepGain);
  // Since the start: 1e-4 of the energy in play. In one step: 1e-3 (the bar of the energy test; the friction
  // sources docs/accuracy.md lists stay below 2e-4 in the Vajont run-out's impacts at Δt 1-10 ms).
  // A smaller Δt is not the cure.
  if (gain > 1e-4 * scale + floor || stepGain > 1e-3 * scale + floor)
    std::printf("  WARNING: the mechanical energy rose by %.3g of the energy in play (%.3g of it in one step, at t = "
                "%.4g s): a spurious gain. Look at energy.png and the energy_gain column of history.csv, see "
                "docs/accuracy.md (\"The energy budget\") for its known sources, and compare a run at half and at "
                "twice the time step to see whether your result depends on it\n",
                std::max(gain, stepGain) / std::max(scale, 1e-300), stepGain / std::max(scale, 1e-300), stepTime);
  std::printf("  wrote %s/history.csv, summary.json, history.png%s%s and energy.png\n", outDir.c_str(),
              scene.supports.empty() ? "" : ", supports.png", scene.seismic.ground.active() ? ", ground_motion.png" : "");
  if (r.snapshotsWritten > 0) std::printf("  wrote %d snapshots: snapshot_00.png ...\n", r.snapshotsWritten);
  if (r.snapshotsWritten < static_cast<int>(c.snapshots.size()))
    std::fprintf(stderr, "ddaslope: warning: %s: %zu of the --snapshots times lie past the run's end (t = %.4g s): not "
                         "drawn\n",
                 casePath.c_str(), c.snapshots.size() - r.snapshotsWritten,
                 r.trace.steps.empty() ? 0.0 : r.trace.steps.back().time);
  if (c.vtk)
    std::printf("  wrote %s/vtk: blocks.pvd, contacts.pvd%s (%d frames; open them in ParaView)\n", outDir.c_str(),
                scene.water.active() ? ", water.pvd" : "", r.vtkFrames);
  return kExitOk;
}

}  // namespace ddaslope::cli

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <algorithm>
#include <fstream>
#include <iostream>

#include <nlohmann/json.hpp>

#include "ddaslope/core/errors.hpp"
#include "ddaslope/io/line_plot.hpp"
#include "ddaslope/io/progress.hpp"
#include "ddaslope/io/run_case.hpp"
#include "ddaslope/io/scene_picture.hpp"
#include "ddaslope/io/scene_vtk.hpp"

namespace ddaslope::io {
namespace {

namespace fs = std::filesystem;

std::string fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.12g", v);
  return buf;
}

MonitorSample sampleOf(const solver::Simulation& sim, int m) {
  const model::Monitor& mon = sim.scene().monitors[m];
  const Vec2 u = mon.point.current - mon.point.initial;
  const Vec2 v = sim.monitorVelocity(m);
  return {u.x(), u.y(), v.x(), v.y()};
}

/// Every joint's strength as the run used it, the automatic weakening distance resolved.
nlohmann::ordered_json jointsEcho(const model::Scene& scene) {
  nlohmann::ordered_json out = nlohmann::ordered_json::object();
  const double w0 = scene.modelHalfSize();
  for (const model::JointProperties& jp : scene.joints) {
    if (jp.bartonBandis) {
      // φr, JRC and JCS as used (scale-corrected); JRC wears only over a weakening distance given.
      out[jp.name] = {{"law", "barton_bandis"},
                      {"residual_friction_angle", radToDeg(jp.frictionAngle)},
                      {"jrc", jp.bartonBandis->jrc},
                      {"jcs", jp.bartonBandis->jcs},
                      {"tensile_strength", jp.tensileStrength},
                      {"jrc_wears_over", jp.bartonBandis->wears ? nlohmann::ordered_json(*jp.weakeningDistance)
                                                                 : nlohmann::ordered_json(nullptr)}};
      continue;
    }
    out[jp.name] = {{"law", "mohr_coulomb"},
                    {"friction_angle", radToDeg(jp.frictionAngle)},
                    {"cohesion", jp.cohesion},
                    {"tensile_strength", jp.tensileStrength},
                    {"residual_friction_angle", radToDeg(jp.residualFriction())},
                    {"residual_cohesion", jp.residualCohesionUsed()},
                    {"weakening_distance", jp.weakeningDistanceIn(w0)},
                    {"weakening_distance_origin", jp.weakeningDistance ? "case" : "automatic (5e-4 w0)"},
                    {"weakening_law", jp.weakeningLaw == model::WeakeningLaw::Linear ? "linear" : "exponential"},
                    {"bond", jp.bond == model::BondPolicy::Initial ? "initial"
                                                                    : (jp.bond == model::BondPolicy::None ? "none" : "always")}};
  }
  // Joint stiffness: the joint's own, or null where the model's penalty acts.
  for (const model::JointProperties& jp : scene.joints) {
    const auto given = [](double k) { return k > 0 ? nlohmann::ordered_json(k) : nlohmann::ordered_json(nullptr); };
    out[jp.name]["normal_stiffness"] = given(jp.normalStiffness);
    out[jp.name]["shear_stiffness"] = given(jp.shearStiffness);
  }
  return out;
}

/// history.csv is written under a temporary name and renamed only when the run completed.
class HistoryWriter {
 public:
  /// `ground`: the input ground motion, written beside the monitors when it is active.
  HistoryWriter(const fs::path& dir, const std::vector<std::string>& monitors, const model::GroundMotion& ground,
                const std::vector<model::Support>& supports)
      : dir_(dir), ground_(ground) {
    fs::create_directories(dir);
    fs::remove(dir / "history.csv");
    fs::remove(dir / "history.partial.csv");
    fs::remove(dir / "summary.json");
    fs::remove(dir / "history.png");
    fs::remove(dir / "supports.png");
    fs::remove(dir / "energy.png");
    fs::remove(dir / "ground_motion.png");
    out_.open(dir / "history.partial.csv");
    if (!out_) throw InputError((dir / "history.csv").string(), "", "cannot write the output file");
    out_ << "time,dt,iterations";
    if (ground_.active()) out_ << ",ground_ax,ground_ay";
    for (const auto& id : monitors) out_ << ',' << id << "_ux," << id << "_uy," << id << "_vx," << id << "_vy";
    // Each support's axial force (N/m, tension positive) and elongation (m).
    for (const auto& b : supports) out_ << ',' << b.id << "_force," << b.id << "_elongation";
    out_ << ",kinetic_energy,potential_energy,elastic_energy,load_work";
    if (ground_.active()) out_ << ",ground_motion_work";  // the record's share of load_work
    out_ << ",energy_gain\n";
  }
  void row(const solver::StepRecord& r, const std::vector<MonitorSample>& s, const std::vector<model::Support>& supports,
           const solver::EnergyBudget& e, double initialMechanical) {
    out_ << fmt(r.time) << ',' << fmt(r.dt) << ',' << r.iterations;
    if (ground_.active()) {
      const Vec2 a = ground_.at(r.time);
      out_ << ',' << fmt(a.x()) << ',' << fmt(a.y());
    }
    for (const auto& m : s) out_ << ',' << fmt(m.ux) << ',' << fmt(m.uy) << ',' << fmt(m.vx) << ',' << fmt(m.vy);
    for (const auto& b : supports) out_ << ',' << fmt(b.force) << ',' << fmt(b.elongation());
    out_ << ',' << fmt(e.kinetic) << ',' << fmt(e.potential) << ',' << fmt(e.elastic) << ',' << fmt(e.loadWork);
    if (ground_.active()) out_ << ',' << fmt(e.groundMotionWork);
    out_ << ',' << fmt(e.mechanical() - initialMechanical) << '\n';
  }
  void finish(bool completed) {
    out_.close();
    if (completed) fs::rename(dir_ / "history.partial.csv", dir_ / "history.csv");
  }

 private:
  fs::path dir_;
  const model::GroundMotion& ground_;
  std::ofstream out_;
};

void writeSummary(const fs::path& dir, const model::Scene& scene, const RunOptions& opt, const RunOutcome& o) {
  using nlohmann::ordered_json;
  ordered_json j;
  j["case"] = opt.casePath;
  j["description"] = scene.description;
  j["status"] = o.completed ? "completed" : (o.budgetStop ? "budget_exceeded" : "non_convergence");
  if (!o.completed) j["failure"] = o.failure;
  if (opt.strengthReduction > 0)
    j["strength_reduction"] = {{"factor", opt.strengthReduction},
                               {"joints", opt.reducedJoints},
                               {"start", opt.sharedEquilibrium ? "settled" : "held"}};
  const solver::RunStatistics& st = o.statistics;
  j["time"] = o.trace.steps.empty() ? 0.0 : o.trace.steps.back().time;
  j["steps"] = st.steps;
  j["time_step_cuts"] = st.cuts;
  j["open_close_iterations"] = st.iterations;
  j["open_close_cycles"] = st.cycles;
  j["steps_with_frozen_contacts"] = st.frozenSteps;
  j["factorisations"] = st.factorisations;
  j["factor_updates"] = st.factorUpdates;
  j["factor_columns"] = st.factorColumns;
  j["state_changes"] = {{"locked_sliding", st.stickSlipChanges}, {"open_closed", st.openCloseChanges}};
  j["linear_solves"] = st.linearSolves;
  j["cg_iterations"] = st.cgIterations;
  j["wall_time_s"] = o.wallTime;
  j["equilibrium"] = {{"steps", st.equilibriumSteps},
                      {"residual", st.equilibriumResidual},
                      {"converged", st.equilibriumConverged},
                      {"relaxed", st.relaxationConverged},
                      {"settling_steps", st.settlingSteps},
                      {"started_at_rest", st.startedAtRest},
                      {"settling", st.settling}};
  if (scene.seismic.active()) {
    ordered_json q = {{"k_h", scene.seismic.kh}, {"k_v", scene.seismic.kv}};
    const model::GroundMotion& g = scene.seismic.ground;
    if (g.active()) {
      const auto peak = [](const std::vector<double>& a) {
        double m = 0;
        for (double v : a) m = std::max(m, std::abs(v));
        return m;
      };
      q["record"] = {{"samples", g.times.size()},
                     {"from_s", g.times.front()},
                     {"to_s", g.times.back()},
                     {"peak_horizontal_m_s2", peak(g.horizontal)},
                     {"peak_vertical_m_s2", peak(g.vertical)}};
    }
    j["seismic"] = q;
  }
  j["max_contacts"] = st.maxContacts;
  j["max_penetration_m"] = st.maxPenetration;
  j["step_limit_m"] = o.stepLimit;
  j["search_distance_m"] = o.searchDistance;
  if (!o.trace.energy.empty()) {
    j["energy_J_per_m"] = {{"mechanical_at_start", o.trace.energy.front().mechanical()},
                           {"mechanical_at_end", o.trace.energy.back().mechanical()},
                           {"largest_gain", o.trace.largestEnergyGain()},
                           {"largest_step_gain", o.trace.largestStepGain()},
                           {"in_play", o.trace.energyInPlay()},
                           {"scale", o.trace.energyScale()}};
    if (scene.seismic.ground.active()) {
      j["energy_J_per_m"]["load_work"] = o.trace.energy.back().loadWork;
      j["energy_J_per_m"]["ground_motion_work"] = o.trace.energy.back().groundMotionWork;
    }
  }
  j["symbolic_analyses"] = st.symbolicAnalyses;
  j["phase_times_s"] = {{"broad_phase", st.times.broadPhase}, {"contacts", st.times.contacts},
                        {"assembly", st.times.assembly},      {"factorisation", st.times.factorisation},
                        {"solve", st.times.solve},            {"state_checks", st.times.stateChecks},
                        {"factor_update", st.times.factorUpdate}, {"update", st.times.update}};
  ordered_json mons = ordered_json::object();
  if (!o.trace.samples.empty())
    for (size_t m = 0; m < o.trace.monitorIds.size(); ++m) {
      const MonitorSample& s = o.trace.samples.back()[m];
      mons[o.trace.monitorIds[m]] = {{"ux", s.ux}, {"uy", s.uy}, {"vx", s.vx}, {"vy", s.vy}};
    }
  j["monitors"] = mons;
  if (!o.finalSupports.empty()) {
    ordered_json sup = ordered_json::object();
    for (const model::Support& b : o.finalSupports)
      sup[b.id] = {{"state", model::supportStateName(b.state)},
                   {"force_n_per_m", b.force},
                   {"capacity_n_per_m", std::isfinite(b.capacity) ? ordered_json(b.capacity) : ordered_json(nullptr)},
                   {"elongation_m", b.elongation()},
                   {"plastic_elongation_m", b.plasticElongation},
                   {"spacing_m", b.spacing},
                   {"force_per_support_n", b.force * b.spacing}};
    j["supports"] = sup;
  }
  ordered_json ex = ordered_json::array();
  for (const auto& r : o.expectations)
    ex.push_back({{"monitor", r.expectation.monitor}, {"quantity", r.expectation.quantity},
                  {"actual", r.reached ? ordered_json(r.actual) : ordered_json(nullptr)},
                  {"passed", r.reached ? ordered_json(r.passed) : ordered_json(nullptr)},
                  {"checked", r.reached}, {"text", r.describe()}});
  j["expected"] = ex;
  j["joints"] = jointsEcho(scene);
  if (scene.water.ru > 0)
    j["water"] = {{"ru", scene.water.ru}, {"ground_unit_weight_kn_per_m3", scene.water.unitWeight / scene.water.ru / 1e3}};
  else if (scene.water.grid)
    j["water"] = {{"pressure_grid_points", scene.water.grid->points().size()}, {"interpolation", "thin-plate spline"}};
  else if (scene.water.active())
    j["water"] = {{"unit_weight_n_per_m3", scene.water.unitWeight}, {"line", [&] {
                    nlohmann::ordered_json l = nlohmann::ordered_json::array();
                    for (const Vec2& p : scene.water.line) l.push_back({p.x() + scene.origin.x(), p.y() + scene.origin.y()});
                    return l;
                  }()}};
  if (const auto& c = scene.tensionCrack)
    j["tension_crack"] = {{"x", c->x}, {"depth", c->depth()}, {"water_depth", c->waterDepth()},
                          {"water_fraction", c->waterFraction}, {"open_by", c->gap}};
  const model::AnalysisSettings& s = scene.settings;
  j["settings"] = {{"duration", s.duration},
                   {"time_step", s.timeStep},
                   {"time_step_origin", s.timeStepOrigin},
                   {"mode", s.mode == model::AnalysisMode::Dynamic ? "dynamic" : "static"},
                   {"plane", s.plane == model::PlaneMode::Strain ? "strain" : "stress"},
                   {"blocks", s.rigidBlocks ? "rigid" : "deformable"},
                   {"contact_treatment", s.contactTreatment == model::ContactTreatment::Edge ? "edge" : "vertex"},
                   {"strain_damping", s.strainDamping},
                   {"penalty", scene.normalPenalty()},
                   {"shear_penalty_ratio", s.shearPenaltyRatio},
                   {"max_displacement_ratio", s.maxDisplacementRatio},
                   {"open_close_max_iterations", s.openCloseMaxIterations},
                   {"friction_tolerance", s.frictionTolerance},
                   {"max_step_cuts", s.maxStepCuts},
                   {"time_step_growth", s.timeStepGrowth > 0 ? s.timeStepGrowth : 1.0},  // automatic: 1 in a run
                   {"step_cut_factor", s.stepCutFactor},
                   {"initial_equilibrium", s.initialEquilibrium},
                   {"settle_dynamically", s.settleDynamically},
                   {"early_rest", s.earlyRest},
                   {"edge_parallel_tolerance", s.edgeParallelToleranceDeg},
                   {"initial_contact_tolerance", scene.touchingGap() / scene.modelHalfSize()},
                   {"contact_state_tolerance", s.contactStateTolerance},
                   {"failure_displacement", s.failureDisplacement},
                   {"resting_speed", s.restingSpeed},
                   {"system_path", s.systemPath == model::SystemPath::Auto    ? "auto"
                                   : s.systemPath == model::SystemPath::Small ? "small"
                                                                              : "large"},
                   {"system_path_in_force", model::largeSystemPath(s, scene.freeUnknowns()) ? "large" : "small"},
                   {"factor_updates", s.factorUpdates ? "on" : "off"}};
  const fs::path tmp = dir / "summary.json.tmp";
  {
    std::ofstream out(tmp);
    out << j.dump(2) << '\n';
  }
  fs::rename(tmp, dir / "summary.json");
}

/// history.png: each monitor's displacement and speed against time; energy.png: where the
/// energy went (kinetic, potential released, stored elastic, and the rest: dissipated);
/// ground_motion.png, under a record: the input ground acceleration on the same time axis.
void writeHistoryPlots(const fs::path& dir, const std::string& casePath, const Trace& trace,
                       const model::GroundMotion& ground) {
  if (trace.steps.empty()) return;
  // At most ~2000 points per line: a long run has tens of thousands of steps.
  const size_t stride = std::max<size_t>(1, trace.steps.size() / 2000);
  // A case without monitors has nothing to draw here: the title says so, and where the motion shows.
  LinePlot motion{trace.monitorIds.empty() ? "No monitors in the case: nothing to plot (the motion: energy.png)"
                                           : "Monitors: " + casePath,
                  "time (s)", "displacement (m) / speed (m/s)", {}};
  for (size_t m = 0; m < trace.monitorIds.size(); ++m) {
    PlotSeries u{trace.monitorIds[m] + " displacement", {}, {}, false}, v{trace.monitorIds[m] + " speed", {}, {}, false};
    for (size_t k = 0; k < trace.steps.size(); k += stride) {
      const MonitorSample& s = trace.samples[k][m];
      u.x.push_back(trace.steps[k].time);
      u.y.push_back(std::hypot(s.ux, s.uy));
      v.x.push_back(trace.steps[k].time);
      v.y.push_back(std::hypot(s.vx, s.vy));
    }
    motion.series.push_back(std::move(u));
    motion.series.push_back(std::move(v));
  }
  writePng(motion, (dir / "history.png").string());
  if (!trace.supportForces.empty()) {
    // Forces apart from the motions: another unit, and the supports' story (loading, yield, slack).
    LinePlot forces{"Supports: " + casePath, "time (s)", "axial force (kN/m, tension positive)", {}};
    for (size_t b = 0; b < trace.supportIds.size(); ++b) {
      PlotSeries f{trace.supportIds[b], {}, {}, false};
      for (size_t k = 0; k < trace.steps.size(); k += stride) {
        f.x.push_back(trace.steps[k].time);
        f.y.push_back(trace.supportForces[k][b] / 1e3);
      }
      forces.series.push_back(std::move(f));
    }
    writePng(forces, (dir / "supports.png").string());
  }
  const solver::EnergyBudget& e0 = trace.energy.front();
  LinePlot energy{"Energy (J/m): " + casePath, "time (s)", "energy since t = 0 (J/m)", {}};
  PlotSeries released{"potential released + load work", {}, {}, false}, kinetic{"kinetic", {}, {}, false},
      elastic{"elastic (change)", {}, {}, false}, dissipated{"dissipated", {}, {}, false};
  for (size_t k = 0; k < trace.steps.size(); k += stride) {
    const solver::EnergyBudget& e = trace.energy[k];
    const double t = trace.steps[k].time;
    for (PlotSeries* p : {&released, &kinetic, &elastic, &dissipated}) p->x.push_back(t);
    released.y.push_back(e0.potential - e.potential + e.loadWork);
    kinetic.y.push_back(e.kinetic);
    elastic.y.push_back(e.elastic - e0.elastic);
    dissipated.y.push_back(e0.mechanical() - e.mechanical());
  }
  energy.series = {released, kinetic, elastic, dissipated};
  writePng(energy, (dir / "energy.png").string());
  if (!ground.active()) return;
  LinePlot input{"Ground acceleration: " + casePath, "time (s)", "ground acceleration (m/s²)", {}};
  PlotSeries ax{"horizontal (+x)", {}, {}, false}, ay{"vertical (up)", {}, {}, false};
  for (size_t k = 0; k < trace.steps.size(); k += stride) {
    const Vec2 a = ground.at(trace.steps[k].time);
    ax.x.push_back(trace.steps[k].time);
    ax.y.push_back(a.x());
    ay.x.push_back(trace.steps[k].time);
    ay.y.push_back(a.y());
  }
  input.series = {ax};
  if (!ground.vertical.empty()) input.series.push_back(ay);
  writePng(input, (dir / "ground_motion.png").string());
}

/// The run's VTK frames: t = 0, the first step at or after each multiple of `every`, the last state.
class VtkFrames {
 public:
  VtkFrames(const std::string& dir, const model::Scene& scene, double every)
      : recorder_(dir, scene), every_(every > 0 ? every : scene.settings.duration / 100) {}
  void observe(const solver::Simulation& s, double time) {
    // 1e-9 of the interval: a time reached by summing steps lands on either side of a multiple.
    if (written_ == 0 || s.finished() || time >= next_ - 1e-9 * every_) write(s);
  }
  /// The state a run stopped in (non-convergence, budget), unless it is already written or
  /// not finite (a diverged run: no NaN in a file).
  void observeStop(const solver::Simulation& s) {
    if ((written_ == 0 || s.time() != last_) && finiteState(s)) write(s);
  }
  int written() const { return written_; }

 private:
  void write(const solver::Simulation& s) {
    char label[32];
    std::snprintf(label, sizeof label, "%06d", written_);
    recorder_.write(s, s.time(), label);
    ++written_;
    last_ = s.time();
    next_ = (std::floor(s.time() / every_ + 1e-9) + 1) * every_;
  }
  VtkRecorder recorder_;
  double every_;
  double next_ = 0, last_ = 0;
  int written_ = 0;
};

}  // namespace

RunOutcome runScene(const model::Scene& scene, const RunOptions& opt) {
  const auto start = std::chrono::steady_clock::now();
  RunOutcome o;
  for (const auto& m : scene.monitors) o.trace.monitorIds.push_back(m.id);
  for (const auto& b : scene.supports) o.trace.supportIds.push_back(b.id);
  const bool recordEnergy = opt.energy || opt.outputDir.has_value();
  std::optional<HistoryWriter> history;
  if (opt.outputDir) history.emplace(*opt.outputDir, o.trace.monitorIds, scene.seismic.ground, scene.supports);
  std::optional<VtkFrames> vtk;
  if (opt.outputDir && opt.vtk) vtk.emplace(*opt.outputDir + "/vtk", scene, opt.vtkEvery);
  else if (opt.outputDir) removeVtkSeries(*opt.outputDir + "/vtk");
  solver::Simulation sim(scene);
  sim.setThreads(opt.threads);
  const PictureFrame frame = frameScene(scene);
  std::vector<double> snapshots = opt.snapshotTimes;
  std::sort(snapshots.begin(), snapshots.end());
  size_t nextSnapshot = 0;
  if (opt.verbose) sim.setLog([](const std::string& line) { std::fprintf(stderr, "  %s\n", line.c_str()); });
  const double duration = scene.settings.duration;
  double lastShown = -1;
  // A long run says what it is about to do before it starts, and off a terminal how far it has
  // got once a minute. Long: a minute's work at ~10 µs per block and step on one core
  // (docs/performance.md), counting the initial equilibrium's first stages; a run that takes a
  // minute all the same (a settling of thousands of blocks) says it at its first progress line.
  const double nominalSteps = duration / scene.settings.timeStep;
  const double blockSteps = (nominalSteps + scene.settings.equilibriumMaxSteps) * static_cast<double>(scene.blocks.size());
  bool sizeSaid = false;
  const auto saySize = [&] {
    if (sizeSaid || !opt.announce) return;
    sizeSaid = true;
    std::fprintf(stderr,
                 "%s  a long run: %zu blocks (%d unknowns), %zu contacts at t = 0; the initial equilibrium (up to %d "
                 "steps, and %d more if it settles dynamically), then %.0f steps of %g s\n",
                 opt.progress ? "\n" : "", scene.blocks.size(), scene.freeUnknowns(), sim.contacts().contacts().size(),
                 scene.settings.equilibriumMaxSteps, solver::kSettlingStepsPerEquilibriumStep * scene.settings.equilibriumMaxSteps,
                 nominalSteps, scene.settings.timeStep);
  };
  if (blockSteps > 6e6) saySize();
  const bool progressLines = opt.announce && !opt.progress;
  auto lastDue = std::chrono::steady_clock::now();
  const auto sinceStart = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  const auto due = [&] {
    const auto now = std::chrono::steady_clock::now();
    if (std::chrono::duration<double>(now - lastDue).count() < (opt.progress ? 0.2 : 60)) return false;
    lastDue = now;
    if (sinceStart() >= 60) saySize();
    return true;
  };
  // Pictures say when the strengths are not the case's own (run --at-fos), and colour motions
  // against the verdict's failure displacement at least: settling of micrometres stays blue.
  std::string title = opt.casePath;
  if (opt.strengthReduction > 0) {
    char at[96];
    std::snprintf(at, sizeof at, " at F = %.6g (joint strengths reduced as fos does)", opt.strengthReduction);
    title += at;
  }
  const double colourFloor =
      scene.settings.failureDisplacement > 0 ? scene.settings.failureDisplacement : 1e-3 * sim.modelHalfSize();
  const auto observe = [&](const solver::Simulation& s, const solver::StepRecord& r) {
    std::vector<MonitorSample> row;
    for (size_t m = 0; m < s.scene().monitors.size(); ++m) row.push_back(sampleOf(s, static_cast<int>(m)));
    if (recordEnergy) o.trace.energy.push_back(s.energy());
    if (history) history->row(r, row, s.scene().supports, o.trace.energy.back(), o.trace.energy.front().mechanical());
    while (opt.outputDir && nextSnapshot < snapshots.size() && r.time >= snapshots[nextSnapshot] - 1e-12) {
      char name[64];
      std::snprintf(name, sizeof name, "/snapshot_%02zu.png", nextSnapshot);
      writeScenePicture(captureState(s), frame, *opt.outputDir + name, title, colourFloor);
      ++nextSnapshot;
    }
    if (vtk) vtk->observe(s, r.time);
    o.trace.steps.push_back(r);
    o.trace.samples.push_back(std::move(row));
    if (!s.scene().supports.empty()) {
      std::vector<double> forces;
      for (const auto& b : s.scene().supports) forces.push_back(b.force);
      o.trace.supportForces.push_back(std::move(forces));
    }
    if (opt.progress && (r.time - lastShown >= duration / 100 || r.time >= duration)) {
      lastShown = r.time;
      std::fprintf(stderr, "\r  t = %-.4g / %.4g s  steps %d  cuts %d, %s%20s", r.time, duration, s.statistics().steps,
                   s.statistics().cuts, formatDuration(sinceStart()).c_str(), "");
      if (r.time >= duration) std::fprintf(stderr, "\n");
    } else if (progressLines && due()) {
      std::fprintf(stderr, "  t = %.4g / %.4g s, steps %d, cuts %d, %s\n", r.time, duration, s.statistics().steps,
                   s.statistics().cuts, formatDuration(sinceStart()).c_str());
    }
  };
  if (opt.progress || progressLines)
    sim.setEquilibriumProgress([&](const char* stage, int step, int budget) {
      if (!due()) return;
      std::fprintf(stderr, "%s  bringing %zu blocks to rest: %s step %d (at most %d), %s%s", opt.progress ? "\r" : "",
                   scene.blocks.size(), stage, step, budget, formatDuration(sinceStart()).c_str(),
                   opt.progress ? "          " : "\n");
    });
  try {
    // The equilibrium of a large scene can take minutes before the first step: say so.
    if (opt.progress)
      std::fprintf(stderr, "  bringing %zu blocks to rest under their static loads ...", scene.blocks.size());
    solver::runAnalysis(sim, observe, opt.sharedEquilibrium);
    o.completed = true;
  } catch (const NonConvergenceError& e) {
    o.failure = e.what();
    o.budgetStop = dynamic_cast<const BudgetExceededError*>(&e) != nullptr;
    if (opt.progress) std::fprintf(stderr, "\n");
    if (vtk) vtk->observeStop(sim);
  }
  if (vtk) o.vtkFrames = vtk->written();
  o.snapshotsWritten = static_cast<int>(nextSnapshot);
  o.statistics = sim.statistics();
  o.finalSupports = sim.scene().supports;
  o.stepLimit = sim.stepLimit();
  o.searchDistance = sim.searchDistance();
  o.wallTime = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (o.completed) o.expectations = evaluateExpectations(o.trace, scene.expectations);
  if (history) {
    history->finish(o.completed);
    if (o.completed) writeHistoryPlots(*opt.outputDir, title, o.trace, scene.seismic.ground);
    writeSummary(*opt.outputDir, scene, opt, o);
  }
  return o;
}

}  // namespace ddaslope::io

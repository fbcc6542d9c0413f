// ddaslope: one command line, subcommands per question.
#include <cerrno>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <cstdio>
#include <iomanip>
#include <iostream>
#include <sstream>

#include <CLI/CLI.hpp>

#include "ddaslope/calibration/backanalysis.hpp"
#include "ddaslope/calibration/contact_comparison.hpp"
#include "ddaslope/io/ground_motion.hpp"
#include "ddaslope/io/job_reader.hpp"
#include "ddaslope/io/probability_reader.hpp"
#include "ddaslope/calibration/probability.hpp"
#include "ddaslope/calibration/strength_search.hpp"
#include "ddaslope/io/json_record.hpp"
#include "ddaslope/calibration/trial_report.hpp"
#include "ddaslope/io/line_plot.hpp"
#include "ddaslope/io/scene_picture.hpp"
#include "ddaslope/model/kinks.hpp"
#include "ddaslope/model/presets.hpp"
#include "ddaslope/model/settings_override.hpp"
#include "ddaslope/core/errors.hpp"
#include "ddaslope/core/byte_record.hpp"
#include "ddaslope/core/task_farm.hpp"
#include "ddaslope/model/input_limits.hpp"
#include "ddaslope/io/case_reader.hpp"
#include "ddaslope/io/run_case.hpp"
#include "ddaslope/solver/simulation.hpp"
#include "cli_common.hpp"
#include "probability_command.hpp"
#include "run_command.hpp"

namespace {

using namespace ddaslope::cli;

int compareContactsCommand(bool deformable, const std::string& csvPath) {
  ddaslope::calibration::ComparisonSettings s;
  s.stiffBlocks = !deformable;
  const auto start = std::chrono::steady_clock::now();
  const auto rows = ddaslope::calibration::compareContactTreatments(s);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("| α (°) | h/b | φ (°) | closed form c_cr (kPa) | edge (kPa) | edge error | vertex (kPa) | vertex error |\n");
  std::printf("|---|---|---|---|---|---|---|---|\n");
  const auto err = [](double v, double ref) -> std::string {
    if (ref == 0) return v == 0 ? "0 (holds at c = 0)" : "c_cr = 0, found " + std::to_string(v / 1e3) + " kPa";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%+.2f %%", 100 * (v - ref) / ref);
    return buf;
  };
  int runs = 0;
  for (const auto& r : rows) {
    runs += r.runs;
    std::printf("| %.0f | %.2f | %.0f | %.2f | %.2f | %s | %.2f | %s |\n", r.alphaDeg, r.heightRatio, r.phiDeg,
                r.closedForm / 1e3, r.edge / 1e3, err(r.edge, r.closedForm).c_str(), r.vertex / 1e3,
                err(r.vertex, r.closedForm).c_str());
  }
  std::printf("\n%zu rows, %d forward runs, %.1f s wall (%s blocks, b = 10 m, ρ = 2000 kg/m³, g = 10 m/s², σt = c)\n",
              rows.size(), runs, wall, deformable ? "deformable (E = 5 GPa, p = 40 E)" : "stiff (E = 500 GPa, p = 200 GN/m)");
  if (!csvPath.empty()) {
    std::FILE* f = std::fopen(csvPath.c_str(), "w");
    if (!f) throw ddaslope::InputError(csvPath, "", "cannot write the file");
    std::fprintf(f, "alpha_deg,h_over_b,phi_deg,closed_form_pa,edge_pa,vertex_pa\n");
    for (const auto& r : rows)
      std::fprintf(f, "%g,%g,%g,%.6g,%.6g,%.6g\n", r.alphaDeg, r.heightRatio, r.phiDeg, r.closedForm, r.edge, r.vertex);
    std::fclose(f);
  }
  for (const auto& r : rows)
    if (!r.bracketed) return kExitNonConvergence;
  return kExitOk;
}

/// A note per concave kink of the sliding surface with a block on it: there the block model leans on
/// a corner that limit-equilibrium slices cannot, so their critical strengths differ.
void printKinkNotes(const ddaslope::model::Scene& scene) {
  const double failure = scene.settings.failureDisplacement > 0 ? scene.settings.failureDisplacement
                                                                 : 1e-3 * scene.modelHalfSize();
  const double near = 1e-6 * scene.modelHalfSize();
  for (const auto& m : scene.movedJointEnds)
    std::printf("  outlines: the joint between %s and %s ended on a concave bend of %s at (%g, %g); it is moved %.3g m up "
                "the upper face%s, so that %s owns the bend and %s slides on without a corner in the notch "
                "(docs/research/bilinear-slab.md; analysis.joint_end_offset 0 keeps it where it was drawn)\n",
                scene.blocks[m.upper].id.c_str(), scene.blocks[m.lower].id.c_str(), scene.blocks[m.fixedBlock].id.c_str(),
                m.kink.x() + scene.origin.x(), m.kink.y() + scene.origin.y(), m.shift.norm(),
                m.parallel ? ", parallel to itself" : ", turning about its other end", scene.blocks[m.lower].id.c_str(),
                scene.blocks[m.upper].id.c_str());
  for (const auto& k : ddaslope::model::concaveKinksUnderBlocks(scene)) {
    if (std::any_of(scene.movedJointEnds.begin(), scene.movedJointEnds.end(),
                    [&](const auto& m) { return (m.kink - k.point).norm() <= near; }))
      continue;
    std::printf("  note: the surface of %s bends up by %.1f° at (%g, %g), where a block reaching %.3g m up the slope "
                "has a corner. ",
                scene.blocks[k.fixedBlock].id.c_str(), k.bendDeg, k.point.x() + scene.origin.x(),
                k.point.y() + scene.origin.y(), k.upslopeReach);
    if (k.upslopeReach <= failure)
      std::printf("That is no more than the verdict's failure displacement (%.3g m): a slide can squeeze the block out "
                  "and rest on the next corner without being called failing. Make it wider (docs/case-format.md, "
                  "\"Kink blocks\")\n", failure);
    else if (k.upslopeReach < 0.1 * k.reachingBlockHeight)
      std::printf("A block that thin (a kink block) leans on it little (docs/calibration.md, \"The chair-shaped "
                  "slide\")\n");
    else if (k.blocksWithCorner >= 2)
      std::printf("%d blocks meet there: a joint ends on the bend, so the block above has its corner in the notch and "
                  "touches both faces. It cannot slide on along the upper face without lifting or bending, which a DDA "
                  "block (uniform strain) cannot do, and F may then follow the contact stiffness: compare "
                  "analysis.penalty_factor 10-2000 and the blocks' own bound (scripts/block_equilibrium.py). The reader "
                  "moves such a joint up the upper face where one block lies on each face (analysis.joint_end_offset, "
                  "here 0 or not possible); a kink block would make another block system (docs/research/bilinear-slab.md)\n",
                  k.blocksWithCorner);
    else
      std::printf("The block may lean on that corner, which limit-equilibrium slices cannot, with a force its width "
                  "sets. On a kink inside the sliding surface a thin block there (section.kink_block_width) takes "
                  "most of that away (docs/calibration.md, \"The chair-shaped slide\"; scripts/block_equilibrium.py "
                  "gives these blocks' own bound)\n");
  }
}

/// Whether point p of block `own` lies on or near (1e-3 w0) the outline of another block.
bool touchesAnotherBlock(const ddaslope::model::Scene& scene, const ddaslope::model::Block& own, const ddaslope::Vec2& p) {
  const double near = 1e-3 * scene.modelHalfSize();
  for (const auto& b : scene.blocks) {
    if (&b == &own || (b.fixed && own.fixed)) continue;
    for (size_t k = 0; k < b.vertices.size(); ++k)
      if (ddaslope::geometry::distanceToSegment(p, b.vertices[k], b.vertices[(k + 1) % b.vertices.size()], nullptr) <= near)
        return true;
  }
  return false;
}

/// The vertices the reader kept that bend a face touching another block by less than the
/// edge-parallel tolerance: the face then meets its neighbour as two contacts judged apart. Empty
/// if none.
std::string slightBendNote(const ddaslope::model::Scene& scene) {
  int slight = 0;
  double offLine = 0;
  std::string first;
  for (const auto& b : scene.blocks) {
    const size_t n = b.vertices.size();
    for (size_t k = 0; k < n; ++k) {
      const ddaslope::Vec2 in = b.vertices[k] - b.vertices[(k + n - 1) % n], out = b.vertices[(k + 1) % n] - b.vertices[k];
      const double turnDeg = std::abs(std::atan2(ddaslope::cross(in, out), in.dot(out))) * 180 / M_PI;
      if (turnDeg >= scene.settings.edgeParallelToleranceDeg || !touchesAnotherBlock(scene, b, b.vertices[k])) continue;
      // How far it lies off its neighbours' chord: the gap initial_contact_tolerance would have to
      // count as touching for the reader to take it as on the line.
      const ddaslope::Vec2 chord = b.vertices[(k + 1) % n] - b.vertices[(k + n - 1) % n];
      offLine = std::max(offLine, std::abs(ddaslope::cross(chord, b.vertices[k] - b.vertices[(k + n - 1) % n])) / chord.norm());
      if (slight++ == 0) {
        char where[160];
        std::snprintf(where, sizeof where, "block %s at (%g, %g), %.3g°", b.id.c_str(),
                      b.vertices[k].x() + scene.origin.x(), b.vertices[k].y() + scene.origin.y(), turnDeg);
        first = where;
      }
    }
  }
  if (slight == 0) return "";
  std::ostringstream m;
  m << slight << " vertices bend their block's outline by less than the edge-parallel tolerance ("
    << scene.settings.edgeParallelToleranceDeg << "°) but are not on a straight line (first: " << first
    << "): each splits a face into contacts judged apart, whose cohesion may fail piecewise. They lie up to "
    << offLine << " m off a straight line; if that is rounding, `--set analysis.initial_contact_tolerance="
    << std::ceil(2 * offLine / scene.modelHalfSize() * 1e9) / 1e9
    << "` (gaps that count as touching at t = 0, as a fraction of w0) takes them as on it";
  return m.str();
}

/// What the reader did to the blocks' outlines, and the vertices it kept that bend a face so little
/// that the face still meets its neighbour as two contacts judged apart.
void printOutlineNotes(const ddaslope::model::Scene& scene) {
  int removed = 0, blocks = 0;
  for (const auto& b : scene.blocks) removed += b.removedCollinearVertices, blocks += b.removedCollinearVertices > 0;
  if (removed > 0)
    std::printf("  outlines: %d vertices on straight edges removed from %d block(s) (T-junctions and split edges: each "
                "face meets its neighbour as one contact, docs/contact-model.md)\n",
                removed, blocks);
  for (const auto& b : scene.blocks)
    if (!b.mergedIds.empty()) {
      std::string ids;
      for (const std::string& id : b.mergedIds) ids += (ids.empty() ? "" : ", ") + id;
      std::printf("  fixed blocks %s merged into %s: they share boundary and meet every block with the same joint, so "
                  "a block across their seam meets them as one contact (docs/contact-model.md)\n",
                  ids.c_str(), b.id.c_str());
    }
  if (const std::string note = slightBendNote(scene); !note.empty()) std::printf("  note: %s\n", note.c_str());
}

/// A warning for the searches where a joint ends on a concave bend of the sliding surface (a
/// corner in a notch: F may follow the contact stiffness, docs/research/bilinear-slab.md).
std::string notchWarning(const ddaslope::model::Scene& scene) {
  for (const auto& k : ddaslope::model::concaveKinksUnderBlocks(scene))
    if (k.blocksWithCorner >= 2 && k.upslopeReach >= 0.1 * k.reachingBlockHeight) {
      std::ostringstream m;
      m << "a joint ends on a concave bend of " << scene.blocks[k.fixedBlock].id << " at (" << k.point.x() + scene.origin.x()
        << ", " << k.point.y() + scene.origin.y() << "): a corner sits in the notch, and the answer may follow the "
        << "contact stiffness; compare analysis.penalty_factor 10-2000 and scripts/block_equilibrium.py --solve fos "
           "(`ddaslope check` says more)";
      return m.str();
    }
  return "";
}

/// The seismic loading in force: the coefficients and the record's span and peaks.
void printSeismicNote(const ddaslope::model::Scene& scene) {
  const ddaslope::model::SeismicLoad& q = scene.seismic;
  if (q.kh != 0 || q.kv != 0)
    std::printf("  pseudo-static seismic load: k_h = %g (a force along %s), k_v = %g (%s), from the initial equilibrium on\n",
                q.kh, q.kh < 0 ? "-x" : "+x", q.kv, q.kv < 0 ? "downward" : "upward");
  if (!q.ground.active()) return;
  double ph = 0, pv = 0;
  for (double a : q.ground.horizontal) ph = std::max(ph, std::abs(a));
  for (double a : q.ground.vertical) pv = std::max(pv, std::abs(a));
  std::printf("  ground-motion record: %zu samples over t = %g-%g s of the analysis, peak %.4g m/s² (%.3g g) horizontal",
              q.ground.times.size(), q.ground.times.front(), q.ground.times.back(), ph, ph / ddaslope::io::kStandardGravity);
  if (!q.ground.vertical.empty()) std::printf(", %.4g m/s² (%.3g g) vertical", pv, pv / ddaslope::io::kStandardGravity);
  std::printf("\n");
  // What a user may not expect of a record (docs/seismic.md).
  const ddaslope::Vec2 first = q.ground.at(q.ground.times.front());
  if (first.norm() > 1e-3 * std::max(ph, pv))
    std::printf("  note: the record starts at %.4g m/s², not 0: a step load, which rings the contact springs; taper it in\n",
                first.norm());
  if (q.ground.times.front() >= scene.settings.duration)
    std::printf("  note: the record starts at t = %g s, after the analysis ends (analysis.duration %g s): it never acts\n",
                q.ground.times.front(), scene.settings.duration);
  double sample = INFINITY;
  for (size_t k = 1; k < q.ground.times.size(); ++k) sample = std::min(sample, q.ground.times[k] - q.ground.times[k - 1]);
  if (scene.settings.timeStep > sample * (1 + 1e-6))  // the samples' times carry their text's round-off
    std::printf("  note: Δt %g s is longer than the record's sampling (%g s): each step applies the record's mean over "
                "the step, so content above %.3g Hz is averaged out\n",
                scene.settings.timeStep, sample, 0.5 / scene.settings.timeStep);
}

int checkCommand(const std::string& casePath, const Overrides& o) {
  ddaslope::model::Scene scene = loadCase(casePath, o);
  applyOverrides(scene, o, casePath);
  const ddaslope::solver::Simulation sim(scene);
  int closed = 0;
  for (const auto& c : sim.contacts().contacts()) closed += c.closed();
  std::printf("%s: valid. %zu blocks, %zu materials, %zu joints, %zu monitors; %zu contacts found at t = 0 "
              "(%d touching); w0 = %g m, penalty = %g N/m\n",
              casePath.c_str(), scene.blocks.size(), scene.materials.size(), scene.joints.size(),
              scene.monitors.size(), sim.contacts().contacts().size(), closed, sim.modelHalfSize(),
              scene.normalPenalty());
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
  printOutlineNotes(scene);
  printSeismicNote(scene);
  printKinkNotes(scene);
  if (ddaslope::io::hasProbabilitySection(casePath)) {
    const ddaslope::io::ProbabilityJob job = ddaslope::io::readProbabilityJob(casePath);
    std::printf("  probability section: %zu uncertain inputs, %d samples (%s, measure %s): valid; run it with "
                "ddaslope probability\n",
                job.spec.inputs.size(), job.spec.samples, ddaslope::calibration::name(job.spec.sampling),
                ddaslope::calibration::name(job.spec.measure));
  }
  return kExitOk;
}


struct CriticalOptions {
  std::string joint;
  std::string solve = "cohesion";
  std::string direction = "auto";  ///< of the seismic coefficient searched for: +x, -x or auto (both)
  double friction = -1;
  double cohesion = -1;
  double width = 0;
  bool json = false;
  int threads = 2;
  std::string curve;       ///< "phiMin:phiMax:n"
  std::string outDir = "out";
  ProgressOptions progress;
  std::string vtkDir;      ///< every trial's final state as a VTK series (recordTrialStates)
};

int curveCommand(const std::string& casePath, const ddaslope::model::Scene& scene, int joint, const CriticalOptions& opt) {
  double lo = 0, hi = 0;
  int n = 0;
  if (std::sscanf(opt.curve.c_str(), "%lf:%lf:%d", &lo, &hi, &n) != 3 || n < 2 || lo < 0 || hi >= 90 || lo >= hi)
    throw ddaslope::InputError("--curve", "", "expected φmin:φmax:n with 0 ≤ φmin < φmax < 90 and n ≥ 2, found \"" + opt.curve + "\"");
  const auto log = startProgress("critical --curve", opt.progress, opt.json);
  ddaslope::calibration::SearchSettings s;
  s.threads = opt.threads;
  s.progress = ddaslope::io::sinkOf(log.get());
  const auto t0 = std::chrono::steady_clock::now();
  const std::unique_ptr<ddaslope::TaskFarm> farm = ddaslope::makeTaskFarm(opt.threads);
  const auto curve =
      ddaslope::calibration::criticalCurve(scene, joint, lo, hi, n, opt.width > 0 ? opt.width : 10, s, farm.get());
  if (!farm->isRoot()) return kExitOk;  // the root writes
  log->finish(true, std::to_string(n) + " points");
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::filesystem::create_directories(opt.outDir);
  const std::string csv = opt.outDir + "/critical_curve.csv", png = opt.outDir + "/critical_curve.png";
  std::FILE* f = std::fopen((csv + ".tmp").c_str(), "w");
  if (!f) throw ddaslope::InputError(csv, "", "cannot write the file");
  std::fprintf(f, "friction_angle_deg,critical_cohesion_pa,failing_pa,stable_pa,found,forward_runs\n");
  ddaslope::io::PlotSeries series{"critical cohesion (" + opt.joint + ")", {}, {}, true};
  int runs = 0;
  bool all = true;
  for (const auto& p : curve) {
    const auto& r = p.cohesion;
    std::fprintf(f, "%g,%.6g,%.6g,%.6g,%d,%d\n", p.frictionDeg, r.critical, r.failingEnd, r.stableEnd, r.found, r.runs);
    series.x.push_back(p.frictionDeg);
    series.y.push_back(r.found ? r.critical / 1e3 : NAN);
    runs += r.runs;
    all &= r.found;
  }
  std::fclose(f);
  std::filesystem::rename(csv + ".tmp", csv);
  ddaslope::io::writePng({"Critical strength: " + casePath, "friction angle φ (°)", "critical cohesion c (kPa)", {series}}, png);
  if (opt.json) {
    ddaslope::io::JsonRecord j;
    std::vector<double> phis, cs;
    for (const auto& p : curve) phis.push_back(p.frictionDeg), cs.push_back(p.cohesion.critical);
    j.set("case", casePath).set("joint", opt.joint).set("friction_angle_deg", phis).set("critical_cohesion_pa", cs);
    j.set("all_found", all).set("forward_runs", runs).set("wall_time_s", wall).set("csv", csv).set("png", png);
    std::printf("%s\n", j.dump().c_str());
  } else {
    for (const auto& p : curve)
      std::printf("  φ = %6.2f°  c_cr = %10.1f Pa%s%s\n", p.frictionDeg, p.cohesion.critical,
                  p.cohesion.message.empty() ? "" : "  ", p.cohesion.message.c_str());
    std::printf("%d forward runs, %.2f s wall; wrote %s and %s\n", runs, wall, csv.c_str(), png.c_str());
  }
  return all ? kExitOk : kExitNonConvergence;
}

/// Where a search's --vtk went (text output).
void printTrialStatesNote(const std::string& dir, int runs) {
  if (!dir.empty())
    std::printf("  wrote %s: blocks.pvd, contacts.pvd: the final state of each of the %d trials, at the value it tried\n",
                dir.c_str(), runs);
}

/// Verdict warnings go to stderr, so a --json result on stdout stays clean.
void warnAboutTrials(const std::string& casePath, const std::string& warning) {
  if (!warning.empty()) std::fprintf(stderr, "ddaslope: warning: %s: %s\n", casePath.c_str(), warning.c_str());
}

/// The yield seismic coefficient k_y (critical --solve seismic-coefficient): along the direction
/// asked, or along both (auto), the smaller being the slope's.
int seismicCoefficientCommand(const std::string& casePath, const ddaslope::model::Scene& scene,
                              const CriticalOptions& opt) {
  // Options of the strength searches mean nothing here: refuse them rather than ignore them.
  for (const auto& [given, name] : {std::pair{!opt.joint.empty(), "--joint"}, std::pair{opt.friction >= 0, "--friction"},
                                    std::pair{opt.cohesion >= 0, "--cohesion"}, std::pair{!opt.curve.empty(), "--curve"}})
    if (given)
      throw ddaslope::InputError(name, "", "not used by --solve seismic-coefficient (set strengths with --set, e.g. "
                                           "joints.NAME.friction_angle=30)");
  if (scene.seismic.kh != 0)
    throw ddaslope::InputError(casePath, "seismic.k_h",
                               "the search sets k_h itself; remove it from the case or the command (--kh)");
  if (scene.seismic.ground.active() && !opt.json)
    std::fprintf(stderr, "ddaslope: note: %s: the ground-motion record is not used: k_y belongs to the slope\n", casePath.c_str());
  ddaslope::model::Scene searched = scene;  // what the trials run: no record, k_h their own
  searched.seismic.ground = {};
  const auto log = startProgress("critical --solve seismic-coefficient", opt.progress, opt.json);
  ddaslope::calibration::SearchSettings s;
  s.threads = opt.threads;
  s.progress = ddaslope::io::sinkOf(log.get());
  recordTrialStates(s, opt.vtkDir, scene);
  std::vector<std::pair<std::string, ddaslope::calibration::CriticalResult>> results;
  for (const char* d : {"+x", "-x"})
    if (opt.direction == "auto" || opt.direction == d)
      results.emplace_back(d, ddaslope::calibration::criticalSeismicCoefficient(scene, d[0] == '-' ? -1 : 1, opt.width, s));
  log->finish(true, std::to_string(results.size()) + " directions searched");
  // The slope's yield coefficient: the smaller of those found.
  size_t best = 0;
  for (size_t k = 1; k < results.size(); ++k)
    if (results[k].second.found && (!results[best].second.found || results[k].second.critical < results[best].second.critical))
      best = k;
  const auto& [direction, r] = results[best];
  int runs = 0;
  double wall = 0;
  for (const auto& [d, x] : results) runs += x.runs, wall += x.wallTime;
  if (opt.json) {
    ddaslope::io::JsonRecord j;
    j.set("case", casePath).set("solve", opt.solve).set("direction", direction).set("k_v", scene.seismic.kv);
    j.set("found", r.found).set("critical", r.critical).set("unit", "g");
    j.set("failing_at", r.failingEnd).set("stable_at", r.stableEnd);
    j.set("forward_runs", runs).set("wall_time_s", wall).set("message", r.message);
    j.set("settings", settingsLine(searched));
    ddaslope::calibration::appendReview(j, r.review);
    ddaslope::calibration::appendTrials(j, r.trials, "k_h");
    if (!opt.vtkDir.empty()) j.set("vtk", opt.vtkDir);
    std::printf("%s\n", j.dump().c_str());
  } else {
    for (const auto& [d, x] : results) {
      if (x.found)
        std::printf("yield seismic coefficient k_y along %s (k_v = %g): %.6g g (failing at %.6g, stable at %.6g)%s\n",
                    d.c_str(), scene.seismic.kv, x.critical, x.failingEnd, x.stableEnd,
                    results.size() > 1 && &x == &r ? "  <- the slope's" : "");
      if (x.found && !x.message.empty()) std::printf("  %s\n", x.message.c_str());
      if (!x.found)
        std::printf("along %s: none: %s\n", d.c_str(), x.message.c_str());
    }
    if (r.found)
      std::printf("  (a force k_y·m·g along %s; a ground acceleration of k_y·g along %s)\n", direction.c_str(),
                  direction == "+x" ? "-x" : "+x");
    std::printf("%d forward runs, %.2f s wall; %s\n", runs, wall, settingsLine(searched).c_str());
    printTrialStatesNote(opt.vtkDir, runs);
  }
  if (!r.found)
    std::fprintf(stderr, "ddaslope: %s: no yield seismic coefficient found after %d forward runs: %s\n", casePath.c_str(),
                 runs, r.message.c_str());
  warnAboutTrials(casePath, ddaslope::calibration::smallMotionWarning(r.trials, "k_h"));
  return r.found ? kExitOk : kExitNonConvergence;
}

int criticalCommand(const std::string& casePath, const Overrides& o, const CriticalOptions& opt) {
  ddaslope::model::Scene scene = loadCase(casePath, o);
  applyOverrides(scene, o, casePath);
  if (!opt.vtkDir.empty() && !opt.curve.empty())
    throw ddaslope::InputError("--vtk", opt.vtkDir, "writes the trials of one search, not of a curve's searches (drop --curve)");
  if (opt.solve == "seismic-coefficient") return seismicCoefficientCommand(casePath, scene, opt);
  if (opt.joint.empty()) throw ddaslope::InputError("--joint", "", "expected the joint to search (--joint NAME)");
  const int joint = jointIndex(scene, opt.joint, casePath);
  if (!opt.curve.empty()) return curveCommand(casePath, scene, joint, opt);
  const auto log = startProgress("critical", opt.progress, opt.json);
  ddaslope::calibration::SearchSettings s;
  s.threads = opt.threads;
  s.progress = ddaslope::io::sinkOf(log.get());
  recordTrialStates(s, opt.vtkDir, scene);
  const bool cohesion = opt.solve == "cohesion";
  const ddaslope::model::JointProperties& jp = scene.joints[joint];
  const double phi = opt.friction >= 0 ? opt.friction : ddaslope::radToDeg(jp.frictionAngle);
  const double c = opt.cohesion >= 0 ? opt.cohesion : jp.cohesion;
  if (opt.friction >= 90) throw ddaslope::InputError("--friction", "", "expected an angle in [0, 90) degrees");
  const auto r = cohesion ? ddaslope::calibration::criticalCohesion(scene, joint, phi, opt.width > 0 ? opt.width : 10, s)
                          : ddaslope::calibration::criticalFriction(scene, joint, c, opt.width > 0 ? opt.width : 0.01, s);
  log->finish(r.found, r.found ? "critical " + opt.solve + " " + std::to_string(r.critical) : r.message);
  const char* unit = cohesion ? "Pa" : "degrees";
  if (opt.json) {
    ddaslope::io::JsonRecord j;
    j.set("case", casePath).set("joint", opt.joint).set("solve", opt.solve).set("found", r.found);
    if (cohesion) j.set("friction_angle_deg", phi); else j.set("cohesion_pa", c);
    j.set("critical", r.found ? r.critical : NAN).set("unit", unit).set("bracket", std::vector<double>{r.failingEnd, r.stableEnd});
    j.set("forward_runs", r.runs).set("wall_time_s", r.wallTime).set("message", r.message);
    j.set("settings", settingsLine(scene));
    ddaslope::calibration::appendReview(j, r.review);
    ddaslope::calibration::appendTrials(j, r.trials, cohesion ? "cohesion_pa" : "friction_angle_deg");
    if (!opt.vtkDir.empty()) j.set("vtk", opt.vtkDir);
    std::printf("%s\n", j.dump().c_str());
  } else if (r.found) {
    std::printf("critical %s of joint '%s' %s: %.6g %s (failing at %.6g, stable at %.6g)%s%s\n", opt.solve.c_str(),
                opt.joint.c_str(),
                (cohesion ? "at φ = " + std::to_string(phi) + "°" : "at c = " + std::to_string(c) + " Pa").c_str(),
                r.critical, unit, r.failingEnd, r.stableEnd, r.message.empty() ? "" : ": ", r.message.c_str());
    std::printf("%d forward runs, %.2f s wall; %s\n", r.runs, r.wallTime, settingsLine(scene).c_str());
    printTrialStatesNote(opt.vtkDir, r.runs);
  } else {
    std::fprintf(stderr, "ddaslope: %s: no critical %s found after %d forward runs: %s\n", casePath.c_str(),
                 opt.solve.c_str(), r.runs, r.message.c_str());
  }
  warnAboutTrials(casePath, ddaslope::calibration::smallMotionWarning(r.trials, cohesion ? "c" : "φ"));
  warnAboutTrials(casePath, slightBendNote(scene));
  warnAboutTrials(casePath, notchWarning(scene));
  return r.found ? kExitOk : kExitNonConvergence;
}

struct FosOptions {
  std::vector<std::string> joints;
  double width = 0.005;
  bool json = false;
  int threads = 2;
  std::string sweep;  ///< "json.path=min:max:n"
  std::string outDir = "out/fos";
  ProgressOptions progress;
  std::string vtkDir;  ///< every trial's final state as a VTK series (recordTrialStates)
};

ddaslope::calibration::FactorOfSafetyResult factorFor(const ddaslope::model::Scene& scene, const std::string& casePath,
                                                      const FosOptions& opt, ddaslope::io::ProgressSink progress = {}) {
  std::vector<int> joints;
  for (const auto& n : opt.joints) joints.push_back(jointIndex(scene, n, casePath));
  ddaslope::calibration::SearchSettings s;
  s.threads = opt.threads;
  s.progress = std::move(progress);
  recordTrialStates(s, opt.vtkDir, scene);
  return ddaslope::calibration::factorOfSafety(scene, joints, opt.width, s);
}

/// F at n values of one case number (e.g. the reservoir level): CSV and PNG in opt.outDir.
int fosSweep(const std::string& casePath, const Overrides& o, const FosOptions& opt) {
  const size_t eq = opt.sweep.find('=');
  double lo = 0, hi = 0;
  int n = 0;
  if (eq == std::string::npos || std::sscanf(opt.sweep.c_str() + eq + 1, "%lf:%lf:%d", &lo, &hi, &n) != 3 || n < 2 ||
      n > 1000 || !std::isfinite(lo) || !std::isfinite(hi))
    throw ddaslope::InputError("--sweep", opt.sweep, "expected json.path=min:max:n with finite min, max and 2 ≤ n ≤ 1000");
  const std::string path = opt.sweep.substr(0, eq);
  const std::string csv = opt.outDir + "/fos_sweep.csv", png = opt.outDir + "/fos_sweep.png";
  // The values are independent searches (one thread each, so a value's F is the same on any
  // farm), spread over the threads, or the ranks under mpirun.
  struct Point {
    ddaslope::calibration::FactorOfSafetyResult fos;
    bool done = false;
  };
  std::vector<Point> points(static_cast<size_t>(n));
  std::vector<int> indices(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) indices[i] = i;
  const auto valueAt = [&](int i) { return lo + (hi - lo) * i / (n - 1); };
  FosOptions single = opt;
  single.threads = 1;
  const auto log = startProgress("fos --sweep", opt.progress, false);
  int finished = 0;
  const std::unique_ptr<ddaslope::TaskFarm> farm = ddaslope::makeTaskFarm(opt.threads);
  farm->run(
      indices,
      [&](int i) {
        ddaslope::model::Scene scene = loadCase(casePath, o, {{path, valueAt(i)}});
        applyOverrides(scene, o, casePath);
        const auto r = factorFor(scene, casePath, single);
        ddaslope::BytePacker b;
        b.put(r.found).put(r.factor).put(r.stableEnd).put(r.failingEnd).put(r.runs).put(r.wallTime).put(r.message);
        return b.bytes();
      },
      [&](int i, const ddaslope::TaskResult& bytes) {
        ddaslope::ByteUnpacker b(bytes);
        auto& r = points[i].fos;
        r.found = b.get<bool>();
        r.factor = b.get<double>();
        r.stableEnd = b.get<double>();
        r.failingEnd = b.get<double>();
        r.runs = b.get<int>();
        r.wallTime = b.get<double>();
        r.message = b.getString();
        points[i].done = true;
        if (log->active())
          log->report({"points", ++finished, n,
                       path + " = " + std::to_string(valueAt(i)) + ": F " + (r.found ? std::to_string(r.factor) : "not found"),
                       {{"value", valueAt(i)}, {"factor_of_safety", r.found ? r.factor : NAN}}});
      });
  if (!farm->isRoot()) return kExitOk;  // the root writes
  log->finish(true, std::to_string(n) + " values");
  for (int i = 0; i < n; ++i) {
    const auto& r = points[i].fos;
    std::printf("  %s = %-10g F = %s (%d forward runs, %.1f s)\n", path.c_str(), valueAt(i),
                r.found ? std::to_string(r.factor).c_str() : r.message.c_str(), r.runs, r.wallTime);
  }
  std::filesystem::create_directories(opt.outDir);
  std::ofstream out(csv + ".tmp");
  out << path << ",factor_of_safety,stable_at,failing_at,found,forward_runs,wall_time_s\n";
  ddaslope::io::PlotSeries series{"F", {}, {}, true};
  bool all = true;
  for (int i = 0; i < n; ++i) {
    const auto& r = points[i].fos;
    const double v = valueAt(i);
    out << v << "," << r.factor << "," << r.stableEnd << "," << r.failingEnd << "," << r.found << "," << r.runs << ","
        << r.wallTime << "\n";
    series.x.push_back(v);
    series.y.push_back(r.found ? r.factor : NAN);
    all &= r.found;
  }
  out.close();
  std::filesystem::rename(csv + ".tmp", csv);
  ddaslope::io::writePng({"Strength-reduction factor of safety: " + casePath, path, "F", {series}}, png);
  std::printf("wrote %s and %s\n", csv.c_str(), png.c_str());
  return all ? kExitOk : kExitNonConvergence;
}

int fosCommand(const std::string& casePath, const Overrides& o, const FosOptions& opt) {
  if (!opt.vtkDir.empty() && !opt.sweep.empty())
    throw ddaslope::InputError("--vtk", opt.vtkDir, "writes the trials of one search, not of a sweep's searches (drop --sweep)");
  if (!opt.sweep.empty()) return fosSweep(casePath, o, opt);
  ddaslope::model::Scene scene = loadCase(casePath, o);
  applyOverrides(scene, o, casePath);
  const auto log = startProgress("fos", opt.progress, opt.json);
  const auto r = factorFor(scene, casePath, opt, ddaslope::io::sinkOf(log.get()));
  log->finish(r.found, r.found ? "F " + std::to_string(r.factor) : r.message);
  if (opt.json) {
    ddaslope::io::JsonRecord j;
    // No answer, no number: the bracket and the message say what is known.
    j.set("case", casePath).set("found", r.found).set("factor_of_safety", r.found ? r.factor : NAN);
    j.set("bracket", std::vector<double>{r.stableEnd, r.failingEnd}).set("width", opt.width);
    j.set("forward_runs", r.runs).set("rounds", r.rounds).set("wall_time_s", r.wallTime).set("message", r.message);
    j.set("settings", settingsLine(scene));
    ddaslope::calibration::appendReview(j, r.review);
    ddaslope::calibration::appendTrials(j, r.trials, "factor");
    if (!opt.vtkDir.empty()) j.set("vtk", opt.vtkDir);
    std::printf("%s\n", j.dump().c_str());
  } else if (r.found) {
    std::printf("factor of safety (strength reduction on %s): %.4f (stable at %.4f, failing at %.4f)\n",
                opt.joints.empty() ? "all joints" : "the named joints", r.factor, r.stableEnd, r.failingEnd);
    if (!r.message.empty()) std::printf("  %s\n", r.message.c_str());
    std::printf("%d forward runs in %d rounds of %d, %.2f s wall; %s\n", r.runs, r.rounds, opt.threads, r.wallTime,
                settingsLine(scene).c_str());
    printTrialStatesNote(opt.vtkDir, r.runs);
  } else {
    std::fprintf(stderr, "ddaslope: %s: no factor of safety found after %d forward runs: %s\n", casePath.c_str(),
                 r.runs, r.message.c_str());
  }
  warnAboutTrials(casePath, ddaslope::calibration::smallMotionWarning(r.trials, "F"));
  warnAboutTrials(casePath, slightBendNote(scene));
  warnAboutTrials(casePath, notchWarning(scene));
  return r.found ? kExitOk : kExitNonConvergence;
}

/// result.json's "precision": each parameter's range and scan, the Δt ensemble, the statement.
void appendPrecision(ddaslope::io::JsonRecord& j, const ddaslope::calibration::Precision& p,
                     const ddaslope::io::BackanalysisJob& job) {
  if (p.parameters.empty()) return;
  ddaslope::io::JsonRecord out;
  for (const auto& r : p.parameters) {
    ddaslope::io::JsonRecord item;
    item.set("name", r.name).set("estimate", r.estimate).set("low", r.low).set("high", r.high);
    item.set("low_is_scan_end", r.openLow).set("high_is_scan_end", r.openHigh);
    item.set("noise_resolution", r.noiseResolution);  // null: no slope to compare the noise with
    for (const auto& s : r.scan) {
      ddaslope::io::JsonRecord point;
      point.set("value", s.value).set("misfit", s.misfit).set("simulated", s.simulated);
      item.append("scan", point);
    }
    out.append("parameters", item);
  }
  for (const auto& m : p.ensemble) {
    ddaslope::io::JsonRecord member;
    member.set("time_step_factor", m.timeStepFactor).set("misfit", m.misfit).set("simulated", m.simulated);
    out.append("time_step_ensemble", member);
  }
  std::vector<std::string> labels;
  for (const auto& o : job.observations) labels.push_back(o.label);
  out.set("observations", labels).set("noise", p.noise).set("statement", p.statement);
  if (p.better) {
    ddaslope::io::JsonRecord b;
    b.set("parameter", p.parameters[p.better->parameter].name).set("value", p.better->value);
    b.set("misfit", p.better->misfit).set("estimate_misfit", p.better->estimateMisfit);
    b.set("misfit_noise", p.better->misfitNoise);
    out.set("search_stopped_short", b);
  } else {
    out.set("search_stopped_short", false);
  }
  j.set("precision", out);
}

int backanalyseCommand(const std::string& jobPath, const std::string& outDir, bool json, const Overrides& o,
                       const ProgressOptions& progress) {
  ddaslope::io::BackanalysisJob job = ddaslope::io::readJob(jobPath);
  // The command line's choices are applied after the job's own (its "preset", "blocks").
  job.model.push_back(o.model);
  for (const auto& s : o.settings) job.caseOverrides.push_back(parseSetting(s));
  const std::unique_ptr<ddaslope::TaskFarm> farm = ddaslope::makeTaskFarm(job.threads);
  const auto log = startProgress("backanalyse", progress, json);
  const ddaslope::calibration::BackanalysisResult r =
      ddaslope::calibration::runBackanalysis(job, farm.get(), ddaslope::io::sinkOf(log.get()));
  if (!farm->isRoot()) return kExitOk;  // the root writes
  log->finish(true, "misfit " + std::to_string(r.misfit) + " after " + std::to_string(r.evaluations) + " evaluations");
  std::filesystem::create_directories(outDir);
  ddaslope::io::JsonRecord j;
  j.set("job", jobPath).set("case", job.casePath);
  for (size_t i = 0; i < r.names.size(); ++i) j.set(r.names[i], r.estimate[i]);
  j.set("misfit", r.misfit).set("evaluations", r.evaluations).set("forward_runs", r.forwardRuns);
  j.set("global_search", r.globalStatus).set("local_search", r.localStatus).set("wall_time_s", r.wallTime);
  const std::string settings = settingsLine(ddaslope::calibration::sceneAt(job, r.estimate));
  j.set("settings", settings);
  if (!r.map.empty()) j.set("constrains_only_a_line", r.lineOnly).set("statement", r.statement);
  for (const auto& f : r.fit) {
    ddaslope::io::JsonRecord item;
    item.set("observation", f.label);
    if (!f.converged) item.set("simulated", "forward run did not converge");
    else if (f.series) item.set("rms_residual", f.simulated);
    else item.set("simulated", f.simulated).set("observed", f.observed);
    item.set("sigma", f.sigma);
    if (!f.trials.empty()) ddaslope::calibration::appendTrials(item, f.trials, "factor");
    j.append("fit_at_estimate", item);
  }
  appendPrecision(j, r.precision, job);
  const std::string result = outDir + "/result.json";
  {
    std::ofstream out(result + ".tmp");
    out << j.dump() << "\n";
  }
  std::filesystem::rename(result + ".tmp", result);
  if (!r.map.empty()) {
    const std::string csv = outDir + "/misfit_map.csv";
    std::ofstream out(csv + ".tmp");
    out << r.names[0] << "," << r.names[1] << ",misfit\n";
    for (size_t a = 0; a < r.axis0.size(); ++a)
      for (size_t b = 0; b < r.axis1.size(); ++b) out << r.axis0[a] << "," << r.axis1[b] << "," << r.map[a][b] << "\n";
    out.close();
    std::filesystem::rename(csv + ".tmp", csv);
    ddaslope::io::HeatMap m{"Misfit: " + jobPath, r.names[0], r.names[1], "misfit (log scale)", r.axis0, r.axis1, r.map,
                            r.estimate[0], r.estimate[1]};
    ddaslope::io::writePng(m, outDir + "/misfit_map.png");
  }
  if (json) {
    std::printf("%s\n", j.dump().c_str());
  } else {
    std::printf("back-analysis of %s\n  forward runs at %s\n", job.casePath.c_str(), settings.c_str());
    for (size_t i = 0; i < r.names.size(); ++i) std::printf("  %s = %.6g\n", r.names[i].c_str(), r.estimate[i]);
    const std::string searches = r.globalStatus.empty() || r.localStatus.empty()
                                     ? r.globalStatus + r.localStatus
                                     : r.globalStatus + "; " + r.localStatus;
    std::printf("  misfit %.4g after %d evaluations (%d forward runs), %.1f s wall\n  %s\n", r.misfit, r.evaluations,
                r.forwardRuns, r.wallTime, searches.c_str());
    for (const auto& f : r.fit) {
      if (!f.converged) std::printf("  %s: forward run did not converge\n", f.label.c_str());
      else if (f.series) std::printf("  %s: RMS residual %.4g (sigma %.4g)\n", f.label.c_str(), f.simulated, f.sigma);
      else std::printf("  %s: simulated %.6g, observed %.6g ± %.4g\n", f.label.c_str(), f.simulated, f.observed, f.sigma);
    }
    if (!r.statement.empty()) std::printf("  %s\n", r.statement.c_str());
    if (!r.precision.statement.empty()) std::printf("  %s\n", r.precision.statement.c_str());
    std::printf("  wrote %s%s\n", result.c_str(), r.map.empty() ? "" : (" and " + outDir + "/misfit_map.csv, .png").c_str());
  }
  return kExitOk;
}

int cutCommand(const std::string& casePath, const std::string& outDir) {
  const ddaslope::model::Scene scene = ddaslope::io::readCase(casePath);
  const std::string text = ddaslope::io::expandSection(casePath);
  std::filesystem::create_directories(outDir);
  const std::string blocks = outDir + "/blocks.json", picture = outDir + "/section.png";
  {
    std::ofstream out(blocks + ".tmp");
    out << text;
  }
  std::filesystem::rename(blocks + ".tmp", blocks);
  const ddaslope::solver::Simulation sim(scene);
  ddaslope::io::writeScenePicture(sim, ddaslope::io::frameScene(scene), picture, casePath + " (cut)");
  int slide = 0;
  for (const auto& b : scene.blocks) slide += !b.fixed;
  std::printf("%s: %zu blocks (%d free, %zu fixed), %zu contacts at t = 0\n  wrote %s and %s\n", casePath.c_str(),
              scene.blocks.size(), slide, scene.blocks.size() - slide, sim.contacts().contacts().size(), blocks.c_str(),
              picture.c_str());
  if (const std::string drawn = ddaslope::io::sectionDrawingSummary(casePath); !drawn.empty())
    std::printf("  %s\n", drawn.c_str());
  printKinkNotes(scene);
  return kExitOk;
}

int runCommandLine(int argc, char** argv) {
  CLI::App app{"ddaslope: shear strength of landslide sliding surfaces and factor of safety of jointed rock "
               "slopes with Discontinuous Deformation Analysis"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("ddaslope ") + DDASLOPE_VERSION + ", " + ddaslope::processSupport());
  std::string casePath;
  Overrides overrides;

  CLI::App* run = app.add_subcommand("run", "run a case and write history.csv and summary.json");
  RunCommandOptions runOpt;
  addRunOptions(run, casePath, overrides, runOpt);

  CLI::App* check = app.add_subcommand("check", "validate a case file without running it");
  check->add_option("case", casePath, "case file (JSON)")->required();
  addModelOptions(check, overrides);

  bool deformable = false;
  std::string csvPath;
  CLI::App* compare = app.add_subcommand(
      "compare-contacts", "critical cohesion of a block on an incline, edge vs vertex treatment vs closed form (27 slopes)");
  compare->add_flag("--deformable", deformable, "deformable rock blocks (E = 5 GPa) instead of stiff ones");
  compare->add_option("--csv", csvPath, "also write the table as CSV");

  std::string cutOut = "out/cut";
  CLI::App* cut = app.add_subcommand("cut", "cut the blocks of a case's slope section; write them as a plain case file and a picture");
  cut->add_option("case", casePath, "case file (JSON) with a section")->required();
  cut->add_option("--out", cutOut, "output directory")->capture_default_str();

  CriticalOptions crit;
  CLI::App* critical = app.add_subcommand("critical", "critical cohesion (at a friction angle) or friction angle (at a cohesion) of one joint, by bisection");
  critical->add_option("case", casePath, "case file (JSON)")->required();
  critical->add_option("--joint", crit.joint, "joint to search (cohesion, friction)");
  critical->add_option("--solve", crit.solve,
                       "cohesion or friction of the joint, or seismic-coefficient: the yield acceleration k_y (in g)")
      ->check(CLI::IsMember({"cohesion", "friction", "seismic-coefficient"}))
      ->capture_default_str();
  critical->add_option("--direction", crit.direction,
                       "seismic-coefficient: the direction of the horizontal force (+x, -x, or auto: both, the smaller wins)")
      ->check(CLI::IsMember({"+x", "-x", "auto"}))
      ->capture_default_str();
  critical->add_option("--friction", crit.friction, "friction angle (degrees) while solving for cohesion (default: the case's)")
      ->check(finiteIn(0, 89.9, "a friction angle in [0, 89.9] degrees"));
  critical->add_option("--cohesion", crit.cohesion, "cohesion (Pa) while solving for friction (default: the case's)")
      ->check(finiteIn(0, 1e12, "a cohesion in [0, 1e12] Pa"));
  // Widths below 1e-6 would ask the bisection for more digits than the verdict has.
  critical->add_option("--width", crit.width, "final bracket width (Pa, degrees or g; default 10 Pa, 0.01° or 1e-3 of k_y)")
      ->check(finiteIn(1e-6, 1e12, "a width in [1e-6, 1e12]"));
  critical->add_option("--threads", crit.threads, "forward runs at once")->capture_default_str()->check(CLI::Range(1, 256));
  addModelOptions(critical, overrides);
  critical->add_flag("--json", crit.json, "print the result as JSON");
  addProgressOptions(critical, crit.progress);
  critical->add_option("--curve", crit.curve, "φmin:φmax:n: the critical (c, φ) curve as CSV and PNG in --out");
  critical->add_option("--out", crit.outDir, "output directory for --curve")->capture_default_str();
  critical->add_option("--vtk", crit.vtkDir, "write each trial's final state as a VTK series in this folder (ParaView)");

  FosOptions fosOpt;
  CLI::App* fos = app.add_subcommand("fos", "strength-reduction factor of safety: largest F with c/F, atan(tan φ/F) stable");
  fos->add_option("case", casePath, "case file (JSON)")->required();
  fos->add_option("--joints", fosOpt.joints, "joints to reduce (default: all)")->delimiter(',');
  fos->add_option("--width", fosOpt.width, "final bracket width of F")->capture_default_str()
      ->check(finiteIn(1e-4, 1, "a width of F in [1e-4, 1]"));
  fos->add_option("--threads", fosOpt.threads, "trial factors per round, run at once")->capture_default_str()->check(CLI::Range(1, 256));
  fos->add_option("--sweep", fosOpt.sweep, "json.path=min:max:n: F at n values of one case number (CSV and PNG in --out)");
  fos->add_option("--out", fosOpt.outDir, "output directory for --sweep")->capture_default_str();
  fos->add_option("--vtk", fosOpt.vtkDir, "write each trial's final state as a VTK series in this folder (ParaView)");
  addModelOptions(fos, overrides);
  fos->add_flag("--json", fosOpt.json, "print the result as JSON");
  addProgressOptions(fos, fosOpt.progress);

  std::string jobPath, baOut = "out/backanalysis";
  bool baJson = false;
  CLI::App* ba = app.add_subcommand("backanalyse", "estimate joint strengths (or any case value) from observations (NLopt)");
  ba->add_option("job", jobPath, "back-analysis job (JSON)")->required();
  ba->add_option("--out", baOut, "output directory")->capture_default_str();
  ba->add_flag("--json", baJson, "print the result as JSON");
  ProgressOptions baProgress;
  addProgressOptions(ba, baProgress);
  addModelOptions(ba, overrides);

  ddaslope::cli::ProbabilityOptions probOpt;
  CLI::App* probability = app.add_subcommand(
      "probability", "probability of failure from uncertain inputs (a case's \"probability\" section): Pf with its "
                     "95 % interval, β, every sample in a CSV");
  ddaslope::cli::addProbabilityOptions(probability, casePath, probOpt);
  addModelOptions(probability, overrides);

  // An error that every MPI rank met in the same study is reported once, by the root.
  const auto report = [](const char* kind, const char* what) {
    if (ddaslope::processRank() == 0 || !ddaslope::errorSharedByAllProcesses()) std::cerr << kind << what << "\n";
  };
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? kExitOk : kExitBadInput;
  }
  try {
    // Under mpirun only the studies made of independent runs spread over the ranks; any other
    // command would run once per rank, each writing the same files.
    const bool spreads = probability->parsed() || ba->parsed() || (fos->parsed() && !fosOpt.sweep.empty()) ||
                         (critical->parsed() && !crit.curve.empty());
    if (ddaslope::processCount() > 1 && !spreads) {
      ddaslope::declareErrorShared();  // every rank refuses alike
      throw ddaslope::InputError("mpirun", "", "only probability, fos --sweep, critical --curve and backanalyse spread "
                                               "over MPI ranks; start this command without mpirun");
    }
    if (run->parsed()) return runCommand(casePath, overrides, runOpt);
    if (check->parsed()) return checkCommand(casePath, overrides);
    if (compare->parsed()) return compareContactsCommand(deformable, csvPath);
    if (critical->parsed()) return criticalCommand(casePath, overrides, crit);
    if (cut->parsed()) return cutCommand(casePath, cutOut);
    if (ba->parsed()) return backanalyseCommand(jobPath, baOut, baJson, overrides, baProgress);
    if (fos->parsed()) return fosCommand(casePath, overrides, fosOpt);
    if (probability->parsed()) return ddaslope::cli::probabilityCommand(casePath, overrides, probOpt);
  } catch (const ddaslope::InputError& e) {
    report("ddaslope: error: ", e.what());
    return kExitBadInput;
  } catch (const ddaslope::NonConvergenceError& e) {
    report("ddaslope: non-convergence: ", e.what());
    return kExitNonConvergence;
  } catch (const std::filesystem::filesystem_error& e) {
    // An --out that is a file, or a place the user may not write to: their input, not our bug.
    report("ddaslope: error: cannot write the output: ", e.what());
    return kExitBadInput;
  } catch (const std::exception& e) {
    report("ddaslope: internal error: ", e.what());
    return 1;
  }
  return kExitOk;
}

}  // namespace

int main(int argc, char** argv) {
  // Under mpirun every rank parses the same command line; the root reports and writes, the
  // others run their share of a study's forward runs (core/task_farm.hpp).
  ddaslope::startProcesses(argc, argv);
  if (ddaslope::processRank() != 0 && !std::freopen("/dev/null", "w", stdout)) return 1;
  const int code = runCommandLine(argc, argv);
  // An error on one rank must not leave the others waiting for it; one that every rank met in a
  // study's task ends them all normally, with its code.
  if (ddaslope::processCount() > 1 && code != kExitOk && code != kExitNonConvergence &&
      !ddaslope::errorSharedByAllProcesses())
    ddaslope::abortProcesses(code);
  ddaslope::stopProcesses();
  return code;
}

#include "critical_command.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>

#include "ddaslope/calibration/strength_search.hpp"
#include "ddaslope/calibration/trial_report.hpp"
#include "ddaslope/core/byte_record.hpp"
#include "ddaslope/core/errors.hpp"
#include "ddaslope/core/task_farm.hpp"
#include "ddaslope/io/case_reader.hpp"
#include "ddaslope/io/json_record.hpp"
#include "ddaslope/io/line_plot.hpp"
#include "crack_search.hpp"
#include "scene_notes.hpp"

namespace ddaslope::cli {
namespace {

/// A search on one thread: each crack position's own, run side by side with the others.
ddaslope::calibration::SearchSettings oneThread() {
  ddaslope::calibration::SearchSettings s;
  s.threads = 1;
  return s;
}

int curveCommand(const std::string& casePath, const Overrides& o, const ddaslope::model::Scene& scene, int joint,
                 const CriticalOptions& opt) {
  const std::optional<ValueRange> range = parseValueRange(opt.curve, 200);
  if (!range || range->lo < 0 || range->hi >= 90 || range->lo >= range->hi)
    throw ddaslope::InputError("--curve", opt.curve, "expected φmin:φmax:n: finite angles 0 ≤ φmin < φmax < 90 (degrees) and a whole n, 2 ≤ n ≤ 200");
  const double lo = range->lo, hi = range->hi;
  const int n = range->n;
  const auto log = startProgress("critical --curve", opt.progress, opt.json);
  ddaslope::calibration::SearchSettings s;
  s.threads = opt.threads;
  s.lookAhead = !opt.noLookAhead;
  s.progress = ddaslope::io::sinkOf(log.get());
  const auto t0 = std::chrono::steady_clock::now();
  const std::unique_ptr<ddaslope::TaskFarm> farm = ddaslope::makeTaskFarm(opt.threads);
  const double width = opt.width > 0 ? opt.width : 10;
  // A crack whose position the case searches: each point at its own least safe crack. A point
  // with none (no position gave a cohesion, or all gave the same) keeps the case's crack, and its
  // crack x is NaN: no position is least safe.
  ddaslope::calibration::PointScene atCrack;
  if (scene.crackSearch)
    atCrack = [&](double phi, double& crackX, int& runs) {
      const auto read = [&](double x) { return loadCase(casePath, o, crackAt(x)); };
      const PointCrack crack = leastSafeCrackOnThisThread(scene, true, width / 10, read, [&](const ddaslope::model::Scene& at) {
        const auto x = ddaslope::calibration::criticalCohesion(at, joint, phi, width / 10, oneThread());
        return crackValueOf(x);
      }, runs);
      crackX = crack.found ? crack.x : NAN;
      return crack.found ? read(crack.x) : scene;
    };
  const auto curve = ddaslope::calibration::criticalCurve(scene, joint, lo, hi, n, width, s, farm.get(), atCrack);
  if (!farm->isRoot()) return kExitOk;  // the root writes
  log->finish(true, std::to_string(n) + " points");
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::filesystem::create_directories(opt.outDir);
  const std::string csv = opt.outDir + "/critical_curve.csv", png = opt.outDir + "/critical_curve.png";
  std::FILE* f = std::fopen((csv + ".tmp").c_str(), "w");
  if (!f) throw ddaslope::InputError(csv, "", "cannot write the file");
  std::fprintf(f, "friction_angle_deg,critical_cohesion_pa,failing_pa,stable_pa,found,forward_runs%s\n",
               scene.crackSearch ? ",tension_crack_x" : "");
  ddaslope::io::PlotSeries series{"critical cohesion (" + opt.joint + ")", {}, {}, true};
  int runs = 0;
  bool all = true;
  for (const auto& p : curve) {
    const auto& r = p.cohesion;
    std::fprintf(f, "%g,%s,%s,%s,%d,%d", p.frictionDeg, csvField(r.critical, r.found).c_str(),
                 csvField(r.failingEnd, r.found).c_str(), csvField(r.stableEnd, r.found).c_str(), r.found, r.runs);
    // NaN (an empty field): no position is least safe (all tied, or none gave a cohesion).
    if (scene.crackSearch) std::fprintf(f, ",%s", csvField(p.crackX).c_str());
    std::fprintf(f, "\n");
    series.x.push_back(p.frictionDeg);
    series.y.push_back(r.found ? r.critical / 1e3 : NAN);
    runs += r.runs;
    all &= r.found;
  }
  std::fclose(f);
  std::filesystem::rename(csv + ".tmp", csv);
  ddaslope::io::writePng({"Critical strength: " + casePath, "friction angle φ (°)", "critical cohesion c (kPa)", {series}}, png);
  if (opt.json) {
    // No answer, no number: such a point's cohesion is null and its angle is listed in no_answer.
    ddaslope::io::JsonRecord j;
    std::vector<double> phis, cs, crackXs, noAnswer;
    std::vector<std::string> messages;
    for (const auto& p : curve) {
      phis.push_back(p.frictionDeg), cs.push_back(p.cohesion.found ? p.cohesion.critical : NAN);
      // null, as the CSV leaves it empty: no position is least safe.
      crackXs.push_back(p.crackX), messages.push_back(p.cohesion.message);
      if (!p.cohesion.found) noAnswer.push_back(p.frictionDeg);
    }
    j.set("case", casePath).set("joint", opt.joint).set("friction_angle_deg", phis).set("critical_cohesion_pa", cs);
    if (scene.crackSearch) j.set("tension_crack_x", crackXs);
    j.set("messages", messages).set("no_answer", noAnswer);
    j.set("all_found", all).set("forward_runs", runs).set("wall_time_s", wall).set("csv", csv).set("png", png);
    std::printf("%s\n", j.dump().c_str());
  } else {
    for (const auto& p : curve) {
      if (p.cohesion.found)
        std::printf("  φ = %6.2f°  c_cr = %10.1f Pa", p.frictionDeg, p.cohesion.critical);
      else
        std::printf("  φ = %6.2f°  no answer", p.frictionDeg);
      if (scene.crackSearch && std::isfinite(p.crackX))
        std::printf(p.cohesion.found ? "  least safe crack at x = %.4g m" : "  at the least safe crack, x = %.4g m:", p.crackX);
      else if (scene.crackSearch && !(p.cohesion.found && p.cohesion.critical == 0))
        std::printf("  no crack position is least safe: the case's x = %.4g m", scene.tensionCrack->x);
      if (!p.cohesion.message.empty()) std::printf("  %s", p.cohesion.message.c_str());
      std::printf("\n");
    }
    std::printf("%d forward runs, %.2f s wall; wrote %s and %s\n", runs, wall, csv.c_str(), png.c_str());
  }
  return all ? kExitOk : kExitNonConvergence;
}

/// The JRC at which a Barton–Bandis joint just holds the slope (critical --solve jrc).
int jrcCommand(const std::string& casePath, const Overrides& o, ddaslope::model::Scene scene, int joint,
               const CriticalOptions& opt) {
  if (!scene.joints[joint].bartonBandis)
    throw ddaslope::InputError("--solve", "jrc", "joint '" + opt.joint + "' is a Mohr–Coulomb joint: JRC belongs to "
                                                 "Barton–Bandis joints (\"law\": \"barton_bandis\")");
  const double width = opt.width > 0 ? opt.width : 0.01;
  // The least safe crack needs the greatest JRC.
  const std::optional<CrackSearch> crack =
      placeCrack(casePath, o, scene, opt.threads, true, width / 10, "critical jrc", opt.progress, opt.json,
                 [&](const ddaslope::model::Scene& at) {
                   const auto x = ddaslope::calibration::criticalJrc(at, joint, width / 10, oneThread());
                   return crackValueOf(x);
                 });
  const auto log = startProgress("critical --solve jrc", opt.progress, opt.json);
  ddaslope::calibration::SearchSettings s;
  s.threads = opt.threads;
  s.lookAhead = !opt.noLookAhead;
  s.progress = ddaslope::io::sinkOf(log.get());
  recordTrialStates(s, opt.vtkDir, scene);
  const auto r = ddaslope::calibration::criticalJrc(scene, joint, width, s);
  log->finish(r.found, r.found ? "critical JRC " + std::to_string(r.critical) : r.message);
  {
    ddaslope::io::JsonRecord j;
    j.set("case", casePath).set("joint", opt.joint).set("solve", opt.solve).set("found", r.found);
    j.set("critical", r.found ? r.critical : NAN).set("unit", "JRC");
    j.set("bracket", bracketField(r.found, r.failingEnd, r.stableEnd));
    j.set("forward_runs", totalRuns(r.runs, crack)).set("runs_ahead_unused", r.runsAheadUnused);
    j.set("wall_time_s", totalWallTime(r.wallTime, crack));
    j.set("message", r.message).set("settings", settingsLine(scene));
    ddaslope::calibration::appendReview(j, r.review, r.stableEnd, r.failingEnd);
    ddaslope::calibration::appendTrials(j, r.trials, "jrc");
    if (scene.tensionCrack) appendCrackSearch(j, crack ? *crack : CrackSearch{}, scene, "critical jrc");
    writeResultFile(opt.outDir + "/critical.json", j.dump() + "\n");
    if (opt.json) std::printf("%s\n", j.dump().c_str());
  }
  if (opt.json) {
    // printed above
  } else if (r.found) {
    std::printf("critical JRC of joint '%s' at φr = %g°, JCS = %g MPa: %.4g (failing at %.4g, stable at %.4g)%s%s\n",
                opt.joint.c_str(), ddaslope::radToDeg(scene.joints[joint].frictionAngle),
                scene.joints[joint].bartonBandis->jcs / 1e6, r.critical, r.failingEnd, r.stableEnd,
                r.message.empty() ? "" : ": ", r.message.c_str());
    std::printf("%s, %.2f s wall; %s\n", forwardRunsText(r.runs, crack).c_str(), totalWallTime(r.wallTime, crack),
                settingsLine(scene).c_str());
  } else {
    std::fprintf(stderr, "ddaslope: %s: no critical JRC found after %s: %s\n", casePath.c_str(),
                 forwardRunsText(r.runs, crack).c_str(), r.message.c_str());
  }
  return r.found ? kExitOk : kExitNonConvergence;
}

/// The yield seismic coefficient k_y (critical --solve seismic-coefficient): along the direction
/// asked, or along both (auto), the smaller being the slope's.
int seismicCoefficientCommand(const std::string& casePath, const Overrides& o, ddaslope::model::Scene scene,
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
  const auto directions = [&opt] {
    std::vector<const char*> d;
    for (const char* x : {"+x", "-x"})
      if (opt.direction == "auto" || opt.direction == x) d.push_back(x);
    return d;
  }();
  // The least safe crack has the least k_y (along the directions asked, the smaller). Positions
  // searched ten times finer than the answer: a tenth of --width, or without it 1e-4 of each
  // position's k_y against the answer's 1e-3.
  const double positionWidth = opt.width > 0 ? opt.width / 10 : 0;
  const std::string quantity = "critical seismic-coefficient (g)";
  const std::optional<CrackSearch> crack =
      placeCrack(casePath, o, scene, opt.threads, false, opt.width > 0 ? positionWidth : -1e-4, quantity, opt.progress,
                 opt.json, [&](const ddaslope::model::Scene& at) {
                   CrackValue v;
                   for (const char* d : directions) {
                     const auto x = ddaslope::calibration::criticalSeismicCoefficient(at, d[0] == '-' ? -1 : 1,
                                                                                      positionWidth, oneThread(), 1e-4);
                     const CrackValue one = crackValueOf(x);
                     v.runs += one.runs;
                     if (one.found && (!v.found || one.value < v.value)) v.found = true, v.value = one.value;
                     if (!one.found && (v.message.empty() || one.fails)) v.message = one.message;
                     v.fails |= one.fails;  // failing without seismic loading: the least k_y of all
                   }
                   if (v.fails) v.found = false;
                   return v;
                 });
  ddaslope::model::Scene searched = scene;  // what the trials run: no record, k_h their own
  searched.seismic.ground = {};
  const auto log = startProgress("critical --solve seismic-coefficient", opt.progress, opt.json);
  ddaslope::calibration::SearchSettings s;
  s.threads = opt.threads;
  s.lookAhead = !opt.noLookAhead;
  s.progress = ddaslope::io::sinkOf(log.get());
  recordTrialStates(s, opt.vtkDir, scene);
  std::vector<std::pair<std::string, ddaslope::calibration::CriticalResult>> results;
  for (const char* d : directions)
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
  int ahead = 0;
  for (const auto& [d, x] : results) runs += x.runs, ahead += x.runsAheadUnused, wall += x.wallTime;
  const std::string runsText = forwardRunsText(runs, crack);
  wall = totalWallTime(wall, crack);
  {
    ddaslope::io::JsonRecord j;
    j.set("case", casePath).set("solve", opt.solve).set("direction", direction).set("k_v", scene.seismic.kv);
    j.set("found", r.found).set("critical", r.found ? r.critical : NAN).set("unit", "g");
    j.set("failing_at", r.found ? r.failingEnd : NAN).set("stable_at", r.found ? r.stableEnd : NAN);
    j.set("bracket", bracketField(r.found, r.failingEnd, r.stableEnd));
    j.set("forward_runs", totalRuns(runs, crack)).set("runs_ahead_unused", ahead);
    j.set("wall_time_s", wall).set("message", r.message);
    j.set("settings", settingsLine(searched));
    ddaslope::calibration::appendReview(j, r.review, r.stableEnd, r.failingEnd);
    ddaslope::calibration::appendTrials(j, r.trials, "k_h");
    if (scene.tensionCrack) appendCrackSearch(j, crack ? *crack : CrackSearch{}, scene, quantity);
    if (!opt.vtkDir.empty()) j.set("vtk", opt.vtkDir);
    writeResultFile(opt.outDir + "/critical.json", j.dump() + "\n");
    if (opt.json) std::printf("%s\n", j.dump().c_str());
  }
  if (!opt.json) {
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
    std::printf("%s, %.2f s wall; %s\n", runsText.c_str(), wall, settingsLine(searched).c_str());
    printTrialStatesNote(opt.vtkDir, runs);
  }
  if (!r.found)
    std::fprintf(stderr, "ddaslope: %s: no yield seismic coefficient found after %s: %s\n", casePath.c_str(),
                 runsText.c_str(), r.message.c_str());
  warnAboutTrials(casePath, ddaslope::calibration::smallMotionWarning(r.trials, "k_h", shellWord(casePath)));
  warnAboutTrials(casePath, ddaslope::calibration::unconvergedEndWarning(r.trials, r.found, r.failingEnd, "k_h",
                                                                          shellWord(casePath)));
  warnAboutTrials(casePath, ddaslope::calibration::unrestedEndWarning(r.trials, r.found, r.failingEnd, "k_h",
                                                                       shellWord(casePath)));
  return r.found ? kExitOk : kExitNonConvergence;
}

}  // namespace

int criticalCommand(const std::string& casePath, const Overrides& o, const CriticalOptions& given) {
  ddaslope::model::Scene scene = loadCase(casePath, o);
  CriticalOptions opt = given;
  // A case with one joint: that joint is the one searched.
  const bool strengthSearch = opt.solve != "seismic-coefficient" && opt.solve != "support";
  if (strengthSearch && opt.joint.empty() && scene.joints.size() == 1) opt.joint = scene.joints[0].name;
  if (!opt.vtkDir.empty() && !opt.curve.empty())
    throw ddaslope::InputError("--vtk", opt.vtkDir, "writes the trials of one search, not of a curve's searches (drop --curve)");
  if (opt.solve == "seismic-coefficient") return seismicCoefficientCommand(casePath, o, scene, opt);
  if (opt.solve == "support") return supportCommand(casePath, o, scene, opt);
  if (!opt.support.empty()) throw ddaslope::InputError("--support", opt.support, "used only with --solve support");
  if (opt.joint.empty())
    throw ddaslope::InputError("--joint", "missing", "expected the joint to search (--joint NAME): the case has several");
  const int joint = jointIndex(scene, opt.joint, casePath);
  if (!opt.curve.empty()) return curveCommand(casePath, o, scene, joint, opt);
  const auto log = startProgress("critical", opt.progress, opt.json);
  ddaslope::calibration::SearchSettings s;
  s.threads = opt.threads;
  s.lookAhead = !opt.noLookAhead;
  s.progress = ddaslope::io::sinkOf(log.get());
  recordTrialStates(s, opt.vtkDir, scene);
  const ddaslope::model::JointProperties jp = scene.joints[joint];  // a copy: a crack search reloads the scene
  if (opt.solve == "jrc") return jrcCommand(casePath, o, scene, joint, opt);
  if (jp.bartonBandis && opt.solve == "cohesion")
    throw ddaslope::InputError("--solve", "cohesion", "joint '" + opt.joint + "' is a Barton–Bandis joint, without "
                                                      "cohesion: search its jrc or its residual friction (friction)");
  const bool cohesion = opt.solve == "cohesion";
  const double phi = opt.friction >= 0 ? opt.friction : ddaslope::radToDeg(jp.frictionAngle);
  const double c = opt.cohesion >= 0 ? opt.cohesion : jp.cohesion;
  if (opt.friction >= 90) throw ddaslope::InputError("--friction", "", "expected an angle in [0, 90) degrees");
  const double width = opt.width > 0 ? opt.width : cohesion ? 10 : 0.01;
  const auto solve = [&](const ddaslope::model::Scene& at, const ddaslope::calibration::SearchSettings& settings) {
    return cohesion ? ddaslope::calibration::criticalCohesion(at, joint, phi, width, settings)
                    : ddaslope::calibration::criticalFriction(at, joint, c, width, settings);
  };
  // A tension crack searched: the strength its least safe position needs, the table printed first.
  // Positions searched ten times finer than the answer (F is flat near the least safe one).
  const std::optional<CrackSearch> crack =
      placeCrack(casePath, o, scene, opt.threads, true, width / 10, "critical " + opt.solve, opt.progress, opt.json,
                 [&](const ddaslope::model::Scene& at) {
                   const auto x = cohesion ? ddaslope::calibration::criticalCohesion(at, joint, phi, width / 10, oneThread())
                                           : ddaslope::calibration::criticalFriction(at, joint, c, width / 10, oneThread());
                   return crackValueOf(x);
                 });
  if (crack) recordTrialStates(s, opt.vtkDir, scene);
  const MechanismPictures pictures(s, scene);
  // Said before the search, whose trials at such a Δt take long, and kept in critical.json.
  const std::string dtWarning = timeStepWarning(scene);
  warnAboutTrials(casePath, dtWarning);
  if (!opt.progress.quiet) saySearchSize(scene);
  const auto r = solve(scene, s);
  log->finish(r.found, r.found ? "critical " + opt.solve + " " + std::to_string(r.critical) : r.message);
  const char* unit = cohesion ? "Pa" : "degrees";
  const std::vector<std::string> drawn =
      r.found ? pictures.write(opt.outDir, casePath, cohesion ? "c (Pa)" : "φ (°)", r.stableEnd, r.failingEnd)
              : std::vector<std::string>{};
  std::vector<std::string> warnings;
  for (std::string w : {ddaslope::calibration::smallMotionWarning(r.trials, cohesion ? "c" : "φ", shellWord(casePath)),
                        ddaslope::calibration::unconvergedEndWarning(r.trials, r.found, r.failingEnd, cohesion ? "c" : "φ",
                                                                     shellWord(casePath)),
                        ddaslope::calibration::unrestedEndWarning(r.trials, r.found, r.failingEnd, cohesion ? "c" : "φ",
                                                                  shellWord(casePath)),
                        slightBendNote(scene), notchWarning(scene), movedJointWarning(scene), unitsWarning(scene), dtWarning})
    if (!w.empty()) warnings.push_back(std::move(w));
  for (std::string w : contactsAtStartWarnings(scene, {joint})) warnings.push_back(std::move(w));
  {
    ddaslope::io::JsonRecord j;
    j.set("case", casePath).set("joint", opt.joint).set("solve", opt.solve).set("found", r.found);
    if (cohesion) j.set("friction_angle_deg", phi); else j.set("cohesion_pa", c);
    j.set("critical", r.found ? r.critical : NAN).set("unit", unit).set("bracket", bracketField(r.found, r.failingEnd, r.stableEnd));
    // The totals, the crack search's included (its own in tension_crack).
    j.set("forward_runs", totalRuns(r.runs, crack)).set("runs_ahead_unused", r.runsAheadUnused);
    j.set("wall_time_s", totalWallTime(r.wallTime, crack));
    j.set("message", r.message).set("settings", settingsLine(scene));
    ddaslope::calibration::appendReview(j, r.review, r.stableEnd, r.failingEnd);
    ddaslope::calibration::appendTrials(j, r.trials, cohesion ? "cohesion_pa" : "friction_angle_deg");
    if (!opt.vtkDir.empty()) j.set("vtk", opt.vtkDir);
    j.set("mechanism_pictures", drawn).set("warnings", warnings);
    if (scene.tensionCrack) appendCrackSearch(j, crack ? *crack : CrackSearch{}, scene, "critical " + opt.solve);
    writeResultFile(opt.outDir + "/critical.json", j.dump() + "\n");
    if (opt.json) std::printf("%s\n", j.dump().c_str());
  }
  if (opt.json) {
    // printed above
  } else if (r.found) {
    const std::string where =
        cohesion          ? "at φ = " + std::to_string(phi) + "°"
        : jp.bartonBandis ? "(Barton–Bandis φr) at JRC = " + std::to_string(jp.bartonBandis->jrc) + ", JCS = " +
                                std::to_string(jp.bartonBandis->jcs / 1e6) + " MPa"
                          : "at c = " + std::to_string(c) + " Pa";
    // No bracket when the slope holds at the least value (stable without cohesion): no failing end.
    char bracket[96] = "";
    if (r.failingEnd != r.stableEnd)
      std::snprintf(bracket, sizeof bracket, " (failing at %.6g, stable at %.6g)", r.failingEnd, r.stableEnd);
    std::printf("critical %s of joint '%s' %s: %.6g %s%s%s%s\n", opt.solve.c_str(), opt.joint.c_str(), where.c_str(),
                r.critical, unit, bracket, r.message.empty() ? "" : ": ", r.message.c_str());
    std::printf("%s, %.2f s wall; %s\n", forwardRunsText(r.runs, crack).c_str(), totalWallTime(r.wallTime, crack),
                settingsLine(scene).c_str());
    printTrialStatesNote(opt.vtkDir, r.runs);
    std::string files;
    for (const auto& f : drawn) files += (files.empty() ? "" : ", ") + f;
    if (!files.empty()) std::printf("  the mechanism: %s (the trials at the bracket's ends)\n", files.c_str());
  } else {
    std::fprintf(stderr, "ddaslope: %s: no critical %s found after %s: %s\n", casePath.c_str(), opt.solve.c_str(),
                 forwardRunsText(r.runs, crack).c_str(), r.message.c_str());
  }
  for (const auto& w : warnings)
    if (w != dtWarning) warnAboutTrials(casePath, w);
  return r.found ? kExitOk : kExitNonConvergence;
}

void addCriticalOptions(CLI::App* cmd, std::string& casePath, Overrides& overrides, CriticalOptions& opt) {
  cmd->add_option("case", casePath, "case file (JSON)")->required();
  cmd->add_option("--joint", opt.joint, "joint to search (cohesion, friction, jrc; default: the case's only joint)");
  cmd->add_option("--solve", opt.solve,
                       "cohesion or friction of the joint (φr of a Barton–Bandis joint), jrc, seismic-coefficient: the yield acceleration k_y (in g), "
                       "or support: the anchor force, bolt capacity or load (--support) for --target-fos")
      ->check(CLI::IsMember({"cohesion", "friction", "jrc", "seismic-coefficient", "support"}))
      ->capture_default_str();
  cmd->add_option("--direction", opt.direction,
                       "seismic-coefficient: the direction of the horizontal force (+x, -x, or auto: both, the smaller wins)")
      ->check(CLI::IsMember({"+x", "-x", "auto"}))
      ->capture_default_str();
  cmd->add_option("--support", opt.support, "support: the id of the support or load to size");
  cmd->add_option("--target-fos", opt.targetFactor,
                  "support: the factor of safety it must give (every joint's c and tan φ divided by it)")
      ->check(finiteIn(0.1, 100, "a factor of safety in [0.1, 100]"))
      ->capture_default_str();
  cmd->add_option("--friction", opt.friction, "friction angle (degrees) while solving for cohesion (default: the case's)")
      ->check(finiteIn(0, 89.9, "a friction angle in [0, 89.9] degrees"));
  cmd->add_option("--cohesion", opt.cohesion, "cohesion (Pa) while solving for friction (default: the case's)")
      ->check(finiteIn(0, 1e12, "a cohesion in [0, 1e12] Pa"));
  // Widths below 1e-6 would ask the bisection for more digits than the verdict has.
  cmd->add_option("--width", opt.width,
                  "final bracket width (Pa, degrees, JRC, g or N/m; default 10 Pa, 0.01°, 0.01, 1e-3 of k_y or of the "
                  "support's bracket)")
      ->check(finiteIn(1e-6, 1e12, "a width in [1e-6, 1e12]"));
  cmd->add_option("--threads", opt.threads, "forward runs at once")->capture_default_str()->check(CLI::Range(1, 256));
  cmd->add_flag("--no-look-ahead", opt.noLookAhead, "run no trial ahead of need: with several threads, the threads a round leaves idle otherwise run the trials the next round may need (the same trials and answer, sooner; docs/calibration.md)");
  addModelOptions(cmd, overrides);
  cmd->add_flag("--json", opt.json, "print the result as JSON");
  addProgressOptions(cmd, opt.progress);
  cmd->add_option("--curve", opt.curve,
                  "φmin:φmax:n: the critical (c, φ) curve; with --solve support, min:max:n (N/m): F against the "
                  "support; as CSV and PNG in --out");
  cmd->add_option("--out", opt.outDir, "output directory: the mechanism pictures (and --curve's CSV and PNG)")
      ->capture_default_str();
  cmd->add_option("--vtk", opt.vtkDir, "write each trial's final state as a VTK series in this folder (ParaView)");
}

}  // namespace ddaslope::cli

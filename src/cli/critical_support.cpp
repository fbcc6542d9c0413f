// `ddaslope critical CASE --solve support --support NAME`: the force of an anchor, the capacity of
// a bolt or the size of a load that makes the slope hold at a target factor of safety, and with
// --curve, the factor of safety against that quantity.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "crack_search.hpp"
#include "critical_command.hpp"
#include "ddaslope/calibration/strength_search.hpp"
#include "ddaslope/calibration/trial_report.hpp"
#include "ddaslope/core/errors.hpp"
#include "ddaslope/io/json_record.hpp"
#include "ddaslope/io/line_plot.hpp"
#include "scene_notes.hpp"

namespace ddaslope::cli {
namespace {

namespace cal = ddaslope::calibration;
using ddaslope::model::SupportQuantity;

SupportQuantity namedSupport(const std::string& casePath, const ddaslope::model::Scene& scene, const std::string& id) {
  if (id.empty())
    throw ddaslope::InputError("--support", "missing", "expected the support or load to size (--support NAME: an id of supports, "
                                                "point_loads or edge_loads)");
  const SupportQuantity q = scene.supportQuantity(id);
  if (q.kind == SupportQuantity::Kind::None) {
    std::string known;
    for (const auto& s : scene.supports) known += (known.empty() ? "" : ", ") + s.id;
    for (const auto& l : scene.pointLoads)
      if (!l.id.empty() && known.find(l.id) == std::string::npos) known += (known.empty() ? "" : ", ") + l.id;
    throw ddaslope::InputError(casePath, "supports", "no support or load named \"" + id + "\" (the case has: " +
                                                         (known.empty() ? "none with an id" : known) + ")");
  }
  if (q.kind == SupportQuantity::Kind::Load && !(q.value > 0))
    throw ddaslope::InputError(casePath, "point_loads", "load \"" + id + "\" has no size, so no direction to keep: give "
                                                        "it a non-zero force in the direction it acts");
  return q;
}

/// F against the support's size: a factor-of-safety search at each of n sizes over [lo, hi].
int supportCurve(const std::string& casePath, const Overrides& o, const ddaslope::model::Scene& scene,
                 const CriticalOptions& opt, const SupportQuantity& q) {
  const std::optional<ValueRange> range = parseValueRange(opt.curve, 200);
  if (!range || range->lo < 0 || range->lo >= range->hi)
    throw ddaslope::InputError("--curve", opt.curve, "expected min:max:n: finite sizes 0 ≤ min < max (N/m) and a whole n, 2 ≤ n ≤ 200");
  const double lo = range->lo, hi = range->hi;
  const int n = range->n;
  const auto t0 = std::chrono::steady_clock::now();
  std::filesystem::create_directories(opt.outDir);
  const std::string csv = opt.outDir + "/support_curve.csv", png = opt.outDir + "/support_curve.png";
  std::FILE* f = std::fopen((csv + ".tmp").c_str(), "w");
  if (!f) throw ddaslope::InputError(csv, "", "cannot write the file");
  std::fprintf(f, "%s_n_per_m,factor_of_safety,stable_at,failing_at,found,forward_runs%s\n",
               q.kind == SupportQuantity::Kind::BoltCapacity ? "capacity" : "force",
               scene.crackSearch ? ",tension_crack_x" : "");
  ddaslope::io::PlotSeries series{"F (" + opt.support + ")", {}, {}, true};
  cal::SearchSettings s;
  s.threads = opt.threads;
  s.lookAhead = !opt.noLookAhead;
  s.caseLabel = shellWord(casePath);
  int runs = 0;
  bool all = true;
  std::vector<double> values, factors, crackXs, noAnswer;  // N/m, F (null: no answer), m
  for (int k = 0; k < n; ++k) {
    const double x = lo + (hi - lo) * k / (n - 1);
    const auto withSupport = [&](ddaslope::model::Scene at) {
      at.setSupportQuantity(opt.support, x);
      return at;
    };
    // A crack whose position the case searches: F at its least safe position for this size.
    PointCrack crack{NAN, false, false, false};
    int crackRuns = 0;
    ddaslope::model::Scene trial = withSupport(scene);
    if (scene.crackSearch) {
      const auto read = [&](double at) { return withSupport(loadCase(casePath, o, crackAt(at))); };
      crack = leastSafeCrackOnThisThread(scene, false, 1e-4, read, [&](const ddaslope::model::Scene& at) {
        cal::SearchSettings one;
        one.threads = 1;
        one.caseLabel = shellWord(casePath);
        const cal::FactorOfSafetyResult r = cal::factorOfSafety(at, {}, 1e-4, one);
        return crackValueOf(r);
      }, crackRuns);
      if (crack.found) trial = read(crack.x);
    }
    const double crackX = crack.found ? crack.x : NAN;  // NaN: no position is least safe
    const cal::FactorOfSafetyResult r = cal::factorOfSafety(trial, {}, 1e-3, s);
    std::fprintf(f, "%.6g,%s,%s,%s,%d,%d", x, csvField(r.factor, r.found).c_str(), csvField(r.stableEnd, r.found).c_str(),
                 csvField(r.failingEnd, r.found).c_str(), r.found, r.runs + crackRuns);
    if (scene.crackSearch) std::fprintf(f, ",%s", csvField(crackX).c_str());
    std::fprintf(f, "\n");
    if (!opt.json) {
      std::printf("  %s %10.4g kN/m: %s", q.name.c_str(), x / 1e3,
                  r.found ? ("F = " + std::to_string(r.factor)).c_str() : ("no answer (" + r.message + ")").c_str());
      if (scene.crackSearch)
        std::printf("%s", pointCrackText(crack.found, crack.tied, crack.fails, crackX, scene.tensionCrack->x, "F").c_str());
      std::printf("\n");
    }
    values.push_back(x), factors.push_back(r.found ? r.factor : NAN), crackXs.push_back(crackX);
    if (!r.found) noAnswer.push_back(x);
    runs += crackRuns;
    series.x.push_back(x / 1e3);
    series.y.push_back(r.found ? r.factor : NAN);
    runs += r.runs;
    all &= r.found;
  }
  std::fclose(f);
  std::filesystem::rename(csv + ".tmp", csv);
  ddaslope::io::writePng({"Factor of safety against " + q.name + ": " + casePath, q.name + " (kN/m)",
                          "factor of safety F", {series}},
                         png);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (opt.json) {
    ddaslope::io::JsonRecord j;
    j.set("case", casePath).set("support", opt.support).set("quantity", q.name).set("all_found", all);
    j.set("values_n_per_m", values).set("factor_of_safety", factors).set("no_answer", noAnswer);
    if (scene.crackSearch) j.set("tension_crack_x", crackXs);
    j.set("forward_runs", runs).set("wall_time_s", wall).set("csv", csv).set("png", png);
    std::printf("%s\n", j.dump().c_str());
  } else {
    std::printf("%d forward runs, %.2f s wall; wrote %s and %s\n", runs, wall, csv.c_str(), png.c_str());
  }
  return all ? kExitOk : kExitNonConvergence;
}

}  // namespace

int supportCommand(const std::string& casePath, const Overrides& o, ddaslope::model::Scene scene, const CriticalOptions& opt) {
  if (!opt.joint.empty() || opt.friction >= 0 || opt.cohesion >= 0)
    throw ddaslope::InputError(!opt.joint.empty() ? "--joint" : opt.friction >= 0 ? "--friction" : "--cohesion", "",
                               "not used by --solve support: every joint is reduced by --target-fos (set strengths "
                               "with --set, e.g. joints.NAME.friction_angle=30)");
  const SupportQuantity q = namedSupport(casePath, scene, opt.support);
  if (!opt.curve.empty()) return supportCurve(casePath, o, scene, opt, q);
  // The least safe crack needs the greatest anchor force or bolt capacity. A load may steady the
  // slope (a toe berm) or burden it (a surcharge), so which crack is least safe for it is not one
  // rule: the case places that crack.
  if (scene.crackSearch && q.kind == SupportQuantity::Kind::Load)
    throw ddaslope::InputError(casePath, "section.tension_crack.search",
                               "sizing a load ('" + opt.support + "') with the crack's position searched: a load may steady "
                               "or burden the slope, so no one position is least safe for it; remove "
                               "section.tension_crack.search from the case and place the crack with section.tension_crack.x, "
                               "or size an anchor or a bolt");
  cal::SearchSettings one;
  one.threads = 1;
  // Positions searched ten times finer than the answer: --width, or without it a tenth of the
  // 1e-3 of the force (at the case's own crack) that the search narrows to.
  double fine = opt.width > 0 ? opt.width / 10 : 0;
  cal::CriticalResult scale;
  if (scene.crackSearch && fine <= 0) {
    scale = cal::criticalSupport(scene, opt.support, opt.targetFactor, 0, one);
    fine = scale.found && scale.critical > 0 ? 1e-4 * scale.critical : 0;
  }
  // The table is printed once the search for the scale, which belongs to the crack's, is counted in.
  std::optional<CrackSearch> crack =
      placeCrack(casePath, o, scene, opt.threads, true, fine, "critical support (N/m)", opt.progress, true,
                 [&](const ddaslope::model::Scene& at) {
                   const cal::CriticalResult x = cal::criticalSupport(at, opt.support, opt.targetFactor, fine, one);
                   return crackValueOf(x);
                 });
  if (crack) {
    crack->runs += scale.runs, crack->wallTime += scale.wallTime;
    if (!opt.json) printCrackSearch(*crack, scene, "critical support (N/m)");
  }
  const auto log = startProgress("critical --solve support", opt.progress, opt.json);
  cal::SearchSettings s;
  s.threads = opt.threads;
  s.progress = ddaslope::io::sinkOf(log.get());
  recordTrialStates(s, opt.vtkDir, scene);
  const cal::CriticalResult r = cal::criticalSupport(scene, opt.support, opt.targetFactor, opt.width, s);
  log->finish(r.found, r.found ? q.name + " " + std::to_string(r.critical) : r.message);
  {
    ddaslope::io::JsonRecord j;
    j.set("case", casePath).set("solve", "support").set("support", opt.support).set("quantity", q.name);
    j.set("target_factor_of_safety", opt.targetFactor).set("found", r.found);
    j.set("critical", r.found ? r.critical : NAN).set("unit", "N/m");
    j.set("per_support_n", r.found ? r.critical * q.spacing : NAN).set("spacing_m", q.spacing);
    j.set("bracket", bracketField(r.found, r.failingEnd, r.stableEnd));
    j.set("forward_runs", totalRuns(r.runs, crack)).set("runs_ahead_unused", r.runsAheadUnused);
    j.set("wall_time_s", totalWallTime(r.wallTime, crack));
    j.set("message", r.message).set("settings", settingsLine(scene));
    cal::appendReview(j, r.review, r.stableEnd, r.failingEnd);
    cal::appendTrials(j, r.trials, "value_n_per_m");
    if (scene.tensionCrack) appendCrackSearch(j, crack ? *crack : CrackSearch{}, scene, "critical support (N/m)");
    if (!opt.vtkDir.empty()) j.set("vtk", opt.vtkDir);
    writeResultFile(opt.outDir + "/critical.json", j.dump() + "\n");
    if (opt.json) std::printf("%s\n", j.dump().c_str());
  }
  if (opt.json) {
    // printed above
  } else if (r.found && r.largestThatHolds) {
    std::printf("largest %s of '%s' that holds at F = %g: %.6g kN/m (stable at %.6g, failing at %.6g)%s%s\n",
                q.name.c_str(), opt.support.c_str(), opt.targetFactor, r.critical / 1e3, r.stableEnd / 1e3,
                r.failingEnd / 1e3, r.message.empty() ? "" : ": ", r.message.c_str());
  } else if (r.found && r.critical == 0) {
    std::printf("%s of '%s' for F = %g: none needed: the slope holds at F = %g without it\n", q.name.c_str(),
                opt.support.c_str(), opt.targetFactor, opt.targetFactor);
  } else if (r.found) {
    std::printf("%s of '%s' for F = %g: %.6g kN/m (failing at %.6g, stable at %.6g)%s%s\n", q.name.c_str(),
                opt.support.c_str(), opt.targetFactor, r.critical / 1e3, r.failingEnd / 1e3, r.stableEnd / 1e3,
                r.message.empty() ? "" : ": ", r.message.c_str());
    if (q.spacing != 1) std::printf("  = %.6g kN per support at %g m spacing\n", r.critical * q.spacing / 1e3, q.spacing);
    std::printf("  (every joint's c and tan φ divided by %g; support capacities are not reduced)\n", opt.targetFactor);
    std::printf("%s, %.2f s wall; %s\n", forwardRunsText(r.runs, crack).c_str(), totalWallTime(r.wallTime, crack),
                settingsLine(scene).c_str());
    printTrialStatesNote(opt.vtkDir, r.runs);
  } else {
    std::fprintf(stderr, "ddaslope: %s: no %s found after %s: %s\n", casePath.c_str(), q.name.c_str(),
                 forwardRunsText(r.runs, crack).c_str(), r.message.c_str());
  }
  for (const auto& b : scene.supports) {
    if (b.id != opt.support) continue;
    // The search sizes the capacity (or force) the support needs; its grout may hold less.
    if (r.found && r.critical > b.bondCapacity)
      std::fprintf(stderr, "ddaslope: warning: %s: support %s needs %.6g kN/m, but its bond over the shorter embedded "
                           "length holds %.6g kN/m: lengthen it or raise bond_strength, or the grout gives way first\n",
                   casePath.c_str(), b.id.c_str(), r.critical / 1e3, b.bondCapacity / 1e3);
    // A passive bolt carries only what the slope's motion stretches it by before a trial is judged.
    if (!r.found && !b.active()) {
      const double failure = scene.settings.failureDisplacement > 0 ? scene.settings.failureDisplacement
                                                                    : 1e-3 * scene.modelHalfSize();
      std::fprintf(stderr, "ddaslope: note: %s: passive bolt %s (stiffness %.4g N/m per m) carries at most about "
                           "%.4g kN/m before the blocks move the failure displacement (%g m) that fails a trial, "
                           "whatever its capacity: a stiffer bolt or a pretension (an anchor) holds more\n",
                   casePath.c_str(), b.id.c_str(), b.stiffness, b.stiffness * failure / 1e3, failure);
    }
  }
  warnAboutTrials(casePath, cal::smallMotionWarning(r.trials, "support", shellWord(casePath)));
  warnAboutTrials(casePath, cal::unconvergedEndWarning(r.trials, r.found, r.failingEnd, "support", shellWord(casePath)));
  warnAboutTrials(casePath, cal::unrestedEndWarning(r.trials, r.found, r.failingEnd, "support", shellWord(casePath)));
  return r.found ? kExitOk : kExitNonConvergence;
}

}  // namespace ddaslope::cli

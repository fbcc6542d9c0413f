#include "fos_command.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
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


ddaslope::calibration::FactorOfSafetyResult factorFor(const ddaslope::model::Scene& scene, const std::string& casePath,
                                                      const FosOptions& opt, ddaslope::io::ProgressSink progress = {},
                                                      std::unique_ptr<MechanismPictures>* pictures = nullptr) {
  std::vector<int> joints;
  for (const auto& n : opt.joints) joints.push_back(jointIndex(scene, n, casePath));
  ddaslope::calibration::SearchSettings s;
  s.threads = opt.threads;
  s.progress = std::move(progress);
  s.trialStart = trialStartOf(opt.trialStart);
  s.lookAhead = !opt.noLookAhead;
  s.caseLabel = shellWord(casePath);
  recordTrialStates(s, opt.vtkDir, scene);
  if (pictures) *pictures = std::make_unique<MechanismPictures>(s, scene);
  return ddaslope::calibration::factorOfSafety(scene, joints, opt.width, s);
}

/// F at n values of one case number (e.g. the reservoir level): CSV and PNG in opt.outDir.
int fosSweep(const std::string& casePath, const Overrides& o, const FosOptions& opt) {
  const size_t eq = opt.sweep.find('=');
  const std::optional<ValueRange> range =
      eq == std::string::npos || eq == 0 ? std::nullopt : parseValueRange(opt.sweep.substr(eq + 1), 1000);
  if (!range)
    throw ddaslope::InputError("--sweep", opt.sweep, "expected json.path=min:max:n: finite min and max and a whole n, 2 ≤ n ≤ 1000");
  const double lo = range->lo, hi = range->hi;
  const int n = range->n;
  const std::string path = opt.sweep.substr(0, eq);
  const std::string csv = opt.outDir + "/fos_sweep.csv", png = opt.outDir + "/fos_sweep.png";
  // The values are independent searches (one thread each, so a value's F is the same on any
  // farm), spread over the threads, or the ranks under mpirun.
  struct Point {
    ddaslope::calibration::FactorOfSafetyResult fos;
    bool crackSearched = false;  ///< the case searches its crack, and the sweep does not place it
    double crackX = NAN;         ///< the least safe crack's position; NaN when no position is
    bool crackFound = false, crackTied = false, crackFails = false;  ///< as PointCrack's
    bool done = false;
  };
  std::vector<Point> points(static_cast<size_t>(n));
  std::vector<int> indices(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) indices[i] = i;
  const auto valueAt = [&](int i) { return lo + (hi - lo) * i / (n - 1); };
  FosOptions single = opt;
  single.threads = 1;
  const auto log = startProgress("fos --sweep", opt.progress, opt.json);
  const auto t0 = std::chrono::steady_clock::now();
  int finished = 0;
  const std::unique_ptr<ddaslope::TaskFarm> farm = ddaslope::makeTaskFarm(opt.threads);
  farm->run(
      indices,
      [&](int i) {
        const auto started = std::chrono::steady_clock::now();
        ddaslope::model::Scene scene = loadCase(casePath, o, {{path, valueAt(i)}});
        // A crack whose position the case searches: F at its least safe position for this value.
        PointCrack crack{NAN, false, false, false};
        bool searched = false;
        int crackRuns = 0;
        // A sweep of the crack's place (its x or its depth) places it: no search may move it. A sweep
        // of anything else, its water among them, searches each value's crack.
        const bool placesCrack = path == "section.tension_crack.x" || path == "section.tension_crack.depth";
        if (scene.crackSearch && !placesCrack) {
          const auto read = [&](double x) {
            std::vector<ddaslope::io::CaseOverride> extra{{path, valueAt(i)}};
            for (auto& c : crackAt(x)) extra.push_back(std::move(c));
            return loadCase(casePath, o, extra);
          };
          FosOptions fine = single;
          fine.width = std::max(1e-4, opt.width / 10);
          crack = leastSafeCrackOnThisThread(scene, false, fine.width, read, [&](const ddaslope::model::Scene& at) {
            const auto r = factorFor(at, casePath, fine);
            return crackValueOf(r);
          }, crackRuns);
          if (crack.found) scene = read(crack.x);
          searched = true;
        }
        const auto r = factorFor(scene, casePath, single);
        ddaslope::BytePacker b;
        // The value's whole time, its crack search's included.
        const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
        b.put(r.found).put(r.factor).put(r.stableEnd).put(r.failingEnd).put(r.runs + crackRuns).put(wall).put(r.message);
        b.put(searched).put(crack.found ? crack.x : NAN).put(crack.found).put(crack.tied).put(crack.fails);
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
        points[i].crackSearched = b.get<bool>();
        points[i].crackX = b.get<double>();
        points[i].crackFound = b.get<bool>();
        points[i].crackTied = b.get<bool>();
        points[i].crackFails = b.get<bool>();
        points[i].done = true;
        if (log->active())
          log->report({"points", ++finished, n,
                       path + " = " + std::to_string(valueAt(i)) + ": F " + (r.found ? std::to_string(r.factor) : "not found"),
                       {{"value", valueAt(i)}, {"factor_of_safety", r.found ? r.factor : NAN}}});
      });
  if (!farm->isRoot()) return kExitOk;  // the root writes
  log->finish(true, std::to_string(n) + " values");
  const bool cracks = points[0].crackSearched;
  double caseCrackX = NAN;
  if (cracks) caseCrackX = loadCase(casePath, o).tensionCrack->x;
  if (!opt.json)
    for (int i = 0; i < n; ++i) {
      const auto& r = points[i].fos;
      // F to the digits its bracket supports, with the bracket, as a single search prints it.
      char f[96];
      std::snprintf(f, sizeof f, "F = %.4f (stable at %.4f, failing at %.4f)", r.factor, r.stableEnd, r.failingEnd);
      std::printf("  %s = %-10g %s (%d forward runs, %.1f s)", path.c_str(), valueAt(i),
                  r.found ? f : ("no answer: " + r.message).c_str(), r.runs, r.wallTime);
      if (cracks) std::printf("%s", pointCrackText(points[i].crackFound, points[i].crackTied, points[i].crackFails,
                                                   points[i].crackX, caseCrackX, "F").c_str());
      std::printf("\n");
    }
  std::filesystem::create_directories(opt.outDir);
  std::ofstream out(csv + ".tmp");
  out << path << ",factor_of_safety,stable_at,failing_at,found,forward_runs," << (cracks ? "tension_crack_x," : "")
      << "wall_time_s\n";
  ddaslope::io::PlotSeries series{"F", {}, {}, true};
  bool all = true;
  for (int i = 0; i < n; ++i) {
    const auto& r = points[i].fos;
    const double v = valueAt(i);
    out << v << "," << csvField(r.factor, r.found) << "," << csvField(r.stableEnd, r.found) << ","
        << csvField(r.failingEnd, r.found) << "," << r.found << "," << r.runs << ",";
    if (cracks) out << csvField(points[i].crackX) << ",";
    out << r.wallTime << "\n";
    series.x.push_back(v);
    series.y.push_back(r.found ? r.factor : NAN);
    all &= r.found;
  }
  out.close();
  std::filesystem::rename(csv + ".tmp", csv);
  ddaslope::io::writePng({"Strength-reduction factor of safety: " + casePath, path, "F", {series}}, png);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  int runs = 0;
  for (const auto& p : points) runs += p.fos.runs;
  if (opt.json) {
    // No answer, no number: such a point's F is null and its value is listed in no_answer.
    ddaslope::io::JsonRecord j;
    std::vector<double> values, factors, crackXs, noAnswer;
    for (int i = 0; i < n; ++i) {
      const auto& r = points[i].fos;
      ddaslope::io::JsonRecord p;
      p.set("value", valueAt(i)).set("found", r.found).set("factor_of_safety", r.found ? r.factor : NAN);
      p.set("stable_at", r.stableEnd > 0 ? r.stableEnd : NAN).set("failing_at", r.failingEnd > 0 ? r.failingEnd : NAN);
      p.set("forward_runs", r.runs).set("wall_time_s", r.wallTime).set("message", r.message);
      if (cracks) p.set("tension_crack_x", points[i].crackX).set("crack_position_found", points[i].crackFound);
      j.append("points", p);
      values.push_back(valueAt(i));
      factors.push_back(r.found ? r.factor : NAN);
      crackXs.push_back(points[i].crackX);
      if (!r.found) noAnswer.push_back(valueAt(i));
    }
    j.set("case", casePath).set("sweep", path).set("values", values).set("factor_of_safety", factors);
    if (cracks) j.set("tension_crack_x", crackXs);
    j.set("no_answer", noAnswer).set("all_found", all).set("width", opt.width);
    j.set("forward_runs", runs).set("wall_time_s", wall).set("csv", csv).set("png", png);
    std::printf("%s\n", j.dump().c_str());
  } else {
    std::printf("%d forward runs, %.2f s wall; wrote %s and %s\n", runs, wall, csv.c_str(), png.c_str());
  }
  return all ? kExitOk : kExitNonConvergence;
}

/// Removes the mechanism pictures an earlier command left in `dir`: a report embeds every picture
/// of the folder, and one of another trial would be taken for this result's.
void removeOldMechanismPictures(const std::string& dir) {
  std::error_code ignored;
  for (const char* file : {"mechanism_stable.png", "mechanism_failed.png"})
    std::filesystem::remove(std::filesystem::path(dir) / file, ignored);
}

/// --check F: the trial the search would run at F, judged as the search judges its bracket's
/// failing end, instead of a search: whether the slope meets a required factor of safety.
int fosCheck(const std::string& casePath, const Overrides& o, const FosOptions& opt) {
  ddaslope::model::Scene scene = loadCase(casePath, o);
  if (scene.crackSearch)
    throw ddaslope::InputError(casePath, "section.tension_crack.search",
                               "--check judges one scene, and this case searches its tension crack's position: run fos "
                               "without --check for the least safe position, or check a copy of the case without "
                               "section.tension_crack.search, its crack placed by section.tension_crack.x");
  std::vector<int> joints;
  for (const auto& n : opt.joints) joints.push_back(jointIndex(scene, n, casePath));
  std::vector<std::string> names;
  for (size_t j = 0; j < scene.joints.size(); ++j)
    if (joints.empty() || std::find(joints.begin(), joints.end(), static_cast<int>(j)) != joints.end())
      names.push_back(scene.joints[j].name);
  // A search's results in the default folder are left alone: a check is not a search.
  const std::string outDir = opt.outGiven ? opt.outDir : "out/fos_check";
  const std::string dtWarning = timeStepWarning(scene);
  warnAboutTrials(casePath, dtWarning);
  ddaslope::calibration::SearchSettings s;
  s.threads = 1;
  s.trialStart = trialStartOf(opt.trialStart);
  s.caseLabel = shellWord(casePath);
  recordTrialStates(s, opt.vtkDir, scene);
  MechanismPictures pictures(s, scene);
  const auto t0 = std::chrono::steady_clock::now();
  const ddaslope::calibration::StrengthReductionCheck check =
      ddaslope::calibration::strengthReductionTrial(scene, joints, opt.check, s);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const ddaslope::calibration::TrialResult& r = check.verdict();
  const bool decided = !r.undecided && r.converged;
  const std::string verdict = !r.converged ? "not_converged" : r.undecided ? "undecided" : r.stable ? "stable" : "failing";
  // The picture of a decided trial only: one that could not say is neither the slope standing nor
  // its mechanism.
  removeOldMechanismPictures(outDir);
  const std::vector<std::string> drawn =
      decided ? pictures.write(outDir, casePath, "F", opt.check, opt.check) : std::vector<std::string>{};
  std::vector<std::string> warnings;
  for (std::string w : {ddaslope::calibration::smallMotionWarning(check.runs, "F", shellWord(casePath)),
                        ddaslope::calibration::unrestedEndWarning(check.runs, decided, opt.check, "F", shellWord(casePath),
                                                                  "the trial"),
                        slightBendNote(scene), notchWarning(scene), movedJointWarning(scene), unitsWarning(scene), dtWarning})
    if (!w.empty()) warnings.push_back(std::move(w));
  for (std::string w : contactsAtStartWarnings(scene, joints)) warnings.push_back(std::move(w));
  const int runs = static_cast<int>(check.runs.size());
  {
    ddaslope::io::JsonRecord j;
    j.set("case", casePath).set("check", opt.check).set("joints", names).set("verdict", verdict);
    // Met: stable at F. Not met: failing at F. Null when the trial could not say.
    if (decided) j.set("meets_factor", r.stable);
    else j.set("meets_factor", NAN);  // null
    j.set("forward_runs", runs).set("wall_time_s", wall);
    j.set("settings", settingsLine(scene)).set("trial_start", ddaslope::calibration::name(check.start));
    ddaslope::calibration::appendTrials(j, check.runs, "factor");
    if (!opt.vtkDir.empty()) j.set("vtk", opt.vtkDir);
    j.set("mechanism_pictures", drawn).set("warnings", warnings);
    writeResultFile(outDir + "/fos.json", j.dump() + "\n");
    if (opt.json) std::printf("%s\n", j.dump().c_str());
  }
  if (!opt.json) {
    std::string on;
    for (const auto& n : names) on += (on.empty() ? "" : ", ") + n;
    // The factor as given: the fewest digits that read back as it.
    char f[32];
    for (int digits = 6; digits <= 17; ++digits)
      if (std::snprintf(f, sizeof f, "%.*g", digits, opt.check); std::strtod(f, nullptr) == opt.check) break;
    if (decided)
      std::printf("F = %s %s: the slope %s with its joints' strengths divided by %s as fos reduces them (joints: %s)\n",
                  f, r.stable ? "met" : "not met", r.stable ? "stands" : "fails", f, on.c_str());
    else
      std::printf("F = %s: %s, its joints' strengths divided by %s (joints: %s)\n", f,
                  r.converged ? "undecided" : "the trial did not converge", f, on.c_str());
    std::printf("  why: %s", r.reason);
    if (r.rule == ddaslope::calibration::VerdictRule::MovedWhileSettling)
      std::printf(" (%s by %.3g m)\n", r.movedMost.c_str(), r.settlingDisplacement);
    else if (!r.decidedBy.empty())
      std::printf(" (%s; largest motion %.3g m after t = 0, run to %.4g s)\n", r.decidedBy.c_str(), r.maxDisplacement,
                  r.timeReached);
    else
      std::printf(" (run to %.4g s)\n", r.timeReached);
    if (!r.converged) {
      // The trial itself: its joints and start, and the model options of this command.
      std::string joints;
      for (const auto& n : opt.joints) joints += (joints.empty() ? " --joints " : ",") + n;
      std::printf("  see why with: ddaslope run %s --at-fos %s%s%s --verbose --out DIR (with this command's model "
                  "options)\n",
                  shellWord(casePath).c_str(), f, joints.c_str(),
                  check.start == ddaslope::calibration::TrialStart::Settled ? " --trial-start settled" : "");
    }
    else if (r.undecided)
      std::printf("  a small motion that neither grew nor stopped, also run %g times longer: run fos for F\n",
                  ddaslope::calibration::kReRunLength);
    std::printf("  %d forward run%s, %.2f s wall; %s\n", runs, runs == 1 ? "" : "s", wall, settingsLine(scene).c_str());
    // Said when asked for, as fos says it.
    if (scene.settings.initialEquilibrium && opt.trialStart == "settled")
      std::printf("  %s\n", opt.check == 1 ? "the trial at F = 1 settled from every contact held, as the search's first "
                                             "trial does: the rest the others start from (--trial-start settled) is its own"
                                           : trialStartNote("the trial", check.start, opt.trialStart).c_str());
    std::printf("  one trial says nothing of other factors, and near the slope's F trials can disagree; fos finds F "
                "and checks its trials against each other (docs/calibration.md, \"Checking a required F\")\n");
    for (const auto& d : drawn) std::printf("  the mechanism: %s\n", d.c_str());
  }
  for (const auto& w : warnings)
    if (w != dtWarning) warnAboutTrials(casePath, w);
  return decided ? kExitOk : kExitNonConvergence;
}

}  // namespace

int fosCommand(const std::string& casePath, const Overrides& o, const FosOptions& opt) {
  if (!opt.vtkDir.empty() && !opt.sweep.empty())
    throw ddaslope::InputError("--vtk", opt.vtkDir, "writes the trials of one search, not of a sweep's searches (drop --sweep)");
  if (!opt.sweep.empty()) return fosSweep(casePath, o, opt);
  if (opt.check > 0) return fosCheck(casePath, o, opt);
  ddaslope::model::Scene scene = loadCase(casePath, o);
  // A tension crack searched: F at its least safe position, the search's table printed first.
  // Near the least safe position F is flat (docs/case-format.md, "Tension crack"): the positions
  // are searched ten times finer than the answer, which is cheap beside them.
  FosOptions single = opt;
  single.threads = 1;
  single.vtkDir.clear();
  single.width = std::max(1e-4, opt.width / 10);
  const std::optional<CrackSearch> crack =
      placeCrack(casePath, o, scene, opt.threads, false, single.width, "F", opt.progress, opt.json,
                 [&](const ddaslope::model::Scene& at) {
                   const auto r = factorFor(at, casePath, single);
                   return crackValueOf(r);
                 });
  // Said before the search, whose trials at such a Δt take long, and kept in fos.json.
  const std::string dtWarning = timeStepWarning(scene);
  warnAboutTrials(casePath, dtWarning);
  if (!opt.progress.quiet) saySearchSize(scene);
  const auto log = startProgress("fos", opt.progress, opt.json);
  std::unique_ptr<MechanismPictures> pictures;
  const auto r = factorFor(scene, casePath, opt, ddaslope::io::sinkOf(log.get()), &pictures);
  const std::string& message = r.message;
  log->finish(r.found, r.found ? "F " + std::to_string(r.factor) : message);
  removeOldMechanismPictures(opt.outDir);
  const std::vector<std::string> drawn =
      r.found ? pictures->write(opt.outDir, casePath, "F", r.stableEnd, r.failingEnd) : std::vector<std::string>{};
  // Said on stderr and kept in fos.json, so that a report carries them.
  std::vector<int> joints;
  for (const auto& n : opt.joints) joints.push_back(jointIndex(scene, n, casePath));
  std::vector<std::string> warnings;
  // A horizontal coefficient that pushes against the failure holds the slope back: F rises with it.
  if (const double kh = scene.seismic.kh; kh != 0 && r.found) {
    const double dx = pictures->horizontalMotion(r.failingEnd, scene);
    if (dx * kh < 0) {
      char w[512];
      std::snprintf(w, sizeof w,
                    "k_h = %g is a force along %s, but the failing trial moved the slope along %s (%.3g m): this k_h "
                    "holds the slope back and raises F. A pseudo-static check loads a slope towards its failure "
                    "(--kh %g); `ddaslope critical %s --solve seismic-coefficient` searches both directions",
                    kh, kh > 0 ? "+x" : "-x", kh > 0 ? "-x" : "+x", std::abs(dx), -kh, shellWord(casePath).c_str());
      warnings.push_back(w);
    }
  }
  for (std::string w : {ddaslope::calibration::smallMotionWarning(r.trials, "F", shellWord(casePath)),
                        ddaslope::calibration::unconvergedEndWarning(r.trials, r.found, r.failingEnd, "F", shellWord(casePath)),
                        ddaslope::calibration::unrestedEndWarning(r.trials, r.found, r.failingEnd, "F", shellWord(casePath)),
                        slightBendNote(scene), notchWarning(scene), movedJointWarning(scene), unitsWarning(scene), dtWarning})
    if (!w.empty()) warnings.push_back(std::move(w));
  for (std::string w : contactsAtStartWarnings(scene, joints)) warnings.push_back(std::move(w));
  {
    ddaslope::io::JsonRecord j;
    // No answer, no number: the bracket and the message say what is known.
    j.set("case", casePath).set("found", r.found).set("factor_of_safety", r.found ? r.factor : NAN);
    j.set("bracket", bracketField(r.found, r.stableEnd, r.failingEnd)).set("width", opt.width);
    // The totals, the crack search's included (its own in tension_crack).
    j.set("forward_runs", totalRuns(r.runs, crack)).set("rounds", r.rounds);
    j.set("runs_ahead_unused", r.runsAheadUnused);
    j.set("wall_time_s", totalWallTime(r.wallTime, crack)).set("message", message);
    j.set("settings", settingsLine(scene)).set("trial_start", ddaslope::calibration::name(r.trialStart));
    ddaslope::calibration::appendReview(j, r.review, r.stableEnd, r.failingEnd);
    ddaslope::calibration::appendTrials(j, r.trials, "factor");
    if (!opt.vtkDir.empty()) j.set("vtk", opt.vtkDir);
    j.set("mechanism_pictures", drawn).set("warnings", warnings);
    if (scene.tensionCrack) appendCrackSearch(j, crack ? *crack : CrackSearch{}, scene, "F");
    // The result beside the pictures, for `ddaslope report` and for the record.
    writeResultFile(opt.outDir + "/fos.json", j.dump() + "\n");
    if (opt.json) std::printf("%s\n", j.dump().c_str());
  }
  if (opt.json) {
    // printed above
  } else if (r.found) {
    std::printf("factor of safety (strength reduction on %s): %.4f (stable at %.4f, failing at %.4f)\n",
                opt.joints.empty() ? "all joints" : "the named joints", r.factor, r.stableEnd, r.failingEnd);
    if (!message.empty()) std::printf("  %s\n", message.c_str());
    if (crack)
      std::printf("%s, the answer's %d in %d rounds of %d, %.2f s wall; %s\n", forwardRunsText(r.runs, crack).c_str(),
                  r.runs, r.rounds, opt.threads, totalWallTime(r.wallTime, crack), settingsLine(scene).c_str());
    else
      std::printf("%d forward runs in %d rounds of %d, %.2f s wall; %s\n", r.runs, r.rounds, opt.threads, r.wallTime,
                  settingsLine(scene).c_str());
    // Said when asked for: the default start is the one every figure in the docs was made with.
    if (opt.trialStart == "settled") std::printf("  %s\n", trialStartNote("the trials after the first", r.trialStart, opt.trialStart).c_str());
    printTrialStatesNote(opt.vtkDir, r.runs);
    std::string joints;
    for (const auto& n : opt.joints) joints += (joints.empty() ? " --joints " : ",") + n;
    std::string files;
    for (const auto& f : drawn) files += (files.empty() ? "" : ", ") + f;
    std::printf("  the mechanism: %s (the trials at the bracket's ends); to run its failing end again: ddaslope run "
                "%s --at-fos %.6g%s --out DIR --vtk (with this command's model options%s)\n",
                files.c_str(), casePath.c_str(), r.failingEnd,
                (joints + (r.trialStart == ddaslope::calibration::TrialStart::Settled ? " --trial-start settled" : "")).c_str(),
                crack && crack->result.found ? " and --set section.tension_crack.x at the least safe position" : "");
  } else {
    std::fprintf(stderr, "ddaslope: %s: no factor of safety found after %s: %s\n", casePath.c_str(),
                 forwardRunsText(r.runs, crack).c_str(), message.c_str());
  }
  for (const auto& w : warnings)
    if (w != dtWarning) warnAboutTrials(casePath, w);
  return r.found ? kExitOk : kExitNonConvergence;
}

void addFosOptions(CLI::App* cmd, std::string& casePath, Overrides& overrides, FosOptions& opt) {
  cmd->add_option("case", casePath, "case file (JSON)")->required();
  cmd->add_option("--joints", opt.joints, "joints to reduce (default: all)")->delimiter(',');
  cmd->add_option("--width", opt.width, "final bracket width of F")->capture_default_str()
      ->check(finiteIn(1e-4, 1, "a width of F in [1e-4, 1]"));
  cmd->add_option("--threads", opt.threads, "trial factors per round, run at once")->capture_default_str()->check(CLI::Range(1, 256));
  CLI::Option* sweep =
      cmd->add_option("--sweep", opt.sweep, "json.path=min:max:n: F at n values of one case number (CSV and PNG in --out)");
  CLI::Option* check = cmd->add_option("--check", opt.check,
                                       "whether the slope meets a required F: the trial the search would run at F, "
                                       "judged as the search judges its trials, instead of a search (--out default "
                                       "out/fos_check; docs/calibration.md)")
                           ->check(finiteIn(0.01, 100, "a factor in [0.01, 100]"))
                           ->excludes(sweep);
  cmd->add_option("--out", opt.outDir,
                  "output directory: the mechanism pictures (and --sweep's CSV and PNG; --check's default: out/fos_check)")
      ->capture_default_str()
      ->each([&opt](const std::string&) { opt.outGiven = true; });
  cmd->add_option("--vtk", opt.vtkDir, "write each trial's final state as a VTK series in this folder (ParaView)");
  addTrialStartOption(cmd, opt.trialStart);
  cmd->add_flag("--no-look-ahead", opt.noLookAhead, "run no trial ahead of need: with several threads, the threads a round leaves idle otherwise run the trials the next round may need (the same trials and answer, sooner; docs/calibration.md)");
  addModelOptions(cmd, overrides);
  cmd->add_flag("--json", opt.json, "print the result as JSON");
  addProgressOptions(cmd, opt.progress);
  // What only a search uses: refused with a check, saying why.
  cmd->parse_complete_callback([cmd, check]() {
    if (check->count() == 0) return;
    for (const char* name : {"--width", "--threads", "--no-look-ahead", "--log-json"})
      if (const CLI::Option* other = cmd->get_option_no_throw(name); other && other->count() > 0)
        throw CLI::ValidationError(name, std::string("belongs to a search for F; --check runs the one trial a search "
                                                     "would run at the required F, with no bracket, rounds or progress "
                                                     "log. Drop ") + name + " or --check");
  });
}


}  // namespace ddaslope::cli

#include "probability_command.hpp"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <optional>
#include <set>

#include "ddaslope/calibration/reliability.hpp"
#include "ddaslope/calibration/sample_runner.hpp"
#include "ddaslope/core/errors.hpp"
#include "ddaslope/core/task_farm.hpp"
#include "ddaslope/io/probability_reader.hpp"
#include "ddaslope/io/json_record.hpp"
#include "ddaslope/io/probability_files.hpp"
#include "scene_notes.hpp"

namespace ddaslope::cli {
namespace {

namespace fs = std::filesystem;
using calibration::SampleResult;
using io::checkFingerprint;
using io::exactText;
using io::SampleTable;
using io::settingsFingerprint;
using io::summaryJson;
using io::writeAtomically;
using io::writePictures;

/// The study as the command line changes it: --samples, --seed, --measure, --sampling.
io::ProbabilityJob readStudy(const std::string& path, const ProbabilityOptions& opt) {
  io::ProbabilityJob job = io::readProbabilityJob(path);
  model::ProbabilitySpec& s = job.spec;
  if (opt.samples > 0) s.samples = opt.samples;
  if (opt.seedGiven) s.seed = opt.seed;
  if (!opt.measure.empty())
    s.measure = opt.measure == "fos" ? model::ProbabilityMeasure::FactorOfSafety : model::ProbabilityMeasure::Verdict;
  if (!opt.sampling.empty())
    s.sampling = opt.sampling == "monte_carlo" ? model::Sampling::MonteCarlo : model::Sampling::LatinHypercube;
  if (!opt.method.empty())
    s.method = opt.method == "importance_sampling" ? model::ProbabilityMethod::ImportanceSampling
               : opt.method == "active_learning"   ? model::ProbabilityMethod::ActiveLearning
                                                   : model::ProbabilityMethod::Sampling;
  if (s.method == model::ProbabilityMethod::ActiveLearning && !opt.measure.empty())
    throw InputError("--measure", opt.measure, "active learning searches F at the samples it learns from and judges "
                                               "its confirmations by verdicts: --measure does not apply");
  if (s.method == model::ProbabilityMethod::ImportanceSampling && s.measure == model::ProbabilityMeasure::FactorOfSafety)
    throw InputError(opt.measure.empty() ? job.file : "--measure", opt.measure.empty() ? "probability.measure" : "fos",
                     "importance sampling judges each sample by one forward run's verdict: expected the measure "
                     "verdict, found fos (F's statistics over weighted samples are not computed)");
  return job;
}

/// Builds the scene of a sample: the case with the sample's values at the inputs' paths and the
/// --set numbers, then the job's model choices and the command line's.
struct SceneMaker {
  const io::ProbabilityJob& job;
  const Overrides& overrides;
  io::ParsedCase parsed{job.caseText, job.casePath};  ///< parsed once: a study reads it per sample
  model::Scene operator()(const std::vector<double>& values) const {
    std::vector<io::CaseOverride> extra;
    for (size_t i = 0; i < values.size(); ++i) extra.emplace_back(job.spec.inputs[i].path, values[i]);
    for (auto& m : io::caseOverridesFor(job.model)) extra.push_back(std::move(m));
    return loadParsedCase(parsed, job.casePath, overrides, extra);
  }
};

/// A --set (or --kh, --kv) on an input's path would replace every sample's value: refused.
void refuseFixedInputs(const io::ProbabilityJob& job, const Overrides& o) {
  for (const std::string& text : o.settings) {
    const io::CaseOverride set = parseSetting(text);
    for (const auto& in : job.spec.inputs)
      if (in.path == set.jsonPath)
        throw InputError("--set", text, "\"" + in.path + "\" is an uncertain input of the study: its samples set it "
                                        "(change its distribution in " + job.file + ")");
  }
}

/// The values the study will draw must all be accepted by the case. Checked before any run, on
/// the samples where each input is smallest and largest, with their other inputs: a distribution
/// that reaches an impossible value (a normal cohesion below 0) is refused with what to use
/// instead. ddaslope never clips or redraws a value: the samples are the distribution's.
void checkDrawnValues(const io::ProbabilityJob& job, const calibration::SampleDesign& design, const SceneMaker& make) {
  const int n = design.inputs();
  std::vector<int> lowest(n, 0), highest(n, 0);
  std::vector<double> lo(n, INFINITY), hi(n, -INFINITY);
  for (int k = 0; k < design.samples(); ++k) {
    const std::vector<double> v = design.values(k);
    for (int i = 0; i < n; ++i) {
      if (v[i] < lo[i]) lo[i] = v[i], lowest[i] = k;
      if (v[i] > hi[i]) hi[i] = v[i], highest[i] = k;
    }
  }
  for (int i = 0; i < n; ++i)
    for (int k : {lowest[i], highest[i]}) {
      const std::vector<double> v = design.values(k);
      try {
        make(v);
      } catch (const InputError& e) {
        const model::Distribution& d = job.spec.inputs[i].distribution;
        const bool unbounded = d.kind == model::DistributionKind::Normal;
        throw InputError(job.file, "probability.inputs[" + std::to_string(i) + "]",
                         "sample " + std::to_string(k) + " draws " + job.spec.inputs[i].path + " = " + exactText(v[i]) +
                             ", which the case refuses (" + e.what() + ")" +
                             (unbounded ? ". A normal distribution has no bounds: use truncated_normal with min "
                                          "and/or max at the physical limits, or lognormal for a positive value"
                                        : ". Bound the distribution within what the case accepts"));
      }
    }
}

/// Active learning classifies population points it never runs: each must be a scene the case
/// accepts, or a refused combination (a residual friction angle drawn above the peak) would be
/// counted silently. Every point is read before any run; the lowest refused index is named,
/// whatever the thread count.
void checkEveryPoint(const io::ProbabilityJob& job, const calibration::SampleDesign& design, const SceneMaker& make,
                     int threads, io::ProgressLog& log) {
  constexpr int kChunk = 1024;
  const int chunks = (design.samples() + kChunk - 1) / kChunk;
  std::vector<int> refused(static_cast<size_t>(chunks), -1);
  std::vector<std::string> why(static_cast<size_t>(chunks));
  std::atomic<int> read{0}, chunksRead{0};
  runOnThreads(chunks, threads, [&](int c) {
    const int end = std::min(design.samples(), (c + 1) * kChunk);
    for (int k = c * kChunk; k < end; ++k) {
      try {
        make(design.values(k));
      } catch (const InputError& e) {
        refused[static_cast<size_t>(c)] = k;
        why[static_cast<size_t>(c)] = e.what();
        return;
      }
    }
    const int done = read += end - c * kChunk;
    // Every 16 chunks: a million points make a thousand chunks.
    if (const int n = ++chunksRead; log.active() && (n % 16 == 0 || n == chunks))
      log.report({"reading points", done, design.samples(), "each point's values read by the case", {}});
  });
  for (int c = 0; c < chunks; ++c)
    if (refused[static_cast<size_t>(c)] >= 0) {
      const int k = refused[static_cast<size_t>(c)];
      std::string values;
      const std::vector<double> v = design.values(k);
      for (size_t i = 0; i < v.size(); ++i)
        values += (i ? ", " : "") + job.spec.inputs[i].path + " = " + exactText(v[i]);
      throw InputError(job.file, "probability.inputs",
                       "population point " + std::to_string(k) + " draws " + values + ", a combination the case refuses (" +
                           why[static_cast<size_t>(c)] + "). Bound the inputs so that every combination is accepted");
    }
}

/// The --out folder, made before any run so that no run's work is lost to an unusable path.
void makeOutputFolder(const std::string& dir) {
  std::error_code made;
  fs::create_directories(dir, made);
  if (made || !fs::is_directory(dir))
    throw InputError("--out", dir, "cannot create the folder" + (made ? ": " + made.message() : std::string()));
}

/// Every file a study of any method writes in its folder: what --overwrite removes, so that no
/// result of the study replaced is left beside the new one's.
void removeStudyFiles(const std::string& dir) {
  for (const char* name : {"samples.csv", "probability_settings.json", "summary.json", "summary.partial.json",
                           "pf_convergence.png", "samples_plane.png", "fos_histogram.png", "sensitivities.png",
                           "learning.csv", "learning_runs.csv", "report.html"})
    fs::remove(dir + "/" + name);
}

/// The study's folder: a study there is continued (--resume), replaced (--overwrite) or kept (an
/// error, so that no sample is ever lost). Returns the samples it holds (resumed).
std::vector<SampleResult> prepareFolder(const ProbabilityOptions& opt, SampleTable& table,
                                        const calibration::SampleDesign& design, const std::string& fingerprint) {
  fs::create_directories(opt.outDir);
  const std::string fingerprintPath = opt.outDir + "/probability_settings.json";
  if (fs::exists(table.path()) && !opt.resume && !opt.overwrite)
    throw InputError(table.path(), "", "holds the samples of a study already: --resume continues it, --overwrite "
                                       "starts again");
  if (opt.overwrite) removeStudyFiles(opt.outDir);
  std::vector<SampleResult> done;
  if (opt.resume && fs::exists(table.path())) {
    checkFingerprint(fingerprintPath, fingerprint);
    done = table.read(design);
  }
  writeAtomically(fingerprintPath, fingerprint);
  return done;
}

/// FORM's design point of the study (docs/probability.md, *Importance sampling*), found with
/// forward runs' verdicts, and what the summary reports of it.
io::DesignPointReport designPoint(const calibration::SampleDesign& design, const SceneMaker& make,
                                  const calibration::SampleSettings& settings, int threads) {
  calibration::LimitState limit;
  limit.dimensions = design.inputs();
  limit.accepts = [&](const std::vector<double>& u) {
    try {
      make(design.valuesAt(u));
      return true;
    } catch (const InputError&) {
      return false;
    }
  };
  limit.judge = [&](const std::vector<double>& u) {
    const std::vector<double> values = design.valuesAt(u);
    model::Scene scene;
    try {
      scene = make(values);
    } catch (const InputError&) {
      // A combination the case refuses inside a ray's reach: counted as failing, which only
      // moves the sampling centre (the samples themselves are checked before they run).
      return calibration::PointVerdict::NotConverged;
    }
    const SampleResult r = calibration::evaluateSample(scene, settings, -1, values);
    return r.outcome == calibration::SampleOutcome::Stable ? calibration::PointVerdict::Stable
           : r.outcome == calibration::SampleOutcome::Fails ? calibration::PointVerdict::Fails
                                                            : calibration::PointVerdict::NotConverged;
  };
  calibration::DesignPointSettings s;
  s.threads = threads;
  io::DesignPointReport report;
  report.point = calibration::findDesignPoint(limit, s);
  if (!report.point.found) return report;
  report.values = design.valuesAt(report.point.u);
  report.importance = calibration::importanceVector(report.point.alpha, design.cholesky());
  return report;
}

/// The design point's inputs, α, γ and γ², one line each.
void printSensitivities(const io::ProbabilityJob& job, const io::DesignPointReport& d) {
  std::printf("    %-44s %14s %9s %9s %8s\n", "input", "value", "alpha", "gamma", "gamma^2");
  for (size_t i = 0; i < d.values.size(); ++i)
    std::printf("    %-44s %14.6g %9.4f %9.4f %7.1f%%\n", job.spec.inputs[i].path.c_str(), d.values[i], d.point.alpha[i],
                d.importance[i], 100 * d.importance[i] * d.importance[i]);
}

void printDesignPoint(const io::ProbabilityJob& job, const io::DesignPointReport& d) {
  const calibration::DesignPoint& p = d.point;
  std::printf("  design point (FORM): β = %.4f, Pf ≈ Φ(−β) = %.4g; %d forward runs on %d rays, %d secant steps%s\n",
              p.beta, calibration::normalCdf(-p.beta), p.runs, p.rays, p.steps,
              p.converged ? "" : " (the direction did not settle: the sampling centre is the nearest point found)");
  printSensitivities(job, d);
  if (!p.otherRegions.empty())
    std::fprintf(stderr, "ddaslope: warning: %s: failure was also found in %zu direction(s) more than 90° from the "
                         "design point's: importance sampling around one point may miss their share of Pf (compare "
                         "with \"method\": \"sampling\")\n",
                 job.file.c_str(), p.otherRegions.size());
}

void printStudy(const io::ProbabilityJob& job);

/// A study's runs, stopped by --stop-after: the learning ends here, and --resume replays them.
struct StopAfterReached {};

/// Active learning's runs (searches and verdicts) as the learning asks for them: each one a
/// journal holds (a resumed study) is replayed, the others run on the task farm (threads, or MPI
/// ranks) and are journalled as they finish; --stop-after ends the learning past its count.
class LearningRuns {
 public:
  LearningRuns(TaskFarm& farm, io::LearningJournal* journal, const calibration::ActiveLearningProblem& problem,
               int stopAfter)
      : farm_(farm), journal_(journal), problem_(problem), stopAfter_(stopAfter) {}

  /// The task of a run: index 2k is the search at population point k, 2k + 1 its verdict.
  TaskResult run(int task) const {
    const int k = task / 2;
    if (task % 2 == 0) {
      const calibration::PerformanceValue v = problem_.evaluate(k);
      return std::string(1, v.converged ? 'c' : 'n') + (v.fails ? 'f' : 's') + std::to_string(v.runs) + "," +
             exactText(v.margin);
    }
    const calibration::PointVerdict v = problem_.judge(k);
    return std::string(1, v == calibration::PointVerdict::Stable ? 's' : v == calibration::PointVerdict::Fails ? 'f' : 'n');
  }

  void replay(const std::vector<io::LearningRun>& runs) {
    for (const io::LearningRun& r : runs) (r.search ? searched_ : judged_)[r.index] = r;
  }
  int replayed() const { return replayed_; }
  int ranNow() const { return ranNow_; }
  /// Called as each run finishes: its kind, and how many of this batch's runs are done.
  std::function<void(bool search, int done, int of)> onFinished;

  std::vector<calibration::PerformanceValue> searches(const std::vector<int>& points) {
    std::vector<calibration::PerformanceValue> out;
    for (const io::LearningRun& r : batch(points, true)) out.push_back(r.value);
    return out;
  }
  std::vector<calibration::PointVerdict> verdicts(const std::vector<int>& points) {
    std::vector<calibration::PointVerdict> out;
    for (const io::LearningRun& r : batch(points, false)) out.push_back(r.verdict);
    return out;
  }

 private:
  std::vector<io::LearningRun> batch(const std::vector<int>& points, bool search) {
    std::map<int, io::LearningRun>& known = search ? searched_ : judged_;
    std::vector<int> tasks;
    int replayedHere = 0;
    for (int k : points)
      if (known.count(k))
        ++replayedHere;
      else
        tasks.push_back(2 * k + (search ? 0 : 1));
    replayed_ += replayedHere;
    const bool stopping = stopAfter_ > 0 && ranNow_ + static_cast<int>(tasks.size()) > stopAfter_;
    if (stopping) tasks.resize(static_cast<size_t>(std::max(0, stopAfter_ - ranNow_)));
    int done = 0;
    if (!tasks.empty()) {
      farm_.another(true);
      farm_.run(tasks, [this](int t) { return run(t); }, [&](int t, const TaskResult& bytes) {
        io::LearningRun r;
        r.search = t % 2 == 0;
        r.index = t / 2;
        if (r.search) {
          r.value.converged = bytes[0] == 'c';
          r.value.fails = bytes[1] == 'f';
          const size_t comma = bytes.find(',');
          std::from_chars(bytes.data() + 2, bytes.data() + comma, r.value.runs);
          std::from_chars(bytes.data() + comma + 1, bytes.data() + bytes.size(), r.value.margin);
        } else {
          r.verdict = bytes[0] == 's'   ? calibration::PointVerdict::Stable
                      : bytes[0] == 'f' ? calibration::PointVerdict::Fails
                                        : calibration::PointVerdict::NotConverged;
        }
        if (journal_) journal_->append(r);
        known[r.index] = r;
        ++ranNow_;
        if (onFinished) onFinished(r.search, replayedHere + ++done, static_cast<int>(points.size()));
      });
    }
    if (stopping) throw StopAfterReached{};
    std::vector<io::LearningRun> out;
    for (int k : points) out.push_back(known.at(k));
    return out;
  }

  TaskFarm& farm_;
  io::LearningJournal* journal_;
  const calibration::ActiveLearningProblem& problem_;
  int stopAfter_;
  std::map<int, io::LearningRun> searched_, judged_;
  int replayed_ = 0, ranNow_ = 0;
};

/// The study by active learning (calibration/active_learning.hpp): a population of `samples`
/// points classified by a surrogate of F learnt from searches, confirmed by forward runs. Every
/// process builds the same population; the root learns and deals the runs, the others run them.
int activeLearningStudy(const io::ProbabilityJob& job, const SceneMaker& make, const calibration::SampleSettings& fos,
                        const model::Scene& reference, const ProbabilityOptions& opt,
                        const std::vector<std::string>& caseSettings, std::chrono::steady_clock::time_point t0) {
  const model::ProbabilitySpec& spec = job.spec;
  const calibration::SampleDesign design(spec);
  const int initial = calibration::initialSearches(design.inputs());
  if (spec.samples <= initial)
    throw InputError(opt.samples > 0 ? "--samples" : job.file, opt.samples > 0 ? std::to_string(opt.samples) : "probability.samples",
                     "active learning classifies a population larger than its " + std::to_string(initial) +
                         " first searches: expected more than " + std::to_string(initial) + " points, found " +
                         std::to_string(spec.samples) + " (for so few, sampling runs every one)");
  const bool root = processRank() == 0;
  const std::string journalPath = opt.outDir + "/learning_runs.csv";
  // Nothing is lost: a folder that holds any study's runs is kept unless --overwrite (or, for an
  // active-learning study, --resume), and the folder must be writable before the runs begin.
  if (root && fs::exists(opt.outDir + "/samples.csv") && !opt.overwrite)
    throw InputError(opt.outDir + "/samples.csv", "", "holds the samples of a sampling study: --overwrite starts again");
  for (const char* held : {"learning.csv", "learning_runs.csv"})
    if (root && fs::exists(opt.outDir + "/" + held) && !opt.overwrite && !opt.resume)
      throw InputError(opt.outDir + "/" + held, "", "holds the runs of an active-learning study already: --resume "
                                                    "continues it, --overwrite starts again");
  checkDrawnValues(job, design, make);
  const auto log = startProgress("probability", opt.progress, opt.json);
  if (root) checkEveryPoint(job, design, make, opt.threads, *log);
  const std::string line = settingsLine(reference);
  calibration::SampleSettings verdict = fos;
  verdict.measure = model::ProbabilityMeasure::Verdict;
  calibration::ActiveLearningProblem problem;
  problem.population.resize(design.inputs(), design.samples());
  for (int k = 0; k < design.samples(); ++k) {
    const std::vector<double> u = design.independent(k);
    for (int i = 0; i < design.inputs(); ++i) problem.population(i, k) = u[static_cast<size_t>(i)];
  }
  const auto sceneOf = [&](int k) {
    try {
      return make(design.values(k));
    } catch (const InputError& e) {  // a combination of values the case refuses
      throw InputError(job.file, "probability", "sample " + std::to_string(k) + " cannot be run: " + e.what());
    }
  };
  problem.evaluate = [&](int k) {
    const SampleResult r = calibration::evaluateSample(sceneOf(k), fos, k, design.values(k));
    calibration::PerformanceValue v;
    v.converged = r.outcome != calibration::SampleOutcome::NotConverged && std::isfinite(r.factor);
    v.margin = v.converged ? r.factor - 1 : 0;
    v.fails = r.outcome == calibration::SampleOutcome::Fails;
    v.runs = r.runs;
    return v;
  };
  problem.judge = [&](int k) {
    const SampleResult r = calibration::evaluateSample(sceneOf(k), verdict, k, design.values(k));
    return r.outcome == calibration::SampleOutcome::Stable ? calibration::PointVerdict::Stable
           : r.outcome == calibration::SampleOutcome::Fails ? calibration::PointVerdict::Fails
                                                            : calibration::PointVerdict::NotConverged;
  };
  const std::unique_ptr<TaskFarm> farm = makeTaskFarm(opt.threads);
  if (!farm->isRoot()) {
    LearningRuns runs(*farm, nullptr, problem, 0);
    while (farm->another(false)) farm->run({}, [&](int t) { return runs.run(t); }, {});
    return kExitOk;
  }

  makeOutputFolder(opt.outDir);
  if (opt.overwrite) removeStudyFiles(opt.outDir);
  // What the result depends on (the case's digest, --set, the forward runs' settings, the
  // population): a resumed study must match it.
  const std::string fingerprint = settingsFingerprint(job, caseSettings, line);
  const std::string fingerprintPath = opt.outDir + "/probability_settings.json";
  io::LearningJournal journal(journalPath);
  std::vector<io::LearningRun> earlier;
  const bool resuming = opt.resume && fs::exists(journalPath);
  if (resuming) {
    checkFingerprint(fingerprintPath, fingerprint, "runs");
    earlier = journal.read(design.samples());
  }
  writeAtomically(fingerprintPath, fingerprint);
  journal.open();
  LearningRuns runs(*farm, &journal, problem, opt.stopAfter);
  runs.replay(earlier);
  problem.evaluateAll = [&](const std::vector<int>& points) { return runs.searches(points); };
  problem.judgeAll = [&](const std::vector<int>& points) { return runs.verdicts(points); };

  calibration::ActiveLearningSettings settings;
  settings.threads = opt.threads;
  settings.resolution = spec.fosWidth / 4;
  if (!opt.json) {
    printStudy(job);
    std::printf("  forward runs at %s, on %s\n", line.c_str(), farm->describe().c_str());
    std::printf("  learning F on %d population points: searches at the points the surrogate is least sure of, %d "
                "per round\n", design.samples(), settings.batch);
    if (resuming)
      std::printf("  resumed: %zu searches and verdicts in %s, replayed\n", earlier.size(), journalPath.c_str());
    else if (opt.resume)
      std::printf("  resumed: no %s yet, so the study starts\n", journalPath.c_str());
    std::fflush(stdout);
  }
  int searchesSoFar = 0, verdictsSoFar = 0;
  settings.progress = [&](int searches, int verdicts, int unsure) {
    searchesSoFar = searches, verdictsSoFar = verdicts;
    if (!log->active()) return;
    char text[96];
    std::snprintf(text, sizeof text, "%d verdicts; %d points unsure", verdicts, unsure);
    log->report({"searches", searches, settings.maxSearches, text, {{"unsure_points", unsure}}});
  };
  // The verdicts that decide the unsure points come in one batch of up to a few hundred runs.
  runs.onFinished = [&](bool search, int done, int of) {
    if (search || !log->active()) return;
    char text[96];
    std::snprintf(text, sizeof text, "%d searches; verdicts of the unsure points and confirmations", searchesSoFar);
    log->report({"verdicts", verdictsSoFar + done, verdictsSoFar + of, text, {}});
  };
  calibration::ActiveLearningResult r;
  try {
    r = calibration::learnFailureDomain(problem, settings);
  } catch (const StopAfterReached&) {
    farm->another(false);
    log->finish(false, std::to_string(runs.ranNow()) + " searches and verdicts made now");
    if (opt.json) {
      io::JsonRecord j;
      j.set("method", "active_learning").set("complete", false).set("runs_made_now", runs.ranNow());
      j.set("runs_replayed", runs.replayed()).set("journal", journalPath);
      std::printf("%s\n", j.dump().c_str());
    } else {
      std::printf("  incomplete: %d searches and verdicts made now (--stop-after %d), %d replayed; wrote %s; --resume "
                  "continues\n",
                  runs.ranNow(), opt.stopAfter, runs.replayed(), journalPath.c_str());
    }
    return kExitOk;
  } catch (...) {
    // The other ranks wait for the next round: they are told there is none, unless the error
    // came from a run and they met it already (an error's exit code ends them, or MPI_Abort).
    if (!errorSharedByAllProcesses()) farm->another(false);
    throw;
  }
  farm->another(false);
  log->finish(r.message.empty(), std::to_string(r.searches) + " searches, " + std::to_string(r.verdicts) + " verdicts");
  if (!r.message.empty()) {
    // Nothing to classify with: no Pf is written.
    std::fprintf(stderr, "ddaslope: %s: active learning could not start: %s\n", job.file.c_str(), r.message.c_str());
    return kExitNonConvergence;
  }
  std::optional<io::DesignPointReport> point;
  const calibration::DesignPoint surrogatePoint = calibration::surrogateDesignPoint(problem, r);
  const std::string designMessage = surrogatePoint.message;
  if (surrogatePoint.found)
    point = io::DesignPointReport{surrogatePoint, design.valuesAt(surrogatePoint.u),
                                  calibration::importanceVector(surrogatePoint.alpha, design.cholesky())};
  const io::DesignPointReport* pointReport = point ? &*point : nullptr;
  for (const char* name : {"samples.csv", "summary.partial.json", "pf_convergence.png", "fos_histogram.png",
                           "sensitivities.png", "samples_plane.png", "report.html"})
    fs::remove(opt.outDir + "/" + name);
  const std::string json = io::activeLearningSummaryJson(job, r, line, pointReport, designMessage);
  const std::vector<std::string> files = io::writeActiveLearningFiles(job, design, r, opt.outDir, pointReport);
  writeAtomically(opt.outDir + "/summary.json", json);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const calibration::LearnedProbability p = calibration::probabilityOf(r);
  if (opt.json) {
    std::printf("%s", json.c_str());
  } else {
    char cov[48] = "none (no point fails)";
    if (std::isfinite(p.coefficientOfVariation)) std::snprintf(cov, sizeof cov, "%.3f", p.coefficientOfVariation);
    std::printf("  Pf = %.4g: %d of %d population points classified failing; 95 %% interval %.4g-%.4g (Wilson, the "
                "population's sampling error), coefficient of variation %s\n",
                p.pf, r.failing, p.converged, p.interval.low, p.interval.high, cov);
    if (std::isfinite(p.beta))
      std::printf("  reliability index β = Φ⁻¹(1 − Pf) = %.4g (%.4g to %.4g)\n", p.beta, p.betaInterval.low,
                  p.betaInterval.high);
    else if (p.converged > 0)
      std::printf("  reliability index β = Φ⁻¹(1 − Pf): %s (%s %.4g with 95 %% confidence)\n",
                  p.pf == 0 ? "unbounded, no point fails" : "-∞, every point fails", p.pf == 0 ? "at least" : "at most",
                  p.pf == 0 ? p.betaInterval.low : p.betaInterval.high);
    std::printf("  forward runs: %d in %d searches of F and %d verdicts; %d surrogate fits\n", r.searchRuns + r.verdicts,
                r.searches, r.verdicts, r.rounds);
    std::printf("  verdicts: %d decided points the surrogate was unsure of (U < 2), %d confirmed points it was sure "
                "of, %d of which contradicted it (and were searched)\n",
                r.decidedByVerdict, r.verdicts - r.decidedByVerdict, r.disagreements);
    if (r.learnt && std::isfinite(r.minU))
      std::printf("  learnt: every point not run has U ≥ 2 (least %.3g), and the last verdicts agreed with the "
                  "surrogate\n", r.minU);
    else if (r.learnt)
      std::printf("  learnt: every point was run\n");
    if (!point)
      std::printf("  design point: none (%s), so no sensitivities\n", designMessage.c_str());
    if (point) {
      std::printf("  design point of the surrogate (its margin 0 nearest the medians, no forward run): β = %.4f, "
                  "Φ(−β) = %.4g\n", point->point.beta, calibration::normalCdf(-point->point.beta));
      printSensitivities(job, *point);
    }
    std::printf("  not converged: %d\n", r.notConverged);
    std::printf("  %.2f s wall on %s (%d searches and verdicts made now, %d replayed); wrote %s/summary.json", wall,
                farm->describe().c_str(), runs.ranNow(), runs.replayed(), opt.outDir.c_str());
    for (const auto& f : files) std::printf(", %s", f.c_str());
    std::printf("\n");
  }
  if (!r.learnt)
    std::fprintf(stderr, "ddaslope: warning: %s: the learning stopped at its budget of %s with %d population points "
                         "still unsure (U < 2, least %.3g): Pf lies within the bounds %.4g-%.4g of the summary\n",
                 job.file.c_str(), r.stoppedBy == "verdicts" ? "2000 verdicts" : "200 searches",
                 r.unsureFailing + r.unsureStable, r.minU, p.bounds.low, p.bounds.high);
  if (r.notConverged > 0)
    std::fprintf(stderr, "ddaslope: warning: %s: %d runs did not converge: counted apart (learning.csv), Pf's bounds "
                         "with them are in the summary\n",
                 job.file.c_str(), r.notConverged);
  // The population sets Pf's precision: N ≈ (1 − Pf)/(Pf·CoV²) for a coefficient of variation CoV.
  if (r.failing == 0)
    std::fprintf(stderr, "ddaslope: warning: %s: no point of the population fails: Pf < %.3g (95 %%); a larger "
                         "population (--samples) or importance_sampling resolves a smaller Pf\n",
                 job.file.c_str(), p.interval.high);
  else if (p.coefficientOfVariation > 0.1 && (1 - p.pf) / (p.pf * 0.01) <= 1e6)
    std::fprintf(stderr, "ddaslope: warning: %s: Pf's coefficient of variation is %.2f with %d population points; "
                         "about %.0f give 0.1 (--samples)\n",
                 job.file.c_str(), p.coefficientOfVariation, p.converged, std::ceil((1 - p.pf) / (p.pf * 0.01)));
  else if (p.coefficientOfVariation > 0.1)
    std::fprintf(stderr, "ddaslope: warning: %s: Pf's coefficient of variation is %.2f with %d population points; a "
                         "coefficient of 0.1 needs more than the 1000000 points allowed: use importance_sampling\n",
                 job.file.c_str(), p.coefficientOfVariation, p.converged);
  return kExitOk;
}

void printStudy(const io::ProbabilityJob& job) {
  const model::ProbabilitySpec& s = job.spec;
  if (s.method == model::ProbabilityMethod::ActiveLearning)
    std::printf("probability of failure: %s (%s), active_learning (searches of F to %g, confirmation verdicts), "
                "population of %d %s points, seed %llu\n",
                job.casePath.c_str(), job.file.c_str(), s.fosWidth, s.samples, calibration::name(s.sampling),
                static_cast<unsigned long long>(s.seed));
  else
    std::printf("probability of failure: %s (%s), %s, measure %s, %s, %d samples, seed %llu\n", job.casePath.c_str(),
                job.file.c_str(), calibration::name(s.method), calibration::name(s.measure),
                calibration::name(s.sampling), s.samples, static_cast<unsigned long long>(s.seed));
  for (const auto& in : s.inputs)
    std::printf("  %s: %s\n", in.path.c_str(), calibration::describe(in.distribution).c_str());
  for (const auto& c : s.correlations)
    std::printf("  correlation %g between %s and %s (of the underlying normals)\n", c.rho, s.inputs[c.a].path.c_str(),
                s.inputs[c.b].path.c_str());
}

void printSummary(const calibration::ProbabilitySummary& s) {
  if (s.converged == 0) {
    std::printf("  no sample converged: no probability of failure\n");
  } else {
    if (s.weighted && std::isfinite(s.pfInterval.high))
      std::printf("  Pf = %.4g (importance sampling: %d of %d converged samples fail, weighted); standard error "
                  "%.3g, coefficient of variation %.3f; 95 %% interval %.4g-%.4g (normal approximation)\n",
                  s.pf, s.failures, s.converged, s.pfStandardError, s.coefficientOfVariation, s.pfInterval.low,
                  s.pfInterval.high);
    else if (s.weighted)
      std::printf("  Pf: no estimate, none of %d importance samples fails (the design point is not where failure "
                  "is)\n", s.converged);
    else
      std::printf("  Pf = %.4g: %d of %d converged samples fail; 95 %% interval %.4g-%.4g (Wilson score)\n", s.pf,
                  s.failures, s.converged, s.pfInterval.low, s.pfInterval.high);
    if (std::isfinite(s.beta))
      std::printf("  reliability index β = Φ⁻¹(1 − Pf) = %.4g (%.4g to %.4g)\n", s.beta, s.betaInterval.low,
                  s.betaInterval.high);
    else
      std::printf("  reliability index β = Φ⁻¹(1 − Pf): %s (%s %.4g with 95 %% confidence)\n",
                  s.pf == 0 ? "unbounded, no sample fails" : "-∞, every sample fails", s.pf == 0 ? "at least" : "at most",
                  s.pf == 0 ? s.betaInterval.low : s.betaInterval.high);
  }
  if (s.hasFactor && s.converged > 0)
    std::printf("  F: mean %.4f ± %.4f (standard error), sd %.4f, median %.4f, range %.4f-%.4f; β = (mean F − 1)/sd F "
                "= %.4g\n",
                s.factorMean, s.factorMeanError, s.factorSd, s.factorMedian, s.factorMin, s.factorMax, s.betaMoments);
  if (s.notConverged > 0)
    std::printf("  not converged: %d samples, not counted above; counted as stable Pf = %.4g, as failing %.4g; 95 %% "
                "bounds with them %.4g-%.4g\n",
                s.notConverged, s.pfNotConvergedStable, s.pfNotConvergedFailing, s.pfBounds.low, s.pfBounds.high);
  else
    std::printf("  not converged: none\n");
  std::string rules;
  for (const auto& [rule, count] : s.rules) rules += (rules.empty() ? "" : ", ") + rule + " " + std::to_string(count);
  std::printf("  deciding rules: %s\n", rules.c_str());
}

}  // namespace

void addProbabilityOptions(CLI::App* cmd, std::string& path, ProbabilityOptions& opt) {
  cmd->add_option("case", path, "a case with a \"probability\" section, or a probability job (JSON)")->required();
  cmd->add_option("--out", opt.outDir, "output directory: samples.csv, summary.json, pictures")->capture_default_str();
  cmd->add_option("--samples", opt.samples, "number of samples N (default: the section's)")->check(CLI::Range(1, 1000000));
  cmd->add_option_function<std::uint64_t>("--seed", [&opt](std::uint64_t s) { opt.seed = s, opt.seedGiven = true; },
                                          "seed of the samples' random numbers (default: the section's)")
      ->check(CLI::Validator(
          [](std::string& text) -> std::string {
            std::uint64_t v = 0;
            const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
            const bool ok = ec == std::errc() && end == text.data() + text.size();
            return ok ? "" : "expected a whole number 0 to 2^64 - 1, found " + text;
          },
          "0 to 2^64 - 1"));
  cmd->add_option("--measure", opt.measure, "verdict (one run per sample) or fos (a strength-reduction search per sample)")
      ->check(CLI::IsMember({"verdict", "fos"}));
  cmd->add_option("--method", opt.method,
                  "sampling (from the inputs' distribution), importance_sampling (around FORM's design point: "
                  "small Pf) or active_learning (a surrogate of F learnt from searches: small Pf, any number of "
                  "failure regions); default: the section's")
      ->check(CLI::IsMember({"sampling", "importance_sampling", "active_learning"}));
  cmd->add_option("--sampling", opt.sampling, "monte_carlo or latin_hypercube (default: the section's)")
      ->check(CLI::IsMember({"monte_carlo", "latin_hypercube"}));
  cmd->add_option("--threads", opt.threads, "samples run at once (the result does not depend on it)")
      ->capture_default_str()
      ->check(CLI::Range(1, 256));
  cmd->add_flag("--resume", opt.resume, "continue the study in --out: run only the samples samples.csv lacks (active learning: the runs learning_runs.csv lacks)");
  cmd->add_flag("--overwrite", opt.overwrite, "start again in an --out that holds a study (its samples are lost)");
  cmd->add_option("--stop-after", opt.stopAfter, "run at most this many samples (active learning: searches and verdicts) now; --resume continues")
      ->check(CLI::Range(1, 1000000));
  cmd->add_flag("--json", opt.json, "print the summary as JSON");
  addProgressOptions(cmd, opt.progress);
}

int probabilityCommand(const std::string& path, const Overrides& o, const ProbabilityOptions& opt) {
  if (opt.resume && opt.overwrite) throw InputError("--resume", "", "--resume and --overwrite exclude each other");
  const auto t0 = std::chrono::steady_clock::now();
  const io::ProbabilityJob job = readStudy(path, opt);
  const model::ProbabilitySpec& spec = job.spec;
  refuseFixedInputs(job, o);
  const SceneMaker make{job, o};
  const model::Scene reference = loadCase(job.casePath, o, io::caseOverridesFor(job.model));
  std::vector<std::string> sampled;
  for (const auto& input : spec.inputs) sampled.push_back(input.path);
  if (processRank() == 0) warnAboutTrials(job.casePath, fixedCrackNote(reference, sampled));
  calibration::SampleSettings settings;
  settings.measure = spec.method == model::ProbabilityMethod::ActiveLearning ? model::ProbabilityMeasure::FactorOfSafety
                                                                            : spec.measure;
  settings.fosWidth = spec.fosWidth;
  for (const auto& name : spec.fosJoints) settings.fosJoints.push_back(jointIndex(reference, name, job.casePath));
  if (spec.method == model::ProbabilityMethod::ActiveLearning)
    return activeLearningStudy(job, make, settings, reference, opt, o.settings, t0);
  calibration::SampleDesign design(spec);
  // A folder holding a study is refused before anything runs (the design point's runs included).
  // The root alone keeps the folder: under mpirun the others would see the file it has just begun.
  if (processRank() == 0 && fs::exists(opt.outDir + "/samples.csv") && !opt.resume && !opt.overwrite)
    throw InputError(opt.outDir + "/samples.csv", "", "holds the samples of a study already: --resume continues it, "
                                                      "--overwrite starts again");
  for (const char* held : {"learning.csv", "learning_runs.csv"})
    if (processRank() == 0 && fs::exists(opt.outDir + "/" + held) && !opt.overwrite)
      throw InputError(opt.outDir + "/" + held, "", "holds the runs of an active-learning study: --overwrite "
                                                       "starts again");
  if (processRank() == 0) makeOutputFolder(opt.outDir);
  std::optional<io::DesignPointReport> form;
  if (spec.method == model::ProbabilityMethod::ImportanceSampling) {
    // Every process finds the same design point (its runs depend on the study only), so the
    // samples it deals need nothing but their index.
    if (processRank() == 0 && !opt.json)
      std::printf("probability of failure: searching the design point (FORM) of %s with forward runs, %d at once\n",
                  job.casePath.c_str(), std::min(opt.threads, 2));
    std::fflush(stdout);
    form = designPoint(design, make, settings, opt.threads);
    if (!form->point.found) {
      std::fprintf(stderr, "ddaslope: %s: no design point: %s (%d forward run%s)\n", job.file.c_str(),
                   form->point.message.c_str(), form->point.runs, form->point.runs == 1 ? "" : "s");
      return kExitNonConvergence;
    }
    design.centreOn(form->point.u);
  }
  checkDrawnValues(job, design, make);
  const std::string line = settingsLine(reference);
  // One sample's run: the same on any thread or rank (its values come from its index).
  const TaskFarm::Task runSample = [&](int k) {
    const std::vector<double> values = design.values(k);
    model::Scene scene;
    try {
      scene = make(values);
    } catch (const InputError& e) {  // a combination of values the case refuses
      throw InputError(job.file, "probability", "sample " + std::to_string(k) + " cannot be run: " + e.what());
    }
    return calibration::packSample(calibration::evaluateSample(scene, settings, k, values));
  };
  const std::unique_ptr<TaskFarm> farm = makeTaskFarm(opt.threads);
  if (!farm->isRoot()) {
    // Under mpirun the other ranks run the samples rank 0 deals; it alone keeps the study folder.
    farm->run({}, runSample, {});
    return kExitOk;
  }

  const std::string csv = opt.outDir + "/samples.csv";
  const std::string summaryPath = opt.outDir + "/summary.json", partialPath = opt.outDir + "/summary.partial.json";
  SampleTable table(csv, spec);
  std::vector<SampleResult> done =
      prepareFolder(opt, table, design, settingsFingerprint(job, o.settings, line, design.centre()));
  std::set<int> have;
  for (const auto& r : done) have.insert(r.index);
  std::vector<int> todo;
  for (int k = 0; k < spec.samples && (opt.stopAfter == 0 || static_cast<int>(todo.size()) < opt.stopAfter); ++k)
    if (!have.count(k)) todo.push_back(k);
  const int resumed = static_cast<int>(done.size());
  if (!opt.json) {
    printStudy(job);
    if (form) printDesignPoint(job, *form);
    std::printf("  forward runs at %s\n", line.c_str());
    if (opt.resume) std::printf("  resumed: %d samples in %s, %zu to run now\n", resumed, csv.c_str(), todo.size());
  }

  // The samples: CSV rows in completion order; everything else from the samples sorted by index.
  if (!todo.empty()) fs::remove(summaryPath);
  const auto log = startProgress("probability", opt.progress, opt.json);
  // Pf so far over every finished sample, a resumed study's earlier ones included.
  int failing = 0, finished = 0;
  for (const SampleResult& r : done) failing += r.outcome == calibration::SampleOutcome::Fails;
  double sampleTime = 0;
  table.open();
  farm->run(todo, runSample, [&](int, const TaskResult& bytes) {
    SampleResult r = calibration::unpackSample(bytes);
    r.weight = design.weight(r.index);
    table.append(r);
    done.push_back(r);
    sampleTime += r.runTime;
    ++finished;
    failing += r.outcome == calibration::SampleOutcome::Fails;
    if (log->active()) {
      const double pf = static_cast<double>(failing) / done.size();
      char text[64];
      std::snprintf(text, sizeof text, "Pf so far %.4g (%d of %zu fail)", pf, failing, done.size());
      log->report({"samples", finished, static_cast<int>(todo.size()), text, {{"probability_of_failure", pf}}});
    }
  });
  log->finish(true, std::to_string(finished) + " samples run");
  std::sort(done.begin(), done.end(), [](const SampleResult& a, const SampleResult& b) { return a.index < b.index; });
  std::vector<double> weights;
  for (const SampleResult& r : done) weights.push_back(r.weight);
  const calibration::ProbabilitySummary summary =
      calibration::summarise(done, spec.samples, spec.measure == model::ProbabilityMeasure::FactorOfSafety,
                             form ? &weights : nullptr);
  const bool complete = summary.finished == spec.samples;
  const io::DesignPointReport* formReport = form ? &*form : nullptr;
  const std::string json = summaryJson(job, summary, line, complete, formReport);
  writeAtomically(complete ? summaryPath : partialPath, json);
  if (complete) fs::remove(partialPath);
  const std::vector<std::string> pictures = writePictures(job, summary, done, opt.outDir, formReport);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (opt.json) {
    std::printf("%s", json.c_str());
  } else {
    printSummary(summary);
    std::printf("  %zu samples run now (%d resumed), %.2f s wall on %s (%.2f s of sample run time)\n", todo.size(),
                resumed, wall, farm->describe().c_str(), sampleTime);
    if (form)
      std::printf("  forward runs: %d for the design point, %d samples\n", form->point.runs, summary.finished);
    std::string files;
    for (const auto& p : pictures) files += ", " + p;
    std::printf("  wrote %s, %s%s\n", csv.c_str(), complete ? "summary.json" : "summary.partial.json", files.c_str());
    if (!complete)
      std::printf("  incomplete: %d of %d samples; --resume continues (--stop-after %d)\n", summary.finished,
                  spec.samples, opt.stopAfter);
  }
  if (summary.notConverged > 0)
    std::fprintf(stderr, "ddaslope: warning: %s: %d samples did not converge: they are counted apart (see the rule "
                         "column of %s), Pf's bounds with them are in the summary\n",
                 job.file.c_str(), summary.notConverged, csv.c_str());
  return kExitOk;
}

}  // namespace ddaslope::cli

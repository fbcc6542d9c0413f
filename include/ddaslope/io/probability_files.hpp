#pragma once
// The files of a probability study in its --out folder (docs/probability.md, *Outputs*):
// samples.csv, appended a row per finished sample and read back by --resume;
// probability_settings.json, what the samples depend on, which a resumed study must match;
// summary.json (summary.partial.json while samples are missing), and the pictures.
#include <cstdio>
#include <string>
#include <vector>

#include "ddaslope/calibration/active_learning.hpp"
#include "ddaslope/calibration/probability.hpp"
#include "ddaslope/calibration/reliability.hpp"
#include "ddaslope/io/probability_reader.hpp"

namespace ddaslope::io {

/// The shortest text that reads back as the same double ("" for NaN): resumed samples and fresh
/// ones then give the same summary bit for bit.
std::string exactText(double v);

/// samples.csv: sample, one column per input path, outcome, rule, factor_of_safety (fos
/// measure), max_displacement_m, run_time_s.
class SampleTable {
 public:
  SampleTable(std::string path, const model::ProbabilitySpec& spec);
  ~SampleTable();
  SampleTable(const SampleTable&) = delete;
  SampleTable& operator=(const SampleTable&) = delete;

  const std::string& path() const { return path_; }
  /// The rows already in the file (a study resumed), checked against the design: the header,
  /// each index within [0, N) and given once, and its input values equal to the design's, to the
  /// last bit. A last line cut short by a kill is dropped (and cut from the file before rows are
  /// appended); a damaged line elsewhere is an InputError.
  std::vector<calibration::SampleResult> read(const calibration::SampleDesign& design);
  /// Opens the file for appending: a new one gets its header, a read one loses a cut-off last line.
  void open();
  /// Appends one row, flushed at once so that a killed study keeps every sample it finished.
  void append(const calibration::SampleResult& r);

 private:
  std::string header() const;
  std::string path_;
  const model::ProbabilitySpec& spec_;
  std::FILE* file_ = nullptr;
  long keepBytes_ = -1;  ///< the file's length up to its last whole row (-1: all of it)
};

/// One forward run of an active-learning study: a search of F or one run's verdict.
struct LearningRun {
  bool search = true;  ///< a search of F (otherwise a verdict)
  int index = 0;       ///< population point
  calibration::PerformanceValue value;                                    ///< a search's
  calibration::PointVerdict verdict = calibration::PointVerdict::Stable;  ///< a verdict's
};

/// learning_runs.csv: every run of an active-learning study, a row as each finishes (kind,
/// sample, outcome, F − 1 to the last bit, forward runs). --resume replays them: the learning
/// is a function of its runs' results, so a resumed study chooses, and writes, exactly what an
/// uninterrupted one would have.
class LearningJournal {
 public:
  explicit LearningJournal(std::string path) : path_(std::move(path)) {}
  ~LearningJournal();
  LearningJournal(const LearningJournal&) = delete;
  LearningJournal& operator=(const LearningJournal&) = delete;

  const std::string& path() const { return path_; }
  /// The runs already in the file, checked: the header, each kind, sample within
  /// [0, population), outcome and margin, and no run given twice. A last line cut short by a kill
  /// is dropped (that run is made again); a damaged line elsewhere is an InputError.
  std::vector<LearningRun> read(int population);
  /// Opens the file for appending (a new one gets its header).
  void open();
  /// Appends one row, flushed at once: a killed study keeps every run it finished.
  void append(const LearningRun& r);

 private:
  std::string path_;
  std::FILE* file_ = nullptr;
  long keepBytes_ = -1;
};

/// Importance sampling's design point, as the summary and the pictures report it.
struct DesignPointReport {
  calibration::DesignPoint point;
  std::vector<double> values;      ///< the inputs at the design point, in case units
  std::vector<double> importance;  ///< γ (calibration::importanceVector)
};

/// probability_settings.json's text: the case's digest, the study's settings (the sample count
/// only for a Latin hypercube, whose strata depend on it: a Monte Carlo study may be extended),
/// the settings every forward run uses, and the design point the samples are centred on
/// (importance sampling), so that a resumed study checks it too.
std::string settingsFingerprint(const ProbabilityJob& job, const std::vector<std::string>& caseSettings,
                                const std::string& settingsLine, const std::vector<double>& centre = {});

/// Refuses (InputError) a resumed study whose probability_settings.json differs from `expected`,
/// naming the first line that differs.
/// `held`: what the folder holds, for the message ("samples", or an active-learning study's "runs").
void checkFingerprint(const std::string& path, const std::string& expected, const std::string& held = "samples");

/// Writes `text` to `path` through a temporary file and a rename: a reader never sees half of it.
void writeAtomically(const std::string& path, const std::string& text);

/// The summary as JSON: no run times and no thread counts, so equal samples give equal bytes.
std::string summaryJson(const ProbabilityJob& job, const calibration::ProbabilitySummary& s,
                        const std::string& settingsLine, bool complete, const DesignPointReport* design = nullptr);

/// pf_convergence.png, and samples_plane.png (two inputs, cohesion and friction angle when
/// both are inputs, coloured by outcome, with the design point), fos_histogram.png (fos measure)
/// and sensitivities.png (importance sampling: γ² of each input). Returns the names written.
std::vector<std::string> writePictures(const ProbabilityJob& job, const calibration::ProbabilitySummary& s,
                                       const std::vector<calibration::SampleResult>& sorted, const std::string& dir,
                                       const DesignPointReport* design = nullptr);

/// Active learning's summary.json text (docs/probability.md, *Active learning*): the study, Pf
/// with its interval and bounds, β, the forward runs (searches' and confirmations'), and how the
/// learning ended. No run times: equal runs give equal bytes.
std::string activeLearningSummaryJson(const ProbabilityJob& job, const calibration::ActiveLearningResult& r,
                                      const std::string& settingsLine, const DesignPointReport* design = nullptr,
                                      const std::string& noDesignPoint = "");

/// Active learning's other files, each written whole through a temporary file: learning.csv (the
/// points run, in the order run: role, the inputs, outcome, F, forward runs, the surrogate's
/// prediction where the point was chosen, whether a confirmation agreed) and samples_plane.png
/// (two inputs: the population as classified, the searches and the confirmations). Returns the
/// names written.
std::vector<std::string> writeActiveLearningFiles(const ProbabilityJob& job, const calibration::SampleDesign& design,
                                                  const calibration::ActiveLearningResult& r, const std::string& dir,
                                                  const DesignPointReport* point = nullptr);

/// sensitivities.png: γ² of each input at the design point, and the side failure lies on.
std::string writeSensitivities(const ProbabilityJob& job, const DesignPointReport& point, const std::string& dir);

}  // namespace ddaslope::io

#pragma once
// What the subcommands share: exit codes, the model options every command that runs forward
// models takes (--preset, --time-step, --blocks, --set, …), reading a case with them, and the
// settings line each result names.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "ddaslope/calibration/strength_search.hpp"
#include "ddaslope/io/case_reader.hpp"
#include "ddaslope/io/progress.hpp"
#include "ddaslope/model/scene.hpp"
#include "ddaslope/model/settings_override.hpp"

namespace ddaslope::cli {

constexpr int kExitOk = 0;
constexpr int kExitBadInput = 2;
constexpr int kExitNonConvergence = 3;

struct Overrides {
  ddaslope::model::SettingsOverride model;  ///< --preset, --time-step, --blocks, --contact-treatment
  double duration = 0;
  std::vector<std::string> settings;  ///< "json.path=value", applied before the case is read
};

/// A command-line number checked like a case number: finite (no nan, inf or overflow) and in
/// [lo, hi].
CLI::Validator finiteIn(double lo, double hi, const std::string& what);

/// "min:max:n" of an option (--curve, --sweep): min and max finite numbers (no nan, inf or
/// overflow), n a whole number in [2, maxCount], and nothing else in the text; nullopt otherwise
/// (the caller says what its option expects).
struct ValueRange {
  double lo = 0, hi = 0;
  int n = 0;
};
std::optional<ValueRange> parseValueRange(const std::string& text, int maxCount);

/// The options every command that runs forward models shares.
void addModelOptions(CLI::App* cmd, Overrides& o);

/// "path=value" → an override; a malformed one is bad input.
ddaslope::io::CaseOverride parseSetting(const std::string& text);

/// Reads the case with every override of the command line in one pass, in order: --set, the
/// extra ones (a sweep's value, a study's sample and its job's model choices), the model options
/// (--preset, --time-step, --blocks, --contact-treatment, --brittle-joints); then run's --duration.
ddaslope::model::Scene loadCase(const std::string& casePath, const Overrides& o,
                                std::vector<ddaslope::io::CaseOverride> extra = {});
/// loadCase on the text of the case file, read once by the caller (a study's samples).
ddaslope::model::Scene loadCaseText(const std::string& text, const std::string& casePath, const Overrides& o,
                                    std::vector<ddaslope::io::CaseOverride> extra = {});
/// loadCaseText of a case parsed once (a study's samples read it many times).
ddaslope::model::Scene loadParsedCase(const ddaslope::io::ParsedCase& parsed, const std::string& casePath,
                                      const Overrides& o, std::vector<ddaslope::io::CaseOverride> extra = {});

/// The settings every forward run of a command uses, and where Δt came from. `trials`: the
/// command's runs are stability trials (their quiet steps grow unless the case says otherwise).
std::string settingsLine(const ddaslope::model::Scene& scene, bool trials = true);

/// --trial-start of fos and run --at-fos: "settled" or "held" (CLI checks the word).
calibration::TrialStart trialStartOf(const std::string& word);
/// Registers --trial-start on a command that reduces strengths as fos does.
CLI::Option* addTrialStartOption(CLI::App* cmd, std::string& word);
/// Where a strength reduction's trials started, in words, and why when it is not the one asked for.
/// `subject`: "the trials", "the run".
std::string trialStartNote(const std::string& subject, calibration::TrialStart used, const std::string& asked);

/// A search's --vtk DIR: every trial's final state becomes a frame of the VTK series in `dir`
/// (io/scene_vtk.hpp) at the value it tried, so ParaView's time slider steps through the trials
/// by value; its verdict rides along as field data (stable, verdict). Written by the root process.
void recordTrialStates(calibration::SearchSettings& s, const std::string& dir, const model::Scene& scene);

/// The mechanism at a search's answer (issue #43): the final state of every trial is kept (a
/// copy of the blocks and contact states, not a picture), and the trials at the bracket's ends
/// are drawn once the search is done: mechanism_stable.png and mechanism_failed.png, blocks
/// coloured by displacement, contacts locked or sliding, supports, loads, water.
class MechanismPictures {
 public:
  /// Observes the search's final states, after any observer `s` has (recordTrialStates).
  MechanismPictures(calibration::SearchSettings& s, const model::Scene& scene);
  /// Draws the trials at `stable` and `failing` (of `quantity`, "F" or a strength) into `dir`;
  /// returns the files written (none for a value no trial ran).
  std::vector<std::string> write(const std::string& dir, const std::string& casePath, const std::string& quantity,
                                 double stable, double failing) const;
  /// How far the trial at `value` moved its free blocks along x: their centroids' mean
  /// displacement, weighted by area (m); 0 when no such trial was kept.
  double horizontalMotion(double value, const model::Scene& initial) const;

 private:
  struct Kept;
  std::shared_ptr<Kept> kept_;
};

int jointIndex(const ddaslope::model::Scene& scene, const std::string& name, const std::string& casePath);

/// A CSV field of a number that may have no value: "%.6g", or empty where the point had no answer
/// (never 0 or nan, which read as values).
std::string csvField(double v, bool known = true);
/// A result's bracket for its JSON: the two ends, or nulls (NaN) when there is no answer.
std::vector<double> bracketField(bool found, double first, double second);

/// Writes a command's result file through a temporary and a rename (its folder made): never half
/// a file that looks complete.
void writeResultFile(const std::string& path, const std::string& text);

/// Progress of a long command: a line on stderr unless --quiet, a --json result or
/// stderr not a terminal; JSON lines with --log-json FILE.
struct ProgressOptions {
  bool quiet = false;
  std::string logJson;
};
void addProgressOptions(CLI::App* cmd, ProgressOptions& p);
/// The command's progress log (never null); under mpirun only rank 0 reports.
std::unique_ptr<ddaslope::io::ProgressLog> startProgress(const std::string& command, const ProgressOptions& p,
                                                         bool jsonResult);

/// Where a search's --vtk went (text output).
void printTrialStatesNote(const std::string& dir, int runs);
/// Verdict warnings go to stderr, so a --json result on stdout stays clean.
void warnAboutTrials(const std::string& casePath, const std::string& warning);
/// `text` as one word of a shell command (quoted if it needs it): a case path in a hint.
std::string shellWord(const std::string& text);

}  // namespace ddaslope::cli

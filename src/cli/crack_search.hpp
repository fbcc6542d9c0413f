#pragma once
// A tension crack's least safe position (section.tension_crack.search), for fos and critical:
// the case's search at each position tried, run at once on the threads or ranks.
#include <functional>
#include <optional>
#include <string>

#include "cli_common.hpp"
#include "ddaslope/calibration/position_search.hpp"
#include "ddaslope/calibration/strength_search.hpp"
#include "ddaslope/io/json_record.hpp"

namespace ddaslope::cli {

/// The search's value at one crack position (the case read with the crack there).
struct CrackValue {
  bool found = false;
  double value = 0;
  int runs = 0;
  std::string message;  ///< why no value, when none
  bool fails = false;   ///< no value because every trial failed (calibration::PositionSample::fails)
};

/// A search's result as one position's value.
CrackValue crackValueOf(const calibration::CriticalResult& r);
CrackValue crackValueOf(const calibration::FactorOfSafetyResult& r);

struct CrackSearch {
  /// Where the least safe crack is; when no position gave a value (`result.found` false), none
  /// is, and the crack stays at the case's x.
  calibration::PositionSearchResult result;
  int runs = 0;  ///< forward runs over every position
  double wallTime = 0;
};

/// The least safe crack of one point of a sweep or a curve.
struct PointCrack {
  double x = 0;        ///< where the point's crack is: the least safe position, or the case's x
  bool found = false;  ///< a position is least safe (else x is the case's)
  bool tied = false;   ///< none is because every position gave the same value
  bool fails = false;  ///< the least safe position is one where the slope fails at every value
};

/// The overrides that put the case's crack at x.
std::vector<io::CaseOverride> crackAt(double x);

/// Searches the crack's position over the case's range: the least `value` (maximise false) or the
/// greatest. `valueAt` runs one position's search on one thread.
CrackSearch searchCrackPosition(const std::string& casePath, const Overrides& o, const model::Scene& scene, int threads,
                                bool maximise, double precision, const std::string& quantity, const ProgressOptions& progress,
                                const std::function<CrackValue(const model::Scene&)>& valueAt);

/// A case that searches its crack (section.tension_crack.search): the least safe position for
/// `quantity` is found, `scene` is read again with the crack there, and the positions tried are
/// printed (unless `json`). None, and `scene` untouched, when the case places its crack itself;
/// `scene` untouched too when no position gave a value (the crack stays at the case's x).
std::optional<CrackSearch> placeCrack(const std::string& casePath, const Overrides& o, model::Scene& scene, int threads,
                                      bool maximise, double precision, const std::string& quantity,
                                      const ProgressOptions& progress, bool json,
                                      const std::function<CrackValue(const model::Scene&)>& valueAt);

/// The least safe crack of one task of a sweep or a curve, which run side by side: its positions
/// one after another on this thread. `read(x)` is the task's scene with the crack at x. Returns
/// the position, or the case's x (`scene`'s) when no position gave a value; the positions'
/// forward runs are added to `runs`.
PointCrack leastSafeCrackOnThisThread(const model::Scene& scene, bool maximise, double precision,
                                      const std::function<model::Scene(double)>& read,
                                      const std::function<CrackValue(const model::Scene&)>& valueAt, int& runs);

/// ", least safe crack at x = …" and the like: where one point's crack of a sweep or a curve is,
/// `x` its least safe position (NaN: none), `caseX` the case's.
std::string pointCrackText(bool found, bool tied, bool fails, double x, double caseX, const std::string& quantity);

/// Why the crack stayed at the case's x: no position in the searched range gave `quantity`.
std::string noCrackPositionNote(const model::Scene& scene, const std::string& quantity, bool tied);
/// How the case places its crack, for notes: "section.tension_crack.x", or where its depth puts it.
std::string crackPlacement(const model::Scene& scene);

/// "N forward runs", and with a crack search "N forward runs (M of them searching the crack's
/// position)": `answerRuns` are the answer's own, the crack search's are added.
std::string forwardRunsText(int answerRuns, const std::optional<CrackSearch>& crack);
/// The answer's forward runs and wall time with the crack search's added (the JSON's totals).
int totalRuns(int answerRuns, const std::optional<CrackSearch>& crack);
double totalWallTime(double answerWallTime, const std::optional<CrackSearch>& crack);

/// The positions tried and the least safe one, for the text output.
void printCrackSearch(const CrackSearch& s, const model::Scene& scene, const std::string& quantity);
/// The same in a command's JSON record (key "tension_crack"); for a crack the case places, its
/// position alone.
void appendCrackSearch(io::JsonRecord& j, const CrackSearch& s, const model::Scene& scene, const std::string& quantity);

}  // namespace ddaslope::cli

#pragma once
// A tension crack's least safe position (section.tension_crack.search), for fos and critical:
// the case's search at each position tried, run at once on the threads or ranks.
#include <functional>
#include <optional>
#include <string>

#include "cli_common.hpp"
#include "ddaslope/calibration/position_search.hpp"
#include "ddaslope/io/json_record.hpp"

namespace ddaslope::cli {

/// The search's value at one crack position (the case read with the crack there).
struct CrackValue {
  bool found = false;
  double value = 0;
  int runs = 0;
  std::string message;  ///< why no value, when none
};

struct CrackSearch {
  calibration::PositionSearchResult result;
  int runs = 0;  ///< forward runs over every position
  double wallTime = 0;
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
/// printed (unless `json`). None, and `scene` untouched, when the case places its crack itself.
std::optional<CrackSearch> placeCrack(const std::string& casePath, const Overrides& o, model::Scene& scene, int threads,
                                      bool maximise, double precision, const std::string& quantity,
                                      const ProgressOptions& progress, bool json,
                                      const std::function<CrackValue(const model::Scene&)>& valueAt);

/// The least safe crack of one task of a sweep or a curve, which run side by side: its positions
/// one after another on this thread. `read(x)` is the task's scene with the crack at x. Returns
/// the position; the positions' forward runs are added to `runs`.
double leastSafeCrackOnThisThread(const model::Scene& scene, bool maximise, double precision,
                                  const std::function<model::Scene(double)>& read,
                                  const std::function<CrackValue(const model::Scene&)>& valueAt, int& runs);

/// The positions tried and the least safe one, for the text output.
void printCrackSearch(const CrackSearch& s, const model::Scene& scene, const std::string& quantity);
/// The same in a command's JSON record (key "tension_crack").
void appendCrackSearch(io::JsonRecord& j, const CrackSearch& s, const model::Scene& scene);

}  // namespace ddaslope::cli

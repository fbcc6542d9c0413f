#pragma once
// What a search's forward runs decided, for the user: every trial as JSON, and a warning when a
// failing verdict rests on very little motion (docs/calibration.md, *Verdict provenance*).
#include <string>
#include <vector>

#include "ddaslope/calibration/strength_search.hpp"
#include "ddaslope/io/json_record.hpp"

namespace ddaslope::calibration {

/// Appends every trial to `j` under "trials": its value (under `valueKey`: "factor",
/// "cohesion_pa", "friction_angle_deg"), the verdict, the rule that decided it, the largest
/// monitor displacement and the failure displacement, the window motions and noise floor,
/// the final speed, simulated time and steps, and whether it was extended or stayed marginal.
void appendTrials(io::JsonRecord& j, const std::vector<TrialRecord>& trials, const std::string& valueKey);

/// A trial called failed while its monitors moved less than this fraction of the failure
/// displacement deserves a look: its verdict rests on the trend of the motion, not its size.
constexpr double kSmallFailureMotion = 0.01;

/// The warning for such trials (empty if none), naming the value as `valueLabel` ("F", "c", "φ").
std::string smallMotionWarning(const std::vector<TrialRecord>& trials, const std::string& valueLabel);

}  // namespace ddaslope::calibration

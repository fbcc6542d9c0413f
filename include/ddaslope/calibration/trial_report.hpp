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
/// displacement of a monitor or a free block (and which) and the failure displacement, the window
/// motions and noise floor (and the deciding point), the final speed, simulated time and steps,
/// its extensions, whether it stayed marginal, and whether it was a review's re-run.
void appendTrials(io::JsonRecord& j, const std::vector<TrialRecord>& trials, const std::string& valueKey);

/// Appends the search's review of its trials under "review": whether trials still contradicted
/// after their re-runs, whether undecided trials bound the answer, how many trials were re-run,
/// and, when they contradict, the range where the verdicts are mixed (`mixed_range`: the search's
/// stable and failing ends, which it sets to that range, found or not; nulls otherwise).
void appendReview(io::JsonRecord& j, const TrialReview& review, double stableEnd, double failingEnd);

/// A trial called failed while its monitors moved less than this fraction of the failure
/// displacement deserves a look: its verdict rests on the trend of the motion, not its size.
constexpr double kSmallFailureMotion = 0.01;

/// The warning for such trials (empty if none), naming the value as `valueLabel` ("F", "c", "φ").
std::string smallMotionWarning(const std::vector<TrialRecord>& trials, const std::string& valueLabel,
                               const std::string& caseLabel = "CASE");

/// The warning (empty if none) when the bracket's failing end is a run that did not converge (a
/// budget spent, Δt cut to its limit): it counts as failing, so the slope may stand there and the
/// answer lie beyond it. `found`: whether the search gave an answer at all.
std::string unconvergedEndWarning(const std::vector<TrialRecord>& trials, bool found, double failingEnd,
                                  const std::string& valueLabel, const std::string& caseLabel = "CASE");

/// A step from rest that implies more than free fall (g) is driven by contact springs, not by the
/// weight of a slope under gravity.
constexpr double kFreeFall = 1;

/// The warning (empty if none) when the bracket's failing end did not start from rest and its
/// start may have decided it (a failure while settling, rule 0, is the settling's own): its
/// settling found no quiet state (a step did not converge, or no step from rest at the analysis
/// Δt converged without a cut or a frozen contact: settling "unsettled"), so the analysis started
/// from the equilibrium's static state, whose kick is unknown; or it stalled in a state a step
/// from which implied more than kFreeFall. Such starts come with verdicts that stop being
/// monotone in the value (docs/contact-model.md, the stiff end of the contact stiffness).
/// `subject` names the trial in the text (a search's "the bracket's failing end", `fos --check`'s
/// "the trial").
std::string unrestedEndWarning(const std::vector<TrialRecord>& trials, bool found, double failingEnd,
                               const std::string& valueLabel, const std::string& caseLabel = "CASE",
                               const std::string& subject = "the bracket's failing end");

}  // namespace ddaslope::calibration

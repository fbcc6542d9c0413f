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

/// A start kick above this (g) may decide a failure by itself: the shipped searches' failing ends
/// that started from a stalled settling implied at most 0.022 g (Goodman & Bray's toppling slope),
/// while a start of 0.57 g on the chair slide at Δt 1 ms moved its critical cohesion (test
/// SofteningJoints.AStalledSettlingStartsFromItsQuietestState).
constexpr double kStartKick = 0.1;

/// The warning (empty if none) when the bracket's failing end did not start from rest and its
/// failure may be that start's, not its strengths': its settling stalled with a first step
/// implying more than kStartKick, or travelled like a failing scene without passing the failure
/// displacement (the analysis then starts from the static relaxation's or the held state).
/// Seen where the verdict stops being monotone in the value: the chair slide at
/// analysis.penalty_factor 1000 and 2000.
std::string unrestedEndWarning(const std::vector<TrialRecord>& trials, bool found, double failingEnd,
                               const std::string& valueLabel, const std::string& caseLabel = "CASE");

}  // namespace ddaslope::calibration

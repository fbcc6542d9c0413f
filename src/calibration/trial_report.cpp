#include "ddaslope/calibration/trial_report.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <vector>

namespace ddaslope::calibration {
namespace {

bool failedOnLittleMotion(const TrialResult& r) {
  return !r.stable && !r.undecided && r.converged && r.rule != VerdictRule::MovedWhileSettling &&
         r.maxDisplacement < kSmallFailureMotion * r.failureDisplacement;
}

}  // namespace

void appendTrials(io::JsonRecord& j, const std::vector<TrialRecord>& trials, const std::string& valueKey) {
  for (const TrialRecord& t : trials) {
    const TrialResult& r = t.result;
    io::JsonRecord item;
    item.set(valueKey, t.value).set("stable", r.stable).set("undecided", r.undecided).set("rule", name(r.rule));
    item.set("max_displacement_m", r.maxDisplacement).set("failure_displacement_m", r.failureDisplacement);
    item.set("settling_displacement_m", r.settlingDisplacement);
    item.set("last_window_motion_m", r.lastWindowMotion).set("previous_window_motion_m", r.previousWindowMotion);
    item.set("noise_floor_m", r.noiseFloor).set("final_speed_m_s", r.finalSpeed);
    item.set("moved_most", r.movedMost).set("decided_by", r.decidedBy);
    item.set("time_s", r.timeReached).set("steps", r.steps);
    item.set("equilibrium_steps", r.equilibriumSteps).set("extended", r.extended).set("extensions", r.extensions);
    item.set("marginal", r.marginal).set("rerun", t.rerun).set("early_rest", r.earlyRest);
    item.set("run_on", r.runOn).set("settling", r.settling).set("start_acceleration_g", r.startAcceleration);
    j.append("trials", item);
  }
}

void appendReview(io::JsonRecord& j, const TrialReview& review, double stableEnd, double failingEnd) {
  io::JsonRecord r;
  r.set("contradiction", review.contradiction).set("undecided", review.undecided).set("reruns", review.reruns);
  r.set("mixed_range", review.contradiction ? std::vector<double>{std::min(stableEnd, failingEnd), std::max(stableEnd, failingEnd)}
                                            : std::vector<double>{NAN, NAN});
  j.set("review", r);
}

namespace {
std::string shortNumber(double v) {
  std::ostringstream o;
  o.precision(8);
  o << v;
  return o.str();
}
}  // namespace

std::string smallMotionWarning(const std::vector<TrialRecord>& trials, const std::string& valueLabel,
                               const std::string& caseLabel) {
  int n = 0;
  const TrialRecord* least = nullptr;
  for (const TrialRecord& t : trials)
    if (failedOnLittleMotion(t.result)) {
      ++n;
      if (!least || t.result.maxDisplacement < least->result.maxDisplacement) least = &t;
    }
  if (n == 0) return "";
  std::ostringstream m;
  m << n << " of " << trials.size() << " trials were called failed after moving less than "
    << 100 * kSmallFailureMotion << " % of the failure displacement (least: " << valueLabel << " = " << least->value
    << " moved " << least->result.maxDisplacement << " m of " << least->result.failureDisplacement
    << " m; rule: " << name(least->result.rule) << "). Such a verdict rests on the trend of the motion, not its "
    << "size: check it with "
    << (valueLabel == "F" ? "`ddaslope run " + caseLabel + " --at-fos " + shortNumber(least->value) + "`"
                          : "`ddaslope run " + caseLabel + " --set ...` at that value")
    << " (history.png), or lengthen analysis.duration";
  return m.str();
}

namespace {
/// The record in force at the failing end: its re-run's, if it was re-run.
const TrialRecord* failingEndRecord(const std::vector<TrialRecord>& trials, double failingEnd) {
  const TrialRecord* end = nullptr;
  for (const TrialRecord& t : trials)
    if (t.value == failingEnd && (!end || t.rerun)) end = &t;
  return end;
}

/// The shortest digits that read back as exactly this value: a trial near a chaotic verdict must be
/// run again at exactly its value, and a value the user typed reads as typed.
std::string preciseNumber(double v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

std::string runCommand(const std::string& valueLabel, const std::string& caseLabel, double value,
                       const std::string& written = "") {
  const std::string x = written.empty() ? shortNumber(value) : written;
  return valueLabel == "F" ? "`ddaslope run " + caseLabel + " --at-fos " + x + " --verbose`"
                           : "`ddaslope run " + caseLabel + " --set ... --verbose` at " + valueLabel + " = " + x;
}
}  // namespace

std::string unrestedEndWarning(const std::vector<TrialRecord>& trials, bool found, double failingEnd,
                               const std::string& valueLabel, const std::string& caseLabel, const std::string& subject) {
  if (!found) return "";
  const TrialRecord* end = failingEndRecord(trials, failingEnd);
  if (!end || end->result.stable || end->result.rule == VerdictRule::MovedWhileSettling) return "";
  const TrialResult& r = end->result;
  const bool unmeasured = r.settling == "unsettled";
  const bool kicked = r.settling == "stalled" && r.startAcceleration > kFreeFall;
  if (!unmeasured && !kicked) return "";
  std::ostringstream m;
  m << subject << ", " << valueLabel << " = " << preciseNumber(failingEnd) << ", did not start from rest: ";
  if (kicked)
    m << "its settling found no rest, and a step from the quietest state it reached implied " << shortNumber(r.startAcceleration)
      << " g, more than free fall: contact springs, not the slope's weight, drive that start";
  else
    m << "its settling measured no quiet state (no step from rest at the analysis Δt converged without cutting Δt or "
         "freezing contacts), and the analysis started from the equilibrium's static state, whose kick is unknown";
  m << ". Its failure may be that start's, not its strengths', and the answer may then follow Δt and the contact "
       "stiffness (as on the chair slide at analysis.penalty_factor 1000 and above: docs/contact-model.md). Check it "
       "with another --time-step or --set analysis.penalty_factor, and see its settling with "
    << runCommand(valueLabel, caseLabel, failingEnd, preciseNumber(failingEnd));
  return m.str();
}

std::string unconvergedEndWarning(const std::vector<TrialRecord>& trials, bool found, double failingEnd,
                                  const std::string& valueLabel, const std::string& caseLabel) {
  if (!found) return "";
  const TrialRecord* end = failingEndRecord(trials, failingEnd);
  if (!end || end->result.converged) return "";
  std::ostringstream m;
  m << "the bracket's failing end, " << valueLabel << " = " << shortNumber(failingEnd)
    << ", is a run that did not converge: it counts as failing, so the slope may stand there and the answer lie "
    << "beyond it. See why with " << runCommand(valueLabel, caseLabel, failingEnd)
    << " (a budget spent: analysis.wall_clock_limit or analysis.max_steps; or Δt cut to its limit)";
  return m.str();
}

}  // namespace ddaslope::calibration

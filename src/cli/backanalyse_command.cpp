#include "backanalyse_command.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>

#include "ddaslope/calibration/backanalysis.hpp"
#include "ddaslope/calibration/trial_report.hpp"
#include "ddaslope/io/case_reader.hpp"
#include "ddaslope/io/job_reader.hpp"
#include "ddaslope/io/json_record.hpp"
#include "ddaslope/io/line_plot.hpp"
#include "scene_notes.hpp"

namespace ddaslope::cli {
namespace {

/// The case numbers the fit sets by their JSON path.
std::vector<std::string> fittedPaths(const ddaslope::io::BackanalysisJob& job) {
  std::vector<std::string> paths;
  for (const auto& p : job.parameters)
    if (!p.jsonPath.empty()) paths.push_back(p.jsonPath);
  return paths;
}

/// result.json's "precision": each parameter's range and scan, the Δt ensemble, the statement.
void appendPrecision(ddaslope::io::JsonRecord& j, const ddaslope::calibration::Precision& p,
                     const ddaslope::io::BackanalysisJob& job) {
  if (p.parameters.empty()) return;
  ddaslope::io::JsonRecord out;
  for (const auto& r : p.parameters) {
    ddaslope::io::JsonRecord item;
    item.set("name", r.name).set("estimate", r.estimate).set("low", r.low).set("high", r.high);
    item.set("low_is_scan_end", r.openLow).set("high_is_scan_end", r.openHigh);
    item.set("noise_resolution", r.noiseResolution);  // null: no slope to compare the noise with
    for (const auto& s : r.scan) {
      ddaslope::io::JsonRecord point;
      point.set("value", s.value).set("misfit", s.misfit).set("simulated", s.simulated);
      item.append("scan", point);
    }
    out.append("parameters", item);
  }
  for (const auto& m : p.ensemble) {
    ddaslope::io::JsonRecord member;
    member.set("time_step_factor", m.timeStepFactor).set("misfit", m.misfit).set("simulated", m.simulated);
    out.append("time_step_ensemble", member);
  }
  std::vector<std::string> labels;
  for (const auto& o : job.observations) labels.push_back(o.label);
  out.set("observations", labels).set("noise", p.noise).set("statement", p.statement);
  if (p.better) {
    ddaslope::io::JsonRecord b;
    b.set("parameter", p.parameters[p.better->parameter].name).set("value", p.better->value);
    b.set("misfit", p.better->misfit).set("estimate_misfit", p.better->estimateMisfit);
    b.set("misfit_noise", p.better->misfitNoise);
    out.set("search_stopped_short", b);
  } else {
    out.set("search_stopped_short", false);
  }
  j.set("precision", out);
}


}  // namespace

int backanalyseCommand(const std::string& jobPath, const std::string& outDir, bool json, const Overrides& o,
                       const ProgressOptions& progress) {
  ddaslope::io::BackanalysisJob job = ddaslope::io::readJob(jobPath);
  // The command line's choices are applied after the job's own (its "preset", "blocks").
  job.model.push_back(o.model);
  for (const auto& s : o.settings) job.caseOverrides.push_back(parseSetting(s));
  const std::unique_ptr<ddaslope::TaskFarm> farm = ddaslope::makeTaskFarm(job.threads);
  // Said before the fit, which may run for hours with the crack where the user may not expect it
  // (and again with the result).
  if (farm->isRoot()) {
    std::vector<double> start;
    for (const auto& p : job.parameters) start.push_back(p.hasStart ? p.start : 0.5 * (p.min + p.max));
    warnAboutTrials(job.casePath, fixedCrackNote(ddaslope::calibration::sceneAt(job, start), fittedPaths(job)));
  }
  const auto log = startProgress("backanalyse", progress, json);
  const ddaslope::calibration::BackanalysisResult r =
      ddaslope::calibration::runBackanalysis(job, farm.get(), ddaslope::io::sinkOf(log.get()));
  if (!farm->isRoot()) return kExitOk;  // the root writes
  log->finish(true, "misfit " + std::to_string(r.misfit) + " after " + std::to_string(r.evaluations) + " evaluations");
  std::filesystem::create_directories(outDir);
  ddaslope::io::JsonRecord j;
  j.set("job", jobPath).set("case", job.casePath);
  for (size_t i = 0; i < r.names.size(); ++i) j.set(r.names[i], r.estimate[i]);
  ddaslope::io::JsonRecord estimate;  // the same values together, for readers that do not know the names
  for (size_t i = 0; i < r.names.size(); ++i) estimate.set(r.names[i], r.estimate[i]);
  j.set("estimate", estimate);
  j.set("misfit", r.misfit).set("evaluations", r.evaluations).set("forward_runs", r.forwardRuns);
  j.set("runs_ahead_unused", r.runsAheadUnused);
  if (job.precision.enabled) j.set("precision_started_early", r.precisionStartedEarly);
  j.set("global_search", r.globalStatus).set("local_search", r.localStatus).set("wall_time_s", r.wallTime);
  const ddaslope::model::Scene atEstimate = ddaslope::calibration::sceneAt(job, r.estimate);
  bool searches = false;  // factor-of-safety observations run trials; series are plain runs
  for (const auto& o : job.observations) searches |= o.kind == ddaslope::io::ObservationSpec::Kind::FactorOfSafety;
  const std::string settings = settingsLine(atEstimate, searches);
  warnAboutTrials(job.casePath, fixedCrackNote(atEstimate, fittedPaths(job)));
  j.set("settings", settings);
  if (!r.map.empty()) j.set("constrains_only_a_line", r.lineOnly).set("statement", r.statement);
  // The same answer in a few tens of runs: said, since a user who wrote this job may not know.
  const std::string direct = ddaslope::calibration::directSearchCommand(job);
  const std::string note =
      direct.empty() ? std::string()
                     : "one joint strength fitted to F = 1 is the strength at which the slope is at its limit: `" + direct +
                           "` finds it by bisection on the stability verdict in a few tens of forward runs (this fit: " +
                           std::to_string(r.forwardRuns) + "), with the job's settings given as options (--preset, --blocks, --set)";
  std::vector<std::string> notes;
  if (!note.empty()) notes.push_back(note);
  // A point estimate alone looks sharper than the data may make it (docs/calibration.md,
  // "Precision"): say that its range was not measured, and how to measure it.
  if (r.precision.parameters.empty())
    notes.push_back(std::string("the estimate is a point: how far the observations fix it was not measured") +
                    (r.map.empty() ? "" : " beyond misfit_map.png's grid") +
                    "; \"precision\": true in the job scans each parameter around it and reruns it at other time steps "
                    "(docs/calibration.md, \"Precision\")");
  if (!notes.empty()) j.set("notes", notes);
  for (const auto& f : r.fit) {
    ddaslope::io::JsonRecord item;
    item.set("observation", f.label);
    if (!f.converged) item.set("simulated", "forward run did not converge");
    else if (f.series) item.set("rms_residual", f.simulated);
    else item.set("simulated", f.simulated).set("observed", f.observed);
    item.set("sigma", f.sigma);
    if (!f.trials.empty()) ddaslope::calibration::appendTrials(item, f.trials, "factor");
    j.append("fit_at_estimate", item);
  }
  appendPrecision(j, r.precision, job);
  const std::string result = outDir + "/result.json";
  {
    std::ofstream out(result + ".tmp");
    out << j.dump() << "\n";
  }
  std::filesystem::rename(result + ".tmp", result);
  if (!r.map.empty()) {
    const std::string csv = outDir + "/misfit_map.csv";
    std::ofstream out(csv + ".tmp");
    out << r.names[0] << "," << r.names[1] << ",misfit\n";
    for (size_t a = 0; a < r.axis0.size(); ++a)
      for (size_t b = 0; b < r.axis1.size(); ++b) out << r.axis0[a] << "," << r.axis1[b] << "," << r.map[a][b] << "\n";
    out.close();
    std::filesystem::rename(csv + ".tmp", csv);
    const auto label = [&](int k) {
      const ddaslope::io::ParameterSpec& p = job.parameters.at(k);
      const std::string unit = ddaslope::io::unitOfCaseValue(p.jsonPath.empty() ? p.property : p.jsonPath);
      return unit.empty() ? r.names[k] : r.names[k] + " (" + unit + ")";
    };
    ddaslope::io::HeatMap m{"Misfit: " + jobPath, label(0), label(1), "misfit (log scale)", r.axis0, r.axis1, r.map,
                            r.estimate[0], r.estimate[1]};
    ddaslope::io::writePng(m, outDir + "/misfit_map.png");
  }
  if (json) {
    std::printf("%s\n", j.dump().c_str());
  } else {
    std::printf("back-analysis of %s\n  forward runs at %s\n", job.casePath.c_str(), settings.c_str());
    for (size_t i = 0; i < r.names.size(); ++i) std::printf("  %s = %.6g\n", r.names[i].c_str(), r.estimate[i]);
    const std::string searches = r.globalStatus.empty() || r.localStatus.empty()
                                     ? r.globalStatus + r.localStatus
                                     : r.globalStatus + "; " + r.localStatus;
    std::printf("  misfit %.4g after %d evaluations (%d forward runs), %.1f s wall\n  %s\n", r.misfit, r.evaluations,
                r.forwardRuns, r.wallTime, searches.c_str());
    for (const auto& f : r.fit) {
      if (!f.converged) std::printf("  %s: forward run did not converge\n", f.label.c_str());
      else if (f.series) std::printf("  %s: RMS residual %.4g (sigma %.4g)\n", f.label.c_str(), f.simulated, f.sigma);
      else std::printf("  %s: simulated %.6g, observed %.6g ± %.4g\n", f.label.c_str(), f.simulated, f.observed, f.sigma);
    }
    if (!r.statement.empty()) std::printf("  %s\n", r.statement.c_str());
    if (!r.precision.statement.empty()) std::printf("  %s\n", r.precision.statement.c_str());
    for (const std::string& n : notes) std::printf("  note: %s\n", n.c_str());
    std::printf("  wrote %s%s\n", result.c_str(), r.map.empty() ? "" : (" and " + outDir + "/misfit_map.csv, .png").c_str());
  }
  return kExitOk;
}

}  // namespace ddaslope::cli

// ddaslope: one command line, subcommands per question.
#include <cstdio>
#include <filesystem>
#include <iostream>

#include <CLI/CLI.hpp>

#include "ddaslope/core/errors.hpp"
#include "ddaslope/core/task_farm.hpp"
#include "backanalyse_command.hpp"
#include "check_command.hpp"
#include "convert_command.hpp"
#include "critical_command.hpp"
#include "fos_command.hpp"
#include "cli_common.hpp"
#include "probability_command.hpp"
#include "report_command.hpp"
#include "run_command.hpp"

namespace {

using namespace ddaslope::cli;

int runCommandLine(int argc, char** argv) {
  CLI::App app{"ddaslope: shear strength of landslide sliding surfaces and factor of safety of jointed rock "
               "slopes with Discontinuous Deformation Analysis"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("ddaslope ") + DDASLOPE_VERSION + ", " + ddaslope::processSupport());
  std::string casePath;
  Overrides overrides;

  CLI::App* run = app.add_subcommand("run", "run a case and write history.csv and summary.json");
  RunCommandOptions runOpt;
  addRunOptions(run, casePath, overrides, runOpt);

  CLI::App* check = app.add_subcommand("check", "validate a case file without running it");
  check->add_option("case", casePath, "case file (JSON)")->required();
  addModelOptions(check, overrides);

  bool deformable = false;
  std::string csvPath;
  CLI::App* compare = app.add_subcommand(
      "compare-contacts", "critical cohesion of a block on an incline, edge vs vertex treatment vs closed form (27 slopes)");
  compare->add_flag("--deformable", deformable, "deformable rock blocks (E = 5 GPa) instead of stiff ones");
  compare->add_option("--csv", csvPath, "also write the table as CSV");

  std::string cutOut = "out/cut";
  CLI::App* cut = app.add_subcommand("cut", "cut the blocks of a case's slope section; write them as a plain case file and a picture");
  cut->add_option("case", casePath, "case file (JSON) with a section")->required();
  cut->add_option("--out", cutOut, "output directory")->capture_default_str();

  ConvertOptions convertOpt;
  CLI::App* convert = app.add_subcommand(
      "convert", "a model of Shi's DDA (ntdda .geo and .ana) to a case, or a case to ntdda's files");
  addConvertOptions(convert, convertOpt);

  CriticalOptions crit;
  CLI::App* critical = app.add_subcommand("critical", "critical cohesion (at a friction angle) or friction angle (at a cohesion) of one joint, by bisection");
  addCriticalOptions(critical, casePath, overrides, crit);

  FosOptions fosOpt;
  CLI::App* fos = app.add_subcommand("fos", "strength-reduction factor of safety: largest F with c/F, atan(tan φ/F) stable");
  addFosOptions(fos, casePath, overrides, fosOpt);

  std::string jobPath, baOut = "out/backanalysis";
  bool baJson = false;
  CLI::App* ba = app.add_subcommand("backanalyse", "estimate joint strengths (or any case value) from observations (NLopt)");
  ba->add_option("job", jobPath, "back-analysis job (JSON)")->required();
  ba->add_option("--out", baOut, "output directory")->capture_default_str();
  ba->add_flag("--json", baJson, "print the result as JSON");
  ProgressOptions baProgress;
  addProgressOptions(ba, baProgress);
  addModelOptions(ba, overrides);

  ddaslope::cli::ProbabilityOptions probOpt;
  CLI::App* probability = app.add_subcommand(
      "probability", "probability of failure from uncertain inputs (a case's \"probability\" section): Pf with its "
                     "95 % interval, β, every sample in a CSV");
  ddaslope::cli::addProbabilityOptions(probability, casePath, probOpt);
  addModelOptions(probability, overrides);

  std::string reportDir, reportOut;
  CLI::App* reportCmd = app.add_subcommand(
      "report", "one self-contained HTML file of an analysis folder (run, fos, critical, backanalyse, probability)");
  reportCmd->add_option("dir", reportDir, "the folder an analysis wrote (its --out)")->required();
  reportCmd->add_option("--out", reportOut, "the HTML file to write (default: DIR/report.html)");

  // An error that every MPI rank met in the same study is reported once, by the root.
  const auto report = [](const char* kind, const char* what) {
    if (ddaslope::processRank() == 0 || !ddaslope::errorSharedByAllProcesses()) std::cerr << kind << what << "\n";
  };
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? kExitOk : kExitBadInput;
  }
  try {
    // Under mpirun only the studies made of independent runs spread over the ranks; any other
    // command would run once per rank, each writing the same files.
    const bool spreads = probability->parsed() || ba->parsed() || (fos->parsed() && !fosOpt.sweep.empty()) ||
                         (critical->parsed() && !crit.curve.empty());
    if (ddaslope::processCount() > 1 && !spreads) {
      ddaslope::declareErrorShared();  // every rank refuses alike
      throw ddaslope::InputError("mpirun", "", "only probability, fos --sweep, critical --curve and backanalyse spread "
                                               "over MPI ranks; start this command without mpirun");
    }
    if (run->parsed()) return runCommand(casePath, overrides, runOpt);
    if (check->parsed()) return checkCommand(casePath, overrides);
    if (compare->parsed()) return compareContactsCommand(deformable, csvPath);
    if (critical->parsed()) return criticalCommand(casePath, overrides, crit);
    if (cut->parsed()) return cutCommand(casePath, cutOut);
    if (convert->parsed()) return convertCommand(convertOpt);
    if (ba->parsed()) return backanalyseCommand(jobPath, baOut, baJson, overrides, baProgress);
    if (fos->parsed()) return fosCommand(casePath, overrides, fosOpt);
    if (probability->parsed()) return ddaslope::cli::probabilityCommand(casePath, overrides, probOpt);
    if (reportCmd->parsed()) return ddaslope::cli::reportCommand(reportDir, reportOut);
  } catch (const ddaslope::InputError& e) {
    report("ddaslope: error: ", e.what());
    return kExitBadInput;
  } catch (const ddaslope::NonConvergenceError& e) {
    report("ddaslope: non-convergence: ", e.what());
    return kExitNonConvergence;
  } catch (const std::filesystem::filesystem_error& e) {
    // An --out that is a file, or a place the user may not write to: their input, not our bug.
    report("ddaslope: error: cannot write the output: ", e.what());
    return kExitBadInput;
  } catch (const std::exception& e) {
    report("ddaslope: internal error: ", e.what());
    return 1;
  }
  return kExitOk;
}

}  // namespace

int main(int argc, char** argv) {
  // Under mpirun every rank parses the same command line; the root reports and writes, the
  // others run their share of a study's forward runs (core/task_farm.hpp).
  ddaslope::startProcesses(argc, argv);
  if (ddaslope::processRank() != 0 && !std::freopen("/dev/null", "w", stdout)) return 1;
  const int code = runCommandLine(argc, argv);
  // An error on one rank must not leave the others waiting for it; one that every rank met in a
  // study's task ends them all normally, with its code.
  if (ddaslope::processCount() > 1 && code != kExitOk && code != kExitNonConvergence &&
      !ddaslope::errorSharedByAllProcesses())
    ddaslope::abortProcesses(code);
  ddaslope::stopProcesses();
  return code;
}

#pragma once
// `ddaslope fos CASE`: the strength-reduction factor of safety, F against one case number
// (--sweep), and whether a required F is met (--check).
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "cli_common.hpp"

namespace ddaslope::cli {

struct FosOptions {
  std::vector<std::string> joints;
  double width = 0.005;
  bool json = false;
  int threads = 2;
  std::string sweep;  ///< "json.path=min:max:n"
  std::string outDir = "out/fos";
  ProgressOptions progress;
  std::string vtkDir;  ///< every trial's final state as a VTK series (recordTrialStates)
  std::string trialStart = "held";  ///< settled or held (calibration::TrialStart)
  bool noLookAhead = false;         ///< calibration::SearchSettings::lookAhead off
  double check = 0;                 ///< --check F: one trial at F instead of a search (0: none)
  bool outGiven = false;            ///< --out given (a check's default folder is not a search's)
};

/// Registers the subcommand's options on `cmd` (its case, the model options into `overrides`, …).
void addFosOptions(CLI::App* cmd, std::string& casePath, Overrides& overrides, FosOptions& opt);

int fosCommand(const std::string& casePath, const Overrides& o, const FosOptions& opt);

}  // namespace ddaslope::cli

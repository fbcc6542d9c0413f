#pragma once
// `ddaslope run CASE --out DIR`: one forward run and its outputs (history.csv, summary.json,
// plots, snapshot pictures, the VTK series).
#include <string>
#include <vector>

#include "cli_common.hpp"

namespace ddaslope::cli {

struct RunCommandOptions {
  std::string outDir = "out";
  bool quiet = false;
  bool verbose = false;
  std::vector<double> snapshots;  ///< times (s) of PNG pictures
  int threads = 1;                ///< of the run's contact search and judgement
  bool vtk = false;               ///< the VTK series in outDir/vtk
  double vtkEvery = 0;            ///< s between VTK frames; 0: a hundredth of the duration
  /// --at-fos: the joints' strengths reduced by this factor as `fos` reduces them (0: not)
  double atFactor = 0;
  std::vector<std::string> reducedJoints;  ///< --joints: the joints --at-fos reduces (empty: all)
  std::string trialStart = "held";         ///< --trial-start: where --at-fos's equilibrium starts, as fos's trials
};

/// Registers the subcommand's options on `cmd` (its case, --out, --snapshots, --vtk, the model
/// options into `overrides`, …).
void addRunOptions(CLI::App* cmd, std::string& casePath, Overrides& overrides, RunCommandOptions& opt);

int runCommand(const std::string& casePath, const Overrides& o, const RunCommandOptions& opt);

}  // namespace ddaslope::cli

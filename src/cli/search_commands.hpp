#pragma once
// `ddaslope critical CASE` (a joint's critical cohesion or friction, its (c, φ) curve, the yield
// seismic coefficient) and `ddaslope fos CASE` (strength-reduction F, and F against one case
// number).
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "cli_common.hpp"

namespace ddaslope::cli {

struct CriticalOptions {
  std::string joint;
  std::string solve = "cohesion";
  std::string direction = "auto";  ///< of the seismic coefficient searched for: +x, -x or auto (both)
  double friction = -1;
  double cohesion = -1;
  double width = 0;
  bool json = false;
  int threads = 2;
  std::string curve;       ///< "phiMin:phiMax:n"
  std::string outDir = "out";
  ProgressOptions progress;
  std::string vtkDir;      ///< every trial's final state as a VTK series (recordTrialStates)
};

struct FosOptions {
  std::vector<std::string> joints;
  double width = 0.005;
  bool json = false;
  int threads = 2;
  std::string sweep;  ///< "json.path=min:max:n"
  std::string outDir = "out/fos";
  ProgressOptions progress;
  std::string vtkDir;  ///< every trial's final state as a VTK series (recordTrialStates)
};

/// Registers each subcommand's options on `cmd` (its case, the model options into `overrides`, …).
void addCriticalOptions(CLI::App* cmd, std::string& casePath, Overrides& overrides, CriticalOptions& opt);
void addFosOptions(CLI::App* cmd, std::string& casePath, Overrides& overrides, FosOptions& opt);

int criticalCommand(const std::string& casePath, const Overrides& o, const CriticalOptions& opt);
int fosCommand(const std::string& casePath, const Overrides& o, const FosOptions& opt);

}  // namespace ddaslope::cli

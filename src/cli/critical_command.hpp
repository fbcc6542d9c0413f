#pragma once
// `ddaslope critical CASE`: a joint's critical cohesion or friction angle by bisection, its (c, φ)
// curve, or the yield seismic coefficient k_y.
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
  std::string support;     ///< --solve support: the support or load sized
  double targetFactor = 1;  ///< --solve support: the factor of safety it must give
  bool noLookAhead = false;  ///< calibration::SearchSettings::lookAhead off
};

/// Registers the subcommand's options on `cmd` (its case, the model options into `overrides`, …).
void addCriticalOptions(CLI::App* cmd, std::string& casePath, Overrides& overrides, CriticalOptions& opt);

/// critical --solve support (critical_support.cpp).
int supportCommand(const std::string& casePath, const Overrides& o, ddaslope::model::Scene scene, const CriticalOptions& opt);

int criticalCommand(const std::string& casePath, const Overrides& o, const CriticalOptions& opt);

}  // namespace ddaslope::cli

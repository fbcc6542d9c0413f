#pragma once
// `ddaslope probability CASE`: the probability of failure of a slope whose inputs are uncertain
// (docs/probability.md).
#include <cstdint>
#include <string>

#include "cli_common.hpp"

namespace ddaslope::cli {

struct ProbabilityOptions {
  std::string outDir = "out/probability";
  int samples = 0;            ///< 0: the section's
  std::uint64_t seed = 0;
  bool seedGiven = false;     ///< --seed given (0 is a seed)
  std::string measure;        ///< verdict or fos; empty: the section's
  std::string sampling;       ///< monte_carlo or latin_hypercube; empty: the section's
  std::string method;         ///< sampling or importance_sampling; empty: the section's
  int threads = 2;            ///< samples run at once
  bool resume = false;        ///< continue the study in outDir, running only the samples it lacks
  bool overwrite = false;     ///< start again in an outDir that holds a study
  int stopAfter = 0;          ///< run at most this many samples now (0: all); --resume continues
  bool json = false;
  ProgressOptions progress;   ///< --quiet, --log-json
};

/// Registers the subcommand's options on `cmd` (its case, --out, --samples, …).
void addProbabilityOptions(CLI::App* cmd, std::string& path, ProbabilityOptions& opt);

int probabilityCommand(const std::string& path, const Overrides& o, const ProbabilityOptions& opt);

}  // namespace ddaslope::cli

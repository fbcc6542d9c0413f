#pragma once
// `ddaslope backanalyse JOB`: joint strengths (or any case value) from observations.
#include <string>

#include "cli_common.hpp"

namespace ddaslope::cli {

int backanalyseCommand(const std::string& jobPath, const std::string& outDir, bool json, const Overrides& o,
                       const ProgressOptions& progress);

}  // namespace ddaslope::cli

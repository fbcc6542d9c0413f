#pragma once
// `ddaslope check CASE` (validate and report, nothing runs), `ddaslope cut CASE` (a section's
// blocks as a plain case and a picture) and `ddaslope compare-contacts` (the edge-to-edge rule
// against original DDA and the closed form on 27 inclines).
#include <string>

#include "cli_common.hpp"

namespace ddaslope::cli {

int checkCommand(const std::string& casePath, const Overrides& o);
int cutCommand(const std::string& casePath, const std::string& outDir);
int compareContactsCommand(bool deformable, const std::string& csvPath);

}  // namespace ddaslope::cli

#pragma once
// `ddaslope report DIR`: one self-contained HTML file (report.html) of an analysis folder written
// by run, fos, critical, backanalyse or probability: the answer with its bracket or interval, the
// settings in force, every table of the result, and its pictures embedded.
#include <string>

namespace ddaslope::cli {

/// Writes DIR/report.html (or `outFile`); exit 2 when DIR holds no analysis.
int reportCommand(const std::string& dir, const std::string& outFile);

}  // namespace ddaslope::cli

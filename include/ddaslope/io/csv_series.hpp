#pragma once
// Two columns of a CSV file with a header row (observation series, reservoir levels).
#include <string>
#include <vector>

namespace ddaslope::io {

struct Series {
  std::vector<double> x, y;
};

/// The cell as a finite number, or false: the whole cell (trailing spaces aside) must be the
/// number (no "nan", "inf", overflow or trailing text).
bool finiteNumber(const std::string& cell, double& value);

/// The cells of a CSV line, split at commas, as spreadsheets write them: spaces and double quotes
/// around a cell removed, empty cells at the end (a trailing comma) dropped, and in a `header`
/// a UTF-8 byte-order mark (Excel's "CSV UTF-8").
std::vector<std::string> csvCells(const std::string& line, bool header = false);

/// The header's names, quoted and comma-separated, for a message ("found "time", "a_h"").
std::string headerFound(const std::vector<std::string>& header);

/// What is wrong with a header (a name given twice), or empty.
std::string headerProblem(const std::vector<std::string>& header);

/// What is wrong with a row of `cells` under a header of `names` (more cells than names), with
/// the row's text `line`, or empty.
std::string rowWidthProblem(const std::vector<std::string>& cells, size_t names, const std::string& line);

/// Reads columns `xColumn` and `yColumn`. Throws InputError naming `referrer` (the file and JSON
/// path that named the CSV) for a missing file or column, and the CSV file and row for a bad cell.
Series readCsvColumns(const std::string& csvPath, const std::string& xColumn, const std::string& yColumn,
                      const std::string& referrerFile, const std::string& referrerPath);

}  // namespace ddaslope::io

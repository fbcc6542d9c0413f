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

/// Reads columns `xColumn` and `yColumn`. Throws InputError naming `referrer` (the file and JSON
/// path that named the CSV) for a missing file or column, and the CSV file and row for a bad cell.
Series readCsvColumns(const std::string& csvPath, const std::string& xColumn, const std::string& yColumn,
                      const std::string& referrerFile, const std::string& referrerPath);

}  // namespace ddaslope::io

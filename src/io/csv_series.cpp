#include "ddaslope/io/csv_series.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "ddaslope/core/errors.hpp"
#include "ddaslope/io/input_file.hpp"

namespace ddaslope::io {
namespace {

std::vector<std::string> splitCells(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream ss(line);
  for (std::string cell; std::getline(ss, cell, ',');) cells.push_back(cell);
  return cells;
}

}  // namespace

bool finiteNumber(const std::string& cell, double& value) {
  const char* begin = cell.c_str();
  char* end = nullptr;
  errno = 0;
  value = std::strtod(begin, &end);
  if (end == begin || errno == ERANGE || !std::isfinite(value)) return false;
  while (*end == ' ' || *end == '\t' || *end == '\r') ++end;
  return *end == '\0';
}

Series readCsvColumns(const std::string& csvPath, const std::string& xColumn, const std::string& yColumn,
                      const std::string& referrerFile, const std::string& referrerPath) {
  const std::string text = readInputFile(csvPath, kMaxCsvFileBytes, referrerFile, referrerPath);
  // Every error names the case (or job) and path that referred to the CSV, and the CSV itself.
  const auto fail = [&](const std::string& what) {
    throw InputError(referrerFile, referrerPath, csvPath + ": " + what);
  };
  std::istringstream in(text);
  std::string line;
  std::getline(in, line);
  if (!line.empty() && line.back() == '\r') line.pop_back();
  const std::vector<std::string> header = splitCells(line);
  int xi = -1, yi = -1;
  for (size_t i = 0; i < header.size(); ++i) {
    if (header[i] == xColumn) xi = static_cast<int>(i);
    if (header[i] == yColumn) yi = static_cast<int>(i);
  }
  if (xi < 0 || yi < 0) fail("columns '" + xColumn + "' and '" + yColumn + "' expected in the header");
  Series s;
  for (int row = 2; std::getline(in, line); ++row) {
    if (line.empty() || line == "\r") continue;
    const std::vector<std::string> cells = splitCells(line);
    double x = 0, y = 0;
    const bool ok = static_cast<int>(cells.size()) > std::max(xi, yi) && finiteNumber(cells[xi], x) &&
                    finiteNumber(cells[yi], y);
    if (!ok) fail("row " + std::to_string(row) + ": expected finite numbers in columns '" + xColumn + "' and '" + yColumn + "'");
    s.x.push_back(x);
    s.y.push_back(y);
  }
  if (s.x.empty()) fail("no data rows");
  return s;
}

}  // namespace ddaslope::io

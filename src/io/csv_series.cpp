#include "ddaslope/io/csv_series.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "ddaslope/core/errors.hpp"
#include "ddaslope/io/input_file.hpp"

namespace ddaslope::io {

std::vector<std::string> csvCells(const std::string& line, bool header) {
  std::vector<std::string> cells;
  std::stringstream ss(line);
  for (std::string cell; std::getline(ss, cell, ',');) cells.push_back(cell);
  if (header && !cells.empty() && cells[0].rfind("\xEF\xBB\xBF", 0) == 0) cells[0].erase(0, 3);
  const auto trim = [](std::string& c) {
    const size_t a = c.find_first_not_of(" \t\r"), b = c.find_last_not_of(" \t\r");
    c = a == std::string::npos ? std::string() : c.substr(a, b - a + 1);
  };
  for (std::string& c : cells) {
    trim(c);
    if (c.size() >= 2 && c.front() == '"' && c.back() == '"') c = c.substr(1, c.size() - 2), trim(c);
  }
  // A trailing comma (a spreadsheet's empty last column) adds no cell.
  while (!cells.empty() && cells.back().empty()) cells.pop_back();
  return cells;
}

std::string headerFound(const std::vector<std::string>& header) {
  std::string out;
  for (size_t k = 0; k < header.size(); ++k) out += (k ? ", \"" : "\"") + header[k] + "\"";
  return header.empty() ? "an empty header" : out;
}

std::string headerProblem(const std::vector<std::string>& header) {
  for (size_t a = 0; a < header.size(); ++a)
    for (size_t b = a + 1; b < header.size(); ++b)
      if (header[a] == header[b])
        return "expected each column named once, found \"" + header[a] + "\" twice (" + headerFound(header) + ")";
  return "";
}

std::string rowWidthProblem(const std::vector<std::string>& cells, size_t names, const std::string& line) {
  if (cells.size() <= names) return "";
  std::string m = "expected " + std::to_string(names) + " cells as in the header, found " + std::to_string(cells.size()) +
                  " (\"" + line + "\")";
  // A number in the cell beyond the header: a decimal comma ("0,2,5" for 2.5) is the likely cause.
  double v = 0;
  if (finiteNumber(cells[names], v)) m += "; write decimals with a point";
  return m;
}

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
  const std::vector<std::string> header = csvCells(line, true);
  int xi = -1, yi = -1;
  for (size_t i = 0; i < header.size(); ++i) {
    if (header[i] == xColumn) xi = static_cast<int>(i);
    if (header[i] == yColumn) yi = static_cast<int>(i);
  }
  if (const std::string problem = headerProblem(header); !problem.empty()) fail("row 1: " + problem);
  if (xi < 0 || yi < 0)
    fail("columns '" + xColumn + "' and '" + yColumn + "' expected in the header, found " + headerFound(header));
  Series s;
  for (int row = 2; std::getline(in, line); ++row) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    const std::vector<std::string> cells = csvCells(line);
    if (const std::string problem = rowWidthProblem(cells, header.size(), line); !problem.empty())
      fail("row " + std::to_string(row) + ": " + problem);
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

#include "ddaslope/io/csv_series.hpp"

#include <fstream>
#include <sstream>

#include "ddaslope/core/errors.hpp"

namespace ddaslope::io {

Series readCsvColumns(const std::string& csvPath, const std::string& xColumn, const std::string& yColumn,
                      const std::string& referrerFile, const std::string& referrerPath) {
  std::ifstream in(csvPath);
  if (!in) throw InputError(referrerFile, referrerPath, "cannot open the CSV file " + csvPath);
  const auto split = [](const std::string& line) {
    std::vector<std::string> cells;
    std::stringstream ss(line);
    for (std::string cell; std::getline(ss, cell, ',');) cells.push_back(cell);
    return cells;
  };
  std::string line;
  std::getline(in, line);
  const std::vector<std::string> header = split(line);
  int xi = -1, yi = -1;
  for (size_t i = 0; i < header.size(); ++i) {
    if (header[i] == xColumn) xi = static_cast<int>(i);
    if (header[i] == yColumn) yi = static_cast<int>(i);
  }
  if (xi < 0 || yi < 0)
    throw InputError(referrerFile, referrerPath,
                     "columns '" + xColumn + "' and '" + yColumn + "' expected in the header of " + csvPath);
  Series s;
  for (int row = 2; std::getline(in, line); ++row) {
    if (line.empty()) continue;
    const std::vector<std::string> cells = split(line);
    try {
      s.x.push_back(std::stod(cells.at(xi)));
      s.y.push_back(std::stod(cells.at(yi)));
    } catch (const std::exception&) {
      throw InputError(csvPath, "row " + std::to_string(row),
                       "expected numbers in columns '" + xColumn + "' and '" + yColumn + "'");
    }
  }
  if (s.x.empty()) throw InputError(referrerFile, referrerPath, "no data rows in " + csvPath);
  return s;
}

}  // namespace ddaslope::io

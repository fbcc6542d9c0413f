#pragma once
// Ground-motion records: a PEER NGA .AT2 file (four header lines, the third naming
// the units, the fourth NPTS and DT, then the accelerations in g) or a CSV with a time column
// and one or two acceleration columns. Every defect is an InputError naming the case and JSON path
// that referred to the record, the record file and its line.
#include <optional>
#include <string>

#include "ddaslope/model/seismic.hpp"

namespace ddaslope::io {

/// Standard gravity (m/s²): a record in g is converted with it, whatever the case's gravity.
constexpr double kStandardGravity = 9.80665;

struct RecordSpec {
  std::string file;                  ///< path of the record
  std::string format;                ///< "at2" or "csv"
  std::string units;                 ///< "g" or "m/s2" (CSV: required; AT2: checked against the file)
  double scale = 1;                  ///< multiplies the accelerations (negative: along −x)
  double start = 0;                  ///< analysis time of the record's t = 0 (s)
  std::optional<double> dt;          ///< the sample interval the case expects, checked against the file
  std::string timeColumn = "time";   ///< CSV columns
  std::string horizontalColumn = "a_h";
  std::string verticalColumn;        ///< empty: no vertical component
};

/// Reads the record; `referrerFile`/`referrerPath` name the case and the JSON path of the record.
model::GroundMotion readGroundMotion(const RecordSpec& spec, const std::string& referrerFile,
                                     const std::string& referrerPath);

}  // namespace ddaslope::io

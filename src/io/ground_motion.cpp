#include "ddaslope/io/ground_motion.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <regex>
#include <sstream>
#include <vector>

#include "ddaslope/core/errors.hpp"
#include "ddaslope/io/csv_series.hpp"
#include "ddaslope/io/input_file.hpp"
#include "ddaslope/model/input_limits.hpp"

namespace ddaslope::io {
namespace {

/// Builds the errors of one record: the case and JSON path that named it, the record and a line.
struct RecordErrors {
  std::string referrerFile, referrerPath, record;
  [[noreturn]] void fail(int line, const std::string& what) const {
    const std::string where = line > 0 ? ", line " + std::to_string(line) : "";
    throw InputError(referrerFile, referrerPath, record + where + ": " + what);
  }
};

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    out.push_back(line);
  }
  return out;
}

/// A record's accelerations in m/s² stay within ±kMaxGroundAcceleration: what a run takes
/// without overflowing (a value in g near the largest double is inf in m/s²).
const std::string kAccelerationRange = "within ±100 g (1000 m/s²)";
bool withinRange(double acceleration) { return std::abs(acceleration) <= model::limits::kMaxGroundAcceleration; }

std::string upper(std::string s) {
  for (char& c : s) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return s;
}

/// Checks the sample interval the case states against the record's.
void checkInterval(const RecordSpec& spec, double dt, int line, const RecordErrors& err) {
  if (spec.dt && std::abs(*spec.dt - dt) > 1e-6 * std::max(*spec.dt, dt)) {
    std::ostringstream m;
    m << "the case expects samples every " << *spec.dt << " s, the record has " << dt << " s";
    err.fail(line, m.str());
  }
}

/// PEER NGA .AT2: lines 1-2 free text, line 3 the units ("... IN UNITS OF G"), line 4
/// "NPTS=  3930, DT= .0100 SEC" (or the older "3930 0.0100 NPTS, DT"), then NPTS values in g.
model::GroundMotion readAt2(const std::string& text, const RecordSpec& spec, const RecordErrors& err) {
  const std::vector<std::string> ls = lines(text);
  if (ls.size() < 5) err.fail(static_cast<int>(ls.size()), "expected four header lines and the accelerations (PEER .AT2)");
  if (upper(ls[2]).find("UNITS OF G") == std::string::npos)
    err.fail(3, "expected the units (\"... IN UNITS OF G\"), found \"" + ls[2] + "\"");
  if (!spec.units.empty() && spec.units != "g")
    err.fail(3, "the case says units \"" + spec.units + "\", the record is in g");
  static const std::regex modern(R"(NPTS\s*=\s*([0-9]+)\s*,\s*DT\s*=\s*([0-9.eE+-]+))", std::regex::icase);
  static const std::regex older(R"(^\s*([0-9]+)\s+([0-9.eE+-]+)\s+NPTS\s*,\s*DT)", std::regex::icase);
  std::smatch m;
  if (!std::regex_search(ls[3], m, modern) && !std::regex_search(ls[3], m, older))
    err.fail(4, "expected NPTS and DT (\"NPTS= 3930, DT= .0100 SEC\"), found \"" + ls[3] + "\"");
  double npts = 0, dt = 0;
  if (!finiteNumber(m[1].str(), npts) || npts < 2 || npts > 1e7)
    err.fail(4, "expected NPTS in [2, 1e7], found " + m[1].str());
  if (!finiteNumber(m[2].str(), dt) || !(dt > 0) || dt > 10) err.fail(4, "expected DT in (0, 10] s, found " + m[2].str());
  checkInterval(spec, dt, 4, err);
  std::vector<double> a;
  for (size_t i = 4; i < ls.size(); ++i) {
    std::istringstream in(ls[i]);
    for (std::string token; in >> token;) {
      double v = 0;
      if (!finiteNumber(token, v)) err.fail(static_cast<int>(i + 1), "expected a finite acceleration, found \"" + token + "\"");
      if (!withinRange(kStandardGravity * v)) err.fail(static_cast<int>(i + 1), "expected an acceleration " + kAccelerationRange + ", found \"" + token + "\" g");
      a.push_back(v);
    }
  }
  if (a.size() != static_cast<size_t>(npts)) {
    std::ostringstream msg;
    msg << "NPTS = " << static_cast<long>(npts) << " on line 4, but the record holds " << a.size()
        << " values: the header disagrees with the data";
    err.fail(static_cast<int>(ls.size()), msg.str());
  }
  model::GroundMotion g;
  for (size_t k = 0; k < a.size(); ++k) {
    g.times.push_back(spec.start + static_cast<double>(k) * dt);
    g.horizontal.push_back(spec.scale * kStandardGravity * a[k]);
  }
  return g;
}

/// CSV with a header row: time (s), horizontal and optionally vertical acceleration.
model::GroundMotion readCsv(const std::string& text, const RecordSpec& spec, const RecordErrors& err) {
  if (spec.units != "g" && spec.units != "m/s2")
    err.fail(0, "expected the units of a CSV record in the case (seismic.record.units: \"g\" or \"m/s2\")");
  const double unit = spec.units == "g" ? kStandardGravity : 1.0;
  const std::vector<std::string> ls = lines(text);
  if (ls.empty()) err.fail(1, "expected a header row");
  const std::vector<std::string> header = csvCells(ls[0], true);
  if (const std::string problem = headerProblem(header); !problem.empty()) err.fail(1, problem);
  const auto column = [&](const std::string& name) {
    if (name.empty()) return -1;
    const auto it = std::find(header.begin(), header.end(), name);
    if (it == header.end()) err.fail(1, "expected a column \"" + name + "\" in the header, found " + headerFound(header));
    return static_cast<int>(it - header.begin());
  };
  const int ti = column(spec.timeColumn), hi = column(spec.horizontalColumn), vi = column(spec.verticalColumn);
  model::GroundMotion g;
  for (size_t i = 1; i < ls.size(); ++i) {
    if (ls[i].empty()) continue;
    const std::vector<std::string> cells = csvCells(ls[i]);
    const int line = static_cast<int>(i + 1);
    if (const std::string problem = rowWidthProblem(cells, header.size(), ls[i]); !problem.empty()) err.fail(line, problem);
    const auto cell = [&](int c, const std::string& what) {
      double v = 0;
      if (c >= static_cast<int>(cells.size()) || !finiteNumber(cells[c], v))
        err.fail(line, "expected a finite " + what + ", found \"" + (c < static_cast<int>(cells.size()) ? cells[c] : "") + "\"");
      return v;
    };
    // An analysis never runs past kMaxDuration, and times beyond it overflow the interpolation.
    const auto time = [&](int c) {
      const double v = cell(c, "time");
      if (!(std::abs(v) <= model::limits::kMaxDuration)) err.fail(line, "expected a time within ±1e6 s, found \"" + cells[c] + "\"");
      return v;
    };
    const auto acceleration = [&](int c, const std::string& what) {
      const double v = cell(c, what);
      if (!withinRange(unit * v)) err.fail(line, "expected a " + what + " " + kAccelerationRange + ", found \"" + cells[c] + "\" " + spec.units);
      return v;
    };
    const double t = time(ti);
    // The record's time 0 is the analysis's start (or seismic.record.start): a sample before it
    // would never be applied, and the record would start with the step to the first one after.
    if (t < 0)
      err.fail(line, "expected times >= 0 s (a record's time 0 is the analysis's start; seismic.record.start "
                     "delays it), found " + cells[ti]);
    if (!g.times.empty() && !(spec.start + t > g.times.back()))
      err.fail(line, "expected times increasing, found " + cells[ti] + " after " + std::to_string(g.times.back() - spec.start));
    g.times.push_back(spec.start + t);
    g.horizontal.push_back(spec.scale * unit * acceleration(hi, "horizontal acceleration"));
    if (vi >= 0) g.vertical.push_back(spec.scale * unit * acceleration(vi, "vertical acceleration"));
  }
  if (g.times.size() < 2) err.fail(static_cast<int>(ls.size()), "expected at least two samples");
  if (spec.dt) {
    for (size_t k = 1; k < g.times.size(); ++k) checkInterval(spec, g.times[k] - g.times[k - 1], static_cast<int>(k + 2), err);
  }
  return g;
}

}  // namespace

model::GroundMotion readGroundMotion(const RecordSpec& spec, const std::string& referrerFile,
                                     const std::string& referrerPath) {
  const RecordErrors err{referrerFile, referrerPath, spec.file};
  const std::string text = readInputFile(spec.file, kMaxCsvFileBytes, referrerFile, referrerPath);
  if (spec.format == "at2") return readAt2(text, spec, err);
  if (spec.format == "csv") return readCsv(text, spec, err);
  err.fail(0, "expected the format \"at2\" or \"csv\", found \"" + spec.format + "\"");
}

}  // namespace ddaslope::io

#pragma once
// The case reader's view of a JSON document: every error names the file and the JSON path, says
// what was expected and what was found (exit 2). Shared by the case reader's files, one per part
// of a case (io/case_reader.cpp, io/section_reader.cpp).
#include <cctype>
#include <cmath>
#include <set>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "ddaslope/core/errors.hpp"
#include "ddaslope/core/types.hpp"

namespace ddaslope::io::case_json {

using nlohmann::json;

inline std::string typeName(const json& j) {
  if (j.is_number()) return "a number";
  if (j.is_string()) return "a string \"" + j.get<std::string>() + "\"";
  if (j.is_boolean()) return "a boolean";
  if (j.is_array()) return "an array of " + std::to_string(j.size());
  if (j.is_object()) return "an object";
  return "null";
}

/// Reads one JSON document with paths in every error message.
class Reader {
 public:
  explicit Reader(std::string file) : file_(std::move(file)) {}

  [[noreturn]] void fail(const std::string& path, const std::string& msg) const {
    throw InputError(file_, path, msg);
  }
  void object(const json& j, const std::string& path) const {
    if (!j.is_object()) fail(path, "expected an object, found " + typeName(j));
  }
  void onlyKeys(const json& j, const std::string& path, const std::set<std::string>& allowed) const {
    object(j, path);
    for (const auto& [k, v] : j.items()) {
      if (allowed.count(k)) continue;
      std::string list;
      for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
      fail(join(path, k), "unknown key '" + k + "' (allowed here: " + list + ")");
    }
  }
  static std::string join(const std::string& path, const std::string& key) {
    return path.empty() ? key : path + "." + key;
  }
  static std::string index(const std::string& path, size_t i) {
    return path + "[" + std::to_string(i) + "]";
  }
  const json& required(const json& j, const std::string& path, const std::string& key) const {
    if (!j.contains(key)) fail(join(path, key), "required key is missing");
    return j.at(key);
  }
  double number(const json& j, const std::string& path) const {
    if (!j.is_number()) fail(path, "expected a number, found " + typeName(j));
    const double v = j.get<double>();
    if (!std::isfinite(v)) fail(path, "expected a finite number");
    return v;
  }
  /// Number in [lo, hi] (open ends where the flags say so).
  double numberIn(const json& j, const std::string& path, double lo, double hi, bool loOpen,
                  bool hiOpen, const std::string& what) const {
    const double v = number(j, path);
    const bool ok = (loOpen ? v > lo : v >= lo) && (hiOpen ? v < hi : v <= hi);
    if (!ok) {
      std::ostringstream m;
      m << "expected " << what << ", found " << v;
      fail(path, m.str());
    }
    return v;
  }
  double optionalIn(const json& j, const std::string& path, const std::string& key, double def,
                    double lo, double hi, bool loOpen, bool hiOpen, const std::string& what) const {
    if (!j.contains(key)) return def;
    return numberIn(j.at(key), join(path, key), lo, hi, loOpen, hiOpen, what);
  }
  int integerIn(const json& j, const std::string& path, const std::string& key, int def, int lo,
                int hi) const {
    if (!j.contains(key)) return def;
    const json& v = j.at(key);
    if (!v.is_number_integer()) fail(join(path, key), "expected an integer, found " + typeName(v));
    const long long x = v.get<long long>();
    if (x < lo || x > hi)
      fail(join(path, key), "expected an integer in [" + std::to_string(lo) + ", " +
                                std::to_string(hi) + "], found " + std::to_string(x));
    return static_cast<int>(x);
  }
  bool boolean(const json& j, const std::string& path, const std::string& key, bool def) const {
    if (!j.contains(key)) return def;
    if (!j.at(key).is_boolean()) fail(join(path, key), "expected true or false, found " + typeName(j.at(key)));
    return j.at(key).get<bool>();
  }
  std::string string(const json& j, const std::string& path) const {
    if (!j.is_string()) fail(path, "expected a string, found " + typeName(j));
    return j.get<std::string>();
  }
  std::string choice(const json& j, const std::string& path, const std::string& key,
                     const std::string& def, const std::set<std::string>& options) const {
    if (!j.contains(key)) return def;
    std::string list;
    for (const auto& o : options) list += (list.empty() ? "" : ", ") + o;
    const json& value = j.at(key);
    if (!value.is_string()) fail(join(path, key), "expected one of " + list + " (a string), found " + typeName(value));
    const std::string v = value.get<std::string>();
    if (!options.count(v)) fail(join(path, key), "expected one of " + list + ", found \"" + v + "\"");
    return v;
  }
  /// A name that appears in output headers and file names (history.csv columns, summary.json):
  /// letters, digits, '_', '-' and '.', 1 to 64 of them, so no output can be misread.
  std::string identifier(const std::string& name, const std::string& path) const {
    bool safe = !name.empty() && name.size() <= 64;
    for (const char ch : name)
      safe = safe && (std::isalnum(static_cast<unsigned char>(ch)) || ch == '_' || ch == '-' || ch == '.');
    if (!safe)
      fail(path, "expected a name of 1-64 letters, digits, '_', '-' or '.', found \"" + name.substr(0, 80) + "\"");
    return name;
  }
  Vec2 point(const json& j, const std::string& path) const {
    if (!j.is_array() || j.size() != 2) fail(path, "expected a point [x, y], found " + typeName(j));
    return {number(j[0], index(path, 0)), number(j[1], index(path, 1))};
  }

  const std::string& file() const { return file_; }

 private:
  std::string file_;
};

}  // namespace ddaslope::io::case_json

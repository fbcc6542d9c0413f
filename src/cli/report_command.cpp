#include "report_command.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <optional>
#include <fstream>
#include <sstream>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli_common.hpp"
#include "ddaslope/calibration/verdict.hpp"
#include "ddaslope/core/errors.hpp"
#include "ddaslope/io/vtk_writer.hpp"

namespace ddaslope::cli {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

std::string escape(const std::string& s) { return io::xmlEscaped(s); }

std::string base64(const std::string& bytes) {
  static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const unsigned v = static_cast<unsigned char>(bytes[i]) << 16 | static_cast<unsigned char>(bytes[i + 1]) << 8 |
                       static_cast<unsigned char>(bytes[i + 2]);
    out += {table[v >> 18], table[v >> 12 & 63], table[v >> 6 & 63], table[v & 63]};
  }
  if (i + 1 == bytes.size()) {
    const unsigned v = static_cast<unsigned char>(bytes[i]) << 16;
    out += {table[v >> 18], table[v >> 12 & 63], '=', '='};
  } else if (i + 2 == bytes.size()) {
    const unsigned v = static_cast<unsigned char>(bytes[i]) << 16 | static_cast<unsigned char>(bytes[i + 1]) << 8;
    out += {table[v >> 18], table[v >> 12 & 63], table[v >> 6 & 63], '='};
  }
  return out;
}

std::string scalar(const json& v) {
  if (v.is_string()) return escape(v.get<std::string>());
  if (v.is_null()) return "&ndash;";
  if (v.is_number_float()) {
    char t[32];
    std::snprintf(t, sizeof t, "%.6g", v.get<double>());
    return t;
  }
  return escape(v.dump());
}

/// A JSON value as HTML: an object as a two-column table, an array of objects as a table with a
/// column per key, an array of scalars as a list.
std::string render(const json& v, int depth = 0) {
  if (v.is_object()) {
    std::string h = "<table class=\"kv\">";
    for (const auto& [k, x] : v.items()) h += "<tr><th>" + escape(k) + "</th><td>" + render(x, depth + 1) + "</td></tr>";
    return h + "</table>";
  }
  if (v.is_array()) {
    const bool rows = !v.empty() && std::all_of(v.begin(), v.end(), [](const json& e) { return e.is_object(); });
    if (!rows) {
      std::string h;
      for (const auto& e : v) h += (h.empty() ? "" : ", ") + render(e, depth + 1);
      return h.empty() ? "&ndash;" : h;
    }
    std::vector<std::string> keys;
    for (const auto& e : v)
      for (const auto& [k, x] : e.items())
        if (std::find(keys.begin(), keys.end(), k) == keys.end()) keys.push_back(k);
    std::string h = "<table class=\"rows\"><tr>";
    for (const auto& k : keys) h += "<th>" + escape(k) + "</th>";
    h += "</tr>";
    for (const auto& e : v) {
      h += "<tr>";
      for (const auto& k : keys) h += "<td>" + (e.contains(k) ? render(e.at(k), depth + 1) : std::string()) + "</td>";
      h += "</tr>";
    }
    return h + "</table>";
  }
  return scalar(v);
}

json readJson(const fs::path& p) {
  try {
    return json::parse(slurp(p));
  } catch (const json::exception& e) {
    throw InputError(p.string(), "", std::string("expected the JSON ddaslope wrote, found a damaged file (") + e.what() +
                                         ")");
  }
}

double number(const json& j, const char* key) {
  return j.contains(key) && j.at(key).is_number() ? j.at(key).get<double>() : NAN;
}

/// The analysis in a folder: its kind, its result and the headline answer.
struct Analysis {
  std::string kind, file;
  json result;
  std::string answer;
  std::vector<std::string> columns;  ///< a sweep's or curve's: its points' columns, in the CSV's order
  std::string note;                  ///< other results in the folder, not reported
};

/// Where the answer's tension crack was, for the headline: the least safe position a search found,
/// or the case's own.
std::string crackText(const json& r) {
  if (!r.contains("tension_crack") || !r["tension_crack"].is_object()) return "";
  const json& t = r["tension_crack"];
  if (!t.contains("x") || !t["x"].is_number()) return "";
  char text[160];
  const double x = t["x"].get<double>();
  if (!t.contains("position_found") || !t["position_found"].is_boolean()) std::snprintf(text, sizeof text, "; tension crack at x = %.4g m", x);
  else if (t["position_found"].get<bool>())
    std::snprintf(text, sizeof text, "; least safe tension crack at x = %.4g m%s", x,
                  t.value("position_fails", false) ? ", where the slope fails at every value tried" : "");
  else std::snprintf(text, sizeof text, "; no crack position least safe: the crack at the case's x = %.4g m", x);
  return text;
}

/// A sweep's or curve's CSV as the report's result: one object per point (empty fields null), and
/// a headline of its span.
Analysis curveOf(const fs::path& file, const std::string& kind) {
  std::ifstream in(file);
  std::string line;
  std::vector<std::string> header;
  const auto split = [](const std::string& l) {
    std::vector<std::string> f;
    std::stringstream ss(l);
    for (std::string x; std::getline(ss, x, ',');) f.push_back(x);
    if (!l.empty() && l.back() == ',') f.emplace_back();
    return f;
  };
  const auto next = [&] {
    if (!std::getline(in, line)) return false;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    return true;
  };
  if (!next() || line.empty()) throw InputError(file.string(), "line 1", "expected the CSV's header, found an empty line");
  header = split(line);
  json points = json::array();
  for (int row = 2; next(); ++row) {
    if (line.empty()) continue;
    const std::vector<std::string> f = split(line);
    if (f.size() != header.size())
      throw InputError(file.string(), "line " + std::to_string(row),
                       "expected " + std::to_string(header.size()) + " fields, found " + std::to_string(f.size()));
    json p = json::object();
    for (size_t i = 0; i < f.size(); ++i) {
      char* end = nullptr;
      const double v = std::strtod(f[i].c_str(), &end);
      p[header[i]] = f[i].empty() ? json() : end && *end == '\0' ? json(v) : json(f[i]);
    }
    if (!p[header[0]].is_number())
      throw InputError(file.string(), "line " + std::to_string(row) + ", " + header[0],
                       "expected the value swept (a number), found \"" + f[0] + "\"");
    points.push_back(p);
  }
  // ddaslope writes at least two points: fewer is a cut-off file.
  if (points.size() < 2)
    throw InputError(file.string(), "", "expected a row per point (at least 2), found " + std::to_string(points.size()) +
                                            ": a cut-off file; run the sweep or curve again");
  Analysis a{kind, file.filename().string(), json{{"points", points}}, "", header, ""};
  // The swept value (first column) and the answer (second): their spans, and the points without one.
  double lo = INFINITY, hi = -INFINITY, vlo = INFINITY, vhi = -INFINITY;
  int none = 0;
  for (const json& p : points) {
    const json& x = p[header[0]];
    const json& v = header.size() > 1 ? p[header[1]] : json();
    if (x.is_number()) lo = std::min(lo, x.get<double>()), hi = std::max(hi, x.get<double>());
    if (v.is_number()) vlo = std::min(vlo, v.get<double>()), vhi = std::max(vhi, v.get<double>());
    else ++none;
  }
  char text[512];
  if (vlo > vhi)
    std::snprintf(text, sizeof text, "%zu points of %s from %.6g to %.6g: none gave %s", points.size(), header[0].c_str(),
                  lo, hi, header.size() > 1 ? header[1].c_str() : "a value");
  else
    std::snprintf(text, sizeof text, "%zu points of %s from %.6g to %.6g: %s from %.6g to %.6g%s", points.size(),
                  header[0].c_str(), lo, hi, header[1].c_str(), vlo, vhi,
                  none ? (", " + std::to_string(none) + " without an answer").c_str() : "");
  a.answer = text;
  return a;
}

/// The result files of single analyses, and of sweeps and curves (a CSV of points, and its
/// picture beside it with the same name) with their titles.
const std::vector<std::string> kSingleResults = {"fos.json", "critical.json", "result.json", "summary.json"};
const std::vector<std::pair<std::string, std::string>> kCurveResults = {
    {"fos_sweep.csv", "Factor of safety over a sweep (fos --sweep)"},
    {"critical_curve.csv", "Critical strength curve (critical --curve)"},
    {"support_curve.csv", "Support curve (critical --solve support --curve)"}};

/// The sweep or curve CSV in the folder, if it was written after every single result there (a
/// folder that several commands wrote into): the newest analysis is the one reported.
std::optional<std::pair<std::string, std::string>> newerCurve(const fs::path& dir) {
  std::optional<std::pair<std::string, std::string>> newest;
  fs::file_time_type when{};
  for (const auto& c : kCurveResults)
    if (fs::exists(dir / c.first) && (!newest || fs::last_write_time(dir / c.first) > when))
      newest = c, when = fs::last_write_time(dir / c.first);
  if (!newest) return std::nullopt;
  for (const auto& single : kSingleResults)
    if (fs::exists(dir / single) && fs::last_write_time(dir / single) > when) return std::nullopt;
  return newest;
}

/// Results in the folder other than `reported` (several commands wrote into it).
std::string otherResults(const fs::path& dir, const std::string& reported) {
  std::vector<std::string> files = kSingleResults;
  for (const auto& c : kCurveResults) files.push_back(c.first);
  std::string others;
  for (const auto& f : files)
    if (f != reported && fs::exists(dir / f)) others += (others.empty() ? "" : ", ") + f;
  return others.empty() ? "" : "the folder also holds " + others + " (older, not in this report: give each analysis a "
                                                                   "folder of its own with --out)";
}

Analysis identifyOne(const fs::path& dir);

Analysis identify(const fs::path& dir) {
  Analysis a;
  if (const auto curve = newerCurve(dir)) a = curveOf(dir / curve->first, curve->second);
  else a = identifyOne(dir);
  a.note = otherResults(dir, a.file);
  return a;
}

/// The newest of the single results in the folder (several commands may have written into it:
/// the pictures beside it are the last command's); empty if none.
std::string newestSingle(const fs::path& dir) {
  std::string newest;
  fs::file_time_type when{};
  for (const auto& single : kSingleResults)
    if (fs::exists(dir / single) && (newest.empty() || fs::last_write_time(dir / single) > when))
      newest = single, when = fs::last_write_time(dir / single);
  return newest;
}

Analysis identifyOne(const fs::path& dir) {
  Analysis a;
  char text[512];
  const std::string chosen = newestSingle(dir);
  if (chosen == "fos.json") {
    a = {"Factor of safety (fos)", "fos.json", readJson(dir / "fos.json"), "", {}, ""};
    const json& r = a.result;
    if (r.contains("check") && r["check"].is_number()) {
      // fos --check: one trial at a required F.
      a.kind = "Required factor of safety checked (fos --check)";
      const std::string verdict = r.value("verdict", "");
      std::string joints;
      if (r.contains("joints") && r["joints"].is_array())
        for (const auto& n : r["joints"])
          if (n.is_string()) joints += (joints.empty() ? "" : ", ") + n.get<std::string>();
      std::snprintf(text, sizeof text, "required F = %.6g: %s (joints: %s; %d forward run%s)", number(r, "check"),
                    verdict == "stable"      ? "met, the slope stands with its joints' strengths divided by it"
                    : verdict == "failing"   ? "not met, the slope fails with its joints' strengths divided by it"
                    : verdict == "undecided" ? "undecided, a small motion that neither grew nor stopped (see the trials)"
                                             : "not converged, the trial could not say (see the trials)",
                    joints.c_str(), r.value("forward_runs", 0), r.value("forward_runs", 0) == 1 ? "" : "s");
    } else if (r.value("found", false))
      std::snprintf(text, sizeof text, "F = %.4f: stable at %.4f, failing at %.4f (%d forward runs)",
                    number(r, "factor_of_safety"), r["bracket"][0].get<double>(), r["bracket"][1].get<double>(),
                    r.value("forward_runs", 0));
    else
      std::snprintf(text, sizeof text, "no factor of safety found: %s", r.value("message", "").c_str());
    a.answer = text + crackText(r);
  } else if (chosen == "critical.json") {
    a = {"Critical strength (critical)", "critical.json", readJson(dir / "critical.json"), "", {}, ""};
    const json& r = a.result;
    const std::string solve = r.value("solve", "");
    if (solve == "seismic-coefficient") a.kind = "Yield seismic coefficient (critical --solve seismic-coefficient)";
    else if (solve == "support") a.kind = "Support or load for a factor of safety (critical --solve support)";
    else if (solve == "jrc") a.kind = "Critical JRC (critical --solve jrc)";
    // The other strength, held while this one was solved for.
    char held[64] = "";
    if (r.contains("friction_angle_deg")) std::snprintf(held, sizeof held, " at φ = %.4g°", number(r, "friction_angle_deg"));
    if (r.contains("cohesion_pa")) std::snprintf(held, sizeof held, " at c = %.6g Pa", number(r, "cohesion_pa"));
    // Seismic coefficients and supports belong to the slope, not to one joint.
    const std::string joint = r.value("joint", "");
    const std::string of = joint.empty() ? "" : " of joint " + joint;
    // A support's quantity and the F it holds the slope at; a seismic coefficient's direction.
    std::string what = "critical " + solve + of + held;
    if (solve == "support" && r.contains("support") && r["support"].is_string()) {
      char at[96] = "";
      if (r.contains("target_factor_of_safety") && r["target_factor_of_safety"].is_number())
        std::snprintf(at, sizeof at, " at F = %.4g", number(r, "target_factor_of_safety"));
      what = r.value("quantity", std::string("size")) + " of " + r["support"].get<std::string>() + at;
    }
    if (solve == "seismic-coefficient" && r.contains("direction") && r["direction"].is_string())
      what = "yield seismic coefficient k_y along " + r["direction"].get<std::string>();
    if (r.value("found", false) && r.contains("bracket") && r["bracket"].size() == 2 && r["bracket"][0].is_number() &&
        r["bracket"][1].is_number())
      std::snprintf(text, sizeof text, "%s = %.6g %s: failing at %.6g, stable at %.6g", what.c_str(),
                    number(r, "critical"), r.value("unit", "").c_str(), r["bracket"][0].get<double>(),
                    r["bracket"][1].get<double>());
    else if (r.value("found", false))
      std::snprintf(text, sizeof text, "%s = %.6g %s", what.c_str(), number(r, "critical"), r.value("unit", "").c_str());
    else
      std::snprintf(text, sizeof text, "no critical value found: %s", r.value("message", "").c_str());
    a.answer = text + crackText(r);
  } else if (chosen == "result.json") {
    a = {"Back-analysis (backanalyse)", "result.json", readJson(dir / "result.json"), "", {}, ""};
    std::string estimate;
    if (a.result.contains("estimate"))
      for (const auto& [k, v] : a.result["estimate"].items()) estimate += k + " = " + scalar(v) + ", ";
    a.answer = estimate + "misfit " + scalar(a.result.value("misfit", json())) + " after " +
               scalar(a.result.value("evaluations", json())) + " evaluations";
  } else if (chosen == "summary.json") {
    json r = readJson(dir / "summary.json");
    if (r.contains("probability_of_failure")) {
      a = {"Probability of failure (probability)", "summary.json", r, "", {}, ""};
      // A bound or β the summary leaves null (no failing sample; Pf of 0 or 1) is said in words.
      const auto shown = [](const json& v, const char* none) {
        if (!v.is_number()) return std::string(none);
        char n[32];
        std::snprintf(n, sizeof n, "%.4g", v.get<double>());
        return std::string(n);
      };
      const double pf = number(r, "probability_of_failure");
      std::snprintf(text, sizeof text, "Pf = %.4g, 95 %% interval %s to %s (%s); reliability index %s", pf,
                    shown(r["interval_95"][0], "none").c_str(), shown(r["interval_95"][1], "none").c_str(),
                    r.value("interval_method", "").c_str(),
                    shown(r.value("reliability_index", json()), pf == 0 ? "unbounded (no sample fails)" : "-∞ (every sample fails)").c_str());
      a.answer = text;
    } else if (r.contains("steps")) {
      a = {"Forward run (run)", "summary.json", r, "", {}, ""};
      std::snprintf(text, sizeof text, "%s: %d steps to t = %.4g s", r.value("status", "").c_str(),
                    r.value("steps", 0), number(r, "time"));
      a.answer = text;
      // run --at-fos: not the case's own strengths, which its description states.
      if (r.contains("strength_reduction")) {
        std::snprintf(text, sizeof text, "at F = %.6g (joint strengths reduced as fos does, not the case's own): ",
                      number(r["strength_reduction"], "factor"));
        a.answer = text + a.answer;
      }
    }
  }
  if (a.kind.empty()) {
    throw InputError(dir.string(), "",
                     "expected a folder written by run, fos, critical, backanalyse or probability (summary.json, "
                     "fos.json, critical.json, result.json, fos_sweep.csv, critical_curve.csv or support_curve.csv), "
                     "found none");
  }
  return a;
}

/// The pictures of the analysis reported (`file`), the answer's first: mechanism, then snapshots,
/// then the rest. A sweep's or curve's picture belongs to it alone.
std::vector<fs::path> pictures(const fs::path& dir, const std::string& file) {
  const auto pictureOf = [](const std::string& csv) { return fs::path(csv).replace_extension(".png").string(); };
  const auto ofACurve = [&](const std::string& name) {
    return std::any_of(kCurveResults.begin(), kCurveResults.end(), [&](const auto& c) { return pictureOf(c.first) == name; });
  };
  const std::string own = pictureOf(file);
  const bool curve = ofACurve(own);
  // In a folder several commands wrote into, a picture not written since the last of the other
  // results is an earlier analysis's (a run's history beside a search's mechanism).
  std::optional<fs::file_time_type> earlier;
  std::vector<std::string> results = kSingleResults;
  for (const auto& c : kCurveResults) results.push_back(c.first);
  for (const auto& r : results)
    if (r != file && fs::exists(dir / r) && (!earlier || fs::last_write_time(dir / r) > *earlier))
      earlier = fs::last_write_time(dir / r);
  std::vector<fs::path> png;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (e.is_regular_file() && e.path().extension() == ".png" && (curve ? name == own : !ofACurve(name)) &&
        !(earlier && e.last_write_time() <= *earlier))
      png.push_back(e.path());
  }
  const auto rank = [](const fs::path& p) {
    const std::string n = p.filename().string();
    return n.rfind("mechanism", 0) == 0 ? 0 : n.rfind("snapshot", 0) == 0 ? 1 : 2;
  };
  std::sort(png.begin(), png.end(), [&](const fs::path& a, const fs::path& b) {
    return rank(a) != rank(b) ? rank(a) < rank(b) : a.filename() < b.filename();
  });
  return png;
}


/// What a picture shows, for its caption (the file's name follows it); `check`: the folder holds a
/// `fos --check`, whose picture is of its one trial.
std::string caption(const std::string& file, bool check) {
  if (check && file.rfind("mechanism_", 0) == 0)
    return file.rfind("mechanism_stable", 0) == 0 ? "The trial at the required F, standing: blocks coloured by displacement"
                                                  : "The trial at the required F, failing: its mechanism";
  static const std::vector<std::pair<std::string, std::string>> known = {
      {"mechanism_stable", "The search's last stable trial: blocks coloured by displacement, arrows, joint states"},
      {"mechanism_failed", "The search's first failing trial: the mechanism at the bracket's failing end"},
      {"snapshot_", "The scene at one of the requested times"},
      {"history", "Monitors' displacements against time"},
      {"energy", "The energy budget against time (kinetic, potential, elastic, work of loads, dissipated)"},
      {"supports", "Each support's axial force against time"},
      {"ground_motion", "The ground-motion record applied"},
      {"critical_curve", "Critical strength along the curve"},
      {"support_curve", "Factor of safety against the support force"},
      {"misfit_map", "Misfit over the strength plane, the estimate marked"},
      {"pf_convergence", "Probability of failure as the samples accumulate, with its interval"},
      {"samples_plane", "The samples in the plane of the first two inputs, by verdict"},
      {"fos_histogram", "The samples' factors of safety"},
      {"sensitivities", "The importance of each input at the design point"},
  };
  for (const auto& [prefix, text] : known)
    if (file.rfind(prefix, 0) == 0) return text;
  return "";
}

/// A trial's value column: its key is the one that is not part of the verdict.
std::string trialValueKey(const json& trial) {
  static const std::vector<std::string> verdictKeys = {
      "stable", "undecided", "rule", "max_displacement_m", "failure_displacement_m", "settling_displacement_m",
      "last_window_motion_m", "previous_window_motion_m", "noise_floor_m", "final_speed_m_s", "moved_most",
      "decided_by", "time_s", "steps", "equilibrium_steps", "extended", "extensions", "marginal", "rerun", "early_rest", "run_on", "settling", "start_acceleration_g"};
  for (const auto& [k, v] : trial.items())
    if (v.is_number() && std::find(verdictKeys.begin(), verdictKeys.end(), k) == verdictKeys.end()) return k;
  return "";
}

std::string valueHeader(const std::string& key) {
  if (key == "factor") return "F";
  if (key == "cohesion_pa") return "c (Pa)";
  if (key == "friction_angle_deg") return "φ (°)";
  std::string h = key;
  std::replace(h.begin(), h.end(), '_', ' ');
  return h;
}

/// A search's trials as a reader wants them: the value tried, the verdict, the rule that decided
/// it in words, and the motions it went by, each header with its unit.
std::string trialsTable(const json& trials) {
  if (!trials.is_array() || trials.empty() || !trials[0].is_object()) return "";
  const std::string key = trialValueKey(trials[0]);
  std::map<std::string, std::string> rules;
  for (int r = 0; r <= static_cast<int>(calibration::VerdictRule::Undecided); ++r)
    rules[calibration::name(static_cast<calibration::VerdictRule>(r))] =
        calibration::describe(static_cast<calibration::VerdictRule>(r));
  const auto num = [](const json& t, const char* k) { return t.contains(k) ? scalar(t.at(k)) : std::string("&ndash;"); };
  std::string h = "<table class=\"rows\"><tr><th>#</th><th>" + escape(valueHeader(key)) +
                  "</th><th>verdict</th><th>decided by the rule</th><th>largest displacement (m)</th>"
                  "<th>failure displacement (m)</th><th>moved most</th><th>judged at</th><th>simulated (s)</th>"
                  "<th>steps</th><th>notes</th></tr>";
  int n = 0;
  for (const json& t : trials) {
    if (!t.is_object()) continue;
    const std::string verdict = t.value("undecided", false) ? "undecided" : t.value("stable", false) ? "stable" : "failing";
    const std::string rule = t.value("rule", "");
    std::string notes;
    const auto note = [&](bool on, const std::string& text) {
      if (on) notes += (notes.empty() ? "" : "; ") + text;
    };
    note(t.value("extended", false), "run extended " + std::to_string(t.value("extensions", 0)) + " times");
    note(t.value("marginal", false), "marginal (the 90 % rule)");
    note(t.value("rerun", false), "run again");
    note(t.value("run_on", false), "a trend failure run on in place, standing as its own re-run");
    note(t.value("settling", "") == "stalled",
         "started from the quietest state of a settling that found no rest (a step from it implied " +
             scalar(t.value("start_acceleration_g", json(0.0))) + " g)");
    note(t.value("settling", "") == "failed" && t.value("rule", "") != "moved_while_settling",
         "its settling moved like a failing scene: started from the equilibrium's static state");
    note(t.value("settling", "") == "unsettled",
         "its settling measured no quiet state: started from the equilibrium's static state, its kick unknown");
    note(t.value("early_rest", false), "stopped early: at rest for certain");
    // Rule (0) decides before t = 0: its evidence is the settling's motion, not the run's.
    note(rule == "moved_while_settling",
         "moved " + scalar(t.value("settling_displacement_m", json(0.0))) + " m while the scene settled");
    h += "<tr><td>" + std::to_string(++n) + "</td><td>" + (key.empty() ? "&ndash;" : scalar(t.at(key))) + "</td><td>" +
         verdict + "</td><td>" + escape(rules.count(rule) ? rules[rule] : rule) + "</td><td>" +
         num(t, "max_displacement_m") + "</td><td>" + num(t, "failure_displacement_m") + "</td><td>" +
         num(t, "moved_most") + "</td><td>" + num(t, "decided_by") + "</td><td>" + num(t, "time_s") + "</td><td>" +
         num(t, "steps") + "</td><td>" + escape(notes) + "</td></tr>";
  }
  return h + "</table>";
}
}  // namespace

int reportCommand(const std::string& dirText, const std::string& outFile) {
  const fs::path dir(dirText);
  if (!fs::is_directory(dir)) throw InputError(dirText, "", "expected an analysis folder, found no folder there");
  const Analysis a = identify(dir);
  const json& r = a.result;
  std::ostringstream h;
  const std::string title = a.kind + ": " + (r.contains("case") ? r["case"].get<std::string>() : dirText);
  h << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>" << escape(title) << "</title>\n"
    << "<style>body{font-family:sans-serif;margin:2em;max-width:1200px;color:#222}"
       "h1{font-size:1.4em}h2{font-size:1.15em;margin-top:1.6em;border-bottom:1px solid #ccc}"
       ".warnings li{color:#8a4b00}.answer{font-size:1.2em;background:#eef4fb;padding:.6em;border-left:4px solid #2a5db0}"
       "table{border-collapse:collapse;margin:.3em 0;font-size:.85em}th,td{border:1px solid #ccc;padding:2px 6px;"
       "text-align:left;vertical-align:top}th{background:#f3f3f3}img{max-width:100%;border:1px solid #ddd;margin:.5em 0}"
       "figure{margin:0 0 1em 0;page-break-inside:avoid}figcaption{font-size:.85em;color:#555}"
       "@media print{body{margin:0}h2{page-break-after:avoid}}</style>\n"
    // Marks the page once loaded: every picture decoded (data-pictures="loaded"), script errors
    // counted (data-script-errors); a headless browser reads them (tests/test_report.cpp).
    << "<script>window.addEventListener('error',function(){var b=document.body;"
       "b.dataset.scriptErrors=String(Number(b.dataset.scriptErrors||0)+1);});"
       "window.addEventListener('load',function(){var ok=true;document.querySelectorAll('img').forEach(function(i){"
       "if(!(i.complete&&i.naturalWidth>0))ok=false;});document.body.dataset.pictures=ok?'loaded':'missing';});"
       "</script></head>\n<body data-script-errors=\"0\">\n";
  h << "<h1>" << escape(title) << "</h1>\n";
  if (r.contains("description")) h << "<p>" << escape(r["description"].get<std::string>()) << "</p>\n";
  h << "<p class=\"answer\">" << escape(a.answer) << "</p>\n";
  if (!a.note.empty()) h << "<p class=\"warnings\">" << escape(a.note) << "</p>\n";
  if (r.contains("message") && r["message"].is_string() && !r["message"].get<std::string>().empty())
    h << "<p>" << escape(r["message"].get<std::string>()) << "</p>\n";
  if (r.contains("warnings") && r["warnings"].is_array() && !r["warnings"].empty()) {
    h << "<h2>Warnings</h2><ul class=\"warnings\">";
    for (const auto& w : r["warnings"]) h << "<li>" << scalar(w) << "</li>";
    h << "</ul>\n";
  }
  if (r.contains("settings"))
    h << "<h2>Settings in force</h2>"
      << (r["settings"].is_string() ? "<p>" + escape(r["settings"].get<std::string>()) + "</p>" : render(r["settings"]))
      << "\n";
  const std::vector<fs::path> png = pictures(dir, a.file);
  if (!png.empty()) {
    h << "<h2>Pictures</h2>\n";
    for (const auto& p : png) {
      const std::string what = caption(p.filename().string(), r.contains("check"));
      h << "<figure><img alt=\"" << escape(what.empty() ? p.filename().string() : what) << "\" src=\"data:image/png;base64,"
        << base64(slurp(p)) << "\"><figcaption>" << escape(what) << (what.empty() ? "" : " ") << "("
        << escape(p.filename().string()) << ")</figcaption></figure>\n";
    }
  }
  json rest = r;
  if (const std::string trials = r.contains("trials") ? trialsTable(r["trials"]) : ""; !trials.empty()) {
    h << "<h2>Trials</h2>\n<p>Each forward run of the "
      << (r.contains("check") ? "check (the trial at the required F; where there were, the trial at F = 1 a settled "
                                "start needs before it and the re-run of an undecided trial after it)"
                              : "search")
      << ", with the rule of the verdict (docs/calibration.md) that decided it.</p>\n"
      << trials << "\n";
    rest.erase("trials");
  }
  if (!a.columns.empty()) {
    // A sweep's or curve's points, in the CSV's own column order.
    h << "<h2>Points (" << escape(a.file) << ")</h2>\n<table class=\"rows\"><tr>";
    for (const auto& c : a.columns) h << "<th>" << escape(c) << "</th>";
    h << "</tr>";
    for (const json& p : r["points"]) {
      h << "<tr>";
      for (const auto& c : a.columns) h << "<td>" << scalar(p.contains(c) ? p.at(c) : json()) << "</td>";
      h << "</tr>";
    }
    h << "</table>\n";
  } else {
    h << "<h2>Result (" << escape(a.file) << ")</h2>\n" << render(rest) << "\n";
  }
  h << "<p style=\"font-size:.8em;color:#777\">Written by ddaslope report from " << escape(dir.string())
    << ". Every number above is the one the analysis wrote.</p>\n</body></html>\n";
  const std::string out = outFile.empty() ? (dir / "report.html").string() : outFile;
  const std::string temporary = out + ".tmp";
  {
    std::ofstream f(temporary, std::ios::binary);
    f << h.str();
    if (!f.flush()) throw InputError(out, "", "cannot write the report");
  }
  fs::rename(temporary, out);
  std::printf("%s: %s\n  %s\n", dirText.c_str(), a.kind.c_str(), a.answer.c_str());
  if (!a.note.empty()) std::printf("  %s\n", a.note.c_str());
  std::printf("  wrote %s (%zu %s embedded)\n", out.c_str(), png.size(), png.size() == 1 ? "picture" : "pictures");
  return kExitOk;
}

}  // namespace ddaslope::cli

#include "ddaslope/io/probability_files.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <cstdio>
#include <fstream>
#include <limits>
#include <map>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "ddaslope/calibration/verdict.hpp"
#include "ddaslope/core/errors.hpp"
#include "ddaslope/io/case_reader.hpp"
#include "ddaslope/io/json_record.hpp"
#include "ddaslope/io/line_plot.hpp"

namespace ddaslope::io {
namespace {
/// An input's path as an axis label, with the unit its value is given in.
std::string withUnit(const std::string& path) {
  const std::string unit = unitOfCaseValue(path);
  return unit.empty() ? path : path + " (" + unit + ")";
}


namespace fs = std::filesystem;
using calibration::SampleOutcome;
using calibration::SampleResult;

/// The rules a sample row may name (docs/probability.md, samples.csv): the verdict's, and
/// "no_bracket" for a factor-of-safety search that found no F. A resumed row's rule is carried
/// into summary.json, so anything else is a damaged row.
bool knownRule(const std::string& rule) {
  using calibration::VerdictRule;
  for (VerdictRule v : {VerdictRule::AtRest, VerdictRule::SlowingDown, VerdictRule::PassedDisplacement,
                        VerdictRule::StillMoving, VerdictRule::MovedWhileSettling, VerdictRule::NotConverged,
                        VerdictRule::Undecided})
    if (rule == calibration::name(v)) return true;
  return rule == "no_bracket";
}

bool factorMeasure(const model::ProbabilitySpec& spec) {
  return spec.measure == model::ProbabilityMeasure::FactorOfSafety;
}

bool importance(const model::ProbabilitySpec& spec) {
  return spec.method == model::ProbabilityMethod::ImportanceSampling;
}

std::vector<std::string> splitFields(const std::string& line) {
  std::vector<std::string> out;
  size_t start = 0;
  for (size_t comma = line.find(','); comma != std::string::npos; comma = line.find(',', start)) {
    out.push_back(line.substr(start, comma - start));
    start = comma + 1;
  }
  out.push_back(line.substr(start));
  return out;
}

/// The rows of a file appended a row at a time, up to its last line end: a study killed while
/// writing a row leaves it without one, and that row's run is made again. `keepBytes`: their length.
std::string wholeRows(const std::string& path, long& keepBytes) {
  std::ifstream in(path, std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(in)), {});
  const size_t lastNewline = text.rfind('\n');
  keepBytes = lastNewline == std::string::npos ? 0 : static_cast<long>(lastNewline + 1);
  return text.substr(0, static_cast<size_t>(keepBytes));
}

bool parseNumber(const std::string& text, double* v) {
  if (text.empty()) {
    *v = std::numeric_limits<double>::quiet_NaN();
    return true;
  }
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), *v);
  // from_chars takes "nan" and "inf", which the writer never writes (NaN is an empty field): a
  // damaged file, not a value to carry into the summary.
  return ec == std::errc() && end == text.data() + text.size() && std::isfinite(*v);
}

/// The plane of the scatter plot: cohesion and friction angle of a joint when both are inputs,
/// otherwise the first two inputs (-1, -1 when there is one input).
std::pair<int, int> planeAxes(const model::ProbabilitySpec& spec) {
  const auto endsWith = [](const std::string& s, const std::string& tail) {
    return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
  };
  int c = -1, phi = -1;
  for (size_t i = 0; i < spec.inputs.size(); ++i) {
    if (c < 0 && endsWith(spec.inputs[i].path, ".cohesion")) c = static_cast<int>(i);
    if (phi < 0 && endsWith(spec.inputs[i].path, ".friction_angle")) phi = static_cast<int>(i);
  }
  if (c >= 0 && phi >= 0) return {c, phi};
  if (spec.inputs.size() >= 2) return {0, 1};
  return {-1, -1};
}

/// The inputs and correlations, as the summary and the fingerprint both name them.
void appendStudy(io::JsonRecord& j, const model::ProbabilitySpec& spec) {
  for (const auto& in : spec.inputs) {
    io::JsonRecord r;
    const model::Distribution& d = in.distribution;
    r.set("path", in.path).set("distribution", calibration::name(d.kind));
    if (d.kind != model::DistributionKind::Uniform) r.set("mean", d.mean).set("sd", d.sd);
    if (std::isfinite(d.min)) r.set("min", d.min);
    if (std::isfinite(d.max)) r.set("max", d.max);
    j.append("inputs", r);
  }
  for (const auto& c : spec.correlations) {
    io::JsonRecord r;
    r.set("between", std::vector<std::string>{spec.inputs[c.a].path, spec.inputs[c.b].path}).set("rho", c.rho);
    j.append("correlations", r);
  }
}

/// A design point's reliability index, FORM's Pf and u, as both importance sampling's and active
/// learning's summaries begin it.
void setDesignPointHead(io::JsonRecord& dp, const DesignPointReport& design) {
  const calibration::DesignPoint& d = design.point;
  dp.set("reliability_index_form", d.beta).set("probability_of_failure_form", calibration::normalCdf(-d.beta));
  dp.set("u", d.u);
}

/// Each input at the design point: its value, α, γ and γ².
void appendDesignInputs(io::JsonRecord& dp, const model::ProbabilitySpec& spec, const DesignPointReport& design) {
  for (size_t i = 0; i < spec.inputs.size(); ++i) {
    const double g = design.importance[i];
    io::JsonRecord in;
    in.set("path", spec.inputs[i].path).set("value", design.values[i]).set("alpha", design.point.alpha[i]);
    in.set("importance_gamma", g).set("importance_share", g * g);
    dp.append("inputs", in);
  }
}

}  // namespace

std::string exactText(double v) {
  if (std::isnan(v)) return "";
  char buf[32];
  const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, ec == std::errc() ? end : buf);
}

SampleTable::SampleTable(std::string path, const model::ProbabilitySpec& spec) : path_(std::move(path)), spec_(spec) {}

SampleTable::~SampleTable() {
  if (file_) std::fclose(file_);
}

std::string SampleTable::header() const {
  std::string h = "sample";
  for (const auto& in : spec_.inputs) h += "," + in.path;
  h += ",outcome,rule";
  if (factorMeasure(spec_)) h += ",factor_of_safety";
  if (importance(spec_)) h += ",weight";
  return h + ",max_displacement_m,run_time_s";
}

std::vector<SampleResult> SampleTable::read(const calibration::SampleDesign& design) {
  std::vector<SampleResult> out;
  if (!fs::exists(path_)) return out;
  std::istringstream lines(wholeRows(path_, keepBytes_));
  std::string line;
  if (!std::getline(lines, line)) return out;
  if (line != header())
    throw InputError(path_, "line 1", "expected the header \"" + header() + "\", found \"" + line +
                                          "\": the samples of another study (other inputs or measure)");
  const size_t n = spec_.inputs.size(), fields = n + 5 + factorMeasure(spec_) + importance(spec_);
  std::set<int> seen;
  for (int number = 2; std::getline(lines, line); ++number) {
    const std::string where = "line " + std::to_string(number);
    const std::vector<std::string> f = splitFields(line);
    if (f.size() != fields)
      throw InputError(path_, where, "expected " + std::to_string(fields) + " fields, found " +
                                         std::to_string(f.size()) + ": the file is damaged");
    SampleResult r;
    const auto [end, ec] = std::from_chars(f[0].data(), f[0].data() + f[0].size(), r.index);
    if (ec != std::errc() || end != f[0].data() + f[0].size() || r.index < 0)
      throw InputError(path_, where, "expected a sample index, found \"" + f[0] + "\"");
    if (r.index >= design.samples())
      throw InputError(path_, where, "holds sample " + f[0] + ", but the study has " +
                                         std::to_string(design.samples()) + " samples: give at least " +
                                         std::to_string(r.index + 1) + " (--samples)");
    if (!seen.insert(r.index).second) throw InputError(path_, where, "sample " + f[0] + " is there twice");
    const std::vector<double> expected = design.values(r.index);
    r.inputs.resize(n);
    for (size_t i = 0; i < n; ++i)
      if (!parseNumber(f[1 + i], &r.inputs[i]) || r.inputs[i] != expected[i])
        throw InputError(path_, where, "sample " + f[0] + " has " + spec_.inputs[i].path + " = " + f[1 + i] +
                                           ", but this study's seed and inputs give " + exactText(expected[i]) +
                                           ": the samples of another study");
    const std::string& outcome = f[n + 1];
    if (outcome == "stable") r.outcome = SampleOutcome::Stable;
    else if (outcome == "fails") r.outcome = SampleOutcome::Fails;
    else if (outcome == "not_converged") r.outcome = SampleOutcome::NotConverged;
    else throw InputError(path_, where, "expected stable, fails or not_converged, found \"" + outcome + "\"");
    r.rule = f[n + 2];
    if (!knownRule(r.rule))
      throw InputError(path_, where, "expected a verdict rule (at_rest, slowing_down, failure_displacement, still_moving, "
                                     "moved_while_settling, not_converged, undecided, no_bracket), found \"" + r.rule + "\"");
    size_t k = n + 3;
    bool ok = true;
    if (factorMeasure(spec_)) ok &= parseNumber(f[k++], &r.factor);
    if (importance(spec_)) {
      ok &= parseNumber(f[k++], &r.weight);
      if (ok && r.weight != design.weight(r.index))
        throw InputError(path_, where, "sample " + f[0] + " has the weight " + f[k - 1] + ", but this study's design "
                                           "point gives " + exactText(design.weight(r.index)) +
                                           ": the samples of another study");
    }
    ok &= parseNumber(f[k++], &r.maxDisplacement);
    ok &= parseNumber(f[k], &r.runTime);
    if (!ok) throw InputError(path_, where, "expected numbers after the rule, found \"" + line + "\"");
    out.push_back(r);
  }
  return out;
}

void SampleTable::open() {
  if (file_) return;
  if (keepBytes_ > 0) fs::resize_file(path_, static_cast<std::uintmax_t>(keepBytes_));
  const bool fresh = keepBytes_ <= 0;  // not read, or not even a whole header line
  file_ = std::fopen(path_.c_str(), fresh ? "w" : "a");
  if (!file_) throw InputError(path_, "", "cannot write the file");
  if (fresh && (std::fprintf(file_, "%s\n", header().c_str()) < 0 || std::fflush(file_) != 0))
    throw InputError(path_, "", "cannot write the file");
}

void SampleTable::append(const SampleResult& r) {
  DDASLOPE_ASSERT(file_, "samples.csv appended before it was opened");
  std::string row = std::to_string(r.index);
  const auto field = [&row](const std::string& text) { row.append(1, ',').append(text); };
  for (double v : r.inputs) field(exactText(v));
  field(calibration::name(r.outcome));
  field(r.rule);
  if (factorMeasure(spec_)) field(exactText(r.factor));
  if (importance(spec_)) field(exactText(r.weight));
  field(exactText(r.maxDisplacement));
  char time[32];
  std::snprintf(time, sizeof time, "%.4f", r.runTime);
  field(time);
  row.append(1, '\n');
  // One write per row, flushed: a kill leaves whole rows and at most one cut-off last line.
  if (std::fputs(row.c_str(), file_) < 0 || std::fflush(file_) != 0)
    throw InputError(path_, "", "cannot write the file (disk full?)");
}

namespace {
constexpr const char* kLearningHeader = "kind,sample,outcome,margin,forward_runs";
}  // namespace

LearningJournal::~LearningJournal() {
  if (file_) std::fclose(file_);
}

std::vector<LearningRun> LearningJournal::read(int population) {
  using calibration::PointVerdict;
  std::vector<LearningRun> out;
  if (!fs::exists(path_)) return out;
  std::istringstream lines(wholeRows(path_, keepBytes_));
  std::string line;
  if (!std::getline(lines, line)) return out;
  if (!line.empty() && line.back() == '\r') line.pop_back();
  if (line != kLearningHeader)
    throw InputError(path_, "line 1", std::string("expected the header \"") + kLearningHeader + "\", found \"" + line + "\"");
  std::set<std::pair<bool, int>> seen;
  for (int number = 2; std::getline(lines, line); ++number) {
    if (!line.empty() && line.back() == '\r') line.pop_back();  // edited on Windows
    const std::string where = "line " + std::to_string(number);
    const std::vector<std::string> f = splitFields(line);
    if (f.size() != 5) throw InputError(path_, where, "expected 5 fields, found " + std::to_string(f.size()) + ": the file is damaged");
    LearningRun r;
    if (f[0] != "search" && f[0] != "verdict")
      throw InputError(path_, where, "expected the kind search or verdict, found \"" + f[0] + "\"");
    r.search = f[0] == "search";
    const auto whole = [&](const std::string& t, int* v) {
      const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), *v);
      return ec == std::errc() && end == t.data() + t.size() && *v >= 0;
    };
    if (!whole(f[1], &r.index) || r.index >= population)
      throw InputError(path_, where, "expected a population point 0 to " + std::to_string(population - 1) +
                                         ", found \"" + f[1] + "\": the runs of another study (other --samples?)");
    if (!seen.insert({r.search, r.index}).second)
      throw InputError(path_, where, "the " + f[0] + " of point " + f[1] + " is there twice");
    const std::string& outcome = f[2];
    if (outcome != "stable" && outcome != "fails" && outcome != "not_converged")
      throw InputError(path_, where, "expected stable, fails or not_converged, found \"" + outcome + "\"");
    int runs = 0;
    if (!whole(f[4], &runs)) throw InputError(path_, where, "expected a count of forward runs, found \"" + f[4] + "\"");
    if (r.search) {
      r.value.runs = runs;
      r.value.converged = outcome != "not_converged";
      r.value.fails = outcome == "fails";
      double margin = 0;
      // F lies where a search can bracket it: above 0, below 1.5^40 (calibration::factorOfSafetyOf).
      if (r.value.converged && (!parseNumber(f[3], &margin) || f[3].empty() || !(margin > -1) || margin > 1e7))
        throw InputError(path_, where, "expected F − 1 of a converged search, above -1 and at most 1e7, found \"" +
                                           f[3] + "\"");
      if (!r.value.converged && !f[3].empty())
        throw InputError(path_, where, "expected no F − 1 for a search that did not converge, found \"" + f[3] + "\"");
      r.value.margin = r.value.converged ? margin : 0;
    } else {
      if (!f[3].empty() || runs != 1)
        throw InputError(path_, where, "expected a verdict's empty F − 1 and 1 forward run, found \"" + f[3] + "\" and \"" +
                                           f[4] + "\"");
      r.verdict = outcome == "stable" ? PointVerdict::Stable : outcome == "fails" ? PointVerdict::Fails
                                                                                  : PointVerdict::NotConverged;
    }
    out.push_back(r);
  }
  return out;
}

void LearningJournal::open() {
  if (file_) return;
  if (keepBytes_ > 0) fs::resize_file(path_, static_cast<std::uintmax_t>(keepBytes_));
  const bool fresh = keepBytes_ <= 0;
  file_ = std::fopen(path_.c_str(), fresh ? "w" : "a");
  if (!file_) throw InputError(path_, "", "cannot write the file");
  if (fresh && (std::fprintf(file_, "%s\n", kLearningHeader) < 0 || std::fflush(file_) != 0))
    throw InputError(path_, "", "cannot write the file");
}

void LearningJournal::append(const LearningRun& r) {
  using calibration::PointVerdict;
  DDASLOPE_ASSERT(file_, "learning_runs.csv appended before it was opened");
  std::string row = std::string(r.search ? "search" : "verdict") + "," + std::to_string(r.index) + ",";
  if (r.search) {
    row += !r.value.converged ? "not_converged" : r.value.fails ? "fails" : "stable";
    row += "," + (r.value.converged ? exactText(r.value.margin) : std::string()) + "," + std::to_string(r.value.runs);
  } else {
    row += r.verdict == PointVerdict::Stable ? "stable" : r.verdict == PointVerdict::Fails ? "fails" : "not_converged";
    row += ",,1";
  }
  row += "\n";
  if (std::fputs(row.c_str(), file_) < 0 || std::fflush(file_) != 0)
    throw InputError(path_, "", "cannot write the file (disk full?)");
}

std::string settingsFingerprint(const io::ProbabilityJob& job, const std::vector<std::string>& caseSettings,
                                const std::string& settingsLine, const std::vector<double>& centre) {
  const model::ProbabilitySpec& s = job.spec;
  io::JsonRecord j;
  j.set("format", "ddaslope probability study 1").set("case_digest", job.caseDigest);
  j.set("measure", calibration::name(s.measure)).set("sampling", calibration::name(s.sampling)).set("seed", s.seed);
  if (importance(s)) {
    // The digits that read back to the same doubles: a design point that moved by one ulp changes
    // every sample.
    std::vector<std::string> u;
    for (double v : centre) u.push_back(exactText(v));
    j.set("method", calibration::name(s.method)).set("design_point_u", u);
  }
  // Monte Carlo samples do not depend on N (more may be added by resuming with a larger --samples);
  // a Latin hypercube's strata do.
  // Active learning chooses its runs from the whole population: every point counts.
  const bool learning = s.method == model::ProbabilityMethod::ActiveLearning;
  if (learning) j.set("method", calibration::name(s.method));
  if (s.sampling == model::Sampling::LatinHypercube || learning) j.set("samples", s.samples);
  appendStudy(j, s);
  if (factorMeasure(s) || learning) j.set("fos_joints", s.fosJoints).set("fos_width", s.fosWidth);
  j.set("set", caseSettings).set("forward_runs", settingsLine);
  return j.dump() + "\n";
}

void checkFingerprint(const std::string& path, const std::string& expected, const std::string& held) {
  if (!fs::exists(path))
    throw InputError(path, "", "is missing, so the " + held + " beside it cannot be checked against this study: start "
                               "again (--overwrite) or in another --out");
  std::ifstream in(path, std::ios::binary);
  const std::string found((std::istreambuf_iterator<char>(in)), {});
  if (found == expected) return;
  std::istringstream a(found), b(expected);
  std::string was, now;
  for (int line = 1;; ++line) {
    const bool more = static_cast<bool>(std::getline(a, was)), more2 = static_cast<bool>(std::getline(b, now));
    if (!more) was = "(the end)";
    if (!more2) now = "(the end)";
    if (was == now && (more || more2)) continue;
    // The line without its indent and trailing comma: `"seed": 1`.
    const auto bare = [](std::string t) {
      t.erase(0, t.find_first_not_of(' '));
      if (!t.empty() && t.back() == ',') t.pop_back();
      return t;
    };
    std::string had = bare(was), has = bare(now);
    // A line that opens a list or an object (`"set": [`) says nothing of what differs in it: the
    // whole value of the first setting that differs is named instead.
    const auto opens = [](const std::string& t) { return !t.empty() && (t.back() == '[' || t.back() == '{'); };
    if (opens(had) || opens(has)) {
      const nlohmann::json o = nlohmann::json::parse(found, nullptr, false), n = nlohmann::json::parse(expected, nullptr, false);
      const std::string& line = opens(has) ? has : had;  // `"set": [`
      const size_t close = line.find('"', 1);
      const std::string key = line.size() > 1 && line[0] == '"' && close != std::string::npos ? line.substr(1, close - 1) : "";
      const auto shown = [&key](const nlohmann::json& doc) {
        std::string t = "\"";
        t.append(key).append("\": ").append(doc.contains(key) ? doc[key].dump() : std::string("(none)"));
        return t;
      };
      if (o.is_object() && n.is_object() && !key.empty()) had = shown(o), has = shown(n);
    }
    throw InputError(path, "line " + std::to_string(line),
                     "the " + held + " in this folder belong to another study: it had " + had + ", this one has " +
                         has + ". Resume with the same case, section and options, or start in another --out");
  }
}

void writeAtomically(const std::string& path, const std::string& text) {
  {
    std::ofstream out(path + ".tmp", std::ios::binary);
    out << text;
    if (!out.flush()) throw InputError(path, "", "cannot write the file");
  }
  fs::rename(path + ".tmp", path);
}

std::string summaryJson(const io::ProbabilityJob& job, const calibration::ProbabilitySummary& s,
                        const std::string& settingsLine, bool complete, const DesignPointReport* design) {
  const model::ProbabilitySpec& spec = job.spec;
  io::JsonRecord j;
  j.set("study", job.file).set("case", job.casePath).set("complete", complete);
  j.set("method", calibration::name(spec.method));
  j.set("measure", calibration::name(spec.measure)).set("sampling", calibration::name(spec.sampling));
  j.set("seed", spec.seed).set("samples_planned", s.planned).set("samples_finished", s.finished);
  appendStudy(j, spec);
  j.set("converged", s.converged).set("not_converged", s.notConverged).set("failing", s.failures);
  j.set("probability_of_failure", s.pf);
  j.set("interval_95", std::vector<double>{s.pfInterval.low, s.pfInterval.high});
  j.set("interval_method", s.weighted ? "normal approximation, Pf ± 1.96 standard errors" : "Wilson score");
  if (s.weighted) j.set("standard_error", s.pfStandardError);
  j.set("coefficient_of_variation", s.coefficientOfVariation);
  if (design) {
    const calibration::DesignPoint& d = design->point;
    j.set("forward_runs", d.runs + s.finished);
    io::JsonRecord dp;
    setDesignPointHead(dp, *design);
    dp.set("runs", d.runs).set("rays", d.rays).set("secant_steps", d.steps);
    dp.set("converged", d.converged).set("other_failure_regions", static_cast<int>(d.otherRegions.size()));
    appendDesignInputs(dp, spec, *design);
    j.set("design_point", dp);
  }
  j.set("not_converged_as_stable", s.pfNotConvergedStable).set("not_converged_as_failing", s.pfNotConvergedFailing);
  j.set("bounds_95_with_not_converged", std::vector<double>{s.pfBounds.low, s.pfBounds.high});
  // β is ±∞ at Pf = 0 or 1: JSON has no infinity, so null there.
  const auto finite = [](double v) { return std::isfinite(v) ? v : std::numeric_limits<double>::quiet_NaN(); };
  j.set("reliability_index", finite(s.beta));
  j.set("reliability_index_interval_95", std::vector<double>{finite(s.betaInterval.low), finite(s.betaInterval.high)});
  if (s.hasFactor) {
    io::JsonRecord f;
    f.set("mean", s.factorMean).set("sd", s.factorSd).set("mean_standard_error", s.factorMeanError);
    f.set("min", s.factorMin).set("median", s.factorMedian).set("max", s.factorMax);
    f.set("reliability_index_moments", finite(s.betaMoments));
    j.set("factor_of_safety", f);
  }
  io::JsonRecord rules;
  for (const auto& [rule, count] : s.rules) rules.set(rule, count);
  j.set("rules", rules).set("settings", settingsLine);
  return j.dump() + "\n";
}

std::string writeSensitivities(const io::ProbabilityJob& job, const DesignPointReport& design, const std::string& dir) {
  // One bar per input, each its own series so that the legend names it.
  std::vector<io::PlotSeries> bars;
  std::vector<std::string> names;
  for (size_t i = 0; i < design.importance.size(); ++i) {
    const double g = design.importance[i], x = static_cast<double>(i + 1);
    // γᵢ > 0: the limit state falls as input i grows, so failure lies at its high values.
    const std::string side = g > 0 ? "high" : "low";
    char label[64];
    std::snprintf(label, sizeof label, ": %.0f %%, failure at %s values", 100 * g * g, side.c_str());
    io::PlotSeries bar{job.spec.inputs[i].path + label, {x - 0.3, x - 0.3, x + 0.3, x + 0.3}, {0, g * g, g * g, 0}, false};
    bar.filled = true;
    bars.push_back(bar);
    names.push_back(job.spec.inputs[i].path);
  }
  io::LinePlot plot{"Sensitivities at the design point: " + job.casePath, "input", "importance γ²", bars};
  plot.xCategories = names;
  io::writePng(plot, dir + "/sensitivities.png");
  return "sensitivities.png";
}

std::vector<std::string> writePictures(const io::ProbabilityJob& job, const calibration::ProbabilitySummary& s,
                                       const std::vector<SampleResult>& sorted, const std::string& dir,
                                       const DesignPointReport* design) {
  std::vector<std::string> written;
  const std::string title = job.casePath;
  {
    // The interval as one outline: its lower end forward, its upper end back.
    io::PlotSeries pf{"Pf", {}, s.runningPf, false};
    io::PlotSeries band{s.weighted ? "95 % interval (normal approximation)" : "95 % interval (Wilson)", {}, s.runningLow,
                        false};
    for (size_t k = 0; k < s.runningPf.size(); ++k) pf.x.push_back(static_cast<double>(k + 1));
    band.x = pf.x;
    band.x.insert(band.x.end(), pf.x.rbegin(), pf.x.rend());
    band.y.insert(band.y.end(), s.runningHigh.rbegin(), s.runningHigh.rend());
    io::writePng({"Probability of failure: " + title, "converged samples (in index order)", "Pf", {pf, band}},
                 dir + "/pf_convergence.png");
    written.push_back("pf_convergence.png");
  }
  const auto [ax, ay] = planeAxes(job.spec);
  if (ax >= 0) {
    std::vector<io::PlotSeries> series;
    for (SampleOutcome o : {SampleOutcome::Stable, SampleOutcome::Fails, SampleOutcome::NotConverged}) {
      io::PlotSeries p{calibration::name(o), {}, {}, true, false};
      for (const SampleResult& r : sorted)
        if (r.outcome == o) p.x.push_back(r.inputs[ax]), p.y.push_back(r.inputs[ay]);
      series.push_back(p);
    }
    if (design) {
      series.push_back({"design point (FORM)", {design->values[ax]}, {design->values[ay]}, true, false, 7});
      std::vector<double> median(job.spec.inputs.size(), 0.0);
      calibration::SampleDesign centred(job.spec);
      const std::vector<double> m = centred.valuesAt(median);
      series.push_back({"medians", {m[ax]}, {m[ay]}, true, false, 7});
    }
    // Importance samples are centred on the design point: half of them fail whatever Pf is.
    io::writePng({(design ? "Importance samples (around the design point, weighted): " : "Samples: ") + title,
                  withUnit(job.spec.inputs[ax].path), withUnit(job.spec.inputs[ay].path), series},
                 dir + "/samples_plane.png");
    written.push_back("samples_plane.png");
  }
  if (s.hasFactor && s.converged > 0) {
    std::vector<double> f;
    for (const SampleResult& r : sorted)
      if (std::isfinite(r.factor)) f.push_back(r.factor);
    // √n bins (5 to 50) over the range, drawn as a step outline, with the normal of the same mean
    // and sd scaled to counts, and F = 1.
    const int bins = std::clamp(static_cast<int>(std::ceil(std::sqrt(static_cast<double>(f.size())))), 5, 50);
    const double lo = s.factorMin, width = std::max(s.factorMax - s.factorMin, 1e-9) / bins;
    std::vector<int> count(static_cast<size_t>(bins), 0);
    for (double v : f) ++count[static_cast<size_t>(std::clamp(static_cast<int>((v - lo) / width), 0, bins - 1))];
    io::PlotSeries hist{"samples per bin", {lo}, {0}, false};
    for (int b = 0; b < bins; ++b) {
      hist.x.insert(hist.x.end(), {lo + b * width, lo + (b + 1) * width});
      hist.y.insert(hist.y.end(), {static_cast<double>(count[b]), static_cast<double>(count[b])});
    }
    hist.x.push_back(lo + bins * width);
    hist.y.push_back(0);
    io::PlotSeries normal{"normal, same mean and sd", {}, {}, false};
    for (int k = 0; k <= 100; ++k) {
      const double x = lo + bins * width * k / 100.0, z = s.factorSd > 0 ? (x - s.factorMean) / s.factorSd : 0;
      normal.x.push_back(x);
      normal.y.push_back(s.factorSd > 0 ? f.size() * width * std::exp(-0.5 * z * z) / (s.factorSd * std::sqrt(2 * M_PI)) : 0);
    }
    const double top = *std::max_element(hist.y.begin(), hist.y.end());
    io::PlotSeries one{"F = 1", {1, 1}, {0, top}, false};
    io::writePng({"Factor of safety: " + title, "F (strength reduction)", "samples", {hist, normal, one}},
                 dir + "/fos_histogram.png");
    written.push_back("fos_histogram.png");
  }
  if (design) written.push_back(writeSensitivities(job, *design, dir));
  return written;
}

std::string activeLearningSummaryJson(const io::ProbabilityJob& job, const calibration::ActiveLearningResult& r,
                                      const std::string& settingsLine, const DesignPointReport* design,
                                      const std::string& noDesignPoint) {
  const model::ProbabilitySpec& spec = job.spec;
  const calibration::LearnedProbability p = calibration::probabilityOf(r);
  const auto finite = [](double v) { return std::isfinite(v) ? v : std::numeric_limits<double>::quiet_NaN(); };
  io::JsonRecord j;
  j.set("study", job.file).set("case", job.casePath).set("complete", true);
  j.set("method", calibration::name(spec.method)).set("sampling", calibration::name(spec.sampling));
  j.set("seed", spec.seed).set("population", r.population);
  appendStudy(j, spec);
  j.set("fos_joints", spec.fosJoints).set("fos_width", spec.fosWidth);
  j.set("converged", p.converged).set("not_converged", r.notConverged).set("failing", r.failing);
  j.set("probability_of_failure", p.pf);
  j.set("interval_95", std::vector<double>{p.interval.low, p.interval.high});
  j.set("interval_method", "Wilson score over the population (its Monte Carlo error; the classification as exact)");
  j.set("coefficient_of_variation", p.coefficientOfVariation);
  j.set("bounds_95_with_unsure_and_not_converged", std::vector<double>{p.bounds.low, p.bounds.high});
  j.set("reliability_index", finite(p.beta));
  j.set("reliability_index_interval_95", std::vector<double>{finite(p.betaInterval.low), finite(p.betaInterval.high)});
  j.set("forward_runs", r.searchRuns + r.verdicts);
  io::JsonRecord l;
  l.set("learnt", r.learnt).set("searches", r.searches).set("search_runs", r.searchRuns);
  if (!r.learnt) l.set("stopped_by_budget_of", r.stoppedBy);
  l.set("verdict_runs", r.verdicts).set("unsure_decided_by_verdict", r.decidedByVerdict);
  l.set("sure_contradicted_by_verdict", r.disagreements);
  l.set("surrogate_fits", r.rounds).set("min_u", finite(r.minU)).set("stop_u", 2.0);
  l.set("unsure_failing", r.unsureFailing).set("unsure_stable", r.unsureStable);
  const Eigen::VectorXd& fitted = r.surrogate.lengthScales();  // empty when nothing was fitted
  std::vector<double> scales(fitted.data(), fitted.data() + fitted.size());
  l.set("length_scales", scales);
  if (!r.message.empty()) l.set("message", r.message);
  j.set("active_learning", l);
  if (design) {
    io::JsonRecord dp;
    setDesignPointHead(dp, *design);
    dp.set("source", "the surrogate's margin 0 nearest the medians (no forward run)");
    appendDesignInputs(dp, spec, *design);
    j.set("design_point", dp);
  } else {
    io::JsonRecord dp;
    dp.set("found", false).set("reason", noDesignPoint);
    j.set("design_point", dp);
  }
  j.set("settings", settingsLine);
  return j.dump() + "\n";
}

std::vector<std::string> writeActiveLearningFiles(const io::ProbabilityJob& job, const calibration::SampleDesign& design,
                                                  const calibration::ActiveLearningResult& r, const std::string& dir,
                                                  const DesignPointReport* point) {
  using calibration::LearnedRole;
  using calibration::PointVerdict;
  std::vector<std::string> written;
  {
    std::string csv = "order,sample,role";
    for (const auto& in : job.spec.inputs) csv += "," + in.path;
    csv += ",outcome,factor_of_safety,forward_runs,predicted_margin,predicted_sd,surrogate_sure,agrees\n";
    int order = 0;
    for (const calibration::LearnedPoint& lp : r.points) {
      csv += std::to_string(order++) + "," + std::to_string(lp.index) + "," + calibration::name(lp.role);
      for (double v : design.values(lp.index)) csv.append(1, ',').append(exactText(v));
      const bool confirmation = lp.role == LearnedRole::Confirmation;
      const char* outcome = confirmation ? (lp.verdict == PointVerdict::Stable  ? "stable"
                                            : lp.verdict == PointVerdict::Fails ? "fails"
                                                                                : "not_converged")
                            : !lp.value.converged ? "not_converged"
                            : lp.value.fails      ? "fails"
                                                  : "stable";
      // Field by field with append: GCC 12 warns (-Wrestrict, wrongly) of "," + a temporary string.
      const auto field = [&csv](const std::string& text) { csv.append(1, ',').append(text); };
      field(outcome);
      field(confirmation || !lp.value.converged ? std::string() : exactText(1 + lp.value.margin));
      field(std::to_string(confirmation ? 1 : lp.value.runs));
      field(exactText(lp.predictedMean));
      field(exactText(lp.predictedSd));
      field(confirmation ? (lp.sure ? "yes" : "no") : "");
      field(confirmation ? (lp.agrees ? "yes" : "no") : "");
      csv.append(1, '\n');
    }
    writeAtomically(dir + "/learning.csv", csv);
    written.push_back("learning.csv");
  }
  const auto [ax, ay] = planeAxes(job.spec);
  if (ax >= 0) {
    // At most 20 000 population points drawn (the first, in index order): enough to see the
    // classified regions without a picture of solid colour.
    const int shown = std::min(r.population, 20000);
    // A small Pf leaves few failing points among the first 20 000: then every failing point is
    // drawn, so that the failure region shows; a large one is drawn from the first 20 000 alone,
    // so that the two classes keep their proportions.
    const bool allFailing = r.failing <= 5000;
    io::PlotSeries stable{"population (first " + std::to_string(shown) + "), classified stable", {}, {}, true, false, 1.2};
    io::PlotSeries fails{std::string("population (") + (allFailing ? "all" : "first " + std::to_string(shown)) +
                             "), classified failing",
                         {}, {}, true, false, 1.8};
    for (int k = 0; k < shown; ++k) {
      const std::vector<double> v = design.values(k);
      io::PlotSeries& s = r.fails[static_cast<size_t>(k)] ? fails : stable;
      s.x.push_back(v[static_cast<size_t>(ax)]);
      s.y.push_back(v[static_cast<size_t>(ay)]);
    }
    for (int k = shown; allFailing && k < r.population; ++k)
      if (r.fails[static_cast<size_t>(k)]) {
        const std::vector<double> v = design.values(k);
        fails.x.push_back(v[static_cast<size_t>(ax)]);
        fails.y.push_back(v[static_cast<size_t>(ay)]);
      }
    io::PlotSeries searchedStable{"searched (F), stable", {}, {}, true, false, 4.5};
    io::PlotSeries searchedFails{"searched (F), failing", {}, {}, true, false, 4.5};
    io::PlotSeries judgedStable{"judged by one run, stable", {}, {}, true, false, 3.5};
    io::PlotSeries judgedFails{"judged by one run, failing", {}, {}, true, false, 3.5};
    for (const calibration::LearnedPoint& lp : r.points) {
      const std::vector<double> v = design.values(lp.index);
      const bool judged = lp.role == LearnedRole::Confirmation;
      const bool fails = judged ? lp.verdict == PointVerdict::Fails : lp.value.converged && lp.value.fails;
      io::PlotSeries& s = judged ? (fails ? judgedFails : judgedStable) : (fails ? searchedFails : searchedStable);
      s.x.push_back(v[static_cast<size_t>(ax)]);
      s.y.push_back(v[static_cast<size_t>(ay)]);
    }
    io::writePng({"Active learning, " + std::to_string(r.population) + " points: " + job.casePath, job.spec.inputs[static_cast<size_t>(ax)].path,
                  job.spec.inputs[static_cast<size_t>(ay)].path,
                  {stable, fails, searchedStable, searchedFails, judgedStable, judgedFails}},
                 dir + "/samples_plane.png");
    written.push_back("samples_plane.png");
  }
  if (point) written.push_back(writeSensitivities(job, *point, dir));
  return written;
}

}  // namespace ddaslope::io

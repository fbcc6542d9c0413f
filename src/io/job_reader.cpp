#include "ddaslope/io/job_reader.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>
#include <nlopt.h>

#include "ddaslope/core/errors.hpp"
#include "json_input.hpp"
#include "ddaslope/io/csv_series.hpp"

namespace ddaslope::io {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

class JobReader;
void readQuantity(const JobReader& r, const json& j, const std::string& p, ObservationSpec& o);

class JobReader {
 public:
  explicit JobReader(std::string file) : file_(std::move(file)) {}
  [[noreturn]] void fail(const std::string& path, const std::string& msg) const { throw InputError(file_, path, msg); }
  void onlyKeys(const json& j, const std::string& path, const std::set<std::string>& allowed) const {
    if (!j.is_object()) fail(path, "expected an object");
    for (const auto& [k, v] : j.items())
      if (!allowed.count(k)) fail(path.empty() ? k : path + "." + k, "unknown key '" + k + "'");
  }
  double number(const json& j, const std::string& path) const {
    if (!j.is_number() || !std::isfinite(j.get<double>())) fail(path, "expected a finite number");
    return j.get<double>();
  }
  std::string string(const json& j, const std::string& path) const {
    if (!j.is_string()) fail(path, "expected a string");
    return j.get<std::string>();
  }
  const json& required(const json& j, const std::string& path, const std::string& key) const {
    if (!j.contains(key)) fail(path.empty() ? key : path + "." + key, "required key is missing");
    return j.at(key);
  }
  fs::path resolve(const std::string& relative) const { return fs::path(file_).parent_path() / relative; }

  /// Two-column series (time, value) from a CSV with a header row.
  void readSeries(const std::string& csv, const std::string& timeColumn, const std::string& valueColumn,
                  const std::string& path, ObservationSpec& o) const {
    const Series series = readCsvColumns(resolve(csv).string(), timeColumn, valueColumn, file_, path);
    o.times = series.x;
    o.values = series.y;
  }

 private:
  std::string file_;
};

/// The monitor quantity a series or runout compares (default: displacement).
void readQuantity(const JobReader& r, const json& j, const std::string& p, ObservationSpec& o) {
  if (!j.contains("quantity")) return;
  o.quantity = r.string(j.at("quantity"), p + ".quantity");
  static const std::set<std::string> known{"ux", "uy", "vx", "vy", "displacement", "speed"};
  if (!known.count(o.quantity))
    r.fail(p + ".quantity", "expected one of ux, uy, vx, vy, displacement, speed, found \"" + o.quantity + "\"");
}

/// "precision": false | true | {"scan_points", "half_width", "time_step_factors"}; absent: on
/// when an observation is a run-out.
void readPrecision(const JobReader& r, const json& doc, BackanalysisJob& job) {
  PrecisionSpec& p = job.precision;
  for (const auto& o : job.observations) p.enabled |= o.kind == ObservationSpec::Kind::Runout;
  if (!doc.contains("precision")) return;
  const json& j = doc.at("precision");
  if (j.is_boolean()) {
    p.enabled = j.get<bool>();
    return;
  }
  r.onlyKeys(j, "precision", {"scan_points", "half_width", "time_step_factors"});
  p.enabled = true;
  if (j.contains("scan_points")) {
    const double n = r.number(j.at("scan_points"), "precision.scan_points");
    if (n != std::floor(n) || n < 2 || n > 101) r.fail("precision.scan_points", "expected an integer in [2, 101]");
    p.scanPoints = static_cast<int>(n);
  }
  if (j.contains("half_width")) {
    p.halfWidth = r.number(j.at("half_width"), "precision.half_width");
    if (!(p.halfWidth > 0 && p.halfWidth <= 1)) r.fail("precision.half_width", "expected a fraction in (0, 1]");
  }
  if (j.contains("time_step_factors")) {
    const json& f = j.at("time_step_factors");
    if (!f.is_array()) r.fail("precision.time_step_factors", "expected an array of numbers");
    p.timeStepFactors.clear();
    for (size_t k = 0; k < f.size(); ++k) {
      const std::string path = "precision.time_step_factors[" + std::to_string(k) + "]";
      const double v = r.number(f[k], path);
      if (!(v >= 0.1 && v <= 10)) r.fail(path, "expected a factor in [0.1, 10]");
      p.timeStepFactors.push_back(v);
    }
  }
}

/// The parameters searched: a joint property or any case number by JSON path, with bounds.
void readParameters(const JobReader& r, const json& doc, BackanalysisJob& job) {
  const json& params = r.required(doc, "", "parameters");
  if (!params.is_array() || params.empty()) r.fail("parameters", "expected a non-empty array");
  for (size_t i = 0; i < params.size(); ++i) {
    const std::string p = "parameters[" + std::to_string(i) + "]";
    const json& j = params[i];
    r.onlyKeys(j, p, {"name", "joint", "property", "path", "min", "max", "start"});
    ParameterSpec s;
    s.name = r.string(r.required(j, p, "name"), p + ".name");
    if (j.contains("path")) {
      s.jsonPath = r.string(j.at("path"), p + ".path");
    } else {
      s.joint = r.string(r.required(j, p, "joint"), p + ".joint");
      s.property = r.string(r.required(j, p, "property"), p + ".property");
      static const std::set<std::string> known{"cohesion", "friction_angle", "tensile_strength",
                                               "residual_cohesion", "residual_friction_angle", "weakening_distance"};
      if (!known.count(s.property))
        r.fail(p + ".property", "expected cohesion, friction_angle, tensile_strength, residual_cohesion, "
                                "residual_friction_angle or weakening_distance, found \"" + s.property + "\"");
    }
    s.min = r.number(r.required(j, p, "min"), p + ".min");
    s.max = r.number(r.required(j, p, "max"), p + ".max");
    if (!(s.max > s.min)) {
      std::ostringstream m;
      m << "expected max > min, found min " << s.min << ", max " << s.max;
      r.fail(p + ".max", m.str());
    }
    if ((s.property == "friction_angle" || s.property == "residual_friction_angle") && (s.min < 0 || s.max >= 90))
      r.fail(p, "friction angle bounds must lie in [0, 90) degrees");
    if (j.contains("start")) {
      s.start = r.number(j.at("start"), p + ".start");
      s.hasStart = true;
      if (s.start < s.min || s.start > s.max) r.fail(p + ".start", "expected a start within [min, max]");
    }
    job.parameters.push_back(s);
  }
}

/// What the search fits: monitor series, a factor of safety, a run-out.
void readObservations(const JobReader& r, const json& doc, BackanalysisJob& job) {
  const json& obs = r.required(doc, "", "observations");
  if (!obs.is_array() || obs.empty()) r.fail("observations", "expected a non-empty array");
  for (size_t i = 0; i < obs.size(); ++i) {
    const std::string p = "observations[" + std::to_string(i) + "]";
    const json& j = obs[i];
    r.onlyKeys(j, p, {"type", "label", "monitor", "quantity", "csv", "time_column", "value_column", "target", "joints",
                      "sigma", "weight"});
    ObservationSpec o;
    const std::string type = r.string(r.required(j, p, "type"), p + ".type");
    o.label = j.contains("label") ? r.string(j.at("label"), p + ".label") : type;
    o.weight = j.contains("weight") ? r.number(j.at("weight"), p + ".weight") : 1.0;
    if (!j.contains("sigma")) r.fail(p + ".sigma", "required key is missing (the measurement uncertainty scales the misfit)");
    o.sigma = r.number(j.at("sigma"), p + ".sigma");
    if (!(o.sigma > 0)) r.fail(p + ".sigma", "expected sigma > 0");
    if (type == "series") {
      o.kind = ObservationSpec::Kind::Series;
      o.monitor = r.string(r.required(j, p, "monitor"), p + ".monitor");
      readQuantity(r, j, p, o);
      r.readSeries(r.string(r.required(j, p, "csv"), p + ".csv"),
                   j.contains("time_column") ? r.string(j.at("time_column"), p + ".time_column") : "time",
                   r.string(r.required(j, p, "value_column"), p + ".value_column"), p + ".csv", o);
    } else if (type == "factor_of_safety") {
      o.kind = ObservationSpec::Kind::FactorOfSafety;
      o.target = r.number(r.required(j, p, "target"), p + ".target");
      if (j.contains("joints")) {
        const json& js = j.at("joints");
        if (!js.is_array()) r.fail(p + ".joints", "expected an array of joint names, found " + js.dump());
        for (size_t k = 0; k < js.size(); ++k)
          o.joints.push_back(r.string(js[k], p + ".joints[" + std::to_string(k) + "]"));
      }
    } else if (type == "runout") {
      o.kind = ObservationSpec::Kind::Runout;
      o.monitor = r.string(r.required(j, p, "monitor"), p + ".monitor");
      readQuantity(r, j, p, o);
      o.target = r.number(r.required(j, p, "target"), p + ".target");
    } else {
      r.fail(p + ".type", "expected series, factor_of_safety or runout, found \"" + type + "\"");
    }
    job.observations.push_back(o);
  }
}

/// The optimiser, the precision study and the misfit grid.
void readSearch(const JobReader& r, const json& doc, BackanalysisJob& job) {
  if (doc.contains("optimiser")) {
    const json& o = doc.at("optimiser");
    r.onlyKeys(o, "optimiser", {"global", "local", "global_evaluations", "local_evaluations", "xtol_rel"});
    if (o.contains("global")) job.optimiser.global = r.string(o.at("global"), "optimiser.global");
    if (o.contains("local")) job.optimiser.local = r.string(o.at("local"), "optimiser.local");
    // An algorithm NLopt does not know is the job's mistake, said here with its path.
    for (const auto& [key, name] : {std::pair{"optimiser.global", job.optimiser.global},
                                    std::pair{"optimiser.local", job.optimiser.local}})
      if (!name.empty() && name != kGridSearch && static_cast<int>(nlopt_algorithm_from_string(name.c_str())) < 0)
        r.fail(key, "expected an NLopt algorithm name (e.g. GN_DIRECT_L, GN_CRS2_LM, LN_BOBYQA, LN_NELDERMEAD; "
                    "\"grid\" for a grid scan as the global stage), found \"" + name + "\"");
    if (o.contains("global_evaluations"))
      job.optimiser.globalEvaluations = static_cast<int>(r.number(o.at("global_evaluations"), "optimiser.global_evaluations"));
    if (o.contains("local_evaluations"))
      job.optimiser.localEvaluations = static_cast<int>(r.number(o.at("local_evaluations"), "optimiser.local_evaluations"));
    if (o.contains("xtol_rel")) job.optimiser.xtolRel = r.number(o.at("xtol_rel"), "optimiser.xtol_rel");
  }
  readPrecision(r, doc, job);
  if (doc.contains("grid_points")) job.gridPoints = static_cast<int>(r.number(doc.at("grid_points"), "grid_points"));
  if (job.gridPoints < 0 || job.gridPoints > 1000)
    throw InputError(job.jobPath, "grid_points", "expected 0 (no misfit map) to 1000 values per parameter, found " +
                                                     std::to_string(job.gridPoints));
  if (job.optimiser.global == kGridSearch) {
    // grid_points^n evaluations: a cap that keeps a typo from asking for years of runs.
    double points = 1;
    for (size_t i = 0; i < job.parameters.size(); ++i) points *= job.gridPoints;
    if (job.gridPoints < 2 || points > 1e5)
      throw InputError(job.jobPath, "grid_points",
                       "the grid search evaluates grid_points^" + std::to_string(job.parameters.size()) +
                           " points: expected 2 or more per parameter and at most 100000 in all, found " +
                           std::to_string(job.gridPoints) + " per parameter");
  }
}

/// The accuracy and model choices the job imposes on its case (preset, blocks, brittle joints).
void readModelChoices(const JobReader& r, const json& doc, BackanalysisJob& job) {
  model::SettingsOverride own;
  own.origin = "job ";
  if (doc.contains("preset")) {
    own.preset = r.string(doc.at("preset"), "preset");
    if (own.preset != "fast" && own.preset != "balanced" && own.preset != "accurate")
      r.fail("preset", "expected fast, balanced or accurate, found \"" + own.preset + "\"");
  }
  if (doc.contains("blocks")) {
    own.blocks = r.string(doc.at("blocks"), "blocks");
    if (own.blocks != "rigid" && own.blocks != "deformable")
      r.fail("blocks", "expected rigid or deformable, found \"" + own.blocks + "\"");
  }
  if (doc.contains("brittle_joints")) {
    if (!doc.at("brittle_joints").is_boolean())
      r.fail("brittle_joints", "expected true or false, found " + doc.at("brittle_joints").dump());
    own.brittleJoints = doc.at("brittle_joints").get<bool>();
  }
  job.model.push_back(own);
}

}  // namespace

BackanalysisJob readJob(const std::string& path) {
  const JobReader r(path);
  const json doc = readJsonFile(path);
  r.onlyKeys(doc, "", {"description", "case", "parameters", "observations", "optimiser", "grid_points", "threads",
                       "preset", "blocks", "brittle_joints", "precision"});
  BackanalysisJob job;
  job.jobPath = path;
  job.casePath = r.resolve(r.string(r.required(doc, "", "case"), "case")).string();
  job.caseText = readInputFile(job.casePath, kMaxJsonFileBytes, path, "case");
  readParameters(r, doc, job);
  readObservations(r, doc, job);
  readSearch(r, doc, job);
  if (doc.contains("threads")) job.threads = static_cast<int>(r.number(doc.at("threads"), "threads"));
  readModelChoices(r, doc, job);
  return job;
}

}  // namespace ddaslope::io

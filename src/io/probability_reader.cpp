#include "ddaslope/io/probability_reader.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <set>
#include <sstream>

#include <Eigen/Eigenvalues>
#include <nlohmann/json.hpp>

#include "ddaslope/core/errors.hpp"
#include "ddaslope/io/case_reader.hpp"
#include "json_input.hpp"

namespace ddaslope::io {
namespace {

using nlohmann::json;
using model::DistributionKind;

/// A study of more samples than this is refused: a million forward runs of a real slope (seconds
/// each) is weeks of one core, and a Latin hypercube keeps N integers per input.
constexpr long long kMaxSamples = 1000000;
/// A truncated normal keeping less of its normal than this has bounds far out in a tail: almost
/// surely a unit slip (kPa for Pa).
constexpr double kMinTruncatedMass = 1e-9;

std::string shown(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

class SectionReader {
 public:
  explicit SectionReader(std::string file) : file_(std::move(file)) {}
  [[noreturn]] void fail(const std::string& path, const std::string& msg) const { throw InputError(file_, path, msg); }
  void onlyKeys(const json& j, const std::string& path, const std::set<std::string>& allowed) const {
    if (!j.is_object()) fail(path, "expected an object, found " + j.dump());
    for (const auto& [k, v] : j.items()) {
      if (allowed.count(k)) continue;
      std::string list;
      for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
      fail(path.empty() ? k : path + "." + k, "unknown key '" + k + "' (allowed here: " + list + ")");
    }
  }
  double number(const json& j, const std::string& path) const {
    if (!j.is_number() || !std::isfinite(j.get<double>())) fail(path, "expected a finite number, found " + j.dump());
    return j.get<double>();
  }
  std::string string(const json& j, const std::string& path) const {
    if (!j.is_string()) fail(path, "expected a string, found " + j.dump());
    return j.get<std::string>();
  }
  std::string choice(const json& j, const std::string& path, const std::set<std::string>& options) const {
    const std::string v = string(j, path);
    if (options.count(v)) return v;
    std::string list;
    for (const auto& o : options) list += (list.empty() ? "" : ", ") + o;
    fail(path, "expected one of " + list + ", found \"" + v + "\"");
  }
  const json& required(const json& j, const std::string& path, const std::string& key) const {
    if (!j.contains(key)) fail(path + "." + key, "required key is missing");
    return j.at(key);
  }

 private:
  std::string file_;
};

/// mean, sd, min, max as the distribution kind asks; a key another kind would use is refused
/// with the kind that uses it, so that a bound is never silently ignored.
model::Distribution readDistribution(const SectionReader& r, const json& j, const std::string& p) {
  model::Distribution d;
  const std::string kind = r.choice(r.required(j, p, "distribution"), p + ".distribution",
                                    {"normal", "lognormal", "uniform", "truncated_normal"});
  d.kind = kind == "normal" ? DistributionKind::Normal
           : kind == "lognormal" ? DistributionKind::Lognormal
           : kind == "uniform" ? DistributionKind::Uniform
                               : DistributionKind::TruncatedNormal;
  const bool moments = d.kind != DistributionKind::Uniform;
  if (moments) {
    d.mean = r.number(r.required(j, p, "mean"), p + ".mean");
    d.sd = r.number(r.required(j, p, "sd"), p + ".sd");
    if (!(d.sd > 0)) r.fail(p + ".sd", "expected a standard deviation > 0, found " + shown(d.sd));
    for (const char* key : {"min", "max"})
      if (j.contains(key) && d.kind != DistributionKind::TruncatedNormal)
        r.fail(p + "." + key, "a " + kind + " distribution has no bounds: use truncated_normal (mean, sd, min and/or "
                              "max) to bound it");
  } else {
    for (const char* key : {"mean", "sd"})
      if (j.contains(key)) r.fail(p + "." + key, "a uniform distribution is given by min and max only");
    r.required(j, p, "min");
    r.required(j, p, "max");
  }
  if (j.contains("min")) d.min = r.number(j.at("min"), p + ".min");
  if (j.contains("max")) d.max = r.number(j.at("max"), p + ".max");
  if (d.kind == DistributionKind::Lognormal && !(d.mean > 0))
    r.fail(p + ".mean", "expected a mean > 0 for a lognormal distribution (its values are positive), found " +
                            shown(d.mean));
  if (d.kind == DistributionKind::TruncatedNormal && !j.contains("min") && !j.contains("max"))
    r.fail(p, "a truncated_normal needs min, max or both (without bounds it is a normal)");
  if (!(d.max > d.min)) r.fail(p + ".max", "expected max > min, found min " + shown(d.min) + ", max " + shown(d.max));
  // Samples, shifted to a design point as importance sampling draws them, lie well within 40
  // standard deviations of the mean: there they must still be numbers (an sd of 1e308 gives inf).
  double farthest = d.max - d.min;
  if (d.kind == DistributionKind::Lognormal) {
    const double s2 = std::log1p((d.sd / d.mean) * (d.sd / d.mean));
    farthest = std::exp(std::log(d.mean) - 0.5 * s2 + 40 * std::sqrt(s2));
  } else if (moments) {
    farthest = std::abs(d.mean) + 40 * d.sd;
  }
  if (!(farthest <= 1e300))
    r.fail(moments ? p + ".sd" : p + ".max",
           moments ? "expected a spread whose samples stay numbers (40 sd from the mean), found mean " + shown(d.mean) +
                         ", sd " + shown(d.sd)
                   : "expected max - min to be a number, found min " + shown(d.min) + ", max " + shown(d.max));
  if (d.kind == DistributionKind::TruncatedNormal) {
    const double a = (d.min - d.mean) / d.sd, b = (d.max - d.mean) / d.sd;
    const double mass = a > 0 ? 0.5 * (std::erfc(a / std::sqrt(2.0)) - std::erfc(b / std::sqrt(2.0)))
                              : 0.5 * (std::erfc(-b / std::sqrt(2.0)) - std::erfc(-a / std::sqrt(2.0)));
    if (!(mass >= kMinTruncatedMass))
      r.fail(p, "the bounds [" + shown(d.min) + ", " + shown(d.max) + "] keep " + shown(mass) +
                    " of the normal (mean " + shown(d.mean) + ", sd " + shown(d.sd) +
                    "): they lie far out in its tail; check the units");
  }
  return d;
}

/// A path a CSV column can be named by, and that names a value of the case proper.
void checkPathText(const SectionReader& r, const std::string& path, const std::string& p) {
  if (path.empty()) r.fail(p, "expected a JSON path of the case, e.g. joints.bedding.cohesion, found \"\"");
  if (path.find_first_of(",\"\n\r") != std::string::npos)
    r.fail(p, "a path with a comma, quote or line break cannot name a CSV column, found \"" + path + "\"");
  for (size_t i = path.find('['); i != std::string::npos; i = path.find('[', i + 1)) {
    const size_t close = path.find(']', i);
    if (close == std::string::npos || close == i + 1 ||
        path.find_first_not_of("0123456789", i + 1) != close)
      r.fail(p, "expected [index] with a whole number in the path, found \"" + path + "\"");
  }
  const std::string head = path.substr(0, path.find_first_of(".["));
  if (head == "probability" || head == "expected" || head == "description")
    r.fail(p, "\"" + path + "\" is not an input of the model: give a number the analysis uses (joints, materials, "
                            "water, seismic, …)");
}

std::vector<model::InputCorrelation> readCorrelations(const SectionReader& r, const json& j,
                                                      const std::vector<model::UncertainInput>& inputs) {
  std::vector<model::InputCorrelation> out;
  if (!j.is_array()) r.fail("probability.correlations", "expected an array, found " + j.dump());
  std::set<std::pair<int, int>> seen;
  for (size_t k = 0; k < j.size(); ++k) {
    const std::string p = "probability.correlations[" + std::to_string(k) + "]";
    r.onlyKeys(j[k], p, {"between", "rho"});
    const json& between = r.required(j[k], p, "between");
    if (!between.is_array() || between.size() != 2)
      r.fail(p + ".between", "expected two input paths, found " + between.dump());
    int idx[2] = {-1, -1};
    for (int e = 0; e < 2; ++e) {
      const std::string path = r.string(between[e], p + ".between[" + std::to_string(e) + "]");
      for (size_t i = 0; i < inputs.size(); ++i)
        if (inputs[i].path == path) idx[e] = static_cast<int>(i);
      if (idx[e] < 0)
        r.fail(p + ".between[" + std::to_string(e) + "]", "\"" + path + "\" is not one of the inputs' paths");
    }
    if (idx[0] == idx[1]) r.fail(p + ".between", "expected two different inputs");
    if (!seen.insert({std::min(idx[0], idx[1]), std::max(idx[0], idx[1])}).second)
      r.fail(p + ".between", "this pair's correlation is given twice");
    const double rho = r.number(r.required(j[k], p, "rho"), p + ".rho");
    if (!(std::abs(rho) < 1)) r.fail(p + ".rho", "expected a correlation in (-1, 1), found " + shown(rho));
    out.push_back({idx[0], idx[1], rho});
  }
  // Pairwise correlations need not fit together (ρ12 = ρ13 = 0.9, ρ23 = −0.9): the matrix must be
  // positive definite for the normals to exist. Its smallest eigenvalue tells how far it is.
  const int n = static_cast<int>(inputs.size());
  Eigen::MatrixXd m = Eigen::MatrixXd::Identity(n, n);
  for (const auto& c : out) m(c.a, c.b) = m(c.b, c.a) = c.rho;
  const double smallest = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(m).eigenvalues().minCoeff();
  if (!(smallest > 1e-10))
    r.fail("probability.correlations", "the correlations do not fit together: their matrix is not positive definite "
                                       "(smallest eigenvalue " + shown(smallest) + "); weaken some of them");
  return out;
}

void readFos(const SectionReader& r, const json& j, model::ProbabilitySpec& s) {
  r.onlyKeys(j, "probability.fos", {"joints", "width"});
  if (j.contains("joints")) {
    const json& js = j.at("joints");
    if (!js.is_array()) r.fail("probability.fos.joints", "expected an array of joint names, found " + js.dump());
    for (size_t k = 0; k < js.size(); ++k)
      s.fosJoints.push_back(r.string(js[k], "probability.fos.joints[" + std::to_string(k) + "]"));
  }
  if (j.contains("width")) {
    s.fosWidth = r.number(j.at("width"), "probability.fos.width");
    if (!(s.fosWidth >= 1e-4 && s.fosWidth <= 1))
      r.fail("probability.fos.width", "expected a width of F in [1e-4, 1], found " + shown(s.fosWidth));
  }
}

model::ProbabilitySpec readSection(const SectionReader& r, const json& j) {
  const std::string p = "probability";
  r.onlyKeys(j, p, {"samples", "method", "sampling", "measure", "seed", "inputs", "correlations", "fos"});
  model::ProbabilitySpec s;
  const json& n = r.required(j, p, "samples");
  if (!n.is_number_integer() || n.get<long long>() < 1 || n.get<long long>() > kMaxSamples)
    r.fail(p + ".samples", "expected a whole number of samples in [1, " + std::to_string(kMaxSamples) + "], found " +
                               n.dump());
  s.samples = static_cast<int>(n.get<long long>());
  if (j.contains("sampling"))
    s.sampling = r.choice(j.at("sampling"), p + ".sampling", {"monte_carlo", "latin_hypercube"}) == "monte_carlo"
                     ? model::Sampling::MonteCarlo
                     : model::Sampling::LatinHypercube;
  if (j.contains("method")) {
    const std::string m = r.choice(j.at("method"), p + ".method", {"sampling", "importance_sampling", "active_learning"});
    s.method = m == "importance_sampling" ? model::ProbabilityMethod::ImportanceSampling
               : m == "active_learning"   ? model::ProbabilityMethod::ActiveLearning
                                          : model::ProbabilityMethod::Sampling;
  }
  if (j.contains("measure"))
    s.measure = r.choice(j.at("measure"), p + ".measure", {"verdict", "fos"}) == "fos"
                    ? model::ProbabilityMeasure::FactorOfSafety
                    : model::ProbabilityMeasure::Verdict;
  if (j.contains("seed")) {
    const json& seed = j.at("seed");
    if (!seed.is_number_unsigned())
      r.fail(p + ".seed", "expected a whole number ≥ 0 (64 bits), found " + seed.dump());
    s.seed = seed.get<std::uint64_t>();
  }
  const json& inputs = r.required(j, p, "inputs");
  if (!inputs.is_array() || inputs.empty()) r.fail(p + ".inputs", "expected a non-empty array of inputs");
  std::set<std::string> paths;
  for (size_t k = 0; k < inputs.size(); ++k) {
    const std::string q = p + ".inputs[" + std::to_string(k) + "]";
    r.onlyKeys(inputs[k], q, {"path", "distribution", "mean", "sd", "min", "max"});
    model::UncertainInput in;
    in.path = r.string(r.required(inputs[k], q, "path"), q + ".path");
    checkPathText(r, in.path, q + ".path");
    if (!paths.insert(in.path).second) r.fail(q + ".path", "\"" + in.path + "\" is an input already");
    in.distribution = readDistribution(r, inputs[k], q);
    s.inputs.push_back(in);
  }
  s.correlations = j.contains("correlations") ? readCorrelations(r, j.at("correlations"), s.inputs)
                                              : std::vector<model::InputCorrelation>{};
  // Read whatever the measure: `--measure fos` may choose it for a section that says "verdict".
  if (j.contains("fos")) readFos(r, j.at("fos"), s);
  if (s.method == model::ProbabilityMethod::ImportanceSampling && s.measure == model::ProbabilityMeasure::FactorOfSafety)
    r.fail(p + ".measure", "importance sampling judges each sample by one forward run's verdict: expected the "
                           "measure verdict, found fos (F's statistics over weighted samples are not computed)");
  return s;
}

/// A value inside the marginal's support, where its density is high: what the case is first
/// asked to accept at an input's path.
double probeValue(const model::Distribution& d) {
  if (d.kind == DistributionKind::Uniform) return 0.5 * (d.min + d.max);
  return std::clamp(d.mean, d.min, d.max);
}

std::string digest(const json& doc) {
  std::uint64_t h = 0xcbf29ce484222325ULL;  // FNV-1a 64
  for (unsigned char c : doc.dump()) h = (h ^ c) * 0x100000001b3ULL;
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

}  // namespace

ProbabilityJob readProbabilityJob(const std::string& path) {
  const SectionReader r(path);
  const json doc = readJsonFile(path);
  if (!doc.is_object()) r.fail("", "expected a case or a probability job (a JSON object)");
  ProbabilityJob job;
  job.file = path;
  if (doc.contains("case")) {
    // A job: the case it names, the model choices it imposes, and the study.
    r.onlyKeys(doc, "", {"description", "case", "preset", "blocks", "brittle_joints", "probability"});
    job.casePath = (std::filesystem::path(path).parent_path() / r.string(doc.at("case"), "case")).lexically_normal().string();
    job.model.origin = "job ";
    if (doc.contains("preset")) job.model.preset = r.choice(doc.at("preset"), "preset", {"fast", "balanced", "accurate"});
    if (doc.contains("blocks")) job.model.blocks = r.choice(doc.at("blocks"), "blocks", {"rigid", "deformable"});
    if (doc.contains("brittle_joints")) {
      if (!doc.at("brittle_joints").is_boolean())
        r.fail("brittle_joints", "expected true or false, found " + doc.at("brittle_joints").dump());
      job.model.brittleJoints = doc.at("brittle_joints").get<bool>();
    }
  } else {
    job.casePath = path;
  }
  if (!doc.contains("probability"))
    r.fail("probability", "required key is missing: the uncertain inputs and how to sample them (docs/probability.md)");
  job.spec = readSection(r, doc.at("probability"));
  job.caseText = readInputFile(job.casePath, kMaxJsonFileBytes, job.casePath == path ? "" : path,
                               job.casePath == path ? "" : "case");
  json caseDoc = parseJsonText(job.caseText, job.casePath);
  if (caseDoc.is_object()) caseDoc.erase("probability");
  job.caseDigest = digest(caseDoc);
  // Every input names a number of the case, which the case accepts at the input's mean (the
  // values drawn are checked before any run: cli/probability_command.cpp).
  const model::Scene base = parseCase(job.caseText, job.casePath);
  for (size_t k = 0; k < job.spec.fosJoints.size(); ++k) {
    bool known = false;
    for (const auto& joint : base.joints) known |= joint.name == job.spec.fosJoints[k];
    if (!known)
      r.fail("probability.fos.joints[" + std::to_string(k) + "]",
             "the case has no joint named \"" + job.spec.fosJoints[k] + "\"");
  }
  for (size_t k = 0; k < job.spec.inputs.size(); ++k) {
    const model::UncertainInput& in = job.spec.inputs[k];
    try {
      parseCase(job.caseText, job.casePath, {{in.path, probeValue(in.distribution)}});
    } catch (const InputError& e) {
      r.fail("probability.inputs[" + std::to_string(k) + "].path",
             "the case cannot vary \"" + in.path + "\" (tried at " + shown(probeValue(in.distribution)) +
                 "): " + e.what());
    }
  }
  return job;
}

bool hasProbabilitySection(const std::string& casePath) {
  const json doc = readJsonFile(casePath);
  return doc.is_object() && doc.contains("probability");
}

}  // namespace ddaslope::io

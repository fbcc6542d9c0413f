// Seeded fuzzers of the input surfaces besides the case file (issue #44, item 2; test_fuzz.cpp
// fuzzes case files): ground-motion records (CSV and PEER AT2), DXF sections, probability and
// back-analysis jobs, the command line with its --set paths, and a damaged samples.csv under
// `probability --resume`. Each mutates shipped (or built) input with a fixed seed, a bounded number
// of times, and expects one of the documented outcomes only: refused as bad input naming the file
// (an InputError, or exit 2 from the command line), or accepted with every number finite, or a
// reported non-convergence (exit 3). Never another exception, an internal error (exit 1), a signal
// or a hang; and no "nan" or "inf" in a file ddaslope writes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "ddaslope/calibration/probability.hpp"
#include "ddaslope/core/errors.hpp"
#include "ddaslope/io/case_reader.hpp"
#include "ddaslope/io/dxf_section.hpp"
#include "ddaslope/io/ground_motion.hpp"
#include "ddaslope/io/job_reader.hpp"
#include "ddaslope/io/probability_reader.hpp"
#include "fuzz_mutations.hpp"
#include "test_io.hpp"

using namespace ddaslope;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

const fs::path kSource = DDASLOPE_SOURCE_DIR;

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

json readJson(const fs::path& p) { return json::parse(slurp(p)); }

void writeFile(const fs::path& p, const std::string& text) { std::ofstream(p, std::ios::binary) << text; }

/// A folder of its own in the temporary directory, empty, removed when the test ends.
struct TempDir {
  fs::path path;
  explicit TempDir(const std::string& name)
      : path(fs::temp_directory_path() / ("ddaslope_fuzz_" + name + "_" + std::to_string(::getpid()))) {
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~TempDir() {
    std::error_code ignored;
    fs::remove_all(path, ignored);
  }
};

/// "nan", "inf" or "infinity" (any case, signed, spaced or quoted): a number written without a
/// finite value.
bool nonFiniteToken(std::string s) {
  s.erase(std::remove_if(s.begin(), s.end(), [](char c) { return c == ' ' || c == '"' || c == '\r' || c == '\t'; }),
          s.end());
  if (!s.empty() && (s[0] == '-' || s[0] == '+')) s.erase(0, 1);
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s == "nan" || s == "inf" || s == "infinity";
}

/// What is wrong with a file ddaslope wrote, or "": a CSV field or a whitespace-separated token of
/// a text file that reads nan or inf, or a JSON file (or JSON lines) that does not parse: JSON has
/// no such numbers, so one written would break it (docs/case-format.md: "no inf or NaN is ever
/// written"). Pictures and other binary files are skipped.
std::string nonFiniteIn(const fs::path& file) {
  const std::string text = slurp(file);
  if (file.extension() == ".png" || text.find('\0') != std::string::npos) return "";
  const bool csv = file.extension() == ".csv";
  const size_t first = text.find_first_not_of(" \t\r\n");
  if (!csv && first != std::string::npos && (text[first] == '{' || text[first] == '[')) {
    if (json::accept(text)) return "";
    std::istringstream in(text);
    int n = 0;
    for (std::string line; std::getline(in, line);)
      if (++n, !line.empty() && !json::accept(line)) return file.string() + ": line " + std::to_string(n) + " is not JSON";
    return "";
  }
  std::istringstream in(text);
  int n = 0;
  for (std::string line; std::getline(in, line);) {
    ++n;
    // Text formats (VTK XML, .pvd): values sit between spaces, tags and quotes.
    if (!csv) std::replace_if(line.begin(), line.end(), [](char c) { return c == '<' || c == '>' || c == '='; }, ' ');
    std::istringstream cells(line);
    for (std::string field; std::getline(cells, field, csv ? ',' : ' ');)
      if (nonFiniteToken(field)) return file.string() + ": line " + std::to_string(n) + " holds \"" + field + "\"";
  }
  return "";
}

/// Every file under `dir` (recursively) free of nan and inf, but `ours` (the test's own input).
void expectFiniteFiles(const fs::path& dir, const fs::path& ours = {}) {
  if (!fs::exists(dir)) return;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file() && e.path() != ours) {
      const std::string bad = nonFiniteIn(e.path());
      EXPECT_TRUE(bad.empty()) << bad;
    }
}

// ---------------------------------------------------------------------------------------------
// Ground-motion records

/// A record's sample instants and accelerations are finite and increasing in time, and so is what
/// a run takes from it: its value and its mean over a step across the whole record.
void expectFiniteRecord(const model::GroundMotion& g) {
  ASSERT_GE(g.times.size(), 2u);
  ASSERT_EQ(g.horizontal.size(), g.times.size());
  if (!g.vertical.empty()) {
    ASSERT_EQ(g.vertical.size(), g.times.size());
  }
  for (size_t k = 0; k < g.times.size(); ++k) {
    ASSERT_TRUE(std::isfinite(g.times[k]) && std::isfinite(g.horizontal[k])) << "sample " << k;
    if (!g.vertical.empty()) {
      ASSERT_TRUE(std::isfinite(g.vertical[k])) << "sample " << k;
    }
    if (k > 0) {
      ASSERT_GT(g.times[k], g.times[k - 1]) << "sample " << k;
    }
  }
  for (int i = 0; i <= 10; ++i) {
    const double t = g.times.front() + (g.times.back() - g.times.front()) * i / 10;
    const Vec2 a = g.at(t), mean = g.meanOver(t, t + 1e-3);
    ASSERT_TRUE(std::isfinite(a.x()) && std::isfinite(a.y()) && std::isfinite(mean.x()) && std::isfinite(mean.y()))
        << "at t = " << t;
  }
}

struct RecordSeed {
  std::string name, text;
  io::RecordSpec spec;
};

/// The shipped records (a two-sample pulse in m/s², the Jiufengershan record in g with a vertical
/// column, cut to its first 60 rows) and the same accelerations as PEER .AT2 files in both header
/// forms (docs/seismic.md, "Formats").
std::vector<RecordSeed> recordSeeds() {
  std::vector<RecordSeed> seeds;
  RecordSeed pulse{"pulse.csv", slurp(kSource / "cases/records/rectangular_pulse_0.5g_0.5s.csv"), {}};
  pulse.spec.format = "csv", pulse.spec.units = "m/s2";
  seeds.push_back(pulse);
  std::istringstream in(slurp(kSource / "cases/records/jiufengershan_synthetic_tcu071.csv"));
  std::string csv, line;
  std::vector<std::string> horizontal;
  for (int n = 0; n < 61 && std::getline(in, line); ++n) {
    csv += line + "\n";
    if (n > 0) horizontal.push_back(line.substr(line.find(',') + 1, line.rfind(',') - line.find(',') - 1));
  }
  RecordSeed three{"jiufengershan.csv", csv, {}};
  three.spec.format = "csv", three.spec.units = "g", three.spec.verticalColumn = "a_v", three.spec.dt = 0.005;
  seeds.push_back(three);
  const std::string header = "PEER NGA STRONG MOTION DATABASE RECORD\nFUZZ 1/1/00, STATION, 000\n"
                             "ACCELERATION TIME SERIES IN UNITS OF G\n";
  std::string values;
  for (size_t k = 0; k < horizontal.size(); ++k) values += " " + horizontal[k] + (k % 5 == 4 ? "\n" : "");
  const std::string npts = std::to_string(horizontal.size());
  RecordSeed modern{"modern.AT2", header + "NPTS=   " + npts + ", DT=   .0050 SEC\n" + values + "\n", {}};
  modern.spec.format = "at2";
  seeds.push_back(modern);
  RecordSeed older{"older.AT2", header + "   " + npts + "   0.0050   NPTS, DT\n" + values + "\n", {}};
  older.spec.format = "at2", older.spec.units = "g", older.spec.scale = -2.5;
  seeds.push_back(older);
  return seeds;
}

}  // namespace

// Records cut short, edited or damaged are refused with the case's JSON path and the record
// named (docs/seismic.md, "Rejected records"), or read into a finite, increasing history.
TEST(Fuzz, MutatedGroundMotionRecordsAreRefusedOrFinite) {
  const std::vector<RecordSeed> seeds = recordSeeds();
  std::mt19937 rng(clitest::fuzzSeed(44));  // issue #44: fixed, so a failure reproduces
  const int kRecords = clitest::fuzzCount(1200);
  int refused = 0, accepted = 0;
  for (int n = 0; n < kRecords; ++n) {
    RecordSeed r = seeds[static_cast<size_t>(n) % seeds.size()];
    const int changes = static_cast<int>(fuzz::uniform(rng, 1, 3));
    for (int k = 0; k < changes; ++k) r.text = fuzz::mutateText(r.text, rng);
    r.spec.file = clitest::writeTemp("fuzz_" + r.name, r.text);
    SCOPED_TRACE("mutation " + std::to_string(n) + " of " + r.name + ":\n" + r.text.substr(0, 600));
    try {
      const model::GroundMotion g = io::readGroundMotion(r.spec, "fuzz_case.json", "seismic.record.file");
      ++accepted;
      expectFiniteRecord(g);
    } catch (const InputError& e) {
      ++refused;
      EXPECT_EQ(e.file(), "fuzz_case.json");
      EXPECT_EQ(e.jsonPath(), "seismic.record.file");
      EXPECT_NE(e.message().find(r.spec.file), std::string::npos) << e.what();
    } catch (const std::exception& e) {
      ADD_FAILURE() << "not an InputError: " << e.what();
    }
  }
  EXPECT_GT(refused, kRecords / 4);
  EXPECT_GT(accepted, kRecords / 20);
  std::printf("fuzz records: %d refused, %d accepted\n", refused, accepted);
}

// ---------------------------------------------------------------------------------------------
// DXF sections

namespace {

struct DrawingSeed {
  std::string text;
  io::DxfSectionSource source;
  json caseDoc;  ///< a case cutting the drawing (its section.dxf.file replaced by the mutation's)
};

std::vector<DrawingSeed> drawingSeeds() {
  std::vector<DrawingSeed> seeds;
  // Vajont's shipped drawing and case.
  const json vajont = readJson(kSource / "cases/vajont_dxf.json");
  const json& dxf = vajont["section"]["dxf"];
  DrawingSeed v{slurp(kSource / "cases" / dxf["file"].get<std::string>()), {}, vajont};
  v.source.units = dxf["units"];
  v.source.scale = dxf["scale"];
  v.source.groundLayer = dxf["layers"]["ground"];
  v.source.slidingSurfaceLayer = dxf["layers"]["sliding_surface"];
  v.source.jointsLayer = dxf["layers"]["joints"];
  v.source.waterLineLayer = dxf["layers"]["water_line"];
  seeds.push_back(v);
  // The basin of tests/make_dxf_fixtures.py drawn in several ways, cut as test_dxf_section.cpp does.
  const json layers = {{"ground", "GROUND"}, {"sliding_surface", "SLIP"}, {"joints", "JOINTS"}, {"water_line", "WATER"}};
  for (const char* name : {"basin", "basin_drawn_otherwise", "basin_r12", "basin_from_below", "basin_mm"}) {
    DrawingSeed b;
    b.text = slurp(fs::path(DDASLOPE_DXF_FIXTURES) / (std::string(name) + ".dxf"));
    b.source.units = std::string(name) == "basin_r12" ? "m" : "";
    b.source.groundLayer = "GROUND", b.source.slidingSurfaceLayer = "SLIP";
    b.source.jointsLayer = "JOINTS", b.source.waterLineLayer = "WATER";
    json section = {{"file", ""}, {"layers", layers}};
    if (!b.source.units.empty()) section["units"] = b.source.units;
    b.caseDoc = {{"gravity", {0, -9.81}},
                 {"materials", {{"rock", {{"density", 2600}, {"young_modulus", 5e9}, {"poisson_ratio", 0.25}}}}},
                 {"joints", {{"rock", {{"friction_angle", 35}}}}},
                 {"section", {{"dxf", section}, {"base_depth", 10}, {"material", "rock"}}},
                 {"analysis", {{"duration", 1}, {"time_step", 0.001}}}};
    seeds.push_back(b);
  }
  return seeds;
}

void expectFinitePoints(const std::vector<Vec2>& points, const char* what) {
  for (size_t i = 0; i < points.size(); ++i)
    ASSERT_TRUE(std::isfinite(points[i].x()) && std::isfinite(points[i].y())) << what << " point " << i;
}

/// A section read from a drawing is what io/dxf_section.cpp promises: lines of at least two
/// finite points, the water line with x increasing, each point with the place it came from. The
/// order of the ground's and sliding surface's points is the section's check when the case is cut
/// (model/section.cpp), which names the drawn point.
void expectValidSection(const io::DxfSection& s) {
  ASSERT_GE(s.ground.size(), 2u);
  ASSERT_GE(s.slidingSurface.size(), 2u);
  expectFinitePoints(s.ground, "ground");
  expectFinitePoints(s.slidingSurface, "sliding surface");
  expectFinitePoints(s.waterLine, "water line");
  for (size_t i = 1; i < s.waterLine.size(); ++i) EXPECT_GT(s.waterLine[i].x(), s.waterLine[i - 1].x());
  for (const auto& [a, b] : s.joints)
    ASSERT_TRUE(std::isfinite(a.x()) && std::isfinite(a.y()) && std::isfinite(b.x()) && std::isfinite(b.y()));
  EXPECT_EQ(s.groundFrom.size(), s.ground.size());
  EXPECT_EQ(s.slidingSurfaceFrom.size(), s.slidingSurface.size());
  EXPECT_EQ(s.jointFrom.size(), s.joints.size());
}

}  // namespace

// Drawings cut short, edited or damaged are refused with the case, a JSON path under section.dxf
// and the drawing named (docs/case-format.md, "Section from a drawing", and "Limits"), or read
// into a valid section, which the case reader then cuts into finite blocks or refuses.
TEST(Fuzz, MutatedDxfSectionsAreRefusedOrValid) {
  const std::vector<DrawingSeed> seeds = drawingSeeds();
  std::mt19937 rng(clitest::fuzzSeed(44));
  const int kDrawings = clitest::fuzzCount(300);
  int refused = 0, read = 0, cut = 0;
  for (int n = 0; n < kDrawings; ++n) {
    DrawingSeed d = seeds[static_cast<size_t>(n) % seeds.size()];
    const int changes = static_cast<int>(fuzz::uniform(rng, 1, 2));
    for (int k = 0; k < changes; ++k) d.text = fuzz::mutateText(d.text, rng);
    d.source.file = clitest::writeTemp("fuzz_section.dxf", d.text);
    SCOPED_TRACE("mutation " + std::to_string(n) + " of drawing " + std::to_string(n % seeds.size()));
    try {
      const io::DxfSection s = io::readDxfSection(d.source, "fuzz_case.json", "section.dxf");
      ++read;
      expectValidSection(s);
    } catch (const InputError& e) {
      ++refused;
      EXPECT_EQ(e.file(), "fuzz_case.json");
      EXPECT_EQ(e.jsonPath().rfind("section.dxf.", 0), 0u) << e.what();
      EXPECT_NE(e.message().find(d.source.file), std::string::npos) << e.what();
      continue;
    } catch (const std::exception& e) {
      ADD_FAILURE() << "not an InputError: " << e.what();
      continue;
    }
    d.caseDoc["section"]["dxf"]["file"] = d.source.file;
    try {
      const model::Scene scene = io::parseCase(d.caseDoc.dump(), "fuzz_case.json");
      ++cut;
      for (const auto& b : scene.blocks) expectFinitePoints(b.vertices, b.id.c_str());
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), "fuzz_case.json");
    } catch (const std::exception& e) {
      ADD_FAILURE() << "cutting the section: not an InputError: " << e.what();
    }
  }
  EXPECT_GT(refused, kDrawings / 4);
  EXPECT_GT(read, kDrawings / 20);
  std::printf("fuzz drawings: %d refused, %d read (%d cut into blocks)\n", refused, read, cut);
}

// ---------------------------------------------------------------------------------------------
// Job files

namespace {

struct JobSeed {
  json doc;
  std::string casePath;  ///< absolute: the mutated job lives in the temporary folder
  bool probability = false;
};

/// The shipped probability and back-analysis jobs, their case and observation files made absolute.
std::vector<JobSeed> jobSeeds() {
  std::vector<JobSeed> seeds;
  const auto add = [&](const fs::path& job, bool probability) {
    JobSeed s{readJson(job), "", probability};
    s.casePath = (job.parent_path() / s.doc["case"].get<std::string>()).lexically_normal().string();
    s.doc["case"] = s.casePath;
    if (s.doc.contains("observations"))
      for (json& o : s.doc["observations"])
        if (o.contains("csv")) o["csv"] = (job.parent_path() / o["csv"].get<std::string>()).string();
    seeds.push_back(s);
  };
  for (const char* p : {"planar_failure/probability.json", "planar_failure/probability_small.json", "vajont/probability.json"})
    add(kSource / "calibration" / p, true);
  for (const auto& e : fs::directory_iterator(kSource / "calibration"))
    if (fs::exists(e.path() / "job.json")) add(e.path() / "job.json", false);
  std::sort(seeds.begin(), seeds.end(), [](const JobSeed& a, const JobSeed& b) { return a.doc.dump() < b.doc.dump(); });
  return seeds;
}

}  // namespace

// Mutated probability and back-analysis jobs are refused with the job (or its case) and a JSON
// path named (docs/probability.md, docs/calibration.md), or read into a study whose numbers are
// finite: a probability study's first samples too.
TEST(Fuzz, MutatedJobsAreRefusedOrFinite) {
  const std::vector<JobSeed> seeds = jobSeeds();
  ASSERT_GE(seeds.size(), 8u);
  std::mt19937 rng(clitest::fuzzSeed(44));
  const int kJobs = clitest::fuzzCount(300);
  int refused = 0, accepted = 0;
  for (int n = 0; n < kJobs; ++n) {
    const JobSeed& seed = seeds[static_cast<size_t>(n) % seeds.size()];
    json doc = seed.doc;
    const int changes = static_cast<int>(fuzz::uniform(rng, 1, 2));
    for (int k = 0; k < changes; ++k) fuzz::mutateJson(doc, rng);
    const std::string text = doc.dump();
    const std::string path = clitest::writeTemp("fuzz_job.json", text);
    SCOPED_TRACE("mutation " + std::to_string(n) + ": " + text);
    try {
      if (seed.probability) {
        const io::ProbabilityJob job = io::readProbabilityJob(path);
        ++accepted;
        ASSERT_GE(job.spec.samples, 1);
        const calibration::SampleDesign design(job.spec);
        for (int k = 0; k < std::min(design.samples(), 20); ++k)
          for (double v : design.values(k)) ASSERT_TRUE(std::isfinite(v)) << "sample " << k;
      } else {
        const io::BackanalysisJob job = io::readJob(path);
        ++accepted;
        for (const auto& p : job.parameters) {
          EXPECT_TRUE(std::isfinite(p.min) && std::isfinite(p.max) && p.min < p.max) << p.name;
          if (p.hasStart) {
            EXPECT_TRUE(std::isfinite(p.start)) << p.name;
          }
        }
        for (const auto& o : job.observations) {
          EXPECT_TRUE(std::isfinite(o.target) && std::isfinite(o.sigma) && std::isfinite(o.weight)) << o.label;
          for (double v : o.values) EXPECT_TRUE(std::isfinite(v)) << o.label;
          for (double t : o.times) EXPECT_TRUE(std::isfinite(t)) << o.label;
        }
      }
    } catch (const InputError& e) {
      ++refused;
      EXPECT_TRUE(e.file() == path || e.file() == seed.casePath) << e.what();
      EXPECT_FALSE(e.message().empty());
    } catch (const std::exception& e) {
      ADD_FAILURE() << "not an InputError: " << e.what();
    }
  }
  EXPECT_GT(refused, kJobs / 4);
  EXPECT_GT(accepted, kJobs / 20);
  std::printf("fuzz jobs: %d refused, %d accepted\n", refused, accepted);
}

// ---------------------------------------------------------------------------------------------
// The command line

namespace {

/// Quoted for the shell, whatever the argument holds.
std::string quoted(const std::string& arg) {
  std::string q = "'";
  for (char c : arg) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

struct CliResult {
  int code = -1;
  std::string err;
};

/// Runs the CLI in `cwd` (relative outputs land there) under a time limit; a run past it shows as
/// exit 124 from timeout(1), a signal as 128 + its number.
CliResult runIn(const fs::path& cwd, const std::vector<std::string>& args, int seconds = 60) {
  const fs::path err = cwd.parent_path() / ("fuzz_stderr_" + std::to_string(::getpid()));
  std::string cmd = "cd ";
  cmd.append(quoted(cwd.string())).append(" && timeout -k 5 ").append(std::to_string(seconds)).append(" ");
  cmd.append(DDASLOPE_CLI);
  for (const auto& a : args) cmd.append(" ").append(quoted(a));
  cmd.append(" >/dev/null 2>").append(quoted(err.string())).append(" </dev/null");
  const int status = std::system(cmd.c_str());
  CliResult r;
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
  r.err = slurp(err);
  fs::remove(err);
  return r;
}

/// The documented outcomes of any command (docs/case-format.md, "Exit codes"): 0, 2 (bad input,
/// named) or 3 (non-convergence, a spent budget, a search without an answer); never 1 (an internal
/// error), a signal or a run past its limit.
void expectDocumentedExit(const CliResult& r) {
  EXPECT_TRUE(r.code == 0 || r.code == 2 || r.code == 3) << "exit " << r.code << "\n" << r.err;
  EXPECT_EQ(r.err.find("internal error"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("terminate"), std::string::npos) << r.err;
  if (r.code == 2) {
    EXPECT_FALSE(r.err.empty()) << "bad input without a message";
  }
}

/// The paths of the case's numbers and names as --set takes them (`blocks[1].vertices[0][0]`).
void setPaths(const json& j, const std::string& at, std::vector<std::string>& out) {
  if (j.is_object()) {
    for (const auto& [k, v] : j.items()) setPaths(v, at.empty() ? k : at + "." + k, out);
  } else if (j.is_array()) {
    for (size_t i = 0; i < j.size(); ++i) setPaths(j[i], at + "[" + std::to_string(i) + "]", out);
  } else {
    out.push_back(at);
  }
}

/// A --set argument: a real path of the case, or one with an odd index or key, given an odd value.
std::string oddSetting(std::mt19937& rng, const std::vector<std::string>& paths) {
  std::string path = fuzz::pick(rng, paths);
  switch (fuzz::uniform(rng, 0, 5)) {
    case 0: {  // an odd index
      const size_t open = path.find('[');
      if (open != std::string::npos)
        path.replace(open + 1, path.find(']', open) - open - 1,
                     fuzz::pick(rng, std::vector<std::string>{"x", "-1", "999", "1.5", "", " 0", "99999999999999999999", "0x1"}));
      break;
    }
    case 1:  // an odd key
      path += fuzz::pick(rng, std::vector<std::string>{".zz", "[0]", ".", "..x", "]", "[", "[0", std::string(300, 'k')});
      break;
    case 2:
      path = fuzz::pick(rng, std::vector<std::string>{"", "=", "analysis", "blocks", "a.b.c", "analysis.duration.x",
                                                       "seismic.k_h", "water.level", "analysis.max_steps"});
      break;
    default:
      break;
  }
  static const std::vector<std::string> values = {
      "nan", "inf", "-inf", "1e400", "-1e400", "1e308", "-1", "0", "1e-320", "", "null", "true", "false", "[]",
      "{}", "\"x\"", "\"open", "x", "2x", "0.5", "3", "1e6", "-1e6", "1e-9", std::string(3000, '7'), "[1,2]", "\"\""};
  return path + "=" + fuzz::pick(rng, values);
}

/// What an option's value might be on a careless or hostile command line.
std::string oddArgument(std::mt19937& rng) {
  static const std::vector<std::string> odd = {
      "nan", "inf", "-inf", "-1", "0", "1e400", "1e-400", "", " ", "1", "0.5", "2", "3", "a,b", "1:2:3", "nan:80:3",
      "0:1:100000", "0:80:2", "fast", "rigid", "deformable", "edge", "vertex", "cohesion", "friction", "support",
      "seismic-coefficient", "jrc", "auto", "+x", "sliding_plane", "interface", "/dev/null/dir", "/dev/null", "-",
      "--", "%s%n", std::string(3000, 'x'), "analysis.duration=0.01:0.02:2", "joints.interface.friction_angle=30:50:2",
      "0,0.01", "-5", "18446744073709551616"};
  return fuzz::pick(rng, odd);
}

/// A value the option takes, so that some mutated command lines still run.
std::string plausibleArgument(const std::string& option) {
  static const std::map<std::string, std::string> values = {
      {"--preset", "fast"}, {"--time-step", "0.002"}, {"--blocks", "deformable"}, {"--contact-treatment", "vertex"},
      {"--kh", "0.1"}, {"--kv", "-0.05"}, {"--out", "elsewhere"}, {"--duration", "0.02"}, {"--snapshots", "0,0.01"},
      {"--vtk-every", "0.01"}, {"--at-fos", "1.5"}, {"--joints", "sliding_plane"}, {"--threads", "2"},
      {"--width", "0.5"}, {"--sweep", "joints.sliding_plane.friction_angle=20:40:2"}, {"--vtk", "vtk"},
      {"--log-json", "log.jsonl"}, {"--joint", "interface"}, {"--solve", "friction"}, {"--direction", "auto"},
      {"--target-fos", "1.2"}, {"--friction", "30"}, {"--cohesion", "1000"}, {"--curve", "30:40:2"},
      {"--samples", "3"}, {"--seed", "7"}, {"--measure", "fos"}, {"--method", "sampling"},
      {"--sampling", "monte_carlo"}, {"--stop-after", "1"}, {"--set", "analysis.duration=0.02"}};
  const auto it = values.find(option);
  return it == values.end() ? "" : it->second;
}

struct Command {
  std::vector<std::string> args;     ///< a valid command line, before mutation
  std::vector<std::string> options;  ///< the subcommand's options (from its add_option/add_flag)
  std::vector<std::string> budget;   ///< appended after the mutations: every run stays short
};

}  // namespace

// Command lines mutated from a valid one of each subcommand, drawn from its real options and
// --set paths with odd values: every outcome is a documented exit code (0, 2 or 3), never an
// internal error, a signal or a hang, and every file written is free of nan and inf.
TEST(Fuzz, MutatedCommandLinesExitAsDocumented) {
  const std::string block = (kSource / "cases/stable_block_40deg.json").string();
  const std::string planar = (kSource / "cases/planar_failure.json").string();
  const std::string slab = (kSource / "cases/bilinear_slab.json").string();
  const std::string study = (kSource / "calibration/planar_failure/probability.json").string();
  std::vector<std::string> paths;
  setPaths(readJson(block), "", paths);
  const std::vector<std::string> model = {"--preset", "--time-step", "--blocks", "--contact-treatment",
                                          "--brittle-joints", "--set", "--kh", "--kv"};
  const auto with = [&](std::vector<std::string> own) {
    own.insert(own.end(), model.begin(), model.end());
    return own;
  };
  // Short runs: a twentieth of a second of the case, a few hundred steps and a second of wall
  // time at most per forward run (a budget stop is a reported non-convergence, exit 3).
  const std::vector<std::string> budget = {"--set", "analysis.max_steps=300", "--set", "analysis.wall_clock_limit=1"};
  const std::vector<Command> commands = {
      {{"check", block}, with({}), {}},
      {{"run", block, "--duration", "0.05", "--quiet"},
       with({"--out", "--duration", "--quiet", "--verbose", "--snapshots", "--vtk", "--vtk-every", "--at-fos", "--joints",
             "--threads"}),
       budget},
      {{"fos", planar, "--set", "analysis.duration=0.05", "--width", "0.2"},
       with({"--joints", "--width", "--threads", "--sweep", "--out", "--vtk", "--json", "--quiet", "--log-json"}), budget},
      {{"critical", block, "--set", "analysis.duration=0.05", "--width", "1"},
       with({"--joint", "--solve", "--direction", "--support", "--target-fos", "--friction", "--cohesion", "--width",
             "--threads", "--json", "--quiet", "--log-json", "--curve", "--out", "--vtk"}),
       budget},
      {{"cut", slab}, {"--out"}, {}},
      {{"probability", study, "--samples", "2", "--threads", "1", "--quiet", "--set", "analysis.duration=0.05"},
       with({"--out", "--samples", "--seed", "--measure", "--method", "--sampling", "--threads", "--resume",
             "--overwrite", "--stop-after", "--json", "--quiet", "--log-json"}),
       {"--stop-after", "2", "--set", "analysis.max_steps=300", "--set", "analysis.wall_clock_limit=1"}},
  };
  std::mt19937 rng(clitest::fuzzSeed(44));
  const int kLaunches = clitest::fuzzCount(60);
  int codes[4] = {0, 0, 0, 0};
  for (int n = 0; n < kLaunches; ++n) {
    const Command& c = commands[static_cast<size_t>(n) % commands.size()];
    std::vector<std::string> args = c.args;
    const int changes = static_cast<int>(fuzz::uniform(rng, 1, 3));
    for (int k = 0; k < changes; ++k) {
      switch (fuzz::uniform(rng, 0, 6)) {
        case 0:  // one of its options, with an odd value
          args.push_back(fuzz::pick(rng, c.options));
          args.push_back(oddArgument(rng));
          break;
        case 6: {  // one of its options, with a value it takes
          const std::string option = fuzz::pick(rng, c.options);
          args.push_back(option);
          if (const std::string v = plausibleArgument(option); !v.empty()) args.push_back(v);
          break;
        }
        case 1:  // one of its options alone
          args.push_back(fuzz::pick(rng, c.options));
          break;
        case 2:  // an argument dropped, or replaced by an odd one
          if (args.size() > 1) {
            const size_t at = fuzz::uniform(rng, 1, args.size() - 1);
            if (fuzz::uniform(rng, 0, 1)) args.erase(args.begin() + static_cast<long>(at));
            else args[at] = oddArgument(rng);
          }
          break;
        case 3:  // an unknown option
          args.push_back(fuzz::pick(rng, std::vector<std::string>{"--bogus", "-x", "--set=", "---", "--durat", "-"}));
          break;
        default:  // a --set with an odd path or value
          args.push_back("--set");
          args.push_back(oddSetting(rng, paths));
      }
    }
    args.insert(args.end(), c.budget.begin(), c.budget.end());
    std::string line;
    for (const auto& a : args) line += " " + (a.size() > 60 ? a.substr(0, 60) + "…" : a);
    SCOPED_TRACE("launch " + std::to_string(n) + ":" + line);
    const TempDir cwd("cli");
    const CliResult r = runIn(cwd.path, args);
    expectDocumentedExit(r);
    if (r.code == 0 || r.code == 2 || r.code == 3) ++codes[r.code];
    expectFiniteFiles(cwd.path);
  }
  std::printf("fuzz command lines: exit 0: %d, exit 2: %d, exit 3: %d\n", codes[0], codes[2], codes[3]);
  EXPECT_GT(codes[2], kLaunches / 4);
  EXPECT_GT(codes[0], 2);
}

// ---------------------------------------------------------------------------------------------
// samples.csv under --resume

// A study's samples.csv cut short, edited or damaged, then resumed (docs/probability.md, "Nothing
// lost"): a cut-off last line is dropped and run again (exit 0), a damaged row elsewhere is refused
// naming samples.csv and its line (exit 2). A resumed study's summary.json has a finite Pf and
// interval, and no file it wrote holds nan or inf.
TEST(Fuzz, DamagedSamplesAreResumedOrRefusedWithTheirLine) {
  const std::string study = (kSource / "calibration/planar_failure/probability.json").string();
  const TempDir root("resume");
  const fs::path whole = root.path / "whole";
  const std::vector<std::string> common = {"probability", study, "--samples", "6", "--threads", "1", "--quiet"};
  std::vector<std::string> args = common;
  args.insert(args.end(), {"--out", whole.string()});
  const CliResult first = runIn(root.path, args);
  ASSERT_EQ(first.code, 0) << first.err;
  const std::string rows = slurp(whole / "samples.csv");
  std::mt19937 rng(clitest::fuzzSeed(44));
  const int kResumes = clitest::fuzzCount(40);
  int resumed = 0, refused = 0;
  for (int n = 0; n < kResumes; ++n) {
    const fs::path dir = root.path / ("damaged_" + std::to_string(n));
    fs::create_directories(dir);
    fs::copy_file(whole / "probability_settings.json", dir / "probability_settings.json");
    std::string damaged = rows;
    const int changes = static_cast<int>(fuzz::uniform(rng, 1, 2));
    for (int k = 0; k < changes; ++k) damaged = fuzz::mutateText(damaged, rng);
    writeFile(dir / "samples.csv", damaged);
    SCOPED_TRACE("mutation " + std::to_string(n) + ":\n" + damaged.substr(0, 1200));
    args = common;
    args.insert(args.end(), {"--out", dir.string(), "--resume"});
    const CliResult r = runIn(root.path, args);
    expectDocumentedExit(r);
    EXPECT_NE(r.code, 3) << r.err;
    if (r.code == 2) {
      ++refused;
      EXPECT_NE(r.err.find("samples.csv"), std::string::npos) << r.err;
      EXPECT_NE(r.err.find("line "), std::string::npos) << r.err;
    }
    if (r.code == 0) {
      ++resumed;
      const json summary = readJson(dir / "summary.json");
      EXPECT_EQ(summary["samples_finished"], 6);
      EXPECT_TRUE(summary["probability_of_failure"].is_number()) << summary.dump();
      for (const char* key : {"interval_95", "bounds_95_with_not_converged"})
        for (const json& v : summary[key]) EXPECT_TRUE(v.is_number()) << key << ": " << summary.dump();
      for (const char* key : {"not_converged_as_stable", "not_converged_as_failing"})
        EXPECT_TRUE(summary[key].is_number()) << key << ": " << summary.dump();
    }
    // Refused, the damaged samples.csv is still the test's own; resumed, ddaslope has rewritten it.
    expectFiniteFiles(dir, r.code == 0 ? fs::path() : dir / "samples.csv");
    fs::remove_all(dir);
  }
  EXPECT_GT(resumed, 0);
  EXPECT_GT(refused, 0);
  std::printf("fuzz resumes: %d resumed, %d refused\n", resumed, refused);
}

// What the fuzzers above found, each pinned by its smallest form: a record value in g near the
// largest double (inf in m/s²: "-nan" in history.csv), a record time past any analysis, a job's
// fos observation whose joints are not an array, and a samples.csv rule that is not UTF-8 (an
// internal error writing summary.json). Each is bad input naming its file and place.
TEST(Fuzz, InputsTheFuzzersFoundAreRefusedWithTheirPlace) {
  const std::string header = "PEER NGA STRONG MOTION DATABASE RECORD\nFUZZ\nACCELERATION TIME SERIES IN UNITS OF G\n";
  io::RecordSpec at2;
  at2.format = "at2";
  at2.file = clitest::writeTemp("huge.AT2", header + "NPTS= 3, DT= .01 SEC\n 0.1 1.7976931348623157e308 0.1\n");
  clitest::expectInputError([&] { io::readGroundMotion(at2, "case.json", "seismic.record.file"); }, "case.json",
                            "seismic.record.file", "line 5: expected an acceleration within ±100 g");
  io::RecordSpec csv;
  csv.format = "csv", csv.units = "m/s2";
  csv.file = clitest::writeTemp("late.csv", "time,a_h\n0,0.1\n1e308,0.1\n");
  clitest::expectInputError([&] { io::readGroundMotion(csv, "case.json", "seismic.record.file"); }, "case.json",
                            "seismic.record.file", "line 3: expected a time within ±1e6 s, found \"1e308\"");
  csv.file = clitest::writeTemp("strong.csv", "time,a_h\n0,0.1\n0.01,1001\n");
  clitest::expectInputError([&] { io::readGroundMotion(csv, "case.json", "seismic.record.file"); }, "case.json",
                            "seismic.record.file", "line 3: expected a horizontal acceleration within ±100 g");

  json job = readJson(kSource / "calibration/vajont/job.json");
  job["case"] = (kSource / "calibration/vajont/case.json").string();
  job["observations"][0]["joints"] = 5;
  const std::string jobPath = clitest::writeTemp("joints_job.json", job.dump());
  clitest::expectInputError([&] { io::readJob(jobPath); }, jobPath, "observations[0].joints",
                            "expected an array of joint names, found 5");

  const std::string study = (kSource / "calibration/planar_failure/probability.json").string();
  const TempDir dir("rule");
  const std::vector<std::string> common = {"probability", study, "--samples", "3", "--threads", "1", "--quiet",
                                           "--out", dir.path.string()};
  std::vector<std::string> args = common;
  args.insert(args.end(), {"--stop-after", "2"});
  ASSERT_EQ(runIn(dir.path, args).code, 0);
  std::string rows = slurp(dir.path / "samples.csv");
  const size_t rule = rows.find(",fails,") != std::string::npos ? rows.find(",fails,") + 7 : rows.find(",stable,") + 8;
  rows.insert(rule, "\xba");
  writeFile(dir.path / "samples.csv", rows);
  args = common;
  args.push_back("--resume");
  const CliResult r = runIn(dir.path, args);
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("samples.csv: line "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("expected a verdict rule"), std::string::npos) << r.err;
}

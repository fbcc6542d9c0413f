// Bad input: a clear error naming the file and the JSON path; exit 2 from the CLI.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "ddaslope/calibration/backanalysis.hpp"
#include "ddaslope/core/errors.hpp"
#include "ddaslope/geometry/polygon.hpp"
#include "ddaslope/io/case_reader.hpp"
#include "ddaslope/io/job_reader.hpp"
#include "test_io.hpp"

using namespace ddaslope;
using nlohmann::json;
using clitest::captureCli;
using clitest::runCli;
using clitest::writeTemp;
namespace fs = std::filesystem;

namespace {

// The minimal form of issue #2, which must always be accepted.
const char* kMinimal = R"({
  "description": "block sliding on a 30 degree plane",
  "gravity": [0, -9.81],
  "materials": {"rock": {"density": 2600, "young_modulus": 5e9, "poisson_ratio": 0.25}},
  "joints": {"bedding": {"friction_angle": 20, "cohesion": 0, "tensile_strength": 0}},
  "default_joint": "bedding",
  "blocks": [
    {"id": "base", "material": "rock", "fixed": true, "vertices": [[0,0],[20,0],[20,1],[0,1]]},
    {"id": "slider", "material": "rock", "vertices": [[2,1],[4,1],[4,2],[2,2]]}
  ],
  "monitors": [{"id": "m1", "block": "slider", "point": [3, 1.5]}],
  "analysis": {"duration": 1.0, "time_step": 0.001}
})";

/// Expects parseCase to fail with this JSON path and a message containing `what`.
void expectError(const json& doc, const std::string& path, const std::string& what) {
  clitest::expectInputError([&] { io::parseCase(doc.dump(), "case.json"); }, "case.json", path, what);
}

json minimal() { return json::parse(kMinimal); }

/// Expects parseCase to refuse raw text (not a JSON document we could build) for a reason
/// containing `what`, naming the file.
void expectTextError(const std::string& text, const std::string& what) {
  try {
    io::parseCase(text, "case.json");
    ADD_FAILURE() << "accepted bad input; expected " << what;
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "case.json");
    EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
  }
}

}  // namespace

TEST(CaseReader, MinimalFormIsAccepted) {
  const model::Scene s = io::parseCase(kMinimal, "case.json");
  EXPECT_EQ(s.blocks.size(), 2u);
  EXPECT_TRUE(s.blocks[0].fixed);
  EXPECT_NEAR(s.joints[0].frictionAngle, 20 * M_PI / 180, 1e-15);  // degrees in, radians inside
  EXPECT_EQ(s.settings.mode, model::AnalysisMode::Dynamic);
}

TEST(CaseReader, InvalidJson) {
  try {
    io::parseCase("{\"blocks\": [", "broken.json");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("broken.json"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("invalid JSON"), std::string::npos);
  }
}

TEST(CaseReader, MissingFile) {
  try {
    io::readCase("/nonexistent/case.json");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "/nonexistent/case.json");
    EXPECT_NE(std::string(e.what()).find("cannot open"), std::string::npos);
  }
}

TEST(CaseReader, UnknownKeys) {
  json d = minimal();
  d["analysis"]["timestep"] = 0.01;
  expectError(d, "analysis.timestep", "unknown key 'timestep'");
  d = minimal();
  d["blocks"][1]["colour"] = "red";
  expectError(d, "blocks[1].colour", "unknown key");
  d = minimal();
  d["extra"] = 1;
  expectError(d, "extra", "unknown key");
}

// Softening joints (issue #14): the residual cannot exceed the peak; the law is one of two.
TEST(CaseReader, BadSofteningJoints) {
  json d = minimal();
  d["joints"]["bedding"]["residual_friction_angle"] = 25;  // peak 20
  expectError(d, "joints.bedding.residual_friction_angle", "≤ the peak friction_angle");
  d = minimal();
  d["joints"]["bedding"]["cohesion"] = 1000;
  d["joints"]["bedding"]["residual_cohesion"] = 2000;
  expectError(d, "joints.bedding.residual_cohesion", "≤ the peak cohesion");
  d = minimal();
  d["joints"]["bedding"]["weakening_distance"] = -0.1;
  expectError(d, "joints.bedding.weakening_distance", "slip distance ≥ 0");
  d = minimal();
  d["joints"]["bedding"]["weakening_law"] = "cubic";
  expectError(d, "joints.bedding.weakening_law", "linear");
  // Accepted: the set distance is kept, the residual friction used as given.
  d = minimal();
  d["joints"]["bedding"]["residual_friction_angle"] = 12;
  d["joints"]["bedding"]["weakening_distance"] = 0.05;
  const model::Scene s = io::parseCase(d.dump(), "case.json");
  EXPECT_DOUBLE_EQ(*s.joints[0].weakeningDistance, 0.05);
  EXPECT_NEAR(s.joints[0].residualFriction(), 12 * M_PI / 180, 1e-15);
}

TEST(CaseReader, BadPolygons) {
  json d = minimal();
  d["blocks"][1]["vertices"] = json::parse("[[2,1],[4,2],[4,1],[2,2]]");  // bow tie
  expectError(d, "blocks[1].vertices", "self-intersecting");
  d["blocks"][1]["vertices"] = json::parse("[[2,1],[3,1],[4,1]]");  // collinear: zero area
  expectError(d, "blocks[1].vertices", "");
  d["blocks"][1]["vertices"] = json::parse("[[2,1],[3,1]]");
  expectError(d, "blocks[1].vertices", "3 to 10000 points");
}

TEST(CaseReader, UnknownReferences) {
  json d = minimal();
  d["blocks"][1]["material"] = "granite";
  expectError(d, "blocks[1].material", "unknown material \"granite\"");
  d = minimal();
  d["default_joint"] = "fault";
  expectError(d, "default_joint", "unknown joint \"fault\"");
  d = minimal();
  d["monitors"][0]["block"] = "nowhere";
  expectError(d, "monitors[0].block", "unknown block");
  // One joint per pair of blocks: two entries for a pair, in either order of its ids, would let
  // the entry written last decide.
  d = minimal();
  d["joints"]["fault"] = {{"friction_angle", 10}};
  d["joint_pairs"] = json::array({{{"blocks", {"base", "slider"}}, {"joint", "bedding"}},
                                  {{"blocks", {"slider", "base"}}, {"joint", "fault"}}});
  expectError(d, "joint_pairs[1].blocks", "already given a joint by joint_pairs[0]");
}

TEST(CaseReader, OutOfRangeValues) {
  json d = minimal();
  d["materials"]["rock"]["density"] = -2600;
  expectError(d, "materials.rock.density", "found -2600");
  d = minimal();
  d["joints"]["bedding"]["friction_angle"] = 90;
  expectError(d, "joints.bedding.friction_angle", "[0, 90)");
  d = minimal();
  d["analysis"]["time_step"] = 0;
  expectError(d, "analysis.time_step", "a time step in [1e-7, 10] s, found 0");
  d = minimal();
  d["analysis"]["time_step"] = -0.001;
  expectError(d, "analysis.time_step", "a time step in [1e-7, 10] s, found -0.001");
  d = minimal();
  d["analysis"]["time_step"] = 1e7;
  expectError(d, "analysis.time_step", "a time step in [1e-7, 10] s, found 1e+07");
  d = minimal();
  d["materials"]["rock"]["density"] = "heavy";
  expectError(d, "materials.rock.density", "expected a number, found a string");
  // A growth factor is whole (grown steps land on its multiples of Δt) or "auto".
  for (const json& g : {json(0), json(1.5), json(101), json("fast")}) {
    d = minimal();
    d["analysis"]["time_step_growth"] = g;
    expectError(d, "analysis.time_step_growth", "expected \"auto\" or a whole factor in [1, 100]");
  }
  d = minimal();
  d["analysis"]["time_step_growth"] = "auto";
  EXPECT_EQ(io::parseCase(d.dump(), "case.json").settings.timeStepGrowth, 0) << "automatic";
  d["analysis"]["time_step_growth"] = 10;
  EXPECT_EQ(io::parseCase(d.dump(), "case.json").settings.timeStepGrowth, 10);
}

TEST(CaseReader, MonitorOutsideItsBlock) {
  json d = minimal();
  d["monitors"][0]["point"] = json::parse("[10, 1.5]");
  expectError(d, "monitors[0].point", "outside block \"slider\"");
}

// Overlapping blocks were accepted, and a search called the explosion of their contacts failure
// at every strength ("fails at every reduction factor tried"). The slider pushed 0.25 m into the
// base shares 2 × 0.25 m² with it, 2·0.5/4.5 = 0.222 m deep.
TEST(CaseReader, OverlappingBlocksAreRefused) {
  json d = minimal();
  d["blocks"][1]["vertices"] = json::parse("[[2,0.75],[4,0.75],[4,1.75],[2,1.75]]");
  d["monitors"][0]["point"] = json::parse("[3, 1.25]");
  expectError(d, "blocks[1].vertices", "overlaps block \"base\" (blocks[0]): 0.5 m² in common, about 0.222222 m deep");
  // Touching, with an extra vertex on the shared edge and a neighbour in a T-junction: accepted.
  d = minimal();
  d["blocks"][1]["vertices"] = json::parse("[[2,1],[3,1],[4,1],[4,2],[2,2]]");
  d["blocks"].push_back(json::parse(R"({"id": "t", "material": "rock", "vertices": [[4,1],[6,1],[6,2],[4,2]]})"));
  EXPECT_EQ(io::parseCase(d.dump(), "case.json").blocks.size(), 3u);
  // Two fixed blocks never meet in contact: their overlap is no one's business.
  d = minimal();
  d["blocks"].push_back(json::parse(R"({"id": "f", "material": "rock", "fixed": true, "vertices": [[10,0.5],[12,0.5],[12,3],[10,3]]})"));
  EXPECT_EQ(io::parseCase(d.dump(), "case.json").blocks.size(), 3u);
}

// The shipped planar failure with its wedge lowered 0.5 m into the rock mass, as written and moved
// to (1e15, 1e15): refused with exit 2 both times.
TEST(Cli, OverlappingBlocksExitWithTwoNearAndFarFromTheOrigin) {
  for (const double shift : {0.0, 1e15}) {
    json d = json::parse(std::ifstream(std::string(DDASLOPE_SOURCE_DIR) + "/cases/planar_failure.json"));
    for (json& b : d["blocks"])
      for (json& v : b["vertices"]) v = json::array({v[0].get<double>() + shift, v[1].get<double>() + shift});
    for (json& v : d["blocks"][1]["vertices"]) v[1] = v[1].get<double>() - 0.5;
    for (json& m : d["monitors"]) m["point"] = json::array({m["point"][0].get<double>() + shift, m["point"][1].get<double>() + shift});
    const std::string path = writeTemp("overlap.json", d.dump());
    std::string err;
    EXPECT_EQ(runCli("fos " + path + " --out /tmp/ddaslope_never", &err), 2) << shift;
    EXPECT_NE(err.find("blocks[1].vertices"), std::string::npos) << err;
    EXPECT_NE(err.find("block \"wedge\" overlaps block \"rock_mass\""), std::string::npos) << err;
    fs::remove(path);
  }
}

// A silent long run: the JSON parser's depth callback rescanned an object's members at each
// member's end, and `check` of a case with 50 000 materials ran for minutes (over 60 s measured)
// without a word. Read in linear time, it takes about a second; 60 s is a hang, not a speed target.
TEST(Cli, FiftyThousandMaterialsAreReadWithoutAHang) {
  json d = minimal();
  json& materials = d["materials"];
  for (int k = 0; k < 50000; ++k) {
    std::string name = "m";
    name += std::to_string(k);
    materials[name] = materials["rock"];
  }
  const std::string path = writeTemp("many_materials.json", d.dump());
  const int status = std::system(("timeout 60 " + std::string(DDASLOPE_CLI) + " check " + path + " >/dev/null").c_str());
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "exit " << WEXITSTATUS(status) << " (124: timed out)";
  fs::remove(path);
}

/// What a command says on stderr in its first three seconds, off a terminal, on a case of the
/// minimal scene run for 1e4 s: 1e7 steps of 2 blocks (at Δt = 1 ms), long work by any measure.
std::string firstWordsOfALongCommand(const std::string& command) {
  json d = minimal();
  d["analysis"]["duration"] = 1e4;
  const std::string path = writeTemp("long_work.json", d.dump());
  const fs::path out = fs::temp_directory_path() / ("ddaslope_long_" + std::to_string(::getpid()));
  const fs::path err = fs::temp_directory_path() / ("ddaslope_long_err_" + std::to_string(::getpid()));
  std::system(("timeout 3 " + std::string(DDASLOPE_CLI) + " " + command + " " + path + " --out " + out.string() +
               " >/dev/null 2>" + err.string())
                  .c_str());
  std::ifstream in(err);
  const std::string text((std::istreambuf_iterator<char>(in)), {});
  fs::remove_all(out);
  fs::remove(err);
  fs::remove(path);
  return text;
}

// A silent long run: `run` of a long scene said nothing before its end off a terminal. It states
// its size first (blocks, unknowns, contacts, steps), then a progress line a minute.
TEST(Cli, ALongRunStatesItsSizeBeforeItStarts) {
  const std::string text = firstWordsOfALongCommand("run");
  EXPECT_NE(text.find("a long run: 2 blocks (6 unknowns), 2 contacts at t = 0"), std::string::npos) << text;
  EXPECT_NE(text.find("then 10000000 steps of 0.001 s"), std::string::npos) << text;
}

// A long search is not silent while its first trial runs (a toppling case with its joints 1.6 mm
// apart is 6158 blocks, and its first trial takes minutes): fos and critical state the size of one
// trial before the first starts.
TEST(Cli, ALongSearchStatesItsSizeBeforeItStarts) {
  for (const std::string command : {"fos", "critical --solve cohesion"}) {
    const std::string text = firstWordsOfALongCommand(command);
    EXPECT_NE(text.find("a long search: each trial is 2 blocks (6 unknowns), 2 contacts at t = 0"), std::string::npos)
        << command << ": " << text;
    EXPECT_NE(text.find("and 10000000 steps of 0.001 s"), std::string::npos) << command << ": " << text;
  }
}

TEST(Cli, BadInputExitsWithTwoAndNamesFileAndPath) {
  json d = minimal();
  d["materials"]["rock"]["density"] = -1;
  const std::string path = writeTemp("bad.json", d.dump());
  std::string err;
  EXPECT_EQ(runCli("run " + path + " --out /tmp/ddaslope_never", &err), 2);
  EXPECT_NE(err.find(path), std::string::npos) << err;
  EXPECT_NE(err.find("materials.rock.density"), std::string::npos) << err;
  EXPECT_FALSE(fs::exists("/tmp/ddaslope_never/history.csv"));
  EXPECT_EQ(runCli("check /nonexistent.json", &err), 2);
  EXPECT_NE(err.find("/nonexistent.json"), std::string::npos) << err;
  fs::remove(path);
}

TEST(Cli, MinimalCaseRunsAndWritesHistoryAndSummary) {
  const std::string path = writeTemp("minimal.json", kMinimal);
  const fs::path out = fs::temp_directory_path() / ("ddaslope_min_" + std::to_string(::getpid()));
  std::string err;
  EXPECT_EQ(runCli("run " + path + " --out " + out.string(), &err), 0) << err;
  std::ifstream h(out / "history.csv");
  std::string header;
  std::getline(h, header);
  EXPECT_EQ(header, "time,dt,iterations,m1_ux,m1_uy,m1_vx,m1_vy,kinetic_energy,potential_energy,elastic_energy,load_work,energy_gain");
  const json summary = json::parse(std::ifstream(out / "summary.json"));
  EXPECT_EQ(summary["status"], "completed");
  EXPECT_EQ(summary["steps"], 1000);
  fs::remove_all(out);
  fs::remove(path);
}

// Non-convergence is reported (exit 3), the partial history is not named like a complete one,
// and summary.json says what failed.
TEST(Cli, NonConvergenceExitsWithThree) {
  json d = json::parse(kMinimal);
  d["blocks"][1]["velocity"] = json::array({0, -50});  // 5 cm per step: above g2·w0 = 0.05·…
  d["analysis"]["max_displacement_ratio"] = 1e-4;
  d["analysis"]["max_step_cuts"] = 0;
  const std::string path = writeTemp("fails.json", d.dump());
  const fs::path out = fs::temp_directory_path() / ("ddaslope_nc_" + std::to_string(::getpid()));
  std::string err;
  EXPECT_EQ(runCli("run " + path + " --out " + out.string(), &err), 3) << err;
  EXPECT_NE(err.find("non-convergence"), std::string::npos) << err;
  EXPECT_FALSE(fs::exists(out / "history.csv"));
  EXPECT_TRUE(fs::exists(out / "history.partial.csv"));
  const json summary = json::parse(std::ifstream(out / "summary.json"));
  EXPECT_EQ(summary["status"], "non_convergence");
  fs::remove_all(out);
  fs::remove(path);
}

// The contact treatment is selectable on the command line: the shipped B2 case holds with the
// default edge treatment and slides with the original vertex one (benchmarks.md B2).
TEST(Cli, ContactTreatmentSwitchShowsTheDifference) {
  const std::string path = std::string(DDASLOPE_SOURCE_DIR) + "/cases/cohesive_block_42kpa.json";
  const fs::path out = fs::temp_directory_path() / ("ddaslope_ct_" + std::to_string(::getpid()));
  std::string err;
  double moved[2];
  int k = 0;
  for (const char* t : {"edge", "vertex"}) {
    ASSERT_EQ(runCli("run " + path + " --quiet --contact-treatment " + t + " --out " + out.string(), &err), 0) << err;
    const json summary = json::parse(std::ifstream(out / "summary.json"));
    EXPECT_EQ(summary["settings"]["contact_treatment"], t);
    const json& m = summary["monitors"]["centre"];
    moved[k++] = std::hypot(m["ux"].get<double>(), m["uy"].get<double>());
  }
  EXPECT_LT(moved[0], 0.01);  // edge: holds
  EXPECT_GT(moved[1], 1.0);   // vertex: slides (frictional a = 3.64 m/s² once the bond is gone)
  fs::remove_all(out);
}

// Bad back-analysis jobs: clear errors naming the file and the JSON path.
TEST(JobReader, BadJobs) {
  const std::string casePath = std::string(DDASLOPE_SOURCE_DIR) + "/cases/planar_failure.json";
  const auto expectJobError = [&](const json& job, const std::string& path, const std::string& what) {
    const std::string file = writeTemp("job.json", job.dump());
    clitest::expectInputError([&] { io::readJob(file); }, file, path, what);
    fs::remove(file);
  };
  const json good = {{"case", casePath},
                     {"parameters", {{{"name", "c"}, {"joint", "sliding_plane"}, {"property", "cohesion"}, {"min", 0}, {"max", 1e5}}}},
                     {"observations", {{{"type", "factor_of_safety"}, {"target", 1.0}, {"sigma", 0.01}}}}};
  json j = good;
  j["optimizer"] = json::object();
  expectJobError(j, "optimizer", "unknown key");
  j = good;
  j["observations"][0].erase("sigma");
  expectJobError(j, "observations[0].sigma", "required");
  j = good;
  j["parameters"][0]["max"] = -1;
  expectJobError(j, "parameters[0].max", "max > min");
  j = good;
  j["parameters"][0]["property"] = "strength";
  expectJobError(j, "parameters[0].property", "cohesion, friction_angle, tensile_strength, residual_cohesion");
  j = good;
  j["observations"][0]["type"] = "velocity";
  expectJobError(j, "observations[0].type", "series, factor_of_safety or runout");
  j = good;
  j["observations"][0] = {{"type", "runout"}, {"monitor", "block"}, {"target", 300}, {"sigma", 50}, {"quantity", "travel"}};
  expectJobError(j, "observations[0].quantity", "ux, uy, vx, vy, displacement, speed, found \"travel\"");
  j = good;
  j["preset"] = "quick";
  expectJobError(j, "preset", "fast, balanced or accurate, found \"quick\"");
  j = good;
  j["blocks"] = "stiff";
  expectJobError(j, "blocks", "rigid or deformable, found \"stiff\"");
  j = good;
  j["parameters"][0]["max"] = -1;
  expectJobError(j, "parameters[0].max", "found min 0, max -1");
  j = good;
  j["optimiser"] = {{"global", "GN_NOPE"}};
  expectJobError(j, "optimiser.global", "an NLopt algorithm name");
  // A series observed after the run's end (planar_failure runs 1 s) is refused when the job runs,
  // not compared with the run's last state: the file, the observation and both times.
  j = good;
  const std::string csv = writeTemp("late.csv", "time,ux\n0.5,0.0\n5.0,0.1\n");
  j["observations"][0] = {{"type", "series"}, {"monitor", "wedge"}, {"quantity", "ux"}, {"csv", csv}, {"time_column", "time"}, {"value_column", "ux"}, {"sigma", 0.01}};
  const std::string file = writeTemp("late_job.json", j.dump());
  clitest::expectInputError([&] { calibration::runBackanalysis(io::readJob(file)); }, file, "observations[0].csv",
                            "t = 5 s, after the run's end");
}

// A case value varied by JSON path must exist and be a number.
TEST(CaseReader, OverrideByJsonPath) {
  const std::string casePath = std::string(DDASLOPE_SOURCE_DIR) + "/cases/planar_failure.json";
  const model::Scene s = io::readCase(casePath, {{"materials.rock.young_modulus", 2e10}, {"blocks[1].vertices[3][0]", 11.5}});
  EXPECT_EQ(s.materials[0].youngModulus, 2e10);
  EXPECT_EQ(s.blocks[1].vertices[3].x(), 11.5);  // the wedge is given counter-clockwise: order kept
  try {
    io::readCase(casePath, {{"materials.granite.density", 1}});
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.jsonPath(), "materials.granite.density");
  }
  // A setting the case leaves at its default can be set (a whole number stays an integer) ...
  const model::Scene t = io::readCase(casePath, {{"analysis.open_close_max_iterations", 6}});
  EXPECT_EQ(t.settings.openCloseMaxIterations, 6);
  // ... but a key the reader does not know is still refused, with the keys it knows.
  try {
    io::readCase(casePath, {{"analysis.open_close_limit", 6}});
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.jsonPath(), "analysis.open_close_limit");
    EXPECT_NE(std::string(e.what()).find("open_close_max_iterations"), std::string::npos) << e.what();
  }
}

// --snapshots writes one PNG per requested time (checked by its signature).
TEST(Cli, SnapshotsArePngPictures) {
  const std::string path = std::string(DDASLOPE_SOURCE_DIR) + "/cases/sliding_block_40deg.json";
  const fs::path out = fs::temp_directory_path() / ("ddaslope_snap_" + std::to_string(::getpid()));
  std::string err;
  ASSERT_EQ(runCli("run " + path + " --quiet --duration 0.5 --snapshots 0,0.25,0.5 --out " + out.string(), &err), 0) << err;
  for (const char* name : {"snapshot_00.png", "snapshot_01.png", "snapshot_02.png"}) {
    std::ifstream f(out / name, std::ios::binary);
    char sig[8] = {};
    f.read(sig, 8);
    EXPECT_EQ(std::string(sig + 1, 3), "PNG") << name;
  }
  EXPECT_FALSE(fs::exists(out / "snapshot_03.png"));
  fs::remove_all(out);
}

// Water: exactly one description, and a level series whose CSV exists, with increasing times.
TEST(CaseReader, WaterErrors) {
  json d = minimal();
  d["water"] = {{"level", 2.0}, {"phreatic_line", json::array({json::array({0, 1}), json::array({1, 1})})}};
  expectError(d, "water", "exactly one of");
  d["water"] = {{"phreatic_line", json::array({json::array({1, 1}), json::array({0, 1})})}};
  expectError(d, "water.phreatic_line[1]", "x increasing");
  d["water"] = {{"level_series", {{"csv", "no_such_levels.csv"}}}};
  expectError(d, "water.level_series.csv", "does not exist");
}

// Seismic coefficients: numbers in [-2, 2] under known keys (issue #17).
TEST(CaseReader, SeismicErrors) {
  json d = minimal();
  d["seismic"] = {{"k_h", "strong"}};
  expectError(d, "seismic.k_h", "expected a number");
  d["seismic"] = {{"k_h", 2.5}};
  expectError(d, "seismic.k_h", "[-2, 2]");
  d["seismic"] = {{"k_v", -3}};
  expectError(d, "seismic.k_v", "[-2, 2]");
  d["seismic"] = {{"kh", 0.1}};
  expectError(d, "seismic.kh", "");
  d["seismic"] = 0.1;
  expectError(d, "seismic", "object");
}

// Ground-motion records (issue #17): every rejected class names the case's JSON path, the record
// file and its line; the CLI exits 2.
TEST(CaseReader, GroundMotionRecordErrors) {
  const std::string header = "PEER NGA STRONG MOTION DATABASE RECORD\nTEST 1/1/00, STATION, 000\n"
                             "ACCELERATION TIME SERIES IN UNITS OF G\n";
  const auto at2 = [&](const std::string& name, const std::string& body) {
    json d = minimal();
    d["seismic"] = {{"record", {{"file", writeTemp(name, header + body)}}}};
    return d;
  };
  expectError(at2("nonpts.AT2", "DT= .0100 SEC\n 0.1 0.2\n"), "seismic.record.file", "line 4: expected NPTS and DT");
  expectError(at2("nan.AT2", "NPTS=    4, DT= .0100 SEC\n 0.1 0.2\n nan 0.1\n"), "seismic.record.file",
              "line 6: expected a finite acceleration, found \"nan\"");
  expectError(at2("count.AT2", "NPTS=    5, DT= .0100 SEC\n 0.1 0.2 0.3 0.4\n"), "seismic.record.file",
              "NPTS = 5 on line 4, but the record holds 4 values");
  json d = at2("dt.AT2", "NPTS=    2, DT= .0100 SEC\n 0.1 0.2\n");
  d["seismic"]["record"]["dt"] = 0.005;
  expectError(d, "seismic.record.file", "line 4: the case expects samples every 0.005 s, the record has 0.01 s");
  d = minimal();
  d["seismic"] = {{"record", {{"file", writeTemp("units.AT2", "A\nB\nVELOCITY IN UNITS OF CM/S\nNPTS= 2, DT= .01\n1 2\n")}}}};
  expectError(d, "seismic.record.file", "line 3: expected the units");
  const auto csv = [&](const std::string& name, const std::string& text) {
    json c = minimal();
    c["seismic"] = {{"record", {{"file", writeTemp(name, text)}, {"units", "g"}}}};
    return c;
  };
  expectError(csv("unsorted.csv", "time,a_h\n0,0.1\n0.02,0.2\n0.01,0.1\n"), "seismic.record.file",
              "line 4: expected times increasing");
  expectError(csv("nan.csv", "time,a_h\n0,0.1\n0.01,nan\n"), "seismic.record.file",
              "line 3: expected a finite horizontal acceleration");
  expectError(csv("column.csv", "t,a_h\n0,0.1\n"), "seismic.record.file",
              "line 1: expected a column \"time\" in the header, found \"t\", \"a_h\"");
  // A record's time 0 is the analysis's start: samples before it would never act, and the run
  // would start with a step to the first sample after it.
  expectError(csv("negative.csv", "time,a_h\n-1,0\n0.1,0.4\n0.2,0\n"), "seismic.record.file",
              "line 2: expected times >= 0 s");
  // A decimal comma splits a value into two cells.
  expectError(csv("comma.csv", "time,a_h\n0,0\n0.1,0,4\n"), "seismic.record.file",
              "line 3: expected 2 cells as in the header, found 3");
  // The header as spreadsheets write it: Excel's byte-order mark, quotes, spaces after commas.
  for (const std::string& head : {std::string("\xEF\xBB\xBFtime,a_h"), std::string("\"time\",\"a_h\""),
                                   std::string("time, a_h")}) {
    const json ok = csv("spreadsheet.csv", head + "\n0,0.1\n0.01,0.2\n");
    EXPECT_NO_THROW(io::parseCase(ok.dump(), "case.json")) << head;
  }
  d = csv("nounits.csv", "time,a_h\n0,0.1\n0.01,0.1\n");
  d["seismic"]["record"].erase("units");
  expectError(d, "seismic.record.units", "required for a CSV record");
  d["seismic"]["record"]["units"] = "gal";
  expectError(d, "seismic.record.units", "\"g\" or \"m/s2\"");
  // On the command line: exit 2, with the record named.
  const std::string bad = writeTemp("cli_count.AT2", header + "NPTS=    5, DT= .0100 SEC\n 0.1 0.2\n");
  json c = minimal();
  c["seismic"] = {{"record", {{"file", bad}}}};
  const std::string path = writeTemp("record_case.json", c.dump());
  std::string err;
  EXPECT_EQ(runCli("check " + path, &err), 2);
  EXPECT_NE(err.find(bad), std::string::npos) << err;
  EXPECT_NE(err.find("line 5"), std::string::npos) << err;
}

// --kh / --set seismic.k_h reach a case that has no seismic object, on any command: the yield
// coefficient of the A3 block (40.1° on 40°) toward the valley (−x) is tan 0.1° = 0.0017453
// (benchmarks.md §E's closed form, 0.5 %); a coefficient out of range is bad input (exit 2).
TEST(Cli, SeismicCoefficientsOnTheCommandLine) {
  const std::string path = std::string(DDASLOPE_SOURCE_DIR) + "/cases/stable_block_40deg.json";
  std::string err;
  // Both directions by default: the slope faces −x, and that is the direction reported.
  const std::string json = captureCli("critical " + path + " --solve seismic-coefficient --json", &err);
  const auto r = nlohmann::json::parse(json);
  EXPECT_NEAR(r["critical"].get<double>(), 0.0017453, 0.005 * 0.0017453) << err;
  EXPECT_EQ(r["direction"], "-x");
  // The default width is 1e-3 of k_y itself, however small, with one thread as with two.
  const auto one = nlohmann::json::parse(captureCli("critical " + path + " --solve seismic-coefficient --threads 1 --json", &err));
  EXPECT_NEAR(one["critical"].get<double>(), 0.0017453, 0.005 * 0.0017453) << err;
  EXPECT_LE(one["failing_at"].get<double>() - one["stable_at"].get<double>(), 1.001e-3 * one["failing_at"].get<double>());
  // Strength options mean nothing to this search: refused, not ignored.
  EXPECT_EQ(runCli("critical " + path + " --solve seismic-coefficient --friction 10", &err), 2);
  EXPECT_NE(err.find("--friction"), std::string::npos) << err;
  EXPECT_EQ(runCli("critical " + path + " --solve seismic-coefficient --kh 0.1", &err), 2);
  EXPECT_NE(err.find("seismic.k_h"), std::string::npos) << err;
  // Past k_y the block slides in a run; below it, it stands (--kh is --set seismic.k_h).
  const fs::path out = fs::temp_directory_path() / ("ddaslope_kh_" + std::to_string(::getpid()));
  ASSERT_EQ(runCli("run " + path + " --quiet --duration 0.5 --kh -0.01 --out " + out.string(), &err), 0) << err;
  const nlohmann::json m = nlohmann::json::parse(std::ifstream(out / "summary.json"))["monitors"]["centre"];
  EXPECT_GT(std::hypot(m["ux"].get<double>(), m["uy"].get<double>()), 0.01);
  EXPECT_EQ(runCli("run " + path + " --kh 3 --out " + out.string(), &err), 2);
  EXPECT_EQ(runCli("run " + path + " --set seismic.k_v=-2.5 --out " + out.string(), &err), 2);
  EXPECT_NE(err.find("seismic.k_v"), std::string::npos) << err;
  fs::remove_all(out);
}

// --set overrides a case number by JSON path; a malformed one is bad input (exit 2).
TEST(Cli, SetOverridesACaseNumber) {
  const std::string path = std::string(DDASLOPE_SOURCE_DIR) + "/cases/stable_block_40deg.json";
  const fs::path out = fs::temp_directory_path() / ("ddaslope_set_" + std::to_string(::getpid()));
  std::string err;
  // φ = 30° on the 40° plane: the stable block now slides (A2's frictional law).
  ASSERT_EQ(runCli("run " + path + " --quiet --duration 0.5 --set joints.interface.friction_angle=30 --out " + out.string(), &err), 0) << err;
  const json summary = json::parse(std::ifstream(out / "summary.json"));
  const json& m = summary["monitors"]["centre"];
  EXPECT_GT(std::hypot(m["ux"].get<double>(), m["uy"].get<double>()), 0.1);
  EXPECT_EQ(runCli("run " + path + " --set joints.interface.friction_angle --out " + out.string(), &err), 2);
  EXPECT_NE(err.find("json.path=value"), std::string::npos) << err;
  EXPECT_EQ(runCli("run " + path + " --set joints.nothing.friction_angle=3 --out " + out.string(), &err), 2);
  EXPECT_NE(err.find("joints.nothing.friction_angle"), std::string::npos) << err;
  fs::remove_all(out);
}

// --set takes what the case file takes: booleans and names as well as numbers, each checked by the
// reader as in the file; a path that names no value (blocks[x]) or a value of another kind is bad
// input with the path, never an internal error.
TEST(Cli, SetTakesBooleansAndNamesAsTheCaseFileDoes) {
  const std::string path = std::string(DDASLOPE_SOURCE_DIR) + "/cases/stable_block_40deg.json";
  const fs::path out = fs::temp_directory_path() / ("ddaslope_settyped_" + std::to_string(::getpid()));
  std::string err;
  ASSERT_EQ(runCli("run " + path + " --quiet --duration 0.1 --set analysis.settle_dynamically=false --set analysis.blocks=rigid "
                   "--set analysis.contact_treatment=vertex --out " + out.string(), &err), 0) << err;
  const json summary = json::parse(std::ifstream(out / "summary.json"));
  EXPECT_EQ(summary["settings"]["settle_dynamically"], false);
  EXPECT_EQ(summary["settings"]["blocks"], "rigid");
  EXPECT_EQ(summary["settings"]["contact_treatment"], "vertex");
  for (const auto& [set, expected] : std::vector<std::pair<std::string, std::string>>{
           {"analysis.blocks=square", "analysis.blocks"},
           {"analysis.settle_dynamically=0", "analysis.settle_dynamically"},
           {"analysis.duration=long", "analysis.duration"},
           {"blocks[x].id=1", "blocks[x].id"},
           {"blocks[99999999999].id=1", "blocks[99999999999].id"},
           {"analysis.duration=nan", "--set"},
           {"analysis.duration=1e999", "--set"}}) {
    EXPECT_EQ(runCli("run " + path + " --quiet --set " + set + " --out " + out.string(), &err), 2) << set << ": " << err;
    EXPECT_NE(err.find(expected), std::string::npos) << set << ": " << err;
    EXPECT_EQ(err.find("internal error"), std::string::npos) << set << ": " << err;
  }
  fs::remove_all(out);
}

// The command line's model options reach the run, and summary.json says where Δt came from:
// `fast` is Δt = 1.6e-3 √(w0/g) (model/presets.cpp; this case has g = 10 m/s²). A bad value is bad input for every command.
TEST(Cli, ModelOptionsAreReportedInTheSummary) {
  const std::string path = std::string(DDASLOPE_SOURCE_DIR) + "/cases/stable_block_40deg.json";
  const fs::path out = fs::temp_directory_path() / ("ddaslope_preset_" + std::to_string(::getpid()));
  std::string err;
  ASSERT_EQ(runCli("run " + path + " --quiet --duration 0.05 --preset fast --blocks rigid --out " + out.string(), &err), 0)
      << err;
  const json settings = json::parse(std::ifstream(out / "summary.json"))["settings"];
  const model::Scene scene = io::readCase(path);
  EXPECT_NEAR(settings["time_step"].get<double>(), 1.6e-3 * std::sqrt(scene.modelHalfSize() / scene.gravity.norm()),
              1e-12);
  EXPECT_EQ(settings["time_step_origin"], "--preset fast");
  EXPECT_EQ(settings["blocks"], "rigid");
  const std::string job = std::string(DDASLOPE_SOURCE_DIR) + "/calibration/two_block_slide/job.json";
  EXPECT_EQ(runCli("backanalyse " + job + " --time-step 0 --out " + out.string(), &err), 2);
  EXPECT_NE(err.find("expected a time step in [1e-7, 10] s, found 0"), std::string::npos) << err;
  EXPECT_EQ(runCli("critical " + path + " --joint interface --preset quick", &err), 2);
  EXPECT_NE(err.find("quick"), std::string::npos) << err;
  fs::remove_all(out);
}

// Presets (docs/accuracy.md): "preset" sets Δt = c √(w0/g), g2 and the penalty factor; explicit
// keys of the same analysis object win; an unknown name is bad input.
TEST(CaseReader, PresetsAndExplicitKeys) {
  json d = minimal();
  d["analysis"].erase("time_step");
  d["analysis"]["preset"] = "balanced";
  const model::Scene s = io::parseCase(d.dump(), "case.json");
  EXPECT_NEAR(s.settings.timeStep, 5.5e-4 * std::sqrt(s.modelHalfSize() / 9.81), 1e-15);
  EXPECT_EQ(s.settings.maxDisplacementRatio, 0.005);
  d["analysis"]["time_step"] = 0.002;
  d["analysis"]["preset"] = "fast";
  const model::Scene t = io::parseCase(d.dump(), "case.json");
  EXPECT_EQ(t.settings.timeStep, 0.002);
  EXPECT_EQ(t.settings.maxDisplacementRatio, 0.01);
  d["analysis"]["preset"] = "quick";
  expectError(d, "analysis.preset", "expected one of accurate, balanced, fast");
}

// Issue #6: a case that sets neither a time step nor a preset runs at `balanced`, in every command
// and so in the calibration loops: Δt = 5.5e-4 √(w0/g) (model/presets.cpp), g2 0.005, penalty
// factor 40. The origin of Δt is reported (check, summary.json, the loops' results).
TEST(CaseReader, NoTimeStepMeansTheBalancedPreset) {
  json d = minimal();
  d["analysis"].erase("time_step");
  const model::Scene s = io::parseCase(d.dump(), "case.json");
  EXPECT_NEAR(s.settings.timeStep, 5.5e-4 * std::sqrt(s.modelHalfSize() / 9.81), 1e-15);
  EXPECT_EQ(s.settings.maxDisplacementRatio, 0.005);
  EXPECT_EQ(s.settings.penaltyFactor, 40);
  EXPECT_EQ(s.settings.timeStepOrigin, "default preset balanced");
  d["analysis"]["time_step"] = 0.002;
  EXPECT_EQ(io::parseCase(d.dump(), "case.json").settings.timeStepOrigin, "analysis.time_step");
}

// The command line's model options win over the case and over a back-analysis job's own, in the
// order preset, time step (a --time-step after --preset keeps the preset's g2 and penalty).
TEST(SettingsOverride, CommandLineWinsInOrder) {
  model::SettingsOverride o;
  o.preset = "fast";
  o.timeStep = 0.004;
  o.blocks = "rigid";
  o.contactTreatment = "vertex";
  json d = minimal();
  d["analysis"]["time_step"] = 0.001;  // the case's own, and its own g2: the command line wins
  d["analysis"]["max_displacement_ratio"] = 0.002;
  const model::Scene s = io::parseCase(d.dump(), "case.json", io::caseOverridesFor(o));
  EXPECT_EQ(s.settings.timeStep, 0.004);
  EXPECT_EQ(s.settings.maxDisplacementRatio, 0.01);  // fast's g2
  EXPECT_EQ(s.settings.penaltyFactor, 10);           // fast's penalty factor
  EXPECT_TRUE(s.settings.rigidBlocks);
  EXPECT_EQ(s.settings.contactTreatment, model::ContactTreatment::Vertex);
  EXPECT_EQ(s.settings.timeStepOrigin, "--time-step");
}

// ---- Issue #15: every class of the fuzzer's table gives exit 2 (bad input, with file and JSON
// path) or exit 3 (a budget stop); none crashes, hangs or exits 0. ----

namespace {

/// The chair slide's section (cases/chair_slide.json) as JSON, for section mutations.
json chairSlide() {
  std::ifstream in(std::string(DDASLOPE_SOURCE_DIR) + "/cases/chair_slide.json");
  return json::parse(in);
}

/// The CLI's exit code and stderr on a case written to a temporary file.
int runCliOn(const json& doc, const std::string& command, const std::string& extra, std::string* err) {
  const std::string path = writeTemp("fuzzed.json", doc.dump());
  const int code = runCli(command + " " + path + " " + extra, err);
  fs::remove(path);
  return code;
}

}  // namespace

// Crash: 100 000 nested arrays overflowed the parser's stack (signal 11). Now refused at depth 64.
TEST(RobustInput, DeeplyNestedJsonIsRefusedNotACrash) {
  const std::string deep = std::string(100000, '[') + std::string(100000, ']');
  std::string text = kMinimal;
  text.replace(text.find("\"block sliding on a 30 degree plane\""), 36, deep);
  expectTextError(text, "nested more than 64");
}

// Hangs: values outside a physical range are refused at their JSON path (docs/case-format.md,
// "Limits"), before any step is taken.
TEST(RobustInput, ValuesThatHungAreRefusedWithTheirPath) {
  json d = minimal();
  d["gravity"] = {0, -2.1e9};
  expectError(d, "gravity", "at most 1000");
  d = minimal();
  d["gravity"] = {0, -1e308};
  expectError(d, "gravity", "at most 1000");
  d = minimal();
  d["analysis"]["duration"] = 1e9;
  expectError(d, "analysis.duration", "(0, 1e6]");
  d = minimal();
  d["analysis"]["duration"] = 1e5;  // within range, but 1e8 steps of 1 ms
  expectError(d, "analysis.duration", "more than the 1e7");
  d = minimal();
  d["analysis"]["time_step"] = 1e-12;
  expectError(d, "analysis.time_step", "[1e-7, 10]");
  d = minimal();
  d["analysis"]["max_displacement_ratio"] = 1e-12;
  expectError(d, "analysis.max_displacement_ratio", "[1e-5, 0.1]");
  d = minimal();
  d["blocks"][1]["angular_velocity"] = 1e6;
  expectError(d, "blocks[1].angular_velocity", "at most 1000 m/s");
  d = minimal();
  d["blocks"][1]["velocity"] = {1e308, 0};
  expectError(d, "blocks[1].velocity", "at most 1000 m/s");
  d = minimal();
  d["materials"]["rock"]["density"] = 1e-10;
  expectError(d, "materials.rock.density", "[1, 1e5]");
  d = minimal();
  d["materials"]["rock"]["young_modulus"] = 1e16;  // beyond RS2's rigid stand-in (2e14), which is accepted
  expectError(d, "materials.rock.young_modulus", "[1e3, 1e15]");
  // A 10 m × 3e-8 m sliver, and a block scaled to 1e-9 m, in a 20 m scene.
  d = minimal();
  d["blocks"][1]["vertices"] = {{2, 1}, {12, 1}, {12, 1 + 3e-8}, {2, 1 + 3e-8}};
  expectError(d, "blocks[1].vertices", "below the 1e-6");
  d = minimal();
  d["blocks"][1]["vertices"] = {{2, 1}, {2 + 1e-9, 1}, {2 + 1e-9, 1 + 1e-9}, {2, 1 + 1e-9}};
  expectError(d, "blocks[1].vertices", "below the 1e-6");
  // 100 000 vertices: refused by count, before the O(n²) simplicity check.
  d = minimal();
  json ring = json::array();
  for (int k = 0; k < 100000; ++k) {
    const double a = 2 * M_PI * k / 100000;
    ring.push_back({3 + 0.5 * std::cos(a), 1.5 + 0.5 * std::sin(a)});
  }
  d["blocks"][1]["vertices"] = ring;
  expectError(d, "blocks[1].vertices", "3 to 10000 points");
}

// A joint set spacing of 1 cm across the 850 m chair slide would cut millions of blocks.
TEST(RobustInput, SectionCutIntoTooManyBlocksIsRefusedBeforeCutting) {
  json d = chairSlide();
  d["section"]["joint_sets"][0]["spacing"] = 0.01;
  expectError(d, "section.joint_sets[0].spacing", "at most 50000");
}

// Accepted invalid: a sliding surface above the ground between crown and toe.
TEST(RobustInput, SlidingSurfaceAboveTheGroundIsRefused) {
  json d = chairSlide();
  json& surface = d["section"]["sliding_surface"];
  const json crown = surface.front(), toe = surface.back();
  surface = {crown, toe};
  // Crown and toe on the ground, which dips 400 m between them: the chord runs above it.
  d["section"]["ground"] = {{crown[0].get<double>() - 100, crown[1].get<double>()}, crown,
                            {crown[0].get<double>() + 1, crown[1].get<double>() - 400}, toe,
                            {toe[0].get<double>() + 100, toe[1].get<double>()}};
  expectError(d, "section.sliding_surface", "below the ground");
}

// Nonsense: a comma in a monitor id shifted history.csv's columns. Names are now restricted.
TEST(RobustInput, NamesThatWouldBreakTheOutputAreRefused) {
  json d = minimal();
  d["monitors"][0]["id"] = "crest,toe";
  expectError(d, "monitors[0].id", "letters, digits");
  d = minimal();
  d["blocks"][1]["id"] = "slider\n";
  expectError(d, "blocks[1].id", "letters, digits");
}

// Wrong code: a number the double cannot hold was an internal error (exit 1). Now bad input.
TEST(RobustInput, OverflowingNumberTokenIsBadInput) {
  std::string text = kMinimal;
  text.replace(text.find("2600"), 4, "1e400");
  expectTextError(text, "invalid JSON");
}

// Unhelpful: a bad CSV row now names the case file and JSON path that referred to the CSV, the
// CSV and the row; a special file (/dev/zero) is refused without reading it.
TEST(RobustInput, CsvErrorsNameTheCaseAndTheCsv) {
  const std::string csv = writeTemp("levels.csv", "time,level\n0,1\n1,abc\n");
  json d = minimal();
  d["water"] = {{"level_series", {{"csv", csv}}}};
  expectError(d, "water.level_series.csv", "row 3");
  fs::remove(csv);
  // A decimal comma ("0,2,5" for a level of 2.5 at t = 0) is one cell too many, not a level of 2.
  const std::string comma = writeTemp("levels_comma.csv", "time,level\n0,2,5\n1,3\n");
  d["water"] = {{"level_series", {{"csv", comma}}}};
  expectError(d, "water.level_series.csv", "row 2: expected 2 cells as in the header, found 3");
  // A spreadsheet's export reads: byte-order mark, quoted names and values, spaces, CRLF and a
  // trailing comma; a column named twice does not.
  const std::string excel = writeTemp("levels_excel.csv", "\xEF\xBB\xBF\"time\", \" level\",\r\n\"0\",\"1\",\r\n1, 2,\r\n");
  d["water"] = {{"level_series", {{"csv", excel}}}};
  const model::Scene read = io::parseCase(d.dump(), "case.json");
  EXPECT_EQ(read.water.seriesLevels, (std::vector<double>{1, 2}));
  const std::string twice = writeTemp("levels_twice.csv", "time,level,level\n0,1,2\n1,2,3\n");
  d["water"] = {{"level_series", {{"csv", twice}}}};
  expectError(d, "water.level_series.csv", "row 1: expected each column named once, found \"level\" twice");
  d["water"] = {{"level_series", {{"csv", "/dev/zero"}}}};
  expectError(d, "water.level_series.csv", "regular file");
}

// The command line: the same ranges, and outputs that cannot be written are bad input (exit 2).
TEST(RobustInput, CommandLineNumbersAndOutputsAreChecked) {
  const std::string path = std::string(DDASLOPE_SOURCE_DIR) + "/cases/stable_block_40deg.json";
  std::string err;
  EXPECT_EQ(runCli("run " + path + " --duration inf --out /tmp/ddaslope_never", &err), 2) << err;
  EXPECT_EQ(runCli("run " + path + " --time-step 1e-12 --out /tmp/ddaslope_never", &err), 2) << err;
  EXPECT_EQ(runCli("run " + path + " --duration 1e5 --out /tmp/ddaslope_never", &err), 2) << err;
  EXPECT_NE(err.find("analysis.duration"), std::string::npos) << err;
  EXPECT_EQ(runCli("critical " + path + " --joint joint --solve friction --cohesion inf", &err), 2) << err;
  EXPECT_EQ(runCli("fos " + path + " --width nan", &err), 2) << err;
  EXPECT_EQ(runCli("fos " + path + " --width 1e-300", &err), 2) << err;
  // fos --check: a factor, one scene (not a sweep's, not a searched crack's).
  EXPECT_EQ(runCli("fos " + path + " --check 0 --out /tmp/ddaslope_never", &err), 2) << err;
  EXPECT_EQ(runCli("fos " + path + " --check nan --out /tmp/ddaslope_never", &err), 2) << err;
  EXPECT_EQ(runCli("fos " + path + " --check 1.2 --sweep materials.rock.density=2000:2600:3 --out /tmp/ddaslope_never", &err), 2)
      << err;
  // A search's options are refused with --check, not silently ignored.
  for (const char* option : {"--width 0.01", "--threads 2", "--no-look-ahead", "--log-json /tmp/ddaslope_never.json"}) {
    EXPECT_EQ(runCli("fos " + path + " --check 1.2 " + option + " --out /tmp/ddaslope_never", &err), 2) << option;
    EXPECT_NE(err.find("--check"), std::string::npos) << err;
    EXPECT_NE(err.find("belongs to a search for F"), std::string::npos) << err;
  }
  const std::string crack = std::string(DDASLOPE_SOURCE_DIR) + "/cases/planar_failure_crack.json";
  EXPECT_EQ(runCli("fos " + crack + " --check 1.1 --out /tmp/ddaslope_never", &err), 2) << err;
  EXPECT_NE(err.find("section.tension_crack.search"), std::string::npos) << err;
  EXPECT_EQ(runCli("run " + path + " --set gravity[1]=inf --out /tmp/ddaslope_never", &err), 2) << err;
  // --out naming an existing file, or a path under one.
  const std::string file = writeTemp("not_a_dir", "x");
  EXPECT_EQ(runCli("run " + path + " --out " + file, &err), 2) << err;
  EXPECT_EQ(runCli("run " + path + " --out " + file + "/sub", &err), 2) << err;
  fs::remove(file);
  // A special file is not read; a 50 MB case is refused from its size, without parsing it.
  EXPECT_EQ(runCli("check /dev/zero", &err), 2) << err;
  EXPECT_NE(err.find("regular file"), std::string::npos) << err;
  const std::string big = writeTemp("big.json", "{\"description\": \"" + std::string(50u << 20, 'x') + "\"}");
  EXPECT_EQ(runCli("check " + big, &err), 2) << err;
  EXPECT_NE(err.find("more than the 16 MB"), std::string::npos) << err;
  fs::remove(big);
}

// Bounded work: analysis.max_steps stops a run with exit 3, a partial history (no history.csv)
// and a summary whose status says why.
TEST(RobustInput, StepBudgetStopsTheRunCleanly) {
  json d = minimal();
  d["analysis"]["max_steps"] = 50;  // the run needs 1000 steps of 1 ms
  const fs::path out = fs::temp_directory_path() / ("ddaslope_budget_" + std::to_string(::getpid()));
  std::string err;
  EXPECT_EQ(runCliOn(d, "run", "--out " + out.string(), &err), 3) << err;
  EXPECT_NE(err.find("budget exceeded"), std::string::npos) << err;
  EXPECT_TRUE(fs::exists(out / "history.partial.csv"));
  EXPECT_FALSE(fs::exists(out / "history.csv"));
  std::ifstream in(out / "summary.json");
  const json summary = json::parse(in);
  EXPECT_EQ(summary["status"], "budget_exceeded");
  EXPECT_EQ(summary["steps"], 50);
  fs::remove_all(out);
}

// A section cut by 3000 joints: a legitimate 3002-block scene, which `check` accepts (0.4 s); its
// run (minutes of equilibrium for 3000 slender slices) is bounded by analysis.wall_clock_limit,
// which covers the equilibrium too: exit 3, budget_exceeded.
TEST(RobustInput, ThousandsOfSectionJointsAreCheckedFastAndRunUnderABudget) {
  json d = chairSlide();
  d["section"].erase("joint_sets");
  json joints = json::array();
  for (int i = 0; i < 3000; ++i) {
    const double x = 0.1 + i * 850.0 / 3000;
    joints.push_back({{x, -200}, {x, 500}});
  }
  d["section"]["joints"] = joints;
  std::string err;
  EXPECT_EQ(runCliOn(d, "check", "", &err), 0) << err;
  d["analysis"]["wall_clock_limit"] = 1;
  const fs::path out = fs::temp_directory_path() / ("ddaslope_slices_" + std::to_string(::getpid()));
  EXPECT_EQ(runCliOn(d, "run", "--out " + out.string(), &err), 3) << err;
  std::ifstream in(out / "summary.json");
  EXPECT_EQ(json::parse(in)["status"], "budget_exceeded");
  fs::remove_all(out);
}

// Supports and edge loads: every mistake names the file and the JSON path (exit 2).
TEST(CaseReader, BadSupports) {
  const auto withSupport = [](const json& support) {
    json d = minimal();
    d["supports"] = json::array({support});
    return d;
  };
  const json bolt = {{"id", "b1"}, {"head", {3, 1.5}}, {"end", {3, 0.5}}, {"stiffness", 1e7}, {"capacity", 1e5}};
  EXPECT_NO_THROW(io::parseCase(withSupport(bolt).dump(), "case.json"));
  json outside = bolt;
  outside["end"] = {30, -5};
  expectError(withSupport(outside), "supports[0].end", "lies in no block");
  json negative = bolt;
  negative["capacity"] = -1;
  expectError(withSupport(negative), "supports[0].capacity", "a capacity > 0");
  json same = bolt;
  same["end"] = {3.5, 1.8};
  expectError(withSupport(same), "supports[0].end", "another block than the head");
  // Neither stiffness nor pretension: accepted, so that a sweep of an anchor's force may start at 0
  // (check says it carries nothing).
  json nothing = bolt;
  nothing.erase("stiffness");
  EXPECT_NO_THROW(io::parseCase(withSupport(nothing).dump(), "case.json"));
  json over = bolt;
  over["pretension"] = 2e5;
  expectError(withSupport(over), "supports[0].pretension", "at most the capacity");
  json zero = bolt;
  zero["head"] = {3, 1};  // on the slider's base, in the slider; the end at the same point in the base
  zero["end"] = {3, 1};
  zero["end_block"] = "base";
  expectError(withSupport(zero), "supports[0].end", "apart from the head");
  json unnamed = bolt;
  unnamed.erase("id");
  expectError(withSupport(unnamed), "supports[0].id", "required key is missing");
  json d = withSupport(bolt);
  d["point_loads"] = json::array({{{"id", "b1"}, {"point", {3, 1.5}}, {"force", {1, 0}}}});
  expectError(d, "supports[0].id", "duplicate id \"b1\"");
}

// A grouted bolt's capacity is the least of its tendon's and its bond's over the length it has in
// each block: 0.8 m in the slider (from y = 1.8 to its base at y = 1), 0.5 m in the base (y = 1 to
// 0.5); per metre of slope at a 2 m spacing.
TEST(CaseReader, GroutedBoltCapacityIsItsWeakestAnchorage) {
  json d = minimal();
  d["supports"] = json::array({{{"id", "b1"}, {"head", {3, 1.8}}, {"end", {3, 0.5}}, {"stiffness", 1e7},
                                {"capacity", 2e5}, {"bond_strength", 1e5}, {"spacing", 2}}});
  const model::Scene s = io::parseCase(d.dump(), "case.json");
  ASSERT_EQ(s.supports.size(), 1u);
  EXPECT_NEAR(s.supports[0].headEmbedment, 0.8, 1e-12);
  EXPECT_NEAR(s.supports[0].endEmbedment, 0.5, 1e-12);
  EXPECT_NEAR(s.supports[0].capacity, 1e5 * 0.5 / 2, 1e-6);
  EXPECT_NEAR(s.supports[0].stiffness, 1e7 / 2, 1e-6);
  d["supports"][0]["bond_strength"] = 1e7;  // the tendon gives way first
  EXPECT_NEAR(io::parseCase(d.dump(), "case.json").supports[0].capacity, 2e5 / 2, 1e-6);
  // Its head on the slider's base, pointing down into the base: no length in the slider, bonded
  // over nothing, a capacity of 0 (as "capacity": 0 is refused, so is this).
  d["supports"][0]["head"] = {3, 1};
  expectError(d, "supports[0].head", "0 m inside its head's block \"slider\"");
}

TEST(CaseReader, BadEdgeLoads) {
  json d = minimal();
  d["edge_loads"] = json::array({{{"from", {2, 2}}, {"to", {4, 2}}, {"pressure", 1e4}}});
  const model::Scene s = io::parseCase(d.dump(), "case.json");
  ASSERT_EQ(s.edgeLoads.size(), 1u);
  // A pressure pushes into the block: down on its top face, 2 m × 10 kPa.
  EXPECT_NEAR(s.edgeLoads[0].resultant().y(), -2e4, 1e-6);
  EXPECT_NEAR(s.edgeLoads[0].resultant().x(), 0, 1e-6);
  d["edge_loads"][0]["to"] = {4.5, 2};
  expectError(d, "edge_loads[0].to", "on the boundary of block \"slider\"");
  d["edge_loads"][0]["to"] = {4, 1.5};  // a chord across the block
  expectError(d, "edge_loads[0]", "its middle 0.25");
  d["edge_loads"][0]["to"] = {4, 2.5};  // its middle outside every block
  expectError(d, "edge_loads[0]", "point lies in no block");
  d["edge_loads"][0]["to"] = {4, 2};
  d["edge_loads"][0]["load"] = {0, -1e4};
  expectError(d, "edge_loads[0]", "exactly one of load");
}

// critical --solve support: a target factor of safety ≤ 0, or no such support: exit 2.
TEST(Cli, SupportSearchRefusesBadTargetsAndNames) {
  const std::string anchored = std::string(DDASLOPE_SOURCE_DIR) + "/cases/planar_failure_anchor.json";
  std::string err;
  EXPECT_EQ(runCli("critical " + anchored + " --solve support --support anchor --target-fos 0", &err), 2);
  EXPECT_NE(err.find("--target-fos"), std::string::npos) << err;
  EXPECT_EQ(runCli("critical " + anchored + " --solve support --support anchor --target-fos -1", &err), 2);
  EXPECT_EQ(runCli("critical " + anchored + " --solve support --support nail", &err), 2);
  EXPECT_NE(err.find("no support or load named \"nail\""), std::string::npos) << err;
  EXPECT_EQ(runCli("critical " + anchored + " --solve support", &err), 2);
  EXPECT_NE(err.find("--support"), std::string::npos) << err;
}

// unit_weight (kN/m³) as RS2 and Slide2 take it: density = 1000·γ/g; one of the two, not both.
TEST(CaseReader, UnitWeightIsADensityUnderTheCasesGravity) {
  json d = minimal();
  d["materials"]["rock"].erase("density");
  d["materials"]["rock"]["unit_weight"] = 25.506;
  EXPECT_NEAR(io::parseCase(d.dump(), "case.json").materials[0].density, 25.506e3 / 9.81, 1e-9);
  d["materials"]["rock"]["density"] = 2600;
  expectError(d, "materials.rock", "found both");
  d["materials"]["rock"].erase("density");
  d["materials"]["rock"].erase("unit_weight");
  expectError(d, "materials.rock", "unit_weight (kN/m³");
  d["materials"]["rock"]["unit_weight"] = -25;
  expectError(d, "materials.rock.unit_weight", "a unit weight in kN/m³");
}

// A Barton–Bandis joint: φr, JRC and JCS; a peak friction angle or a cohesion is refused, JRC and
// JCS out of range are named, and JRC on a Mohr–Coulomb joint is refused.
TEST(CaseReader, BadBartonBandisJoints) {
  json d = minimal();
  d["joints"]["bedding"] = {{"law", "barton_bandis"}, {"residual_friction_angle", 25}, {"jrc", 8}, {"jcs", 50e6}};
  const model::Scene s = io::parseCase(d.dump(), "case.json");
  ASSERT_TRUE(s.joints[0].bartonBandis.has_value());
  EXPECT_DOUBLE_EQ(s.joints[0].bartonBandis->jrc, 8);
  EXPECT_NEAR(s.joints[0].frictionAngle, degToRad(25), 1e-15);
  // Barton & Bandis (1982): JRC_n = JRC_0 (L_n/L_0)^(−0.02 JRC_0), JCS_n = JCS_0 (L_n/L_0)^(−0.03 JRC_0).
  d["joints"]["bedding"]["scale"] = {{"field_length", 2.0}};
  const model::Scene scaled = io::parseCase(d.dump(), "case.json");
  EXPECT_NEAR(scaled.joints[0].bartonBandis->jrc, 8 * std::pow(20.0, -0.16), 1e-12);
  EXPECT_NEAR(scaled.joints[0].bartonBandis->jcs, 50e6 * std::pow(20.0, -0.24), 1e-3);
  d["joints"]["bedding"].erase("scale");
  d["joints"]["bedding"]["jrc"] = 25;
  expectError(d, "joints.bedding.jrc", "a JRC in [0, 20]");
  d["joints"]["bedding"]["jrc"] = 8;
  d["joints"]["bedding"]["jcs"] = 0;
  expectError(d, "joints.bedding.jcs", "a JCS in [1e5, 1e9] Pa");
  d["joints"]["bedding"]["jcs"] = 50e6;
  d["joints"]["bedding"]["friction_angle"] = 30;
  expectError(d, "joints.bedding.friction_angle", "residual_friction_angle (φr), jrc and jcs");
  json mc = minimal();
  mc["joints"]["bedding"]["jrc"] = 8;
  expectError(mc, "joints.bedding.jrc", "used only by a Barton–Bandis joint");
}

// r_u: a ratio in [0, 1], alone (not with a water surface), with the ground's unit weight when the
// case has several materials.
TEST(CaseReader, BadPorePressureRatio) {
  json d = minimal();
  d["water"] = {{"ru", 0.25}};
  const model::Scene s = io::parseCase(d.dump(), "case.json");
  EXPECT_NEAR(s.water.unitWeight, 0.25 * 2600 * 9.81, 1e-9);
  EXPECT_DOUBLE_EQ(s.water.headAt(3), 2);  // the slider's top: the ground at x = 3
  d["water"]["ru"] = 1.5;
  expectError(d, "water.ru", "a pore-pressure ratio r_u in [0, 1]");
  d["water"] = {{"ru", 0.25}, {"level", 3}};
  expectError(d, "water", "exactly one of level");
  d["water"] = {{"ru", 0.25}};
  d["materials"]["clay"] = {{"density", 1900}, {"young_modulus", 1e8}, {"poisson_ratio", 0.3}};
  expectError(d, "water.ground_unit_weight", "several materials");
}

// An index in an override's path (--set blocks[1].id, a job's path) names an element or is bad
// input saying what an index is: never a conversion that throws (stoul's "internal error") or
// wraps, whatever its length or sign.
TEST(CaseReader, OverrideIndexIsAWholeNumberBelowTheArraysSize) {
  const auto expect = [](const std::string& path, const std::string& what) {
    clitest::expectInputError([&] { io::parseCase(kMinimal, "case.json", {io::CaseOverride(path, 1)}); }, "case.json",
                              path, what);
  };
  expect("blocks[x].id", "blocks[x]: expected an index (a whole number from 0), found \"x\"");
  expect("blocks[-1].id", "blocks[-1]: expected an index (a whole number from 0), found \"-1\"");
  expect("blocks[].id", "expected an index (a whole number from 0), found \"\"");
  expect("blocks[1.5].id", "found \"1.5\"");
  expect("blocks[2].id", "blocks[2]: expected an index below 2 (blocks has 2 entries), found 2");
  expect("blocks[99999999999999999999].id", "expected an index below 2 (blocks has 2 entries), found 99999999999999999999");
  expect("blocks[18446744073709551617].vertices[0][0]", "expected an index below 2");
  expect("blocks[1].vertices[0][7]", "blocks[1].vertices[0][7]: expected an index below 2 (blocks[1].vertices[0] has 2 entries)");
  expect("analysis[0]", "analysis[0]: expected an array at analysis to index, found an object");
  expect("blocks[0.id", "expected an index closed by ]");
  // Leading zeros name the same element.
  const model::Scene s = io::parseCase(kMinimal, "case.json", {io::CaseOverride("blocks[0001].vertices[1][0]", 4.5)});
  EXPECT_EQ(s.blocks[1].vertices[1].x(), 4.5);
}

// The same from the command line: exit 2, the case, the path and what an index is.
TEST(Cli, SetPathWithABadIndexExitsWithTwoAndSaysWhatAnIndexIs) {
  const std::string path = std::string(DDASLOPE_SOURCE_DIR) + "/cases/stable_block_40deg.json";
  std::string err;
  for (const auto& [set, expected] : std::vector<std::pair<std::string, std::string>>{
           {"blocks[x].id=1", "blocks[x]: expected an index (a whole number from 0), found \"x\""},
           {"blocks[-1].id=1", "blocks[-1]: expected an index (a whole number from 0), found \"-1\""},
           {"blocks[99999999999999999999].id=1", "expected an index below 2 (blocks has 2 entries), found 99999999999999999999"},
           {"blocks[7].id=1", "expected an index below 2 (blocks has 2 entries), found 7"}}) {
    EXPECT_EQ(runCli("check " + path + " --set '" + set + "'", &err), 2) << set << ": " << err;
    EXPECT_NE(err.find(path), std::string::npos) << set << ": " << err;
    EXPECT_NE(err.find(expected), std::string::npos) << set << ": " << err;
    EXPECT_EQ(err.find("internal error"), std::string::npos) << set << ": " << err;
  }
}

// --set takes a JSON literal: a number (read exactly as before: the value std::stod gives, to the
// bit), true or false, a bare word or a quoted string (any text, even one that reads as a number);
// the reader then checks its type as in the file. null is refused: a key is not unset this way.
TEST(Cli, SetTakesJsonLiterals) {
  const std::string path = std::string(DDASLOPE_SOURCE_DIR) + "/cases/stable_block_40deg.json";
  const fs::path out = fs::temp_directory_path() / ("ddaslope_setliteral_" + std::to_string(::getpid()));
  std::string err;
  ASSERT_EQ(runCli("run " + path + " --quiet --duration 0.01 --set 'description=\"two \\\"quoted\\\" words\"' "
                   "--set 'analysis.blocks=\"rigid\"' --set analysis.settle_dynamically=false "
                   "--set analysis.time_step=0.00123456789012345678 --out " + out.string(), &err), 0) << err;
  const json summary = json::parse(std::ifstream(out / "summary.json"));
  EXPECT_EQ(summary["description"], "two \"quoted\" words");
  EXPECT_EQ(summary["settings"]["blocks"], "rigid");
  EXPECT_EQ(summary["settings"]["settle_dynamically"], false);
  EXPECT_EQ(summary["settings"]["time_step"].get<double>(), std::stod("0.00123456789012345678"));
  ASSERT_EQ(runCli("run " + path + " --quiet --duration 0.01 --set 'description=\"1e3\"' --out " + out.string(), &err), 0) << err;
  EXPECT_EQ(json::parse(std::ifstream(out / "summary.json"))["description"], "1e3");
  for (const auto& [set, expected] : std::vector<std::pair<std::string, std::string>>{
           {"analysis.duration=null", "found null"},
           {"analysis.duration=\"2\"", "analysis.duration: expected a number here, as the case has it, found a string \"2\""},
           {"analysis.settle_dynamically=no", "analysis.settle_dynamically: expected true or false, found a string \"no\""},
           {"description=\"open", "expected a string closed by its \" at the end"},
           {"analysis.duration=2x", "quote a string that starts like a number"}}) {
    EXPECT_EQ(runCli("run " + path + " --quiet --set '" + set + "' --out " + out.string(), &err), 2) << set << ": " << err;
    EXPECT_NE(err.find(expected), std::string::npos) << set << ": " << err;
  }
  fs::remove_all(out);
}

// The verdict watches every free block (monitors only report), so a case without monitors is a
// whole case for every command: check, run, fos and critical answer it, never an internal error
// or an abort.
TEST(Cli, CaseWithoutMonitorsIsJudgedByItsFreeBlocks) {
  json doc = json::parse(std::ifstream(std::string(DDASLOPE_SOURCE_DIR) + "/cases/stable_block_40deg.json"));
  doc.erase("monitors");
  doc.erase("expected");
  const std::string path = writeTemp("no_monitors.json", doc.dump());
  const fs::path out = fs::temp_directory_path() / ("ddaslope_nomonitor_" + std::to_string(::getpid()));
  std::string err;
  EXPECT_NE(clitest::captureCli("check " + path, &err).find("0 monitors"), std::string::npos) << err;
  EXPECT_EQ(runCli("run " + path + " --quiet --duration 0.05 --out " + out.string(), &err), 0) << err;
  // φ = 40.1° on a 40° plane: F = tan 40.1° / tan 40° = 1.0031, stable without cohesion.
  EXPECT_NE(clitest::captureCli("fos " + path + " --quiet", &err).find("factor of safety"), std::string::npos) << err;
  EXPECT_NE(clitest::captureCli("critical " + path + " --quiet", &err).find("critical cohesion"), std::string::npos) << err;
  EXPECT_EQ(err.find("internal error"), std::string::npos) << err;
  fs::remove_all(out);
}

// A range of an option (critical --curve, fos --sweep) is two finite numbers and a whole count,
// and nothing more: sscanf took "nan" and "inf" (a curve at NaN friction angles ran for minutes),
// trailing text and counts past int. Each is bad input naming the option, at once.
TEST(RobustInput, RangesOfCurvesAndSweepsAreFiniteAndWhole) {
  const std::string path = std::string(DDASLOPE_SOURCE_DIR) + "/cases/stable_block_40deg.json";
  const std::string anchor = std::string(DDASLOPE_SOURCE_DIR) + "/cases/planar_failure_anchor.json";
  std::string err;
  for (const char* curve : {"nan:80:3", "10:inf:3", "-inf:40:3", "NAN:40:3", "1e999:40:3", "10:40:3x", "10:40:1e3",
                            "10:40:99999999999", "10:40:201", "10:40", "10:40:3:4", ":40:3", "10:40:1", "40:10:3"}) {
    EXPECT_EQ(runCli(std::string("critical ") + path + " --quiet --curve " + curve + " --out /tmp/ddaslope_never", &err), 2)
        << curve << ": " << err;
    EXPECT_NE(err.find("--curve"), std::string::npos) << curve << ": " << err;
  }
  for (const char* curve : {"nan:1e6:3", "0:inf:3", "0:1e6:3junk"}) {
    EXPECT_EQ(runCli(std::string("critical ") + anchor + " --quiet --solve support --support anchor --curve " + curve +
                         " --out /tmp/ddaslope_never", &err), 2)
        << curve << ": " << err;
    EXPECT_NE(err.find("--curve"), std::string::npos) << curve << ": " << err;
  }
  for (const char* sweep : {"analysis.duration=nan:3:3", "analysis.duration=1:inf:3", "analysis.duration=1:2:3.5",
                            "analysis.duration=1:2:3:4", "=1:2:3", "analysis.duration=1:2:1001"}) {
    EXPECT_EQ(runCli(std::string("fos ") + path + " --quiet --sweep '" + sweep + "' --out /tmp/ddaslope_never", &err), 2)
        << sweep << ": " << err;
    EXPECT_NE(err.find("--sweep"), std::string::npos) << sweep << ": " << err;
  }
}

// Values a user typed in another unit are read as the schema's and give confident nonsense (a
// density of 2.6 t/m³ as kg/m³: F = 275 on the README's slope). They are valid input, so they are
// warned about, each with the value it would be in the schema's unit; a free block touching
// nothing is a misplaced block, warned about by check.
TEST(RobustInput, ValuesInAnotherUnitAndFloatingBlocksAreWarned) {
  struct Slip {
    const char* set;
    const char* says;
  };
  const std::string path = writeTemp("units.json", kMinimal);
  for (const Slip& s : {Slip{"materials.rock.density=2.6", "density = 2.6 kg/m³"},
                        Slip{"materials.rock.young_modulus=5000", "young_modulus = 5000 Pa"},
                        Slip{"joints.bedding.friction_angle=0.5236", "0.5236 rad would be 30°"},
                        Slip{"joints.bedding.cohesion=20", "20 kPa would be 20000 Pa"}}) {
    std::string err;
    const std::string out = clitest::captureCli("check " + path + " --set " + s.set, &err);
    EXPECT_NE(out.find(s.says), std::string::npos) << s.set << ": " << out;
  }
  std::string err;
  EXPECT_EQ(clitest::captureCli("check " + path, &err).find("values to check"), std::string::npos);
  json d = minimal();
  d["blocks"][1]["vertices"] = {{2, 5}, {4, 5}, {4, 6}, {2, 6}};  // 4 m above the base
  d["monitors"][0]["point"] = {3, 5.5};
  const std::string floating = writeTemp("floating.json", d.dump());
  EXPECT_NE(clitest::captureCli("check " + floating, &err).find("block slider touches no other block"), std::string::npos);
  // A reservoir level in another datum (a level below every block) wets nothing; one at the
  // slider's mid-height is silent.
  json wet = minimal();
  wet["water"] = {{"level", -1000}};
  const std::string dry = writeTemp("dry_water.json", wet.dump());
  EXPECT_NE(clitest::captureCli("check " + dry, &err).find("the water wets no free block"), std::string::npos);
  wet["water"] = {{"level", 1.5}};
  const std::string half = writeTemp("half_water.json", wet.dump());
  EXPECT_EQ(clitest::captureCli("check " + half, &err).find("wets no free block"), std::string::npos);
  // A pressure grid drawn 10 km away: its pressures at the blocks are its plane's extrapolation.
  wet["water"] = {{"pressure_grid", {{"points", {{1e4, 0, 1e4}, {1e4 + 5, 0, 1e4}, {1e4, 5, 0}}}}}};
  const std::string far = writeTemp("far_grid.json", wet.dump());
  EXPECT_NE(clitest::captureCli("check " + far, &err).find("pressure_grid has no point within"), std::string::npos);
  wet["water"] = {{"pressure_grid", {{"points", {{0, 0, 1e4}, {5, 0, 1e4}, {0, 5, 0}}}}}};
  const std::string near = writeTemp("near_grid.json", wet.dump());
  EXPECT_EQ(clitest::captureCli("check " + near, &err).find("pressure_grid has no point"), std::string::npos);
}

// A horizontal coefficient along the slope's failure lowers F, against it raises F (Hoek & Bray's
// planar slide, which fails towards −x): fos says when k_h holds the slope back, and which way
// a pseudo-static check should load it.
TEST(RobustInput, AHorizontalCoefficientAgainstTheFailureIsWarned) {
  const std::string planar = std::string(DDASLOPE_SOURCE_DIR) + "/cases/planar_failure.json";
  const auto fos = [&](const std::string& kh, std::string* err) {
    return nlohmann::json::parse(clitest::captureCli("fos " + planar + " --json --quiet --width 0.02 --kh " + kh, err));
  };
  std::string against, along, none;
  const double up = fos("0.1", &against)["factor_of_safety"], down = fos("-0.1", &along)["factor_of_safety"],
               still = fos("0", &none)["factor_of_safety"];
  EXPECT_GT(up, still);
  EXPECT_LT(down, still);
  EXPECT_NE(against.find("holds the slope back and raises F"), std::string::npos) << against;
  EXPECT_NE(against.find("--kh -0.1"), std::string::npos) << against;
  EXPECT_EQ(along.find("holds the slope back"), std::string::npos) << along;
  EXPECT_EQ(none.find("holds the slope back"), std::string::npos) << none;
}

// A search on a joint no contact uses cannot follow its strength: the README's first slope with a
// vertical joint named but never cut (no joint line in the section) answers "stable even with
// φ = 0" for it, and says that the joint has no contact.
TEST(RobustInput, ASearchOnAJointWithoutContactsSaysSo) {
  const std::string wedge = writeTemp("wedge.json", R"({
    "materials": {"rock": {"density": 2600, "young_modulus": 5e9, "poisson_ratio": 0.25}},
    "joints": {"bedding": {"friction_angle": 30, "cohesion": 50000}, "vertical": {"friction_angle": 35, "cohesion": 0}},
    "default_joint": "vertical",
    "section": {"ground": [[-60, 40], [0, 40], [20, 0], [80, 0]], "sliding_surface": [[-30, 40], [16, 8]],
                "base_depth": 20, "material": "rock", "sliding_joint": "bedding"},
    "analysis": {"duration": 3}})");
  std::string err;
  clitest::captureCli("critical " + wedge + " --joint vertical --solve friction --quiet --out " +
                          (fs::temp_directory_path() / "ddaslope_untouched").string(), &err);
  EXPECT_NE(err.find("joint vertical has no contact at t = 0"), std::string::npos) << err;
  clitest::captureCli("critical " + wedge + " --joint bedding --solve friction --quiet --out " +
                          (fs::temp_directory_path() / "ddaslope_untouched").string(), &err);
  EXPECT_EQ(err.find("has no contact"), std::string::npos) << err;
}

// The touching gap (1.5 mm by default) takes rounding for contact, and says so where it closed a
// face drawn open: a block drawn 1 mm beside another starts bonded to it, and `check` notes that
// with the gap's size and the setting that keeps it open. And a sliver thinner than the gap (a
// 1 mm film under a slab) keeps its corners: vertices go only within a hundredth of the block's
// own thickness, not at the gap (which would leave it two points).
TEST(RobustInput, TheTouchingGapSaysWhatItClosedAndSparesSlivers) {
  json d = minimal();
  d["blocks"][0]["vertices"] = {{0, 0}, {40, 0}, {40, 1}, {0, 1}};           // w0 = 20 m: the gap is 1.5 mm
  d["blocks"][1]["vertices"] = {{2, 1.001}, {4, 1.001}, {4, 2}, {2, 2}};     // 1 mm above the base
  d["monitors"][0]["point"] = {3, 1.5};
  std::string err;
  std::string out = clitest::captureCli("check " + writeTemp("gap.json", d.dump()), &err);
  EXPECT_NE(out.find("start closed and bonded across gaps of up to 1 mm"), std::string::npos) << out;
  EXPECT_NE(out.find("initial_contact_tolerance=1e-6"), std::string::npos) << out;
  d["analysis"]["initial_contact_tolerance"] = 1e-6;
  out = clitest::captureCli("check " + writeTemp("gap_open.json", d.dump()), &err);
  EXPECT_EQ(out.find("closed and bonded across"), std::string::npos) << out;
  // A 10 m × 1 mm film on the base: each corner lies 1 mm off the diagonal of its neighbours,
  // within the gap, and stays.
  d = minimal();
  d["blocks"][0]["vertices"] = {{0, 0}, {40, 0}, {40, 1}, {0, 1}};
  d["blocks"][1]["vertices"] = {{2, 1}, {12, 1}, {12, 1.001}, {2, 1.001}};
  d["monitors"][0]["point"] = {7, 1.0005};
  const model::Scene s = io::parseCase(d.dump(), "film.json");
  EXPECT_EQ(s.blocks[1].vertices.size(), 4u);
  EXPECT_NEAR(std::abs(geometry::signedArea(s.blocks[1].vertices)), 10 * 0.001, 1e-9);
}

// Axis labels carry the unit each case value is written in (docs/case-format.md), by the path's
// end: a key that means different things in different objects by its parent too.
TEST(CaseReader, UnitsOfCaseValuesFollowTheFormat) {
  const std::vector<std::pair<std::string, std::string>> expected{
      {"joints.sliding_plane.cohesion", "Pa"},          {"joints.j.friction_angle", "°"},
      {"materials.rock.unit_weight", "kN/m³"},          {"water.unit_weight", "N/m³"},
      {"water.level", "m"},                             {"joints.j.normal_stiffness", "Pa/m"},
      {"point_loads[0].force[1]", "N/m"},               {"supports[1].pretension", "N"},
      {"supports[0].stiffness", "N/m"},                 {"section.tension_crack.x", "m"},
      {"seismic.k_h", ""},                              {"analysis.time_step", "s"}};
  for (const auto& [path, unit] : expected) EXPECT_EQ(io::unitOfCaseValue(path), unit) << path;
}

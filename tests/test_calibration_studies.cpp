// Every study in calibration/ (job.json, observations, expected.json) runs and meets the result
// it expects (issue #4).
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "ddaslope/calibration/backanalysis.hpp"
#include "ddaslope/calibration/strength_search.hpp"
#include "ddaslope/core/errors.hpp"
#include "ddaslope/io/case_reader.hpp"
#include "ddaslope/io/job_reader.hpp"
#include "test_io.hpp"

namespace fs = std::filesystem;
using namespace ddaslope;
using nlohmann::json;

namespace {
std::vector<std::string> studies() {
  std::vector<std::string> out;
  for (const auto& e : fs::directory_iterator(fs::path(DDASLOPE_SOURCE_DIR) / "calibration"))
    if (e.is_directory() && fs::exists(e.path() / "job.json") && fs::exists(e.path() / "expected.json"))
      out.push_back(e.path().string());
  std::sort(out.begin(), out.end());
  return out;
}
}  // namespace

class CalibrationStudy : public ::testing::TestWithParam<std::string> {};

TEST_P(CalibrationStudy, MeetsItsExpectedResult) {
  const fs::path dir = GetParam();
  const io::BackanalysisJob job = io::readJob((dir / "job.json").string());
  const json expected = json::parse(std::ifstream(dir / "expected.json"));
  const calibration::BackanalysisResult r = calibration::runBackanalysis(job);
  SCOPED_TRACE(r.statement);
  if (expected.contains("estimates"))
    for (const auto& [name, e] : expected.at("estimates").items()) {
      const auto it = std::find(r.names.begin(), r.names.end(), name);
      ASSERT_NE(it, r.names.end()) << name;
      const double got = r.estimate[it - r.names.begin()], want = e.at("value").get<double>();
      const double tol = e.contains("relative_tolerance") ? e.at("relative_tolerance").get<double>() * std::abs(want)
                                                          : e.at("absolute_tolerance").get<double>();
      EXPECT_NEAR(got, want, tol) << name;
    }
  if (expected.contains("constrains_only_a_line")) {
    EXPECT_EQ(r.lineOnly, expected.at("constrains_only_a_line").get<bool>());
  }
  // An observed range the simulated value at the estimate must fall in (what the data say).
  if (expected.contains("fit_within"))
    for (const auto& [label, range] : expected.at("fit_within").items()) {
      const auto it = std::find_if(r.fit.begin(), r.fit.end(), [&](const auto& f) { return f.label == label; });
      ASSERT_NE(it, r.fit.end()) << label;
      ASSERT_TRUE(it->converged) << label;
      EXPECT_GE(it->simulated, range.at(0).get<double>()) << label;
      EXPECT_LE(it->simulated, range.at(1).get<double>()) << label;
    }
  // A rough objective's estimate is a range (calibration/precision.hpp): the range the study
  // reports must reach at least this far on each side of the estimate.
  if (expected.contains("range_at_least"))
    for (const auto& [name, half] : expected.at("range_at_least").items()) {
      const auto it = std::find_if(r.precision.parameters.begin(), r.precision.parameters.end(),
                                   [&](const auto& p) { return p.name == name; });
      ASSERT_NE(it, r.precision.parameters.end()) << name << ": no precision measured";
      EXPECT_LE(it->low, it->estimate - half.get<double>()) << name;
      EXPECT_GE(it->high, it->estimate + half.get<double>()) << name;
      EXPECT_TRUE(std::isfinite(it->noiseResolution)) << name;
    }
  if (expected.contains("factor_of_safety_at_estimate")) {
    const json& e = expected.at("factor_of_safety_at_estimate");
    const auto f = calibration::factorOfSafety(calibration::sceneAt(job, r.estimate), {}, 0.002);
    ASSERT_TRUE(f.found) << f.message;
    EXPECT_NEAR(f.factor, e.at("value").get<double>(), e.at("relative_tolerance").get<double>() * e.at("value").get<double>());
  }
}

// A synthetic study's observations are ddaslope's own (make_observations.sh runs its case, which
// holds the true values): the model of today must still reproduce them, within a tenth of their
// σ. Otherwise the study recovers the truth of another model, and a drift of the forward model
// shows up only as an estimate a little off its truth.
TEST_P(CalibrationStudy, SyntheticObservationsAreThoseOfTheModel) {
  const fs::path dir = GetParam();
  if (!fs::exists(dir / "make_observations.sh")) GTEST_SKIP() << "observed in the field, not made by the model";
  const io::BackanalysisJob job = io::readJob((dir / "job.json").string());
  std::vector<calibration::ObservationFit> fit;
  calibration::misfitOf(job, io::readCase(job.casePath), nullptr, nullptr, 1, &fit);
  ASSERT_FALSE(fit.empty());
  for (const calibration::ObservationFit& f : fit) {
    ASSERT_TRUE(f.series && f.converged) << f.label;
    EXPECT_LT(f.simulated, 0.1 * f.sigma) << f.label << ": RMS of simulated − observed at the case's own values; "
                                          << "run " << (dir / "make_observations.sh").string();
  }
}

INSTANTIATE_TEST_SUITE_P(Studies, CalibrationStudy, ::testing::ValuesIn(studies()),
                         [](const auto& info) { return fs::path(info.param).filename().string(); });

// The optimisers ask for one point at a time. A point asked again is not run again, and with a
// spare thread the point DIRECT asks next (the mirror of the one it asks now) runs ahead. Neither
// may change what the optimisers see: the job's result is the same to the bit with one thread
// and with two.
TEST(BackanalysisEvaluations, RunningAheadAndRepeatsChangeNothing) {
  io::BackanalysisJob job = io::readJob((fs::path(DDASLOPE_SOURCE_DIR) / "calibration/two_block_slide/job.json").string());
  job.threads = 1;
  const calibration::BackanalysisResult one = calibration::runBackanalysis(job);
  job.threads = 2;
  const calibration::BackanalysisResult two = calibration::runBackanalysis(job);
  ASSERT_EQ(one.estimate.size(), 1u);
  EXPECT_EQ(one.estimate[0], two.estimate[0]);
  EXPECT_EQ(one.misfit, two.misfit);
  EXPECT_EQ(one.evaluations, two.evaluations);
  EXPECT_EQ(one.forwardRuns, two.forwardRuns);
  ASSERT_EQ(one.fit.size(), two.fit.size());
  for (size_t k = 0; k < one.fit.size(); ++k) EXPECT_EQ(one.fit[k].simulated, two.fit[k].simulated);
  // The local stage starts at the global stage's best point, already run: one forward run per
  // point asked (a series observation is one run), and that point not again.
  EXPECT_LE(one.forwardRuns, one.evaluations - 1);
  EXPECT_EQ(one.runsAhead, 0);
  // DIRECT's second and third points are 0.5 ∓ 1/3 of the range, the third the exact mirror of
  // the second about the first: run ahead and taken, at least that one.
  EXPECT_GE(two.runsAhead - two.runsAheadUnused, 1);
}

// A job whose observation names a monitor the case lacks is the user's mistake: it reaches the
// caller as an input error (exit 2 at the command line), with or without a run ahead, instead of
// an optimiser status and an infinite misfit.
TEST(BackanalysisEvaluations, AnErrorOfAForwardRunReachesTheCaller) {
  io::BackanalysisJob job = io::readJob((fs::path(DDASLOPE_SOURCE_DIR) / "calibration/two_block_slide/job.json").string());
  job.observations.at(0).monitor = "nowhere";
  for (int threads : {1, 2}) {
    job.threads = threads;
    EXPECT_THROW(calibration::runBackanalysis(job), InputError) << threads << " threads";
  }
}

// One joint strength fitted to F = 1 is the critical strength: the job is pointed to `critical`.
// Another observation, or a residual strength, is not.
TEST(BackanalysisEvaluations, AStrengthFittedToFEqualToOneIsPointedToCritical) {
  const fs::path dir = fs::path(DDASLOPE_SOURCE_DIR) / "calibration";
  io::BackanalysisJob job = io::readJob((dir / "vajont/job.json").string());
  EXPECT_EQ(calibration::directSearchCommand(job),
            "ddaslope critical " + job.casePath + " --joint sliding_surface --solve friction");
  job.parameters.at(0).property = "cohesion";
  EXPECT_NE(calibration::directSearchCommand(job).find("--solve cohesion"), std::string::npos);
  job.observations.at(0).target = 1.2;
  EXPECT_EQ(calibration::directSearchCommand(job), "");
  EXPECT_EQ(calibration::directSearchCommand(io::readJob((dir / "vajont_runout/job.json").string())), "");
  EXPECT_EQ(calibration::directSearchCommand(io::readJob((dir / "jiufengershan/job.json").string())), "");
}

// The precision study may start on the spare thread at the global stage's best while the local
// stage polishes it. It is kept only if the polish leaves the estimate where it was (here, a
// local stage of one evaluation: the start itself) and stopped if it moves (the study's own
// local stage): either way the study is the one a single thread makes, to the bit.
TEST(BackanalysisEvaluations, APrecisionStudyStartedEarlyIsTheSameStudy) {
  io::BackanalysisJob job = io::readJob((fs::path(DDASLOPE_SOURCE_DIR) / "calibration/two_block_slide/job.json").string());
  job.precision.enabled = true;
  job.precision.scanPoints = 5;
  job.precision.timeStepFactors = {0.9, 1.1};
  for (int localEvaluations : {1, job.optimiser.localEvaluations}) {
    job.optimiser.localEvaluations = localEvaluations;
    job.threads = 1;
    const calibration::BackanalysisResult one = calibration::runBackanalysis(job);
    job.threads = 2;
    const calibration::BackanalysisResult two = calibration::runBackanalysis(job);
    SCOPED_TRACE(localEvaluations);
    ASSERT_EQ(one.estimate, two.estimate);
    EXPECT_EQ(one.forwardRuns, two.forwardRuns);
    ASSERT_EQ(one.precision.parameters.size(), 1u);
    ASSERT_EQ(two.precision.parameters.size(), 1u);
    const auto& a = one.precision.parameters[0].scan;
    const auto& b = two.precision.parameters[0].scan;
    ASSERT_EQ(a.size(), 5u);
    ASSERT_EQ(b.size(), 5u);
    for (size_t k = 0; k < a.size(); ++k) {
      EXPECT_EQ(a[k].value, b[k].value);
      EXPECT_EQ(a[k].misfit, b[k].misfit);
      EXPECT_EQ(a[k].simulated, b[k].simulated);
    }
    ASSERT_EQ(one.precision.ensemble.size(), 3u);
    ASSERT_EQ(two.precision.ensemble.size(), 3u);
    for (size_t k = 0; k < 3; ++k) {
      EXPECT_EQ(one.precision.ensemble[k].timeStepFactor, two.precision.ensemble[k].timeStepFactor);
      EXPECT_EQ(one.precision.ensemble[k].misfit, two.precision.ensemble[k].misfit);
      EXPECT_EQ(one.precision.ensemble[k].simulated, two.precision.ensemble[k].simulated);
    }
    EXPECT_EQ(one.precision.statement, two.precision.statement);
    EXPECT_FALSE(one.precisionStartedEarly);
    // One local evaluation is the global stage's best itself: the early study is kept.
    if (localEvaluations == 1) {
      EXPECT_TRUE(two.precisionStartedEarly);
    } else {
      // The job's own local stage moves the estimate (9° is the truth, DIRECT's best is not):
      // the early study is stopped, and its finished runs are counted as unused.
      EXPECT_FALSE(two.precisionStartedEarly);
    }
  }
}

// A precision scan coarser than the range it measures: φ of the 30° sliding block from its
// displacement at 2 s (the closed form d = a t²/2 with a = g(sin 30° − cos 30° tan φ): 3.6256 m at
// φ = 20°, 0.34 m per degree) with σ = 5 cm allows about ±0.15°, and the scan's neighbours, 0.8°
// away, both lie outside it. The statement says the range is narrower than the scan resolves,
// between those neighbours, instead of "20 to 20".
TEST(BackanalysisEvaluations, ARangeNarrowerThanThePrecisionScanIsSaidToBe) {
  const fs::path job = fs::temp_directory_path() / ("ddaslope_narrow_" + std::to_string(::getpid()) + ".json");
  std::ofstream(job) << nlohmann::json{
      {"case", (fs::path(DDASLOPE_SOURCE_DIR) / "cases/sliding_block_30deg.json").string()},
      {"parameters", {{{"name", "phi"}, {"joint", "interface"}, {"property", "friction_angle"}, {"min", 5}, {"max", 29}}}},
      {"observations", {{{"type", "runout"}, {"monitor", "centre"}, {"target", 3.6256}, {"sigma", 0.05}}}},
      {"optimiser", {{"global", "GN_DIRECT_L"}, {"local", "LN_BOBYQA"}, {"global_evaluations", 20},
                     {"local_evaluations", 20}, {"xtol_rel", 1e-4}}}}.dump();
  const calibration::BackanalysisResult r = calibration::runBackanalysis(io::readJob(job.string()));
  fs::remove(job);
  EXPECT_NEAR(r.estimate[0], 20, 0.05);
  const std::string& s = r.precision.statement;
  EXPECT_NE(s.find("over less than the scan resolves"), std::string::npos) << s;
  EXPECT_EQ(s.find(" to 20 ("), std::string::npos) << s;
}

// An estimate whose range was not measured says so, and how to measure it; with the job's
// "precision" it gives the range instead (the two-block slide's φ from the toe's history).
TEST(BackanalysisEvaluations, AnEstimateWithoutItsRangeSaysSo) {
  const std::string job = (fs::path(DDASLOPE_SOURCE_DIR) / "calibration/two_block_slide/job.json").string();
  std::string err;
  const json plain = json::parse(clitest::captureCli("backanalyse " + job + " --quiet --json --out " +
                                                         (fs::temp_directory_path() / "ddaslope_point").string(), &err));
  ASSERT_TRUE(plain.contains("notes")) << plain.dump();
  EXPECT_NE(plain["notes"].dump().find("the estimate is a point"), std::string::npos) << plain["notes"].dump();
  json withPrecision = json::parse(std::ifstream(job));
  withPrecision["precision"] = true;
  withPrecision["case"] = (fs::path(DDASLOPE_SOURCE_DIR) / "calibration/two_block_slide/case.json").string();
  withPrecision["observations"][0]["csv"] = (fs::path(DDASLOPE_SOURCE_DIR) / "calibration/two_block_slide/observations.csv").string();
  const std::string path = clitest::writeTemp("job_precision.json", withPrecision.dump());
  const json ranged = json::parse(clitest::captureCli("backanalyse " + path + " --quiet --json --out " +
                                                          (fs::temp_directory_path() / "ddaslope_ranged").string(), &err));
  ASSERT_TRUE(ranged.contains("precision")) << err;
  EXPECT_EQ(ranged.value("notes", json::array()).dump().find("the estimate is a point"), std::string::npos);
}

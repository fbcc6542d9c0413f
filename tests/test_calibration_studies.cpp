// Every study in calibration/ (job.json, observations, expected.json) runs and meets the result
// it expects (issue #4).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "ddaslope/calibration/backanalysis.hpp"
#include "ddaslope/calibration/strength_search.hpp"
#include "ddaslope/io/job_reader.hpp"

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

INSTANTIATE_TEST_SUITE_P(Studies, CalibrationStudy, ::testing::ValuesIn(studies()),
                         [](const auto& info) { return fs::path(info.param).filename().string(); });

// A back-analysis predicts each search's F from its earlier evaluations (FactorHints): a plane
// through the nearest ones once there are dims + 1, the nearest one's F before. On F linear in
// the parameters (F = 0.5 + c/100 kPa + φ/50°, as limit equilibrium of a planar slide is in c and
// nearly in φ) the plane is exact to round-off.
TEST(FactorHints, PredictsAPlaneExactlyAndTheNearestBeforeThereAreEnough) {
  io::BackanalysisJob job;
  job.parameters.resize(2);
  job.parameters[0].min = 0, job.parameters[0].max = 60000;
  job.parameters[1].min = 20, job.parameters[1].max = 34;
  const auto plane = [](const std::vector<double>& x) { return 0.5 + x[0] / 1e5 + x[1] / 50; };
  calibration::FactorHints hints(job);
  EXPECT_FALSE(hints.predict(0, {30000, 27}).has_value());
  hints.record(0, {10000, 22}, plane({10000, 22}));
  hints.record(0, {50000, 31}, plane({50000, 31}));
  EXPECT_DOUBLE_EQ(*hints.predict(0, {12000, 23}), plane({10000, 22})) << "two points in two dimensions: the nearest";
  hints.record(0, {20000, 33}, plane({20000, 33}));
  hints.record(0, {45000, 21}, plane({45000, 21}));
  EXPECT_NEAR(*hints.predict(0, {30000, 27}), plane({30000, 27}), 1e-12);
  EXPECT_NEAR(*hints.predict(0, {59000, 34}), plane({59000, 34}), 1e-12);
  EXPECT_FALSE(hints.predict(1, {30000, 27}).has_value()) << "another observation has its own record";
}

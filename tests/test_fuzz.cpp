// A mutation fuzzer of our own (issue #15): mutations of the shipped cases, with a fixed seed, go
// through the case reader and, when accepted, a short run. Every one must end in one of two ways:
// refused as bad input (an InputError naming the file, with a message), or a run that completes or
// stops with a reported non-convergence, every recorded number finite. Nothing else: no crash, no
// other exception, no hang (each run is bounded by analysis.max_steps and a wall-clock budget).
// The sanitizer build (scripts/sanitize) runs this test too; test_fuzz_surfaces.cpp fuzzes the
// other input surfaces (records, drawings, jobs, the command line, a resumed samples.csv).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "ddaslope/core/errors.hpp"
#include "ddaslope/io/case_reader.hpp"
#include "test_io.hpp"
#include "ddaslope/io/run_case.hpp"
#include "fuzz_mutations.hpp"

using namespace ddaslope;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

std::vector<json> shippedCases() {
  std::vector<json> out;
  for (const auto& e : fs::directory_iterator(fs::path(DDASLOPE_SOURCE_DIR) / "cases")) {
    if (e.path().extension() != ".json") continue;
    std::ifstream in(e.path());
    out.push_back(json::parse(in));
  }
  std::sort(out.begin(), out.end(), [](const json& a, const json& b) { return a.dump() < b.dump(); });
  return out;
}

bool traceFinite(const io::Trace& t) {
  for (const auto& row : t.samples)
    for (const auto& m : row)
      if (!std::isfinite(m.ux) || !std::isfinite(m.uy) || !std::isfinite(m.vx) || !std::isfinite(m.vy)) return false;
  for (const auto& e : t.energy)
    if (!std::isfinite(e.kinetic) || !std::isfinite(e.potential) || !std::isfinite(e.elastic) ||
        !std::isfinite(e.loadWork))
      return false;
  return true;
}

}  // namespace

TEST(Fuzz, MutatedShippedCasesAreRefusedOrRunCleanly) {
  const std::vector<json> corpus = shippedCases();
  ASSERT_GE(corpus.size(), 10u);
  std::mt19937 rng(clitest::fuzzSeed(15));  // issue #15: fixed, so a failure reproduces
  const int kCases = clitest::fuzzCount(300);
  int refused = 0, completed = 0, stopped = 0;
  for (int n = 0; n < kCases; ++n) {
    json doc = corpus[static_cast<size_t>(n) % corpus.size()];
    const int changes = std::uniform_int_distribution<int>(1, 2)(rng);
    for (int k = 0; k < changes; ++k) fuzz::mutateJson(doc, rng);
    const std::string text = doc.dump();
    SCOPED_TRACE("mutation " + std::to_string(n) + ": " + text.substr(0, 400));
    model::Scene scene;
    try {
      scene = io::parseCase(text, "fuzz.json");
    } catch (const InputError& e) {
      ++refused;
      EXPECT_EQ(e.file(), "fuzz.json");
      EXPECT_FALSE(e.message().empty());
      continue;
    } catch (const std::exception& e) {
      ADD_FAILURE() << "not an InputError: " << e.what();
      continue;
    }
    // A short, bounded run: 20 steps of the case's own Δt at most, and half a second of wall time.
    scene.settings.duration = std::min(scene.settings.duration, 20 * scene.settings.timeStep);
    scene.settings.maxSteps = 200;
    scene.settings.wallClockLimit = 0.5;
    try {
      io::RunOptions opt;
      const io::RunOutcome r = io::runScene(scene, opt);
      (r.completed ? completed : stopped)++;
      if (!r.completed) {
        EXPECT_FALSE(r.failure.empty());
      }
      EXPECT_TRUE(traceFinite(r.trace));
    } catch (const InputError& e) {
      ++refused;  // found when the scene is set up (its equilibrium, say): bad input all the same
      EXPECT_FALSE(e.message().empty());
    } catch (const std::exception& e) {
      ADD_FAILURE() << "run ended with " << e.what();
    }
  }
  // The mutations exercise both sides: most are refused, some still run.
  EXPECT_GT(refused, kCases / 4);
  EXPECT_GT(completed + stopped, 10);
  std::printf("fuzz: %d refused, %d completed, %d stopped with a reported non-convergence\n", refused, completed,
              stopped);
}

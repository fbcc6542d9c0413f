// Every shipped case runs and meets the expected values it carries; runs are deterministic.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "ddaslope/io/case_reader.hpp"
#include "ddaslope/io/run_case.hpp"

namespace fs = std::filesystem;
using namespace ddaslope;

namespace {
std::vector<std::string> shippedCases() {
  std::vector<std::string> out;
  for (const auto& e : fs::directory_iterator(fs::path(DDASLOPE_SOURCE_DIR) / "cases"))
    if (e.path().extension() == ".json") out.push_back(e.path().string());
  std::sort(out.begin(), out.end());
  return out;
}
std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}
}  // namespace

class ShippedCase : public ::testing::TestWithParam<std::string> {};

TEST_P(ShippedCase, MeetsItsExpectedValues) {
  const model::Scene scene = io::readCase(GetParam());
  ASSERT_FALSE(scene.expectations.empty()) << "a shipped case must carry expected values";
  const io::RunOutcome o = io::runScene(scene, {});
  ASSERT_TRUE(o.completed) << o.failure;
  for (const auto& r : o.expectations) EXPECT_TRUE(r.passed) << r.describe();
}

INSTANTIATE_TEST_SUITE_P(Cases, ShippedCase, ::testing::ValuesIn(shippedCases()),
                         [](const auto& info) { return fs::path(info.param).stem().string(); });

// The same case run twice gives byte-identical history.csv (issue #2: bisection and NLopt need
// a well-defined function).
TEST(Determinism, HistoryIsByteIdentical) {
  const std::string path = std::string(DDASLOPE_SOURCE_DIR) + "/cases/sliding_block_40deg.json";
  const fs::path dir = fs::temp_directory_path() / ("ddaslope_det_" + std::to_string(::getpid()));
  std::string first;
  for (int k = 0; k < 2; ++k) {
    io::RunOptions opt;
    opt.outputDir = (dir / std::to_string(k)).string();
    ASSERT_TRUE(io::runScene(io::readCase(path), opt).completed);
    const std::string h = slurp(dir / std::to_string(k) / "history.csv");
    ASSERT_GT(h.size(), 1000u);
    if (k == 0) first = h; else EXPECT_EQ(first, h);
  }
  fs::remove_all(dir);
}

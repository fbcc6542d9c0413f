// Progress of long commands (io/progress.hpp, issue #19): the JSON-lines log scripts read, and the
// terminal line that must stay off a pipe.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <thread>
#include <nlohmann/json.hpp>
#include <sstream>

#include "ddaslope/io/progress.hpp"
#include "test_io.hpp"

using namespace ddaslope;
using nlohmann::json;

namespace {
std::vector<json> readLines(const std::string& path) {
  std::ifstream in(path);
  std::vector<json> out;
  for (std::string line; std::getline(in, line);) out.push_back(json::parse(line));  // throws if not JSON
  return out;
}
}  // namespace

TEST(Progress, RemainingTimeIsTheElapsedPaceTimesWhatIsLeft) {
  // 3 of 12 trials in 6 s: 2 s a trial, 9 left: 18 s.
  EXPECT_DOUBLE_EQ(io::remainingTime(6, 3, 12), 18);
  EXPECT_DOUBLE_EQ(io::remainingTime(6, 12, 12), 0);
  EXPECT_LT(io::remainingTime(6, 0, 12), 0);   // no pace yet
  EXPECT_LT(io::remainingTime(6, 3, 0), 0);    // no plan yet
  EXPECT_EQ(io::formatDuration(1.25), "1.2 s");
  EXPECT_EQ(io::formatDuration(125), "2 min 05 s");
  EXPECT_EQ(io::formatDuration(3780), "1 h 03 min");
}

TEST(Progress, TheJsonLogHasAStartEveryEventAndAnEnd) {
  const std::string path = clitest::writeTemp("progress.jsonl", "");
  {
    io::ProgressLog log("fos", false, path);
    log.report({"narrow", 3, 12, "F stable at 1.1, fails at \"1.2\"", {{"stable_end", 1.1}, {"failing_end", 1.2}}});
    log.report({"bracket", 1, 0, "", {{"best_misfit", INFINITY}}});
    log.finish(true, "F 1.15");
  }
  const std::vector<json> lines = readLines(path);
  ASSERT_EQ(lines.size(), 4u);
  EXPECT_EQ(lines[0]["event"], "start");
  EXPECT_EQ(lines[1]["stage"], "narrow");
  EXPECT_EQ(lines[1]["done"], 3);
  EXPECT_EQ(lines[1]["planned"], 12);
  EXPECT_EQ(lines[1]["stable_end"], 1.1);
  EXPECT_EQ(lines[1]["detail"], "F stable at 1.1, fails at \"1.2\"");  // quotes escaped
  EXPECT_TRUE(lines[2]["planned"].is_null());      // not known yet: null, never a made-up number
  EXPECT_TRUE(lines[2]["best_misfit"].is_null());  // JSON has no infinity
  EXPECT_EQ(lines[3]["event"], "end");
  EXPECT_EQ(lines[3]["ok"], true);
  std::filesystem::remove(path);
}

TEST(Progress, FosLogsEveryForwardRunAndEndsOnItsResult) {
  // The planar failure's strength reduction (F = 1.1133 by Hoek & Bray): one event per forward
  // run, the last one's bracket the result's, and no progress line on a stderr that is a file.
  const std::string log = clitest::writeTemp("fos.jsonl", "");
  std::string err;
  const std::string pictures = log + ".pictures";  // not the working directory's out/fos, which other tests write too
  const std::string out = clitest::captureCli(
      "fos " + std::string(DDASLOPE_SOURCE_DIR) + "/cases/planar_failure.json --json --log-json " + log + " --out " +
          pictures,
      &err);
  std::filesystem::remove_all(pictures);
  const json result = json::parse(out);
  const std::vector<json> lines = readLines(log);
  int progress = 0;
  for (const json& l : lines) progress += l["event"] == "progress";
  EXPECT_EQ(progress, result["forward_runs"].get<int>());
  const json& last = lines[lines.size() - 2];
  EXPECT_EQ(last["stage"], "narrow");
  EXPECT_EQ(last["done"], result["forward_runs"]);
  EXPECT_EQ(last["planned"], last["done"]);  // the plan met: nothing left
  EXPECT_EQ(last["stable_end"], result["bracket"][0]);
  EXPECT_EQ(last["failing_end"], result["bracket"][1]);
  EXPECT_EQ(lines.back()["event"], "end");
  EXPECT_EQ(err.find('\r'), std::string::npos) << "a progress line went to a file: " << err;
  std::filesystem::remove(log);
}

TEST(Progress, AnUnwritableLogIsBadInput) {
  std::string err;
  const int code = clitest::runCli(
      "fos " + std::string(DDASLOPE_SOURCE_DIR) + "/cases/planar_failure.json --log-json /dev/null/p.jsonl", &err);
  EXPECT_EQ(code, 2);
  EXPECT_NE(err.find("--log-json"), std::string::npos) << err;
}

// Off a terminal a long search is not silent until its end: it writes a plain line once an
// interval (a minute in the CLI; 0.1 s here) from a clock of its own, with the latest trial, or
// saying that none has finished; never before the first interval has passed.
TEST(Progress, OffATerminalLongWorkWritesALineAnInterval) {
  ::testing::internal::CaptureStderr();
  const auto start = std::chrono::steady_clock::now();
  {
    // Three intervals before the trial and three after: the lines are due at 0.1 s and at
    // 0.4-0.5 s, and a busy machine may delay each by up to 0.2 s without failing the test.
    io::ProgressLog log("fos", false, "", true, 0.1);
    std::this_thread::sleep_for(std::chrono::milliseconds(300));  // lines: no trial yet
    log.report({"narrow", 2, 12, "F stable at 1.1", {}});
    std::this_thread::sleep_for(std::chrono::milliseconds(300));  // lines: the trial
    log.finish(true, "done");
  }
  const double took = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const std::string text = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(text.rfind("  fos working, no trial finished yet, ", 0), 0u) << text;
  EXPECT_NE(text.find("\n  fos narrow: 2 of ~12, F stable at 1.1, "), std::string::npos) << text;
  const auto lines = std::count(text.begin(), text.end(), '\n');
  EXPECT_GE(lines, 2) << text;
  EXPECT_LE(lines, std::floor(took / 0.1)) << text;  // one line per interval at most, the first after one
}

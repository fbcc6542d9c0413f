// `ddaslope report DIR` (issue #43): one self-contained HTML file per analysis folder, opened in a
// real browser (Debian's Chromium, headless): every picture decodes and no script error occurs.
#include <gtest/gtest.h>

#include <chrono>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "test_io.hpp"

namespace fs = std::filesystem;

namespace {

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

/// The DOM Chromium holds once the page has loaded (--dump-dom), or "" without Chromium.
std::string loadedPage(const fs::path& html) {
  const fs::path out = html.parent_path() / "dom.txt";
  const std::string cmd = "chromium --headless --no-sandbox --disable-gpu --dump-dom 'file://" + html.string() + "' >" +
                          out.string() + " 2>/dev/null";
  if (std::system(cmd.c_str()) != 0) return "";
  return slurp(out);
}

}  // namespace

// A run, a fos, a critical, a back-analysis and a probability folder, a sweep's and a curve's, each give report.html: the
// answer as the analysis wrote it, its pictures embedded (no file beside the HTML is needed), and,
// loaded in headless Chromium, every picture decoded (the page's own check sets
// data-pictures="loaded") with no script error. Chromium is installed by scripts/install-deps.
TEST(Report, EveryAnalysisFolderOpensInABrowserWithItsPictures) {
  ASSERT_EQ(std::system("command -v chromium >/dev/null 2>&1"), 0)
      << "Chromium is needed for this test: scripts/install-deps installs it (Debian package chromium)";
  const std::string src = DDASLOPE_SOURCE_DIR;
  const fs::path root = fs::temp_directory_path() / ("ddaslope_report_" + std::to_string(::getpid()));
  fs::remove_all(root);
  std::string err;
  const struct {
    std::string name, command, answer;
    size_t pictures;
  } analyses[] = {
      {"run", "run " + src + "/cases/toppling_slope.json --snapshots 0,1 --quiet", "completed", 4},
      {"fos", "fos " + src + "/cases/planar_failure.json --quiet", "F = 1.1142", 2},
      {"critical", "critical " + src + "/cases/planar_failure.json --quiet", "critical cohesion of joint sliding_plane at φ = 30°", 2},
      {"backanalyse", "backanalyse " + src + "/calibration/two_block_slide/job.json --quiet", "friction_angle = ", 0},
      {"probability", "probability " + src + "/calibration/planar_failure/probability_small.json --quiet", "Pf = ", 3},
      // Hoek & Bray's dry planar failure with its crack searched: F 1.1110 with the crack 6.61 m
      // behind the crest, x = -18.16 (the case's description); the search's parabola puts it at -18.14.
      {"crack", "fos " + src + "/cases/planar_failure_crack.json --quiet", "least safe tension crack at x = -18.14 m", 2},
      {"seismic", "critical " + src + "/cases/planar_failure.json --solve seismic-coefficient --quiet",
       "yield seismic coefficient k_y along -x = ", 0},
      {"support", "critical " + src + "/cases/planar_failure_anchor.json --solve support --support anchor --target-fos 1.5 --quiet",
       "anchor force of anchor at F = 1.5 = ", 0},
      {"sweep", "fos " + src + "/cases/planar_failure.json --sweep joints.sliding_plane.cohesion=0:50000:3 --quiet",
       "3 points of joints.sliding_plane.cohesion from 0 to 50000: factor_of_safety from", 1},
      {"curve", "critical " + src + "/cases/planar_failure.json --joint sliding_plane --curve 20:40:3 --quiet",
       "3 points of friction_angle_deg from 20 to 40: critical_cohesion_pa from", 1},
  };
  for (const auto& a : analyses) {
    const fs::path dir = root / a.name;
    clitest::captureCli(a.command + " --out " + dir.string(), &err);
    const std::string printed = clitest::captureCli("report " + dir.string(), &err);
    EXPECT_NE(printed.find(a.answer), std::string::npos) << a.name << ": " << printed;
    const std::string embedded = std::to_string(a.pictures) + (a.pictures == 1 ? " picture embedded" : " pictures embedded");
    EXPECT_NE(printed.find(embedded), std::string::npos) << a.name << ": " << printed;
    const fs::path html = dir / "report.html";
    const std::string text = slurp(html);
    EXPECT_NE(text.find("<p class=\"answer\">"), std::string::npos) << a.name;
    EXPECT_EQ(text.find("src=\"" + dir.string()), std::string::npos) << a.name << ": a picture not embedded";
    const std::string dom = loadedPage(html);
    EXPECT_NE(dom.find("data-pictures=\"loaded\""), std::string::npos) << a.name << ": " << dom.substr(0, 400);
    EXPECT_NE(dom.find("data-script-errors=\"0\""), std::string::npos) << a.name;
  }
  EXPECT_EQ(clitest::runCli("report " + root.string(), &err), 2);
  EXPECT_NE(err.find("expected a folder written by run, fos, critical, backanalyse or probability"), std::string::npos)
      << err;
  EXPECT_EQ(clitest::runCli("report " + (root / "nothing").string(), &err), 2);

  // A folder two commands wrote into: the newer analysis is reported, with its own picture, and
  // the older result named as left out.
  const fs::path both = root / "both";
  clitest::captureCli("fos " + src + "/cases/planar_failure.json --quiet --out " + both.string(), &err);
  fs::last_write_time(both / "fos.json", fs::last_write_time(both / "fos.json") - std::chrono::hours(1));
  clitest::captureCli("fos " + src + "/cases/planar_failure.json --sweep joints.sliding_plane.cohesion=0:50000:3 --quiet --out " +
                          both.string(), &err);
  std::string printed = clitest::captureCli("report " + both.string(), &err);
  EXPECT_NE(printed.find("Factor of safety over a sweep"), std::string::npos) << printed;
  EXPECT_NE(printed.find("the folder also holds fos.json (older, not in this report"), std::string::npos) << printed;
  EXPECT_NE(printed.find("(1 picture embedded)"), std::string::npos) << printed;
  // A cut-off CSV (its header alone) and one whose swept values are not numbers are refused.
  std::string header = slurp(both / "fos_sweep.csv");
  header.resize(header.find('\n') + 1);
  fs::create_directories(root / "cut");
  std::ofstream(root / "cut" / "fos_sweep.csv") << header;
  EXPECT_EQ(clitest::runCli("report " + (root / "cut").string(), &err), 2);
  EXPECT_NE(err.find("fos_sweep.csv: expected a row per point (at least 2), found 0"), std::string::npos) << err;
  fs::create_directories(root / "words");
  std::ofstream(root / "words" / "support_curve.csv") << "x,y\nfoo,bar\nbaz,1\n";
  EXPECT_EQ(clitest::runCli("report " + (root / "words").string(), &err), 2);
  EXPECT_NE(err.find("support_curve.csv: line 2, x: expected the value swept (a number), found \"foo\""), std::string::npos)
      << err;
  fs::remove_all(root);
}

// The warnings a search gave (fos.json's "warnings", also said on stderr) head the report, and a
// damaged result file is refused with its name, not rendered as if complete.
TEST(Report, WarningsAreShownAndADamagedResultIsRefused) {
  const fs::path dir = fs::temp_directory_path() / ("ddaslope_report_w_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "fos.json") << R"({"case": "c.json", "found": true, "factor_of_safety": 1.25,
      "bracket": [1.24, 1.26], "forward_runs": 9, "warnings": ["3 of 9 trials were called failed after moving <1 %"]})";
  std::string err;
  clitest::captureCli("report " + dir.string(), &err);
  const std::string html = slurp(dir / "report.html");
  EXPECT_NE(html.find("<h2>Warnings</h2>"), std::string::npos);
  EXPECT_NE(html.find("moving &lt;1 %"), std::string::npos) << "escaped, not markup";
  EXPECT_NE(html.find("F = 1.2500: stable at 1.2400, failing at 1.2600"), std::string::npos);
  std::ofstream(dir / "fos.json") << R"({"case": "c.json", "found": tr)";
  EXPECT_EQ(clitest::runCli("report " + dir.string(), &err), 2);
  EXPECT_NE(err.find("fos.json"), std::string::npos) << err;
  fs::remove_all(dir);
}

// A required F checked (`fos --check`) is reported as a check, with the picture of its own trial
// only: a picture an earlier search left in the folder is not taken for the check's.
TEST(Report, ACheckOfARequiredFactorIsReportedAsOne) {
  const fs::path dir = fs::temp_directory_path() / ("ddaslope_report_check_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  const std::string c = std::string(DDASLOPE_SOURCE_DIR) + "/cases/planar_failure.json";
  std::string err;
  clitest::captureCli("fos " + c + " --quiet --out " + dir.string(), &err);
  ASSERT_TRUE(fs::exists(dir / "mechanism_stable.png"));
  // Hoek & Bray's F is 1.1133: 1.3 is not met.
  clitest::captureCli("fos " + c + " --check 1.3 --quiet --out " + dir.string(), &err);
  const std::string printed = clitest::captureCli("report " + dir.string(), &err);
  EXPECT_NE(printed.find("Required factor of safety checked (fos --check)"), std::string::npos) << printed;
  EXPECT_NE(printed.find("required F = 1.3: not met"), std::string::npos) << printed;
  EXPECT_NE(printed.find("(1 picture embedded)"), std::string::npos) << printed;
  EXPECT_FALSE(fs::exists(dir / "mechanism_stable.png"));
  fs::remove_all(dir);
}

// Two analyses written into one folder: the report is of the newer one, whose pictures the folder
// holds, and it names the older result as older. Written fos then critical, and critical then
// fos, on Hoek & Bray's planar slide.
TEST(Report, TheNewestOfTwoAnalysesInAFolderIsReported) {
  const fs::path dir = fs::temp_directory_path() / ("ddaslope_report_two_" + std::to_string(::getpid()));
  const std::string c = std::string(DDASLOPE_SOURCE_DIR) + "/cases/planar_failure.json";
  const std::string fos = "fos " + c + " --quiet --width 0.02 --out " + dir.string();
  const std::string critical =
      "critical " + c + " --joint sliding_plane --solve cohesion --quiet --out " + dir.string();
  for (const bool fosFirst : {true, false}) {
    fs::remove_all(dir);
    std::string err;
    clitest::captureCli(fosFirst ? fos : critical, &err);
    clitest::captureCli(fosFirst ? critical : fos, &err);
    const std::string printed = clitest::captureCli("report " + dir.string(), &err);
    const std::string newer = fosFirst ? "Critical strength (critical)" : "Factor of safety (fos)";
    const std::string older = fosFirst ? "fos.json" : "critical.json";
    EXPECT_NE(printed.find(newer), std::string::npos) << printed;
    EXPECT_NE(printed.find("the folder also holds " + older + " (older"), std::string::npos) << printed;
  }
  // A run after a search: its two plots, not the search's mechanism pictures still in the folder.
  fs::remove_all(dir);
  std::string err;
  clitest::captureCli(fos, &err);
  clitest::captureCli("run " + c + " --quiet --out " + dir.string(), &err);
  ASSERT_TRUE(fs::exists(dir / "mechanism_failed.png"));
  const std::string printed = clitest::captureCli("report " + dir.string(), &err);
  EXPECT_NE(printed.find("Forward run (run)"), std::string::npos) << printed;
  EXPECT_NE(printed.find("(2 pictures embedded)"), std::string::npos) << printed;
  fs::remove_all(dir);
}

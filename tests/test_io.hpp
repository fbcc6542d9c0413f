#pragma once
// Test helpers for what a user hands to ddaslope: running the executable (its exit code, what it
// printed), temporary files, and the InputError a reader must throw.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <functional>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <system_error>
#include <vector>

#include "ddaslope/core/errors.hpp"

namespace clitest {

/// A fuzzer's seed: fixed in the suite, so that a failure reproduces; DDASLOPE_FUZZ_SEED gives a
/// campaign another one (docs/validation.md).
inline unsigned fuzzSeed(unsigned fixed) {
  const char* v = std::getenv("DDASLOPE_FUZZ_SEED");
  return v && *v ? static_cast<unsigned>(std::strtoul(v, nullptr, 10)) : fixed;
}
/// A fuzzer's number of inputs, times DDASLOPE_FUZZ_SCALE (a whole number, 1 if unset) for a
/// longer campaign.
inline int fuzzCount(int fixed) {
  const char* v = std::getenv("DDASLOPE_FUZZ_SCALE");
  const long scale = v && *v ? std::strtol(v, nullptr, 10) : 1;
  return fixed * static_cast<int>(scale >= 1 ? scale : 1);
}

/// Runs the CLI with `args` and returns its exit code (stderr into *stderrText).
inline int runCli(const std::string& args, std::string* stderrText) {
  const std::filesystem::path err = std::filesystem::temp_directory_path() / ("ddaslope_err_" + std::to_string(::getpid()));
  const std::string cmd = std::string(DDASLOPE_CLI) + " " + args + " >/dev/null 2>" + err.string();
  const int status = std::system(cmd.c_str());
  std::ifstream in(err);
  stderrText->assign(std::istreambuf_iterator<char>(in), {});
  std::filesystem::remove(err);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

/// Runs the CLI with `args` and returns its exit code, what it printed on stdout into *stdoutText
/// and on stderr into *stderrText: for a command whose exit code is not 0 (a search with no
/// answer) but whose output is checked. `launcher` runs it (e.g. "timeout 2": stopped after 2 s).
inline int runCliCapturing(const std::string& args, std::string* stdoutText, std::string* stderrText,
                           const std::string& launcher = "") {
  const std::filesystem::path tmp = std::filesystem::temp_directory_path();
  const std::filesystem::path out = tmp / ("ddaslope_out_" + std::to_string(::getpid()));
  const std::filesystem::path err = tmp / ("ddaslope_err_" + std::to_string(::getpid()));
  const std::string cmd =
      (launcher.empty() ? "" : launcher + " ") + DDASLOPE_CLI + " " + args + " >" + out.string() + " 2>" + err.string();
  const int status = std::system(cmd.c_str());
  std::ifstream e(err), o(out);
  stderrText->assign(std::istreambuf_iterator<char>(e), {});
  stdoutText->assign(std::istreambuf_iterator<char>(o), {});
  std::filesystem::remove(out);
  std::filesystem::remove(err);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

/// Runs the CLI, expects exit 0, and returns what it printed on stdout (stderr into *stderrText).
inline std::string captureCli(const std::string& args, std::string* stderrText) {
  std::string text;
  EXPECT_EQ(runCliCapturing(args, &text, stderrText), 0) << args << ": " << *stderrText;
  return text;
}

/// The files writeTemp wrote, removed when the test program ends (each test runs as a process
/// of its own under ctest): a test that fails half way leaves nothing behind either.
struct TempFiles {
  std::vector<std::filesystem::path> paths;
  ~TempFiles() {
    for (const auto& p : paths) {
      std::error_code ignored;
      std::filesystem::remove(p, ignored);
    }
  }
};
inline TempFiles& tempFiles() {
  static TempFiles files;
  return files;
}

/// Writes `text` to a file named after `name` and the process in the temporary folder.
inline std::string writeTemp(const std::string& name, const std::string& text) {
  const std::filesystem::path p = std::filesystem::temp_directory_path() / (std::to_string(::getpid()) + "_" + name);
  std::ofstream(p) << text;
  tempFiles().paths.push_back(p);
  return p.string();
}

/// Expects `read` to throw an InputError naming `file` and `path`, with `what` in its message.
inline void expectInputError(const std::function<void()>& read, const std::string& file, const std::string& path,
                             const std::string& what) {
  try {
    read();
    ADD_FAILURE() << "accepted bad input; expected an error at " << path;
  } catch (const ddaslope::InputError& e) {
    EXPECT_EQ(e.file(), file);
    EXPECT_EQ(e.jsonPath(), path) << e.what();
    EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
  }
}

}  // namespace clitest

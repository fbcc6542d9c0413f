#pragma once
// Three kinds of failure (STYLE.md): bad input, a broken invariant, and non-convergence.
#include <stdexcept>
#include <string>

namespace ddaslope {

/// Bad input: carries the file, the JSON path and what was expected / found.
class InputError : public std::runtime_error {
 public:
  InputError(std::string file, std::string jsonPath, const std::string& message);
  const std::string& file() const { return file_; }
  const std::string& jsonPath() const { return jsonPath_; }
  const std::string& message() const { return message_; }

 private:
  std::string file_;
  std::string jsonPath_;
  std::string message_;
};

/// A broken internal invariant: a bug in ddaslope, reported with source file and line.
class InternalError : public std::logic_error {
 public:
  InternalError(const char* sourceFile, int line, const std::string& message);
};

/// The analysis could not continue (open-close iteration or step control gave up).
class NonConvergenceError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A run stopped by its budget (analysis.max_steps or analysis.wall_clock_limit): reported like a
/// non-convergence (exit 3), with its own status.
class BudgetExceededError : public NonConvergenceError {
 public:
  using NonConvergenceError::NonConvergenceError;
};

}  // namespace ddaslope

#define DDASLOPE_ASSERT(cond, msg)                                      \
  do {                                                                  \
    if (!(cond)) throw ::ddaslope::InternalError(__FILE__, __LINE__, msg); \
  } while (false)

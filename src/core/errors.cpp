#include "ddaslope/core/errors.hpp"

namespace ddaslope {

InputError::InputError(std::string file, std::string jsonPath, const std::string& message)
    : std::runtime_error(file + ": " + (jsonPath.empty() ? std::string() : jsonPath + ": ") + message),
      file_(std::move(file)),
      jsonPath_(std::move(jsonPath)),
      message_(message) {}

InternalError::InternalError(const char* sourceFile, int line, const std::string& message)
    : std::logic_error(std::string("internal error at ") + sourceFile + ":" + std::to_string(line) +
                       ": " + message) {}

}  // namespace ddaslope

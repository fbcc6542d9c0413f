#pragma once
// JSON parsing with input_file.hpp's limits, for the readers in io/ (private: the public headers
// do not expose nlohmann::json).
#include <string>

#include <nlohmann/json.hpp>

#include "ddaslope/io/input_file.hpp"

namespace ddaslope::io {

/// Parses JSON text with the depth limit; syntax errors, overflowing numbers (1e400) and too deep
/// nesting are InputErrors naming `file`.
nlohmann::json parseJsonText(const std::string& text, const std::string& file);

/// readInputFile + parseJsonText.
nlohmann::json readJsonFile(const std::string& path);

}  // namespace ddaslope::io

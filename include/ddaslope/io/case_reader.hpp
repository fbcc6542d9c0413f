#pragma once
// Reads a case file (JSON, docs/case-format.md) into a Scene. Only this layer sees JSON.
#include <string>

#include "ddaslope/model/scene.hpp"

namespace ddaslope::io {

/// Throws InputError (file, JSON path, expected vs found) on any bad input.
model::Scene readCase(const std::string& path);
/// Same, from text already loaded (`file` names it in errors).
model::Scene parseCase(const std::string& text, const std::string& file);

}  // namespace ddaslope::io

#pragma once
// The `section` of a case: blocks cut from a slope section (docs/case-format.md, "Section").
#include <map>
#include <string>

#include "ddaslope/model/scene.hpp"
#include "json_reader.hpp"

namespace ddaslope::io {

/// Cuts the case's section (if any) into blocks appended to s.blocks, with the sliding joint on
/// every pair of base and slide block.
void readSection(const case_json::Reader& r, const case_json::json& doc, model::Scene& s,
                 const std::map<std::string, int>& materialIds, const std::map<std::string, int>& jointIds);

}  // namespace ddaslope::io

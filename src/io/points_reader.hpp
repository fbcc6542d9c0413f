#pragma once
// The parts of a case that sit on blocks: monitors, point and edge loads, fixed points and
// supports (bolts, anchors). Each point is checked to lie in its block; a block not named is the
// one that contains the point (a free one before a fixed one).
#include "ddaslope/model/scene.hpp"
#include "json_reader.hpp"

namespace ddaslope::io {

void readPointsAndLoads(const case_json::Reader& r, const case_json::json& doc, model::Scene& s);

}  // namespace ddaslope::io

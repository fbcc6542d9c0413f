#pragma once
// A slope section drawn in CAD: a DXF drawing whose named layers hold the ground,
// the sliding surface, the joints and the water line (docs/case-format.md, "Section from a
// drawing"). io/dxf_section.cpp is the only file that includes dxflib.
#include <string>
#include <utility>
#include <vector>

#include "ddaslope/core/types.hpp"

namespace ddaslope::io {

/// What a case says about its drawing (`section.dxf`).
struct DxfSectionSource {
  std::string file;           ///< the DXF, resolved against the case's folder
  std::string units;          ///< "m", "mm", "ft", …; empty: the drawing's own ($INSUNITS)
  double scale = 1;           ///< metres = drawn coordinate × unit × scale (a 1:1000 sheet: 1000)
  std::string groundLayer;          ///< required
  std::string slidingSurfaceLayer;  ///< required
  std::string jointsLayer;          ///< empty: the joints are not drawn
  std::string waterLineLayer;       ///< empty: the water is not drawn
};

/// The drawn lines in metres, and where each came from for messages about them.
struct DxfSection {
  std::vector<Vec2> ground;          ///< x non-decreasing (a line drawn right to left is turned)
  std::vector<Vec2> slidingSurface;  ///< crown to toe, x increasing
  std::vector<Vec2> waterLine;       ///< x increasing; empty unless its layer is given
  std::vector<std::pair<Vec2, Vec2>> joints;
  /// For each point of ground and sliding surface and for each joint: the file, the layer, the
  /// entity and the drawn point (`f.dxf: layer "GROUND", LWPOLYLINE #1 (handle 2F), point 3 at
  /// (685, 228.7) m`).
  std::vector<std::string> groundFrom, slidingSurfaceFrom, jointFrom;
  std::string summary;  ///< one line: units, scale and what each layer gave (`check`, `cut`)
};

/// Reads the section's lines from the drawing. Bad input throws InputError naming `caseFile`
/// and a JSON path under `jsonPath` (…file, …units, …layers.ground, …), with the DXF, the layer
/// and the entity (type, index on its layer, handle) in the message.
DxfSection readDxfSection(const DxfSectionSource& source, const std::string& caseFile, const std::string& jsonPath);

}  // namespace ddaslope::io

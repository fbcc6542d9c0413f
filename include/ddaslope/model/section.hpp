#pragma once
// Blocks from a slope section: the slide mass between the ground and the sliding surface, cut
// by internal joints, and a fixed base below.
#include <string>
#include <vector>

#include "ddaslope/core/types.hpp"
#include "ddaslope/model/block.hpp"

namespace ddaslope::model {

struct JointSet {
  double angleDeg = 90;   ///< inclination of the lines, counter-clockwise from +x (degrees)
  double spacing = 1;     ///< perpendicular spacing (m)
  Vec2 origin{0, 0};      ///< a point on one line of the set
};

struct SectionSpec {
  std::vector<Vec2> ground;          ///< ground surface, x non-decreasing, across the model
  std::vector<Vec2> slidingSurface;  ///< from crown to toe, x increasing, ends on the ground
  double baseDepth = 0;              ///< base bottom this far below the lowest point (m)
  std::vector<std::pair<Vec2, Vec2>> joints;  ///< each extended to a line through the mass
  std::vector<JointSet> jointSets;
  /// Width (m) of the block cut just up the slope of each concave kink of the sliding surface by a
  /// vertical joint; 0: no such joint (docs/case-format.md, "Section"). Used when given
  /// (`kinkBlockAuto` false).
  double kinkBlockWidth = 0;
  /// Not given: max(5e-3 w0, 2 × failureDisplacement), and no kink block where an inclined joint
  /// ends on the kink, where the cut would leave the crown's piece without another joint, or where
  /// the surface rises beyond the bend (docs/research/kink-blocks.md).
  bool kinkBlockAuto = true;
  double failureDisplacement = 0;  ///< the case's analysis.failure_displacement (0: its default)
};

struct SectionBlocks {
  Block base;                 ///< fixed
  std::vector<Block> slide;   ///< left to right (by centroid x)
};

/// Cuts the section. Throws InputError with a JSON path (relative to the section object) and an
/// empty file name when the section is malformed; the case reader adds the file.
SectionBlocks cutSection(const SectionSpec& spec);

}  // namespace ddaslope::model

#pragma once
// Blocks from a slope section: the slide mass between the ground and the sliding surface, cut
// by internal joints, and a fixed base below.
#include <optional>
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

/// A vertical tension crack behind the crest (Hoek & Bray's planar failure): from the ground at x
/// down to the sliding surface, which it ends. The slide is the mass in front of it (towards the
/// toe); the mass behind it joins the fixed base, its wall a small gap behind the slide's so the
/// crack is open and carries only its water.
struct TensionCrack {
  double x = 0;              ///< position (m), between the crown and the toe
  double waterFraction = 0;  ///< water depth in the crack as a fraction of its depth, in [0, 1]
  bool placedByDepth = false;  ///< x found from section.tension_crack.depth
};

/// Where a crack was cut: its position, top (on the ground) and bottom (on the sliding surface),
/// the gap to the base's wall behind it, and the water standing in it.
struct CrackGeometry {
  double x = 0, top = 0, bottom = 0, gap = 0;
  double waterFraction = 0;
  bool placedByDepth = false;  ///< x found from section.tension_crack.depth
  Vec2 toe{0, 0};  ///< where the sliding surface daylights: the crack drains there
  double depth() const { return top - bottom; }
  double waterDepth() const { return waterFraction * depth(); }
};

struct SectionSpec {
  std::vector<Vec2> ground;          ///< ground surface, x non-decreasing, across the model
  std::vector<Vec2> slidingSurface;  ///< x increasing, ends on the ground; its higher end is the crown
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
  std::optional<TensionCrack> tensionCrack;
};

struct SectionBlocks {
  Block base;                 ///< fixed
  std::vector<Block> slide;   ///< left to right (by centroid x)
  std::optional<CrackGeometry> crack;
};

/// A slope facing −x: its sliding surface, x increasing, rises from the toe to the crown. The cut
/// and the crack treat it as the same slope mirrored.
bool facesMinusX(const SectionSpec& spec);

/// The x at which the depth from the ground down to the sliding surface first equals `depth`,
/// going from the crown towards the toe; NaN when it never does.
double crackPositionAtDepth(const SectionSpec& spec, double depth);

/// Hoek & Bray's water in a tension crack: a phreatic line from the toe, where the sliding surface
/// daylights and drains, to the water surface in the crack (a pressure linear along a planar
/// sliding surface, hydrostatic in the crack), kept below the ground.
std::vector<Vec2> crackWaterLine(const CrackGeometry& crack, const std::vector<Vec2>& ground);

/// Cuts the section. Throws InputError with a JSON path (relative to the section object) and an
/// empty file name when the section is malformed; the case reader adds the file.
SectionBlocks cutSection(const SectionSpec& spec);

}  // namespace ddaslope::model

#pragma once
// The physical and numerical ranges a case may ask for (docs/case-format.md, "Limits"). Outside
// them a run would overflow, never end, or answer below the numbers' resolution; the reader and
// the command line refuse such input with the range, instead of running it.

namespace ddaslope::model::limits {

/// Gravity up to 100 g: a centrifuge model. Beyond it nothing a slope does is meant.
constexpr double kMaxGravity = 1000;          // m/s²
/// A ground-motion record's accelerations (before its scale): 100 g, far beyond the largest
/// recorded peaks (a few g). A record in g near the largest double would overflow to inf when
/// converted to m/s².
constexpr double kMaxGroundAcceleration = 1000;  // m/s²
constexpr double kMinDensity = 1;             // kg/m³: lighter than air is not a rock
constexpr double kMaxDensity = 1e5;           // kg/m³: ten times osmium
constexpr double kMinYoungModulus = 1e3;      // Pa: a gel
/// Up to RS2's and UDEC's rigid stand-ins (E = 2e14 Pa is common) and a little beyond; above
/// kStiffestRock no rock exists, and `check` names such a material a rigid stand-in.
constexpr double kMaxYoungModulus = 1e15;     // Pa
constexpr double kStiffestRock = 2e11;        // Pa: the stiffest intact rocks (eclogite, ~1.7e11)
/// Initial speed of any point of a block (|v| + |ω|·size): faster than any landslide or rockfall
/// by an order of magnitude.
constexpr double kMaxInitialSpeed = 1e3;      // m/s
constexpr double kMinTimeStep = 1e-7;         // s
constexpr double kMaxTimeStep = 10;           // s
constexpr double kMaxDuration = 1e6;          // s: eleven days of a creeping slope
/// duration / Δt: at a few ms per step of a large scene, a week of computing.
constexpr double kMaxNominalSteps = 1e7;
/// Step limit g2 = max_displacement_ratio: below 1e-5 a step moves less than the contact
/// tolerance resolves.
constexpr double kMinDisplacementRatio = 1e-5;
/// Blocks thinner than this fraction of the scene (2·area / perimeter against the bounding box)
/// sit below the resolution of its coordinates and contact tolerances.
constexpr double kMinRelativeThickness = 1e-6;
/// Scene size (bounding box) in metres: from a laboratory sample to a mountain range.
constexpr double kMinSceneSize = 1e-3;
constexpr double kMaxSceneSize = 1e6;
constexpr int kMaxBlockVertices = 10000;
constexpr int kMaxBlocks = 50000;

}  // namespace ddaslope::model::limits

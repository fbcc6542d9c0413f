#pragma once
// Models of Shi's DDA as ntdda ("DDA for Windows", doolin/ntdda) stores them: a geometry file
// (.geo) of joint lines and points, and an analysis file (.ana) of settings and properties, each
// in ntdda's XML form (DDAML) or the plain text form of Shi's original code. Read into a
// ddaslope case, and a case written back as DDAML. Our own reader, from the formats as ntdda's
// readers take them (docs/case-format.md, "Models from Shi's DDA").
#include <string>
#include <vector>

#include "ddaslope/core/types.hpp"
#include "ddaslope/geometry/line_arrangement.hpp"
#include "ddaslope/model/scene.hpp"

namespace ddaslope::io {

/// Where an element came from, for notes and errors: "line 12: <Joint>".
struct NtddaSource {
  int line = 0;
  std::string element;
  std::string where() const;
};

struct NtddaLine {
  Vec2 a{0, 0}, b{0, 0};
  int type = 1;  ///< joint type (joints), material (material lines), bolt type (bolts)
  NtddaSource source;
};

struct NtddaPoint {
  Vec2 p{0, 0};
  NtddaSource source;
};

struct NtddaGeometry {
  std::string file;
  bool xml = true;  ///< DDAML; false: the original text form
  /// e00: nodes closer than 1.25 e00 w0 are one (ntdda's dc02 scale w0, below).
  double edgeNodeDistance = 0.01;
  std::vector<NtddaLine> joints, materialLines, fixedLines, bolts, boundaryLines;
  std::vector<NtddaPoint> fixedPoints, measuredPoints, loadPoints, holePoints, seismicPoints;
  /// Elements read and not mapped (named in the notes).
  std::vector<NtddaSource> unmapped;
  std::vector<std::string> notes;  ///< what the reader could not take
};

struct NtddaMaterial {
  double unitMass = 0, unitWeight = 0, youngModulus = 0, poissonRatio = 0, damping = 0;
  double stress[3] = {0, 0, 0}, strain[3] = {0, 0, 0}, velocity[3] = {0, 0, 0};
  NtddaSource source;
};

struct NtddaJointType {
  double friction = 0, cohesion = 0, tensile = 0;  ///< degrees, Pa, Pa
  NtddaSource source;
};

/// A load point's force history: (t, fx, fy) records.
struct NtddaLoadHistory {
  std::vector<Vec3> records;
  NtddaSource source;
};

struct NtddaBoltProperties {
  double stiffness = 0, strength = 0, pretension = 0;
  NtddaSource source;
};

struct NtddaAnalysis {
  std::string file;
  bool xml = true;  ///< DDAML; false: the original text form
  bool dynamic = true;
  bool gravityPhase = false;   ///< <Gravity flag="yes">: Shi's gravity turn-on phase
  double gravity = 9.81;       ///< m/s², acting down −y
  bool planeStrain = true;
  int steps = 0;
  double timeStep = 0;         ///< s
  double maxDisplacement = 0;  ///< g2, a fraction of w0
  double penaltyFactor = 50;   ///< ntdda's penalty / largest E
  bool autoPenalty = false;
  std::vector<NtddaMaterial> materials;
  std::vector<NtddaJointType> joints;
  std::vector<NtddaLoadHistory> loads;
  std::vector<NtddaBoltProperties> bolts;
  std::vector<NtddaSource> unmapped;
  std::vector<std::string> notes;  ///< what the reader could map only in part
};

/// Reads a geometry file, DDAML or text (told apart by a leading '<'). Throws InputError naming
/// the file, the line and element, and what was expected and found.
NtddaGeometry readNtddaGeometry(const std::string& path);
/// Reads an analysis file, DDAML or text. (ntdda's text form has records of time-dependent
/// loads after the counts, but ntdda reads none of them, and neither does this.)
NtddaAnalysis readNtddaAnalysis(const std::string& path);

/// ntdda's geometric scale (dc02): from the joint lines' bounding box.
double ntddaScale(const std::vector<NtddaLine>& joints);

/// A model converted to a case: the JSON text and what could not be mapped exactly.
struct ConvertedModel {
  std::string caseJson;
  std::vector<std::string> notes;
  int blocks = 0, fixedBlocks = 0;
  geometry::LineArrangement arrangement;
};

/// The case of a geometry (and an analysis, without which materials, joints and settings are
/// placeholders, each named in a note). Throws InputError when the lines close no block.
ConvertedModel convertNtddaModel(const NtddaGeometry& geometry, const NtddaAnalysis* analysis);

/// A scene as DDAML: every block edge part of a joint line (collinear edges merged, split where
/// the joint changes), fixed blocks held by fixed points, monitors as measured points, point
/// loads, supports as bolts; notes name what ntdda cannot hold.
struct NtddaFiles {
  std::string geometry, analysis;
  std::vector<std::string> notes;
  int jointLines = 0;
};
NtddaFiles writeNtddaModel(const model::Scene& scene, const std::string& caseName);

}  // namespace ddaslope::io

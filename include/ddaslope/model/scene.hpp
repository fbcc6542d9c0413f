#pragma once
// Everything an analysis needs: blocks, materials, joints, loads, monitors, settings.
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "ddaslope/model/analysis_settings.hpp"
#include "ddaslope/model/block.hpp"
#include "ddaslope/model/block_point.hpp"
#include "ddaslope/model/materials.hpp"
#include "ddaslope/model/section.hpp"
#include "ddaslope/model/seismic.hpp"
#include "ddaslope/model/support.hpp"
#include "ddaslope/model/water.hpp"

namespace ddaslope::model {

struct Monitor {
  std::string id;
  BlockPoint point;
};

struct PointLoad {
  BlockPoint point;
  Vec2 force{0, 0};  ///< N per metre of thickness, at t = 0
  Vec2 rate{0, 0};   ///< N/m per second: the force at time t is force + rate · t
  std::string id{};  ///< optional: names the load for a support search (critical --support)
  bool ofEdgeLoad = false;  ///< a Gauss point of an edge load (equivalentPointLoads)
  Vec2 at(double t) const { return force + t * rate; }
};

/// A load distributed along a block's boundary from `from` to `to` (a surcharge, a berm, a
/// foundation): traction varying linearly from q0 to q1 (N/m² = N/m per metre of edge).
struct EdgeLoad {
  std::string id;
  int block = 0;
  Vec2 from{0, 0}, to{0, 0};
  Vec2 q0{0, 0}, q1{0, 0};
  /// The resultant (N/m) and where it acts.
  Vec2 resultant() const { return 0.5 * (q0 + q1) * (to - from).norm(); }
};

/// The point loads equivalent to an edge load: the traction at the two Gauss points of the
/// segment, each with half its length. Exact for a DDA block, whose displacement is linear in
/// position: the work of a linear traction on a linear displacement is a quadratic, which
/// two-point Gauss integration integrates exactly.
std::vector<PointLoad> equivalentPointLoads(const EdgeLoad& l);

struct FixedPoint {
  BlockPoint point;  ///< held at point.initial by a penalty spring
};

/// A joint that ended on a concave bend of a fixed block's surface, moved up the upper face
/// (model/kinks.hpp, moveJointEndsOffBends).
struct MovedJointEnd {
  int fixedBlock = 0;
  int upper = 0, lower = 0;  ///< the blocks on either side of the joint: on the upper face, on the lower
  Vec2 kink{0, 0};
  Vec2 shift{0, 0};          ///< of the joint's end, along the upper face (m)
  bool parallel = true;      ///< the joint kept its direction (else it turned about its other end)
};

/// An expected value a shipped case carries with it (checked by the test suite and `run`).
struct Expectation {
  std::string monitor{};
  std::string quantity{};  ///< ux, uy, vx, vy, displacement (|u|), speed (|v|)
  std::optional<double> time{};  ///< at this time; absent: the maximum over the run
  std::optional<double> value{};
  double relativeTolerance = 0;
  double absoluteTolerance = 0;
  std::optional<double> atMost{};
  std::optional<double> atLeast{};
  std::string source{};
};

/// What a support search varies for a named support or load (critical --solve support).
struct SupportQuantity {
  enum class Kind { None, AnchorForce, BoltCapacity, Load };
  Kind kind = Kind::None;
  std::string name;    ///< "anchor force", "bolt capacity", "load"
  double value = 0;    ///< the case's own (N/m)
  double spacing = 1;  ///< a support's out-of-plane spacing (m): per support = value × spacing
};

struct Scene {
  std::string description;
  Vec2 gravity{0, -9.81};
  std::vector<Material> materials;
  std::vector<JointProperties> joints;
  int defaultJoint = 0;
  /// Joint per unordered block pair (lower index first); others use defaultJoint.
  std::map<std::pair<int, int>, int> pairJoints;
  std::vector<Block> blocks;
  std::vector<Monitor> monitors;
  std::vector<PointLoad> pointLoads;
  std::vector<FixedPoint> fixedPoints;
  std::vector<Support> supports;
  /// Distributed loads on block edges, as the case gives them; each is applied as the point
  /// loads of its Gauss points (in pointLoads, with the distributed load's id).
  std::vector<EdgeLoad> edgeLoads;
  std::vector<Expectation> expectations;
  WaterTable water;  ///< no water unless its line is set
  /// A section's tension crack (section.tension_crack), in the case's coordinates (not shifted
  /// by `origin`), with the range its position is searched in, when given.
  std::optional<CrackGeometry> tensionCrack;
  std::optional<std::pair<double, double>> crackSearch;
  SeismicLoad seismic;  ///< none unless set
  /// Joints the reader moved off concave bends of a fixed block (analysis.joint_end_offset).
  std::vector<MovedJointEnd> movedJointEnds;
  AnalysisSettings settings;
  /// Where the case's coordinates were: every coordinate of a scene far from (0, 0) (a national
  /// grid) is held relative to this point, so that a step's displacement is not lost in the
  /// round-off of coordinates millions of metres large; outputs add it back (io/case_reader).
  Vec2 origin{0, 0};

  int jointBetween(int a, int b) const;
  /// Half the larger side of the model's bounding box: Shi's w0.
  double modelHalfSize() const;
  /// The gap (m) that counts as touching at t = 0, and the distance from a straight line within
  /// which a vertex is on it: analysis.initial_contact_tolerance × w0, or by default the
  /// millimetre's rounding (kRoundedCoordinateGap) held within [1e-6, 1e-4] × w0.
  double touchingGap() const;
  /// The time (s) from which the loads stay the same: 0 in a scene whose loads never change (no
  /// record that acts, one scaled to 0 does not; no level series that changes the level; no load
  /// rate); the end of a ground-motion record's last non-zero stretch (it is zero after its
  /// samples) or the last change of a water-level series (held after it); infinity with a load
  /// rate. (A support's law does not depend on time: like a contact, it changes only by changing
  /// state.)
  double lastLoadChange() const;
  /// Shi's step limit g2·w0, held to a tenth of the thinnest free block's thickness 2S/perimeter:
  /// the largest vertex displacement a step may make (m).
  double stepLimit() const;
  /// Unknowns of the free blocks: 6 each, 3 if rigid (what the solver path goes by).
  int freeUnknowns() const;
  /// Normal penalty in use (explicit, or factor × max E).
  double normalPenalty() const;
  int blockIndex(const std::string& id) const;  ///< −1 when absent
  /// The quantity a support search varies for the support or load `id` (Kind::None: no such
  /// name). An anchor (a pretension, or no stiffness) is searched on its force; a passive bolt on
  /// its capacity; a point or edge load on the size of its resultant, its direction kept.
  SupportQuantity supportQuantity(const std::string& id) const;
  /// Sets that quantity to `value` (N/m): an anchor's capacity is raised to its force if below.
  void setSupportQuantity(const std::string& id, double value);
  /// f(BlockPoint&) for every point carried by a block: monitors, point loads, fixed points and
  /// both ends of every support.
  template <class F>
  void forEachBlockPoint(F&& f) {
    for (Monitor& m : monitors) f(m.point);
    for (PointLoad& l : pointLoads) f(l.point);
    for (FixedPoint& p : fixedPoints) f(p.point);
    for (Support& b : supports) f(b.head), f(b.end);
  }
};

}  // namespace ddaslope::model

#pragma once
// Supports: rock bolts, cables and anchors as DDA elements (docs/supports.md). A support is an
// axial spring between a point of one block (its head) and a point of another (its end, often in
// a fixed block): Shi's bolt, with a pretension, a tensile capacity and what happens beyond it.
// All forces are per metre of slope (a bolt's own figures divided by its out-of-plane spacing).
#include <cmath>
#include <string>
#include <vector>

#include "ddaslope/core/types.hpp"
#include "ddaslope/model/block_point.hpp"

namespace ddaslope::model {

/// What a support does beyond its capacity.
enum class SupportFailure {
  Yield,    ///< perfectly plastic: the force stays at the capacity while it lengthens (a tendon
            ///< yielding, or grout slipping along its bond)
  Rupture,  ///< brittle: the force drops to zero for good
};

/// The state of a support after a step (judged, like contacts, in each open-close iterate).
enum class SupportState {
  Elastic,  ///< force = pretension + stiffness × elastic elongation
  Yielded,  ///< at its capacity, lengthening plastically
  Slack,    ///< a tendon shortened below its unloaded length carries nothing (no compression)
  Broken,   ///< ruptured: carries nothing for the rest of the run
};

struct Support {
  std::string id;
  BlockPoint head;  ///< the anchored block's point (where a bolt's plate sits)
  BlockPoint end;   ///< the point in the rock it is anchored to (its fixed length's end)
  double stiffness = 0;   ///< axial, N/m per metre of slope (0: a constant force, the pretension)
  double pretension = 0;  ///< N/m: the force at the drawn length (an anchor's lock-off load)
  double capacity = INFINITY;  ///< N/m: the least of the tendon's strength and the bond's on either side
  SupportFailure failure = SupportFailure::Yield;
  bool carriesCompression = false;  ///< a bar in compression (a dowel); tendons go slack instead
  double initialLength = 0;  ///< |end − head| as drawn (m)
  /// For the record: the bond strength (N/m of bolt per metre of slope) and the bolt's length in
  /// the head's and the end's block; the capacity already holds their least bond capacity.
  double bondStrength = INFINITY;
  double headEmbedment = 0, endEmbedment = 0;
  double bondCapacity = INFINITY;  ///< bond × the shorter embedment (N/m): what the grout holds
  double spacing = 1;  ///< out of plane (m): the forces here are a support's own ÷ spacing
  /// An anchor holds a force (its pretension, or it has no stiffness); a passive bolt answers
  /// the blocks' motion.
  bool active() const { return pretension > 0 || stiffness <= 0; }

  // The state after the last accepted step.
  SupportState state = SupportState::Elastic;
  double plasticElongation = 0;  ///< m
  double force = 0;              ///< axial force, tension positive (N/m)
  double work = 0;               ///< done on the support by the blocks (J/m): stored or dissipated

  /// Elongation now (m): current length − drawn length.
  double elongation() const { return (end.current - head.current).norm() - initialLength; }
  /// The force an elastic support would carry at elongation e, from its present plastic state.
  double elasticForce(double e) const { return pretension + stiffness * (e - plasticElongation); }
};

/// The state a support takes at elongation e (its force judged against its law): from
/// `elasticForce(e)` with the plastic elongation of the step's start. Broken stays broken.
SupportState judgeSupport(const Support& s, double e);

/// The force of support s in `state` at elongation e, and its plastic elongation then.
double supportForce(const Support& s, SupportState state, double e);
double plasticElongationAfter(const Support& s, SupportState state, double e);

const char* supportStateName(SupportState s);

}  // namespace ddaslope::model

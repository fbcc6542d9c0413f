#include "ddaslope/model/support.hpp"

namespace ddaslope::model {

SupportState judgeSupport(const Support& s, double e) {
  if (s.state == SupportState::Broken) return SupportState::Broken;
  // A constant-force anchor (no stiffness) holds its pretension whatever it does.
  if (s.stiffness <= 0) return SupportState::Elastic;
  const double f = s.elasticForce(e);
  if (f > s.capacity) return s.failure == SupportFailure::Rupture ? SupportState::Broken : SupportState::Yielded;
  if (f < 0 && !s.carriesCompression) return SupportState::Slack;
  return SupportState::Elastic;
}

double supportForce(const Support& s, SupportState state, double e) {
  switch (state) {
    case SupportState::Elastic: return s.stiffness > 0 ? s.elasticForce(e) : s.pretension;
    case SupportState::Yielded: return s.capacity;
    case SupportState::Slack:
    case SupportState::Broken: return 0;
  }
  return 0;
}

double plasticElongationAfter(const Support& s, SupportState state, double e) {
  // Yielding, the elastic part stays at the capacity's: the rest of the elongation is plastic.
  if (state == SupportState::Yielded && s.stiffness > 0) return e - (s.capacity - s.pretension) / s.stiffness;
  return s.plasticElongation;
}

const char* supportStateName(SupportState s) {
  switch (s) {
    case SupportState::Elastic: return "elastic";
    case SupportState::Yielded: return "yielded";
    case SupportState::Slack: return "slack";
    case SupportState::Broken: return "broken";
  }
  return "?";
}

}  // namespace ddaslope::model

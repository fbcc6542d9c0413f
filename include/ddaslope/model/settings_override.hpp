#pragma once
// The accuracy and model choices a command or a back-analysis job may impose on a case's own
// analysis settings: an accuracy preset, a time step, rigid or deformable blocks, the contact
// treatment, brittle joints. They reach the case as overrides of its JSON, in that order, so an
// explicit time step wins over a preset (io::caseOverridesFor).
#include <string>

#include "ddaslope/model/scene.hpp"

namespace ddaslope::model {

struct SettingsOverride {
  std::string preset;            ///< fast, balanced or accurate; empty: keep the case's
  double timeStep = 0;           ///< s; 0: keep
  std::string blocks;            ///< rigid or deformable; empty: keep
  std::string contactTreatment;  ///< edge or vertex; empty: keep
  /// Every joint brittle (weakening distance 0): original DDA's bond, lost the moment a contact
  /// slides. The first-failure answer, beside the softening default (docs/calibration.md).
  bool brittleJoints = false;
  /// Prefix naming the source in AnalysisSettings::timeStepOrigin: "--" gives "--preset fast".
  std::string origin = "--";
};

}  // namespace ddaslope::model

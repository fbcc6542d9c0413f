#include "ddaslope/model/settings_override.hpp"

#include "ddaslope/model/presets.hpp"

namespace ddaslope::model {

void SettingsOverride::apply(Scene& scene) const {
  AnalysisSettings& s = scene.settings;
  if (!preset.empty()) {
    // The names were validated where they were read (CLI11's IsMember, the job reader).
    applyPreset(s, *findPreset(preset), scene.modelHalfSize(), scene.gravity.norm());
    s.timeStepOrigin = origin + "preset " + preset;
  }
  if (timeStep > 0) {
    s.timeStep = timeStep;
    s.timeStepOrigin = origin + "time-step";
  }
  if (!blocks.empty()) s.rigidBlocks = blocks == "rigid";
  if (!contactTreatment.empty())
    s.contactTreatment = contactTreatment == "vertex" ? ContactTreatment::Vertex : ContactTreatment::Edge;
  if (brittleJoints)
    for (JointProperties& j : scene.joints) j.weakeningDistance = 0;
}

}  // namespace ddaslope::model

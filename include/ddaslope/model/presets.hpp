#pragma once
// Accuracy presets (docs/accuracy.md): bundles of the settings that trade speed for accuracy.
// The time step scales with the model's own time scale √(w0/g), so a preset means the same for a
// 1 m block and a 1 km slide.
#include <optional>
#include <string>

#include "ddaslope/model/analysis_settings.hpp"

namespace ddaslope::model {

struct Preset {
  const char* name;
  double timeStepCoefficient;  ///< Δt = coefficient · √(w0/g)
  double maxDisplacementRatio;
  double penaltyFactor;
};

/// The preset of a case that sets neither a preset nor its own time step, and so of every
/// command's forward runs, the calibration loops' included, unless the case or the command chooses.
inline constexpr const char* kDefaultPreset = "balanced";

/// fast, balanced or accurate; nullopt for any other name.
std::optional<Preset> findPreset(const std::string& name);
/// Sets Δt, g2 and the penalty factor (and the penalty to automatic) from the preset.
void applyPreset(AnalysisSettings& s, const Preset& p, double modelHalfSize, double gravity);

}  // namespace ddaslope::model

#include "ddaslope/model/presets.hpp"

#include <cmath>

namespace ddaslope::model {

namespace {
// Calibrated on the two-block slide of calibration/two_block_slide (w0 = 32.5 m, √(w0/g) =
// 1.82 s), where the settings matter (docs/accuracy.md): error in the toe's travel at 2 s against
// the finest setting 0.5 %, 0.3 % and < 0.001 %; relative cost 1 : 2 : 6. `fast` takes the soft
// penalty (×10): at 3 ms a stiffer one errs by 2–17 %.
constexpr Preset kPresets[] = {
    {"fast", 1.6e-3, 0.01, 10},
    {"balanced", 5.5e-4, 0.005, 40},
    {"accurate", 1.6e-4, 0.005, 100},
};
}  // namespace

std::optional<Preset> findPreset(const std::string& name) {
  for (const Preset& p : kPresets)
    if (name == p.name) return p;
  return std::nullopt;
}

void applyPreset(AnalysisSettings& s, const Preset& p, double modelHalfSize, double gravity) {
  s.timeStep = p.timeStepCoefficient * std::sqrt(modelHalfSize / std::max(gravity, 1e-3));
  s.maxDisplacementRatio = p.maxDisplacementRatio;
  s.penaltyFactor = p.penaltyFactor;
  s.penalty = 0;
  s.timeStepOrigin = std::string("preset ") + p.name;
}

}  // namespace ddaslope::model

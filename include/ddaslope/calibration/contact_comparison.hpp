#pragma once
// Critical cohesion of a block on an incline with each contact treatment against the closed
// form c_cr = (W sin α − W cos α tan φ)/b (the table of docs/contact-model.md).
#include <vector>

namespace ddaslope::calibration {

struct ComparisonSettings {
  std::vector<double> alphasDeg{30, 40, 50};
  std::vector<double> heightRatios{0.25, 0.5, 1.0};  ///< h/b
  std::vector<double> phisDeg{10, 20, 30};
  /// Stiff blocks (E = 2.5 × penalty: rigid compared with their springs, the founding paper's
  /// setting) or the default deformable rock (E = 5 GPa, penalty 40 E).
  bool stiffBlocks = true;
  int threads = 2;
};

struct ComparisonRow {
  double alphaDeg = 0, heightRatio = 0, phiDeg = 0;
  double closedForm = 0;  ///< Pa
  double edge = 0;        ///< critical cohesion found, Pa
  double vertex = 0;
  int runs = 0;           ///< forward runs for both treatments
  bool bracketed = true;
};

/// One row per (α, h/b, φ). Each critical value is a bisection on c over [0, 2 W sin α / b]
/// to a width of 1e-4 of that range; a block that holds at c = 0 gets 0.
std::vector<ComparisonRow> compareContactTreatments(const ComparisonSettings& settings);

}  // namespace ddaslope::calibration

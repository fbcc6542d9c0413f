#include "ddaslope/calibration/contact_comparison.hpp"

#include <cmath>

#include "ddaslope/calibration/bisection.hpp"
#include "ddaslope/calibration/verdict.hpp"
#include "ddaslope/core/task_farm.hpp"
#include "ddaslope/model/incline_scene.hpp"

namespace ddaslope::calibration {
namespace {

model::InclineSpec specOf(const ComparisonRow& r) {
  model::InclineSpec s{r.alphaDeg, 10, 10 * r.heightRatio, r.phiDeg, 0, 2000, 10};
  s.duration = 0.5;
  return s;
}

/// Critical cohesion with one treatment; σt = c so that tall blocks do not topple first.
double critical(const ComparisonRow& row, model::ContactTreatment t, bool stiff, ComparisonRow& out) {
  const model::InclineSpec spec = specOf(row);
  const auto stableAt = [&](double c) {
    model::InclineSpec s = spec;
    s.cohesion = c;
    model::Scene sc = model::makeInclineScene(s);
    sc.joints[0].tensileStrength = c;
    sc.joints[0].weakeningDistance = 0;  // the founding paper's comparison is of original DDA's brittle bond
    sc.settings.contactTreatment = t;
    if (stiff) {
      sc.settings.penalty = 2e11;
      sc.materials[0].youngModulus = 5e11;
    }
    return judgeStability(sc).stable;
  };
  if (stableAt(0)) {
    ++out.runs;
    return 0;
  }
  const double top = 2 * spec.density * spec.g * spec.h * std::sin(degToRad(spec.alphaDeg));
  const BisectionResult r = bisect(stableAt, 0, top, 1e-4 * top);
  out.runs += r.runs + 1;
  out.bracketed &= r.bracketed;
  return r.critical;
}

}  // namespace

std::vector<ComparisonRow> compareContactTreatments(const ComparisonSettings& settings) {
  std::vector<ComparisonRow> rows;
  for (double a : settings.alphasDeg)
    for (double hb : settings.heightRatios)
      for (double phi : settings.phisDeg) {
        ComparisonRow r;
        r.alphaDeg = a;
        r.heightRatio = hb;
        r.phiDeg = phi;
        r.closedForm = model::criticalCohesion(specOf(r));
        rows.push_back(r);
      }
  // Rows are independent forward-model searches: share them among threads (results do not
  // depend on the schedule, each row is computed alone).
  runOnThreads(static_cast<int>(rows.size()), settings.threads, [&](int k) {
    ComparisonRow& r = rows[static_cast<size_t>(k)];
    r.edge = critical(r, model::ContactTreatment::Edge, settings.stiffBlocks, r);
    r.vertex = critical(r, model::ContactTreatment::Vertex, settings.stiffBlocks, r);
  });
  return rows;
}

}  // namespace ddaslope::calibration

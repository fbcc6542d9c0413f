#include "ddaslope/calibration/bisection.hpp"

#include <cmath>
#include <sstream>

namespace ddaslope::calibration {

BisectionResult bisect(const std::function<bool(double)>& stableAt, double lo, double hi, double width) {
  BisectionResult r;
  const bool stableLo = stableAt(lo), stableHi = stableAt(hi);
  r.runs = 2;
  if (stableLo == stableHi) {
    std::ostringstream m;
    m << "not bracketed: both ends (" << lo << ", " << hi << ") are " << (stableLo ? "stable" : "failing");
    r.message = m.str();
    r.critical = stableLo ? lo : hi;
    r.stableEnd = r.failingEnd = r.critical;
    return r;
  }
  double stable = stableLo ? lo : hi, failing = stableLo ? hi : lo;
  while (std::abs(stable - failing) > width) {
    const double mid = 0.5 * (stable + failing);
    (stableAt(mid) ? stable : failing) = mid;
    ++r.runs;
  }
  r.bracketed = true;
  r.stableEnd = stable;
  r.failingEnd = failing;
  r.critical = 0.5 * (stable + failing);
  return r;
}

}  // namespace ddaslope::calibration

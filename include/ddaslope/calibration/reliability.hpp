#pragma once
// Probabilities of small failures (docs/probability.md, *Importance sampling*): the design point
// of the first-order reliability method (FORM), found with forward runs' verdicts along rays of
// the standard normal space, and the importance-sampling weights around it.
//
// The space is that of the study's independent standard normals u (the correlated normals are
// L u, the inputs their marginals: calibration/probability.hpp). The design point is the failing
// point nearest the origin (the inputs' medians); its distance is FORM's reliability index β, its
// direction the inputs' sensitivities. A verdict is binary, so the limit state is never
// differentiated: along a ray from the origin the verdict changes once, at a radius found by
// bisection, and the ray of least radius is sought by fitting the limit state's tangent plane
// through the points that neighbouring rays find (a secant step on the surface).
#include <functional>
#include <limits>
#include <string>
#include <vector>

namespace ddaslope::calibration {

/// What one forward run says at a point u.
enum class PointVerdict { Stable, Fails, NotConverged };

/// The slope as a function of u.
struct LimitState {
  int dimensions = 0;
  /// Whether the case accepts the inputs at u (no forward run): a ray ends where it stops
  /// accepting them (a cohesion drawn below 0).
  std::function<bool(const std::vector<double>& u)> accepts;
  /// One forward run at u. Called from several threads at once when threads > 1.
  std::function<PointVerdict(const std::vector<double>& u)> judge;
};

struct DesignPointSettings {
  /// The largest radius searched: a ray still stable there never fails (Φ(−8) = 6e-16).
  double maxRadius = 8;
  /// The width to which each ray's radius is bisected.
  double tolerance = 0.01;
  /// The secant steps stop when the direction turns by less than this (radians).
  double angleTolerance = 0.02;
  int maxSteps = 8;
  /// Forward runs at once (at most two: a ray is trisected whatever the thread count, so the
  /// design point does not depend on it).
  int threads = 1;
};

struct DesignPoint {
  bool found = false;
  std::vector<double> u;   ///< the failing point nearest the origin found (mid-bracket on its ray)
  double beta = std::numeric_limits<double>::infinity();  ///< |u|
  std::vector<double> alpha;  ///< u / β: where the failure lies, as direction cosines
  int runs = 0;               ///< forward runs spent
  int rays = 0;               ///< rays searched
  int steps = 0;              ///< secant steps taken
  bool converged = false;     ///< the last step turned the direction by less than angleTolerance
  /// Other failing directions found more than 90° from the design point's (e.g. failure at both
  /// low and high values of an input): importance sampling around one point misses the others.
  std::vector<std::vector<double>> otherRegions;
  std::string message;  ///< why none was found
};

/// The design point of `limit`. The origin is judged first: a slope that fails (or does not
/// converge) at the medians has no design point (found = false, with a message). Rays go first
/// along the 2n axes (then the 2ⁿ diagonals, n ≤ 6, if no axis fails); the axis intercepts give
/// the first direction (the plane through them), then secant steps refine it. A run that does
/// not converge counts as failing here: it only moves the sampling centre, never the estimate.
DesignPoint findDesignPoint(const LimitState& limit, const DesignPointSettings& settings);

/// Importance sampling's weight of the point u = centre + z, z standard normal: the ratio of the
/// standard normal density at u to the sampling density (the standard normal centred on
/// `centre`), exp(−z·centre − |centre|²/2).
double importanceWeight(const std::vector<double>& z, const std::vector<double>& centre);

/// Der Kiureghian's importance vector γ (Der Kiureghian 2005, *Engineering Design Reliability
/// Handbook*, ch. 14): α carried to the correlated normals x = L u, γ = L⁻ᵀα / |L⁻ᵀα|, the
/// linearised limit state's gradient in x. Independent inputs: γ = α, and γᵢ² is input i's share
/// of the limit state's variance. `lower` is L, row-major.
std::vector<double> importanceVector(const std::vector<double>& alpha, const std::vector<double>& lower);

}  // namespace ddaslope::calibration

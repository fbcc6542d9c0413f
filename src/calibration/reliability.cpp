#include "ddaslope/calibration/reliability.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>

#include "ddaslope/calibration/bisection.hpp"

namespace ddaslope::calibration {
namespace {

using Vec = Eigen::VectorXd;

std::vector<double> toStd(const Vec& v) { return {v.data(), v.data() + v.size()}; }

/// Where a ray from the origin first fails.
struct Ray {
  bool fails = false;
  double radius = std::numeric_limits<double>::infinity();  ///< mid-bracket
  Vec direction;
  Vec point() const { return radius * direction; }
};

class RaySearch {
 public:
  RaySearch(const LimitState& limit, const DesignPointSettings& s) : limit_(limit), s_(s) {}

  int runs() const { return runs_; }
  int rays() const { return rays_; }

  bool stableAt(const Vec& u) {
    ++runs_;
    return limit_.judge(toStd(u)) == PointVerdict::Stable;
  }

  /// The farthest radius along `d` (at most maxRadius) at which the case accepts the inputs.
  double reach(const Vec& d) const {
    if (limit_.accepts(toStd(s_.maxRadius * d))) return s_.maxRadius;
    double lo = 0, hi = s_.maxRadius;  // the origin is accepted: the study was read there
    while (hi - lo > 1e-3 * s_.tolerance) {
      const double mid = 0.5 * (lo + hi);
      (limit_.accepts(toStd(mid * d)) ? lo : hi) = mid;
    }
    return lo;
  }

  /// The first failure along the unit direction `d`, searched around `guess` (a radius, or ∞:
  /// from the ray's reach down). `failsAtReach`: the run at the reach is known to fail.
  Ray along(const Vec& d, double guess, bool failsAtReach = false) {
    ++rays_;
    Ray ray;
    ray.direction = d;
    const double far = reach(d);
    const auto stable = [&](double r) { return stableAt(r * d); };
    double lo = 0, hi = far;  // stable at lo, failing at hi
    if (std::isfinite(guess) && guess < far) {
      lo = std::max(0.0, guess - 0.1);
      hi = std::min(far, guess + 0.1);
      const std::vector<bool> ok = evaluateAll(stable, {lo, hi}, s_.threads);
      if (!ok[0]) {  // failing below the guess: step down to a stable radius (the origin is)
        hi = lo;
        for (double step = 0.25; lo > 0; step *= 2) {
          lo = std::max(0.0, hi - step);
          if (lo == 0 || stable(lo)) break;
          hi = lo;
        }
      } else if (ok[1]) {  // stable above it: step up to a failing one, or to the reach
        lo = hi;
        for (double step = 0.25;; step *= 2) {
          if (lo >= far) return ray;
          hi = std::min(far, lo + step);
          if (!stable(hi)) break;
          lo = hi;
        }
      }
    } else if (!failsAtReach && stable(far)) {
      return ray;
    }
    // Trisection whatever the thread count: two runs a round, at once when threads allow, so that
    // the design point (and every sample centred on it) is the same on any number of threads.
    while (hi - lo > s_.tolerance) {
      const double a = lo + (hi - lo) / 3, b = lo + 2 * (hi - lo) / 3;
      const std::vector<bool> ok = evaluateAll(stable, {a, b}, s_.threads);
      if (!ok[0]) hi = a;
      else if (!ok[1]) lo = a, hi = b;
      else lo = b;
    }
    ray.fails = true;
    ray.radius = 0.5 * (lo + hi);
    return ray;
  }

 private:
  const LimitState& limit_;
  const DesignPointSettings& s_;
  std::atomic<int> runs_{0};
  std::atomic<int> rays_{0};
};

/// The plane through n points of n-space (rows of `p`), as w with w·x = 1; false when they are
/// (nearly) dependent or the plane passes through the origin.
bool planeThrough(const Eigen::MatrixXd& p, Vec* w) {
  const Eigen::FullPivLU<Eigen::MatrixXd> lu(p);
  if (lu.rank() < p.rows()) return false;
  *w = lu.solve(Vec::Ones(p.rows()));
  return w->allFinite() && w->norm() > 0;
}

}  // namespace

DesignPoint findDesignPoint(const LimitState& limit, const DesignPointSettings& s) {
  const int n = limit.dimensions;
  DesignPoint out;
  RaySearch search(limit, s);
  const auto finish = [&](const Ray* best) {
    out.runs = search.runs();
    out.rays = search.rays();
    if (!best) return out;
    out.found = true;
    out.u = toStd(best->point());
    out.beta = best->radius;
    out.alpha = toStd(best->direction);
    return out;
  };
  if (!search.stableAt(Vec::Zero(n))) {
    out.message = "the slope does not stand at the inputs' medians (the origin of the standard normal space): "
                  "failure is not rare there, so plain sampling (\"method\": \"sampling\") estimates Pf";
    return finish(nullptr);
  }

  // Each axis both ways, judged at its reach at once; the failing ones bisected.
  std::vector<Vec> directions;
  for (int i = 0; i < n; ++i)
    for (double sign : {1.0, -1.0}) directions.push_back(sign * Vec::Unit(n, i));
  const auto failingAtReach = [&](const std::vector<Vec>& dirs) {
    std::vector<double> index(dirs.size());
    for (size_t k = 0; k < dirs.size(); ++k) index[k] = static_cast<double>(k);
    const std::vector<bool> ok = evaluateAll(
        [&](double k) {
          const Vec& d = dirs[static_cast<size_t>(k)];
          return search.stableAt(search.reach(d) * d);
        },
        index, s.threads);
    std::vector<Ray> rays;
    for (size_t k = 0; k < dirs.size(); ++k)
      if (!ok[k]) rays.push_back(search.along(dirs[k], std::numeric_limits<double>::infinity(), true));
    return rays;
  };
  std::vector<Ray> found = failingAtReach(directions);
  // The plane through the axis intercepts: exact for a linear limit state.
  Vec normal = Vec::Zero(n);
  for (int i = 0; i < n; ++i) {
    double nearest = std::numeric_limits<double>::infinity();
    for (const Ray& r : found) {
      const double along = r.direction(i);
      if (std::abs(along) > 0.5 && r.fails && r.radius < std::abs(nearest)) nearest = along * r.radius;
    }
    if (std::isfinite(nearest)) normal(i) = 1 / nearest;
  }
  if (normal.norm() == 0 && n > 1 && n <= 6) {
    directions.clear();
    for (int mask = 0; mask < (1 << n); ++mask) {
      Vec d(n);
      for (int i = 0; i < n; ++i) d(i) = (mask >> i & 1) ? -1.0 : 1.0;
      directions.push_back(d.normalized());
    }
    found = failingAtReach(directions);
  }
  const auto nearest = [&]() -> const Ray* {
    const Ray* best = nullptr;
    for (const Ray& r : found)
      if (r.fails && (!best || r.radius < best->radius)) best = &r;
    return best;
  };
  if (!nearest()) {
    char radius[32];
    std::snprintf(radius, sizeof radius, "%g", s.maxRadius);
    out.message = std::string("no run failed within radius ") + radius + " of the medians along the axes" +
                  (n > 1 && n <= 6 ? " and diagonals" : "") +
                  " of the standard normal space (or as far as the case accepts the inputs): Pf is too small "
                  "to matter, or failure lies in a direction not searched (plain sampling would show it)";
    return finish(nullptr);
  }
  if (normal.norm() > 0) found.push_back(search.along(normal.normalized(), 1 / normal.norm()));

  // Secant steps on the limit state: the plane through the base point and its neighbours at
  // angle ~0.15 rad, whose nearest point gives the next direction.
  if (n > 1) {
    Ray base = *nearest();
    for (int step = 0; step < s.maxSteps; ++step) {
      ++out.steps;
      const Vec d = base.direction;
      const Eigen::HouseholderQR<Eigen::MatrixXd> qr(d);
      const Eigen::MatrixXd q = qr.householderQ();  // columns 1..n−1 span the tangent space of d
      Eigen::MatrixXd p(n, n);
      p.row(0) = base.point().transpose();
      bool complete = true;
      for (int j = 1; j < n && complete; ++j) {
        const Ray r = search.along((d + 0.15 * q.col(j)).normalized(), base.radius);
        found.push_back(r);
        complete = r.fails;
        if (complete) p.row(j) = r.point().transpose();
      }
      Vec w;
      if (!complete || !planeThrough(p, &w)) break;
      const Vec next = w.normalized();
      const double turn = std::acos(std::clamp(next.dot(d), -1.0, 1.0));
      const Ray r = search.along(next, 1 / w.norm());
      found.push_back(r);
      if (turn < s.angleTolerance) {
        out.converged = true;
        break;
      }
      if (!r.fails) break;
      base = r;
    }
  }
  const Ray* best = nearest();
  for (const Ray& r : found)
    if (r.fails && r.direction.dot(best->direction) < 0) {
      bool known = false;
      for (const auto& o : out.otherRegions) known = known || Eigen::Map<const Vec>(o.data(), n).dot(r.direction) > 0;
      if (!known) out.otherRegions.push_back(toStd(r.point()));
    }
  if (n == 1) out.converged = true;
  return finish(best);
}

double importanceWeight(const std::vector<double>& z, const std::vector<double>& centre) {
  double dot = 0, c2 = 0;
  for (size_t i = 0; i < z.size(); ++i) dot += z[i] * centre[i], c2 += centre[i] * centre[i];
  return std::exp(-dot - 0.5 * c2);
}

std::vector<double> importanceVector(const std::vector<double>& alpha, const std::vector<double>& lower) {
  const int n = static_cast<int>(alpha.size());
  const Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> l(lower.data(), n, n);
  const Vec y = l.transpose().triangularView<Eigen::Upper>().solve(Eigen::Map<const Vec>(alpha.data(), n));
  return toStd(y.normalized());
}

}  // namespace ddaslope::calibration

// The DDA forward model around its step: construction, the accepted step (advance, commit), the
// run's bookkeeping (statistics, energy, monitors) and runAnalysis. The step itself is in
// step.cpp and open_close.cpp, the contact update in contact_update.cpp, the initial
// equilibrium in equilibrium.cpp.
#include "ddaslope/solver/simulation.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>

#include "ddaslope/assembly/block_terms.hpp"
#include "ddaslope/contact/contact_law.hpp"
#include "ddaslope/core/cancellation.hpp"
#include "ddaslope/core/errors.hpp"
#include "ddaslope/geometry/polygon.hpp"
#include "stopwatch.hpp"

namespace ddaslope::solver {

using contact::Contact;

namespace {

/// The interior angle of a counter-clockwise outline at its vertex k (π where it runs straight).
double interiorAngle(const std::vector<Vec2>& v, size_t k) {
  const size_t n = v.size();
  const Vec2 in = v[k] - v[(k + n - 1) % n], out = v[(k + 1) % n] - v[k];
  return M_PI - std::atan2(cross(in, out), in.dot(out));
}

/// Per block, per vertex, the seams of a base of several fixed blocks (contact::kFlatCorner,
/// contact::kInternalEdge): a vertex where other fixed blocks fill the rest of a straight angle or
/// more around it (a seam flush with the face, or a T-junction on another's face), and an edge
/// lying against another fixed block's. Their union has no corner and no face there, and a free
/// block sliding along the face must pass over the seam: taken as a corner, the far block's corner
/// catches the slider's front face and stops it dead, and the seam's face pushes a corner over it
/// out of the base. Empty unless two fixed blocks meet.
std::vector<std::vector<char>> seamVertices(const model::Scene& scene) {
  std::vector<size_t> fixed;
  for (size_t b = 0; b < scene.blocks.size(); ++b)
    if (scene.blocks[b].fixed) fixed.push_back(b);
  std::vector<std::vector<char>> flat;
  if (fixed.size() < 2) return flat;
  const double tol = scene.touchingGap();
  std::vector<geometry::Aabb> box(scene.blocks.size());
  for (const size_t b : fixed) box[b] = geometry::boundingBox(scene.blocks[b].vertices);
  const auto apart = [&](size_t a, size_t b) {
    return (box[a].lo.array() > box[b].hi.array() + tol).any() || (box[b].lo.array() > box[a].hi.array() + tol).any();
  };
  const auto onBoundary = [&](const Vec2& x, const std::vector<Vec2>& v) {
    for (size_t m = 0; m < v.size(); ++m)
      if (geometry::distanceToSegment(x, v[m], v[(m + 1) % v.size()], nullptr) <= tol) return true;
    return false;
  };
  flat.resize(scene.blocks.size());
  for (const size_t i : fixed) {
    const std::vector<Vec2>& vi = scene.blocks[i].vertices;
    flat[i].assign(vi.size(), 0);
    std::vector<size_t> near;  // the fixed blocks that can touch this one
    for (const size_t j : fixed)
      if (j != i && !apart(i, j)) near.push_back(j);
    for (size_t k = 0; k < vi.size(); ++k) {
      // The angle the fixed blocks fill around the vertex: its own, and each neighbour's there
      // (its vertex's, or π on the middle of its edge).
      double around = interiorAngle(vi, k);
      for (const size_t j : near) {
        const std::vector<Vec2>& vj = scene.blocks[j].vertices;
        size_t m = 0;
        while (m < vj.size() && (vj[m] - vi[k]).norm() > tol) ++m;
        if (m < vj.size()) around += interiorAngle(vj, m);
        else if (onBoundary(vi[k], vj)) around += M_PI;
      }
      if (around >= M_PI * (1 - 1e-9)) flat[i][k] |= contact::kFlatCorner;
      // The edge from k lies against another fixed block's boundary: its ends and middle on it.
      const Vec2 a = vi[k], e = vi[(k + 1) % vi.size()];
      for (const size_t j : near)
        if (onBoundary(a, scene.blocks[j].vertices) && onBoundary(e, scene.blocks[j].vertices) &&
            onBoundary(0.5 * (a + e), scene.blocks[j].vertices)) {
          flat[i][k] |= contact::kInternalEdge;
          break;
        }
    }
  }
  return flat;
}

}  // namespace

Simulation::Simulation(model::Scene scene)
    : scene_(std::move(scene)),
      integrator_(scene_.settings.mode == model::AnalysisMode::Dynamic),
      stepSize_(scene_.settings.timeStep, scene_.settings.stepCutFactor) {
  if (scene_.settings.wallClockLimit > 0)
    deadline_ = std::chrono::steady_clock::now() +
                std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                    std::chrono::duration<double>(scene_.settings.wallClockLimit));
  w0_ = scene_.modelHalfSize();
  for (model::JointProperties& j : scene_.joints) {
    j.weakeningDistance = j.weakeningDistanceIn(w0_);
    jointStrength_.push_back(contact::jointStrength(j));
  }
  for (const model::Block& b : scene_.blocks) mass_.push_back(scene_.materials[b.material].density * b.moments.area);
  stepLimit_ = scene_.stepLimit();
  // A record, a reservoir history or a load that changes in time must be followed at the case's
  // Δt, however quiet the blocks: quiet steps grow only from the loads' last change on (the end
  // of a record or history; never under a load rate).
  lastLoadChange_ = scene_.lastLoadChange();
  if (const model::AnalysisSettings& st = scene_.settings;
      st.timeStepGrowth > 1 && st.mode == model::AnalysisMode::Dynamic && std::isfinite(lastLoadChange_))
    stepSize_.allowGrowthTo(st.timeStepGrowth * st.timeStep);
  searchDistance_ = 2.5 * stepLimit_;
  flatCorners_ = seamVertices(scene_);
  penalty_ = scene_.normalPenalty();
  shearPenalty_ = penalty_ * scene_.settings.shearPenaltyRatio;
  for (const model::JointProperties& j : scene_.joints) {
    jointNormalStiffness_.push_back(j.normalStiffness);
    jointShearStiffness_.push_back(j.shearStiffness);
  }
  for (const model::Material& m : scene_.materials)
    elasticity_.push_back(assembly::elasticityMatrix(m.youngModulus, m.poissonRatio, scene_.settings.plane));
  for (size_t b = 0; b < scene_.blocks.size(); ++b) {
    const model::Block& blk = scene_.blocks[b];
    double beta = 0;
    if (!blk.fixed && !scene_.settings.rigidBlocks && scene_.settings.strainDamping > 0) {
      const Mat6 mass = (mass_[b] / blk.moments.area) * assembly::unitMassMatrix(blk.moments);
      const double w1 = assembly::lowestStrainFrequency(
          mass, assembly::elasticStiffness(blk.moments.area, elasticity_[blk.material]));
      if (w1 > 0) beta = 2 * scene_.settings.strainDamping / w1;
    }
    strainRetardation_.push_back(beta);
  }
  markActiveBlocks({});
  lightestPenetration_ = INFINITY;
  for (const model::Block& b : scene_.blocks)
    if (!b.fixed && scene_.gravity.norm() > 0)
      lightestPenetration_ = std::min(lightestPenetration_, 1e-3 * scene_.materials[b.material].density *
                                                                b.moments.area * scene_.gravity.norm() / penalty_);
  detectContacts(true);
}

void Simulation::markActiveBlocks(const std::vector<bool>& held) {
  active_.assign(scene_.blocks.size(), -1);
  nActive_ = 0;
  for (size_t b = 0; b < scene_.blocks.size(); ++b)
    if (!scene_.blocks[b].fixed && (held.empty() || !held[b])) active_[b] = nActive_++;
}

void Simulation::commit(Attempt& a, double dt, bool weakens) {
  Stopwatch sw;
  commitPoints(a);
  for (size_t b = 0; b < scene_.blocks.size(); ++b) {
    const int i = active_[b];
    if (i < 0) continue;
    model::Block& blk = scene_.blocks[b];
    const Vec6 d = a.d.segment<6>(6 * i);
    blk.velocity = integrator_.velocityAfter(d, blk.velocity, dt);
    blk.stress += elasticity_[blk.material] * d.tail<3>();
    blk.applyDisplacement(d);
  }
  for (const Contact& c : a.contacts)
    if (c.closed()) stats_.maxPenetration = std::max(stats_.maxPenetration, c.normalForce / normalStiffness(c));
  contacts_.contacts() = std::move(a.contacts);
  a.contacts.clear();
  for (Contact& c : contacts_.contacts()) {
    if (!weakens) {
      // Before t = 0 a separation is the slope's loading history, not damage: its gap is the zero.
      c.openingAtStart = c.closed() ? 0.0 : openingAfterStep(c);
      continue;
    }
    // A softening joint loses strength with the slip accumulated by the accepted steps.
    c.slipDistance += std::abs(c.stepSlip);
    const model::JointProperties& j = scene_.joints[c.joint];
    if (*j.weakeningDistance > 0) c.intact = std::min(c.intact, contact::remainingStrength(j, c.slipDistance));
    // One that separated with its bond (no tensile strength to crack) keeps it through a hairline
    // opening and loses it at an opening of the weakening distance; friction is slip's alone.
    if (!c.closed() && c.bonded) {
      c.opening = std::max(c.opening, openingAfterStep(c) - c.openingAtStart);
      if (c.opening >= *j.weakeningDistance) c.bonded = false;
    }
  }
  recordSolverStatistics();
  stats_.times.update += sw.lap();
}

void Simulation::recordSolverStatistics() {
  stats_.symbolicAnalyses = linearSolver_.symbolicAnalyses();
  stats_.factorisations = linearSolver_.stats().factorisations;
  stats_.factorUpdates = linearSolver_.stats().factorModifications;
  stats_.linearSolves = linearSolver_.stats().solves;
  stats_.cgIterations = linearSolver_.stats().cgIterations;
  stats_.probedSubstitutions = linearSolver_.stats().probedSubstitutions;
  stats_.probeFirstSeconds = linearSolver_.stats().probeFirstSeconds;
  stats_.probeRepeatSeconds = linearSolver_.stats().probeRepeatSeconds;
  stats_.factorEntries = linearSolver_.factorEntries();
  stats_.panelSubstitutions = linearSolver_.panelSubstitutions();
  stats_.panelBytes = linearSolver_.panelBytes();
}

int Simulation::unknownsPerBlock() const { return scene_.settings.rigidBlocks ? 3 : 6; }

bool Simulation::largeSystem() const { return model::largeSystemPath(scene_.settings, unknownsPerBlock() * nActive_); }


std::pair<double, int> Simulation::fastestBlock(const Attempt& a) const {
  double worst = 0;
  int which = -1;
  for (size_t b = 0; b < scene_.blocks.size(); ++b)
    if (active_[b] >= 0) {
      const double d = scene_.blocks[b].maxVertexDisplacement(a.d.segment<6>(6 * active_[b]));
      if (which < 0 || d > worst) worst = d, which = static_cast<int>(b);
    }
  return {worst, which};
}

double Simulation::largestVertexDisplacement(const Attempt& a) const { return fastestBlock(a).first; }

std::string Simulation::fastestBlockNote(const Attempt& a) const {
  // Diagnostics: which block moved most, and where it is, so a log shows what keeps a scene
  // from settling.
  const auto [worst, which] = fastestBlock(a);
  if (which < 0) return "";
  const model::Block& blk = scene_.blocks[static_cast<size_t>(which)];
  std::ostringstream m;
  m << "; most: block \"" << blk.id << "\" at (" << blk.moments.centroid.x() << ", " << blk.moments.centroid.y()
    << ") by " << worst << " m";
  return m.str();
}

bool Simulation::finished() const {
  return time_ >= scene_.settings.duration * (1 - 1e-12);
}

void Simulation::checkDeadline() const {
  throwIfCancelled();  // a step is the cancellation point of a run no longer needed
  if (!deadline_ || std::chrono::steady_clock::now() < *deadline_) return;
  std::ostringstream why;
  why << "stopped at t = " << time_ << " s after " << stats_.steps << " steps"
      << (stats_.steps == 0 ? " (still bringing the scene to equilibrium)" : "")
      << ": the budget analysis.wall_clock_limit (" << scene_.settings.wallClockLimit << " s) is spent";
  throw BudgetExceededError(why.str());
}

double Simulation::nextLanding() const {
  // The first multiple after time_ of the quiet-step cap (grown steps land on it rather than
  // cross it) and of the landing period; the duration instead of a point within round-off of
  // it, and the later of two points that close to each other (no step of a few ulps). A multiple
  // less than a thousandth of Δt ahead counts as reached: time_ summed over the many Δt steps of a
  // record, before steps may grow, drifts from the multiples of Δt by round-off, and a sliver of
  // a step to land on one would only cost a refactorisation.
  const double dt = scene_.settings.timeStep, close = 1e-6 * dt;
  const auto nextMultiple = [&](double period) {
    if (period <= 0) return std::numeric_limits<double>::infinity();
    const double nearest = std::round(time_ / period) * period;
    return nearest > time_ + 1e-3 * dt ? nearest : nearest + period;
  };
  const double a = growing() ? nextMultiple(stepSize_.growthCap()) : std::numeric_limits<double>::infinity();
  const double b = nextMultiple(landingPeriod_);
  double next = std::abs(a - b) <= close ? std::max(a, b) : std::min(a, b);
  if (std::abs(next - scene_.settings.duration) <= close) next = scene_.settings.duration;
  return next;
}

StepRecord Simulation::advance() {
  checkDeadline();
  detectContacts(false);
  const double remaining = scene_.settings.duration - time_;
  double dt = stepSize_.proposal(remaining);
  // Where the step ends if it is not cut: the duration, or the first landing after time_ that
  // it would reach (nextLanding).
  double landsOn = dt == remaining ? scene_.settings.duration : -1;
  if (const double next = nextLanding(); time_ + dt > next - 1e-9 * scene_.settings.timeStep) {
    dt = next - time_;
    landsOn = next;
  }
  const double first = dt;
  const bool grows = growing();
  std::string failure;
  for (int cuts = 0; cuts <= scene_.settings.maxStepCuts; ++cuts) {
    Attempt a = tryStep(dt, Regime::Analysis, cuts >= 2, true);
    if (a.converged) {
      if (a.frozeContacts) ++stats_.frozenSteps;
      for (int i = 0; i < nActive_; ++i) {
        loadWork_ += a.loads[i].dot(a.d.segment<6>(6 * i));
        groundMotionWork_ += a.groundLoads[i].dot(a.d.segment<6>(6 * i));
      }
      commit(a, dt, true);
      // A state that overflowed would fill the history with inf and NaN: stop at the first one.
      for (const model::Block& b : scene_.blocks)
        if (!b.velocity.allFinite() || !b.vertices.front().allFinite()) {
          std::ostringstream msg;
          msg << "the model diverged at t = " << time_ << " s: block \"" << b.id
              << "\" no longer has a finite position and velocity (look at the loads, gravity and initial velocities)";
          throw NonConvergenceError(msg.str());
        }
      time_ = (cuts == 0 && landsOn >= 0) ? landsOn : time_ + dt;
      // A step accepted only by freezing cycling contacts was not cured by its cuts: the next
      // starts from the Δt before them, or a cycle met at rest would shrink Δt step after step
      // without end.
      // Quiet: no state changed after the first solve, no cut, and the blocks crept (Δt grows
      // only where nothing happens within a step).
      if (grows && cuts == 0 && !a.frozeContacts && a.iterations <= 2 &&
          largestVertexDisplacement(a) < 0.02 * stepLimit_)
        stepSize_.acceptedQuiet(dt);
      else
        stepSize_.accepted(dt, cuts > 0 && !a.frozeContacts);
      ++stats_.steps;
      stats_.cuts += cuts;
      stats_.iterations += a.iterations;

      return {time_, dt, a.iterations, cuts};
    }
    failure = a.failure;
    if (log_) log_("t = " + std::to_string(time_) + " s: Δt " + std::to_string(dt) + " s cut: " + a.failure);
    dt = stepSize_.cut(dt);
  }
  std::ostringstream msg;
  msg << "step at t = " << time_ << " s not accepted after " << scene_.settings.maxStepCuts
      << " time-step cuts (Δt tried from " << first << " s down to " << dt / scene_.settings.stepCutFactor
      << " s); last failure: " << failure;
  throw NonConvergenceError(msg.str());
}

EnergyBudget Simulation::energy() const {
  EnergyBudget e = storedEnergy(scene_, mass_, elasticity_, contacts_.contacts(), penalty_, [&](const Contact& c) {
    return std::pair{normalStiffness(c), shearStiffness(c)};
  });
  e.loadWork = loadWork_;
  e.groundMotionWork = groundMotionWork_;
  return e;
}

Vec2 Simulation::monitorVelocity(int m) const {
  const model::Monitor& mon = scene_.monitors[m];
  const model::Block& b = scene_.blocks[mon.point.block];
  return b.tAt(mon.point.current) * b.velocity;
}

void runAnalysis(Simulation& sim, const StepObserver& observe, const HeldEquilibrium* shared) {
  const model::AnalysisSettings& st = sim.scene().settings;
  const double maxSteps = st.maxSteps > 0 ? st.maxSteps : 100 * st.duration / st.timeStep + 1000;
  sim.bringToEquilibrium(shared);
  observe(sim, StepRecord{});
  while (!sim.finished()) {
    std::ostringstream why;
    if (sim.statistics().steps >= maxSteps) {
      why << "stopped at t = " << sim.time() << " s after " << sim.statistics().steps << " steps, the budget "
          << (st.maxSteps > 0 ? "analysis.max_steps" : "(100 × duration/Δt + 1000: Δt has collapsed)")
          << "; raise analysis.max_steps or look at the time-step cuts (--verbose)";
      throw BudgetExceededError(why.str());
    }
    observe(sim, sim.advance());
  }
}

}  // namespace ddaslope::solver

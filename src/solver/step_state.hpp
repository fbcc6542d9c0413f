#pragma once
// What one attempt at a step (Simulation::tryStep) carries from stage to stage: the contacts it
// judges, K's terms and b, the solver's path, and the bookkeeping of the open-close iteration.
// Private to src/solver (step.cpp and open_close.cpp).
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "ddaslope/assembly/block_sparse_matrix.hpp"
#include "ddaslope/assembly/contact_terms.hpp"
#include "ddaslope/assembly/system_terms.hpp"
#include "ddaslope/solver/factor_springs.hpp"
#include "ddaslope/solver/linear_solver.hpp"
#include "ddaslope/solver/simulation.hpp"
#include "ddaslope/solver/state_cycle.hpp"
#include "stopwatch.hpp"

namespace ddaslope::solver {

// The step's contact kinematics, edited in place by one attempt and restored when it ends. A
// contact that locks within the attempt re-anchors its shear spring (its kinematics change); a
// cut Δt retries from the step's own. A copy of them all per attempt would move every contact's
// kinematics (megabytes in a large wall) for the few contacts that lock.
class AttemptKinematics {
 public:
  explicit AttemptKinematics(std::vector<assembly::ContactKinematics>& step) : step_(step) {}
  AttemptKinematics(const AttemptKinematics&) = delete;
  AttemptKinematics& operator=(const AttemptKinematics&) = delete;
  ~AttemptKinematics() {
    // Newest first: a contact replaced twice gets its step value back.
    for (auto it = saved_.rbegin(); it != saved_.rend(); ++it) step_[it->first] = it->second;
  }
  const assembly::ContactKinematics& operator[](size_t q) const { return step_[q]; }
  void replace(size_t q, const assembly::ContactKinematics& k) {
    saved_.emplace_back(q, step_[q]);
    step_[q] = k;
  }

 private:
  std::vector<assembly::ContactKinematics>& step_;
  std::vector<std::pair<size_t, assembly::ContactKinematics>> saved_;
};

/// K kept as its terms: products from the terms, entries assembled into `matrix` only when a
/// factorisation asks for them (once per change of K).
class TermsOnDemand final : public SystemOperator {
 public:
  TermsOnDemand(const assembly::SystemTerms& terms, assembly::BlockSparseMatrix& matrix)
      : terms_(terms), matrix_(matrix) {}
  void changed() { assembled_ = false; }
  void multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const override { terms_.multiply(x, y); }
  const assembly::BlockSparseMatrix& matrix() const override {
    if (!assembled_) terms_.assembleInto(matrix_);
    assembled_ = true;
    return matrix_;
  }
  long patternVersion() const override { return matrix_.patternVersion(); }

 private:
  const assembly::SystemTerms& terms_;
  assembly::BlockSparseMatrix& matrix_;
  mutable bool assembled_ = false;
};

struct Simulation::StepState {
  /// An attempt at a step of `dt` in `regime` from the step's contacts (copied: the attempt
  /// judges its own) and kinematics (edited in place, restored when the attempt ends).
  /// `freezeCycling`, `holdSmallViolations`: see Simulation::tryStep.
  StepState(double dt, Regime regime, bool freezeCycling, bool holdSmallViolations, const std::vector<int>& active, const std::vector<contact::Contact>& contacts,
            std::vector<assembly::ContactKinematics>& kinematics, assembly::BlockSparseMatrix& matrix)
      : dt(dt),
        regime(regime),
        freezeCycling(freezeCycling),
        holdSmallViolations(holdSmallViolations),
        active(active),
        kin(kinematics),
        lazySystem(terms, matrix),
        assembledSystem(matrix) {
    a.contacts = contacts;
    flips.assign(a.contacts.size(), 0);
  }
  // K's terms point into the block terms and the kinematics held here.
  StepState(const StepState&) = delete;
  StepState& operator=(const StepState&) = delete;

  /// The active block indices of a contact's vertex and edge block (−1: fixed or held).
  std::pair<int, int> ends(const contact::Contact& c) const {
    return std::pair{active[c.key().vertexBlock], active[c.key().edgeBlock]};
  }
  /// Adds s·v to b (v: the vertex block's six entries, then the edge block's), and its size to
  /// the round-off scale of b where the solve stops at round-off.
  void addTerm(const contact::Contact& c, double s, const Vec12& v) {
    const auto [i, j] = ends(c);
    addTerm(i, j, s, v);
  }
  /// The same between active blocks i and j (−1: fixed or held).
  void addTerm(int i, int j, double s, const Vec12& v) {
    if (i >= 0) rhs.segment<6>(6 * i) += s * v.head<6>();
    if (j >= 0) rhs.segment<6>(6 * j) += s * v.tail<6>();
    if (!residualAtRoundOff) return;
    if (i >= 0) magnitude.segment<6>(6 * i) += std::abs(s) * v.head<6>().cwiseAbs();
    if (j >= 0) magnitude.segment<6>(6 * j) += std::abs(s) * v.tail<6>().cwiseAbs();
  }
  /// The solution's entries for the two blocks of contact c (zero for a fixed one).
  Vec12 gather(const contact::Contact& c) const {
    const auto [i, j] = ends(c);
    Vec12 d = Vec12::Zero();
    if (i >= 0) d.head<6>() = a.d.segment<6>(6 * i);
    if (j >= 0) d.tail<6>() = a.d.segment<6>(6 * j);
    return d;
  }
  /// The solution's entries for active blocks i and j (zero for −1).
  Vec12 gather(int i, int j) const {
    Vec12 d = Vec12::Zero();
    if (i >= 0) d.head<6>() = a.d.segment<6>(6 * i);
    if (j >= 0) d.tail<6>() = a.d.segment<6>(6 * j);
    return d;
  }
  /// The springs the closed contacts put into K now (what a factor that follows them holds), with
  /// their normal and shear stiffness from `stiffness(contact)`.
  template <class Stiffness>
  std::vector<ContactSprings> springs(const Stiffness& stiffness) const {
    std::vector<ContactSprings> out;
    out.reserve(a.contacts.size());
    for (size_t q = 0; q < a.contacts.size(); ++q) {
      const contact::Contact& c = a.contacts[q];
      if (!c.closed()) continue;
      const auto [i, j] = ends(c);
      const auto [kn, ks] = stiffness(c);
      ContactSprings sp{c.key(), i, j, kn, 0, kin[q].normal, Vec12::Zero()};
      if (c.state == contact::ContactState::Locked) sp.shearK = ks, sp.shear = kin[q].shearLocked;
      out.push_back(sp);
    }
    return out;
  }
  /// K as the solver sees it: kept as its terms on the large-system path, assembled otherwise.
  const SystemOperator& system() const {
    return followFactor ? static_cast<const SystemOperator&>(lazySystem) : assembledSystem;
  }

  const double dt;
  const Regime regime;
  const bool freezeCycling, holdSmallViolations;
  const std::vector<int>& active;
  Stopwatch sw;
  Attempt a;
  AttemptKinematics kin;

  // The blocks' terms of K and b (assembleBlockTerms), and b's round-off scale.
  std::vector<Mat6> blockK;
  std::vector<Vec6> blockF, blockMagnitude;

  // The solver's path (configureSolver).
  bool followFactor = false;        ///< the factor follows the contact springs (analysis.factor_updates)
  bool residualAtRoundOff = false;  ///< solves stop at the round-off of b's terms
  FactorBlockTerms blockTerms;      ///< the block terms of this step's K
  assembly::SystemTerms terms;
  TermsOnDemand lazySystem;
  const AssembledSystem assembledSystem;

  // One iterate: b and its round-off scale, the friction of the sliding contacts, the springs
  // switched on and off since the factor was made.
  Eigen::VectorXd rhs, magnitude;
  std::vector<double> friction;
  std::vector<SparseCholesky::Column> added, removed;
  bool stiffnessChanged = true;  ///< K must be rebuilt: the last judgement changed a state
  bool nextSolveStrict = false;  ///< the last judgement changed none: solve to the full target
  bool solvedStrictly = false;   ///< the last solution met the full target

  // The supports: their elongation vector on the step's start geometry (assembly/support_terms),
  // their active blocks, and their elongation at the step's start.
  std::vector<Vec12> supportV;
  std::vector<std::pair<int, int>> supportEnds;
  std::vector<double> supportElongation0;

  // Judging (open_close.cpp).
  contact::StateTolerance stateTolerance{};
  std::vector<int> flips;  ///< state changes of each contact within the attempt
  StateCycleDetector cycles;
};

/// What the judgement of one iterate changed.
struct Simulation::IterateChanges {
  bool states = false;           ///< a contact's state or slide direction
  bool bonds = false;            ///< a contact's bond
  bool frictionSettled = false;  ///< the sliding contacts' normal forces have settled
};

}  // namespace ddaslope::solver

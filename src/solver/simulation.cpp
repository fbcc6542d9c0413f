#include "ddaslope/solver/simulation.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <map>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>

#include "ddaslope/assembly/block_terms.hpp"
#include "ddaslope/assembly/system_terms.hpp"
#include "ddaslope/assembly/water_terms.hpp"
#include "ddaslope/contact/broad_phase.hpp"
#include "ddaslope/contact/contact_law.hpp"
#include "ddaslope/contact/narrow_phase.hpp"
#include "ddaslope/core/block_order.hpp"
#include "ddaslope/core/errors.hpp"
#include "ddaslope/core/parallel.hpp"
#include "ddaslope/core/prefetch.hpp"
#include "ddaslope/solver/state_cycle.hpp"

namespace ddaslope::solver {

using assembly::ContactKinematics;
using contact::Contact;
using contact::ContactState;

namespace {

/// Springs changed at once beyond which a new factorisation is cheaper than following them. Each
/// changed spring is one column of update/downdate; on a large wall about a thousand columns cost
/// one factorisation, and a limit a little below that break-even settled the wall fastest
/// (docs/performance.md, "Measurements behind the solver's constants").
constexpr size_t kMaxFactorModificationRank = 800;
/// CG iterations with a stale factor before a large system refactorises (see tryStep).
constexpr int kLargeSystemCgIterations = 4;
// Relative residual to which a large system solves while its contact states change (tryStep; the
// states are judged again on the next solution): one CG iteration with a factor that follows the
// states reaches it, against two for the full 1e-12.
constexpr double kJudgingResidual = 1e-8;
/// Stage 3's budget, in steps per analysis.equilibrium_max_steps (200 by default: 4000 steps).
constexpr int kSettlingStepsPerEquilibriumStep = 20;

class Stopwatch {
 public:
  double lap() {
    const auto now = std::chrono::steady_clock::now();
    const double s = std::chrono::duration<double>(now - last_).count();
    last_ = now;
    return s;
  }

 private:
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};


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
}  // namespace

Simulation::Simulation(model::Scene scene)
    : scene_(std::move(scene)),
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
  // Shi's step limit g2·w0 scales with the model. In a kilometre slope with a 15 m wedge it
  // exceeds the wedge, and the contact search (2.5 times the limit) then pairs corners farther
  // apart than the blocks are wide: contacts metres deep appear from nowhere (the Vajont
  // run-out ejected its toe wedge so). The limit is therefore also held to a tenth of the
  // thinnest free block's thickness 2S/perimeter (half the side of a square).
  stepLimit_ = scene_.settings.maxDisplacementRatio * w0_;
  for (const model::Block& b : scene_.blocks)
    if (!b.fixed) stepLimit_ = std::min(stepLimit_, 0.1 * 2 * b.moments.area / geometry::perimeter(b.vertices));
  searchDistance_ = 2.5 * stepLimit_;
  penalty_ = scene_.normalPenalty();
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

void Simulation::detectContacts(bool initial) {
  Stopwatch sw;
  std::vector<geometry::Aabb> boxes;
  std::vector<bool> fixed;
  for (const model::Block& b : scene_.blocks) {
    boxes.push_back(geometry::boundingBox(b.vertices));
    fixed.push_back(b.fixed);
  }
  const auto pairs = contact::findCandidatePairs(boxes, fixed, searchDistance_, sweepOrder_);
  stats_.times.broadPhase += sw.lap();

  const contact::NarrowPhaseSettings nps{searchDistance_,
                                         degToRad(scene_.settings.edgeParallelToleranceDeg)};
  const auto known = [this](const contact::ContactKey& k) { return contacts_.contains(k); };
  // The pair cache reuses the decisions of pairs whose blocks have barely moved; the candidates
  // are those a search of every pair gives, bit for bit.
  contact::PairCache::Polygons polygons;
  if (pairCacheOn_) {
    polygons.reserve(scene_.blocks.size());
    for (const model::Block& b : scene_.blocks) polygons.push_back(&b.vertices);
    pairCache_.prepare(polygons, pairs, nps, contacts_.keyVersion());
    stats_.pairsReused += pairCache_.reused();
    stats_.pairsSearched += pairCache_.searched();
  } else {
    stats_.pairsSearched += static_cast<long>(pairs.size());
  }
  // Each thread searches a contiguous run of the pairs; joined in order, the candidates are the
  // serial loop's.
  std::vector<std::vector<contact::ContactCandidate>> found(static_cast<size_t>(threads_));
  const int chunks = parallelChunks(static_cast<int>(pairs.size()), threads_, [&](int begin, int end, int chunk) {
    for (int k = begin; k < end; ++k) {
      const contact::BlockPair& p = pairs[static_cast<size_t>(k)];
      if (pairCacheOn_)
        pairCache_.find(k, polygons, nps, known, found[static_cast<size_t>(chunk)]);
      else
        contact::findContacts(p.a, scene_.blocks[p.a].vertices, p.b, scene_.blocks[p.b].vertices, nps, known,
                              found[static_cast<size_t>(chunk)]);
    }
  });
  std::vector<contact::ContactCandidate> candidates = std::move(found[0]);
  for (int k = 1; k < chunks; ++k)
    candidates.insert(candidates.end(), found[static_cast<size_t>(k)].begin(), found[static_cast<size_t>(k)].end());
  std::vector<int> joints;
  std::vector<char> bondedIfNew;
  joints.reserve(candidates.size());
  for (const auto& c : candidates) {
    joints.push_back(scene_.jointBetween(c.key.vertexBlock, c.key.edgeBlock));
    bondedIfNew.push_back(scene_.joints[joints.back()].bond == model::BondPolicy::Always);
  }
  contacts_.update(std::move(candidates), joints, bondedIfNew);
  if (pairCacheOn_) pairCache_.finish(contacts_.keyVersion());

  if (initial) {
    // Contacts touching at the start are closed and intact (bonded); the spring's zero is at
    // the initial gap, so that coordinates rounded in the case file do not preload it.
    const double tol = scene_.settings.initialContactTolerance * w0_;
    for (Contact& c : contacts_.contacts()) {
      if (c.geometry.gap > tol) continue;
      c.state = ContactState::Locked;
      c.bonded = scene_.joints[c.joint].bond != model::BondPolicy::None;
      c.lockRatio = c.geometry.ratio;
      c.normalOffset = c.geometry.gap >= -tol ? c.geometry.gap : 0.0;
    }
  }
  // The halves pair up as they did while the keys and their paired edges stand.
  if (contacts_.pairingVersion() != partnerVersion_) {
    pairEdgeHalves();
    partnerVersion_ = contacts_.pairingVersion();
  }
  const auto& cs = contacts_.contacts();
  kinematics_.resize(cs.size());
  parallelFor(static_cast<int>(cs.size()), threads_, [&](int q) {
    const Contact& c = cs[static_cast<size_t>(q)];
    assembly::lineariseInto(scene_.blocks[c.key().vertexBlock], scene_.blocks[c.key().edgeBlock], c,
                            kinematics_[static_cast<size_t>(q)]);
  });
  stats_.maxContacts = std::max(stats_.maxContacts, static_cast<int>(contacts_.contacts().size()));
  stats_.times.contacts += sw.lap();
}

void Simulation::pairEdgeHalves() {
  // The two end contacts of one edge-to-edge contact share the pair of edges that lie against
  // each other: (vertex block, its paired edge) and (edge block, contact edge).
  const auto& cs = contacts_.contacts();
  partner_.assign(cs.size(), -1);
  // Halves sorted by their pair of edges (then by index): each edge pair's contacts are
  // neighbours, and exactly two of them make one edge-to-edge contact.
  // Ordered by the lower block of the pair, then within it (core/block_order.hpp).
  using Half = std::pair<std::array<int, 4>, int>;
  std::vector<Half> keyed;
  keyed.reserve(cs.size());
  int blocks = 0;
  for (size_t q = 0; q < cs.size(); ++q) {
    const Contact& c = cs[q];
    if (c.geometry.pairedEdge < 0) continue;
    std::array<int, 2> a{c.key().vertexBlock, c.geometry.pairedEdge}, b{c.key().edgeBlock, c.key().edge};
    if (b < a) std::swap(a, b);
    keyed.push_back({{a[0], a[1], b[0], b[1]}, static_cast<int>(q)});
    blocks = std::max(blocks, a[0] + 1);
  }
  const std::vector<Half> halves =
      sortedByBlock(keyed, blocks, [](const Half& h) { return h.first[0]; }, std::less<Half>());
  for (size_t k = 0; k < halves.size();) {
    size_t end = k + 1;
    while (end < halves.size() && halves[end].first == halves[k].first) ++end;
    if (end - k == 2) {
      partner_[halves[k].second] = halves[k + 1].second;
      partner_[halves[k + 1].second] = halves[k].second;
    }
    k = end;
  }
}

std::vector<contact::ContactJudgement> Simulation::judgeContacts(
    const std::vector<Contact>& cs, const std::vector<contact::ContactResponse>& response, Regime regime,
    const contact::StateTolerance& tol) const {
  std::vector<contact::ContactJudgement> out(cs.size());
  const bool edge = scene_.settings.contactTreatment == model::ContactTreatment::Edge;
  // A pair is judged at its first half, which reads its second half's contact and response from
  // further on in the arrays (a neighbouring block's contacts): asked for kPartnerAhead contacts
  // early, so that the wait for memory overlaps the judgements in between.
  constexpr size_t kPartnerAhead = 16;
  const bool pairs = edge && regime != Regime::HeldEquilibrium;
  for (size_t q = 0; q < cs.size(); ++q) {
    if (pairs && q + kPartnerAhead < cs.size()) {
      const int ahead = partner_[q + kPartnerAhead];
      if (ahead > static_cast<int>(q + kPartnerAhead)) {
        prefetchBytes(&cs[static_cast<size_t>(ahead)], sizeof(Contact));
        prefetchBytes(&response[static_cast<size_t>(ahead)], sizeof(contact::ContactResponse));
      }
    }
    const Contact& c = cs[q];
    if (regime == Regime::HeldEquilibrium) {
      out[q] = contact::judgeHeldContact(c.state, c.bonded, response[q], tol);
      continue;
    }
    const int p = partner_[q];
    if (!edge || p < 0) {
      out[q] = contact::judgeVertexContact(c.state, c.slideDirection, c.bonded, response[q], strengthOf(c), tol);
      continue;
    }
    if (p < static_cast<int>(q)) continue;  // judged with its partner
    const Contact& o = cs[p];
    const auto [j1, j2] = contact::judgeEdgeContact({c.state, c.slideDirection, c.bonded},
                                                    {o.state, o.slideDirection, o.bonded}, response[q],
                                                    response[p], strengthOf(c), strengthOf(o), tol);
    out[q] = j1;
    out[p] = j2;
  }
  return out;
}

double Simulation::edgeLength(const Contact& c) const {
  const auto& v = scene_.blocks[c.key().edgeBlock].vertices;
  return (v[(c.key().edge + 1) % v.size()] - v[c.key().edge]).norm();
}

contact::ContactStrength Simulation::strengthOf(const Contact& c) const {
  // Original DDA: each vertex-to-edge half of an edge-to-edge contact carries c·L/2.
  return contact::contactStrength(jointStrength_[c.joint], c.intact, c.geometry.overlap / 2);
}

double Simulation::slidingResistance(const Contact& c) const {
  return contact::shearStrength(c.bonded, c.normalForce, strengthOf(c));
}

std::vector<double> Simulation::slidingFriction(const std::vector<Contact>& cs) const {
  // The ends of a sliding edge share its friction equally. With each end's own N tan φ the friction
  // follows the difference of the normal forces, which the block's rotation and shear strain set;
  // that difference stretches a deformable block along the edge, and Poisson's ratio turns the
  // stretch into a normal squeeze that changes the normal forces again. This non-symmetric coupling
  // is a flutter instability of steady sliding, which walks a block down a slope it should creep
  // along (docs/accuracy.md, "Strain damping and friction flutter"). Shared, the friction depends
  // on the sum of the normal forces only and the loop is cut; both forces lie on the edge, so a
  // rigid block moves the same either way, and only a deformable block's stretch along the edge,
  // ∫ x τ dx, loses the friction gradient. Only deformable blocks under the edge treatment share,
  // where the pair is one contact judged against the whole edge's strength: the vertex treatment
  // (original DDA) judges each end against its own, which must then be the friction it meets.
  // Rigid blocks do not flutter (no strain for the loop to run through) and keep per-end friction:
  // a pair that sticks keeps the shear it slid with, and a shared half on a heel that then lifts
  // would drop half the edge's friction at once.
  std::vector<double> friction(cs.size(), 0.0);
  for (size_t q = 0; q < cs.size(); ++q)
    if (cs[q].state == ContactState::Sliding) friction[q] = slidingResistance(cs[q]);
  if (scene_.settings.contactTreatment != model::ContactTreatment::Edge || scene_.settings.rigidBlocks)
    return friction;
  for (size_t q = 0; q < cs.size(); ++q) {
    const int p = partner_[q];
    if (p <= static_cast<int>(q) || cs[q].state != ContactState::Sliding) continue;
    const Contact& o = cs[p];
    if (o.state != ContactState::Sliding || o.slideDirection != cs[q].slideDirection) continue;
    friction[q] = friction[p] = 0.5 * (friction[q] + friction[p]);
  }
  return friction;
}

void Simulation::assembleBlockTerms(double dt, Regime regime, std::vector<Mat6>& k, std::vector<Vec6>& f,
                                    std::vector<Vec6>& loads, std::vector<Vec6>& magnitude,
                                    std::vector<Vec6>* groundLoads) const {
  k.assign(nActive_, Mat6::Zero());
  f.assign(nActive_, Vec6::Zero());
  loads.assign(nActive_, Vec6::Zero());
  magnitude.assign(nActive_, Vec6::Zero());
  const bool carryVelocity = (regime == Regime::Analysis || regime == Regime::Settling) &&
                             scene_.settings.mode == model::AnalysisMode::Dynamic;
  // Water (and any load history) at the end of the step; equilibrium is found at t = 0.
  const model::WaterTable water = scene_.water.at(regime == Regime::Analysis ? time_ + dt : 0.0);
  // Seismic body acceleration (model/seismic.hpp): the pseudo-static part always; in the
  // analysis, the ground motion's mean over the step, so that the step receives exactly the
  // record's impulse however the record is sampled. A load, so that its work enters the budget.
  Vec2 inertial = scene_.seismic.pseudoStatic(scene_.gravity);
  Vec2 recordInertial = Vec2::Zero();
  if (regime == Regime::Analysis && scene_.seismic.ground.active())
    recordInertial = -model::SeismicLoad::toModelFrame(scene_.seismic.ground.meanOver(time_, time_ + dt), scene_.gravity);
  inertial += recordInertial;
  if (groundLoads) groundLoads->assign(nActive_, Vec6::Zero());
  const bool shaking = inertial.x() != 0 || inertial.y() != 0;
  for (size_t b = 0; b < scene_.blocks.size(); ++b) {
    const int i = active_[b];
    if (i < 0) continue;
    const model::Block& blk = scene_.blocks[b];
    // ρ·S₀/S: a block's mass is its initial one however its area strains (Shi's ρ·S is not).
    const double density = mass_[b] / blk.moments.area;
    const Mat6 mass = density * assembly::unitMassMatrix(blk.moments);
    // Newmark β = 1/2, γ = 1 (Shi): K += 2M/Δt², F += 2M V/Δt.
    const Mat6 elastic = assembly::elasticStiffness(blk.moments.area, elasticity_[blk.material]);
    k[i] = elastic + (2 / (dt * dt)) * mass;
    // Kelvin–Voigt damping of the strain rates, σ_v = β E ε̇, at the step's mean rate D/Δt: it
    // dissipates d·(β/Δt)K_e·d ≥ 0 in every step and leaves rest and rigid motion alone.
    if (carryVelocity && strainRetardation_[b] > 0)
      k[i] += (strainRetardation_[b] / dt) * elastic;
    const Vec6 body = assembly::bodyForce(blk.moments.area, density * scene_.gravity);
    const Vec6 stress = assembly::initialStressForce(blk.moments.area, blk.stress);
    f[i] = body + stress;
    magnitude[i] = body.cwiseAbs() + stress.cwiseAbs();
    if (carryVelocity) {
      const Vec6 inertia = (2 / dt) * mass * blk.velocity;
      f[i] += inertia;
      magnitude[i] += inertia.cwiseAbs();
    }
    if (water.active()) loads[i] += assembly::waterForce(blk, water);
    if (shaking) loads[i] += assembly::bodyForce(blk.moments.area, density * inertial);
    if (groundLoads) (*groundLoads)[i] = assembly::bodyForce(blk.moments.area, density * recordInertial);
  }
  for (const model::PointLoad& l : scene_.pointLoads) {
    const int i = active_[l.point.block];
    // The load at the end of the step (implicit, like every other term).
    if (i >= 0)
      loads[i] += assembly::pointForce(scene_.blocks[l.point.block].moments.centroid, l.point.current,
                                       l.at(regime == Regime::Analysis ? time_ + dt : 0.0));
  }
  for (int i = 0; i < nActive_; ++i) f[i] += loads[i], magnitude[i] += loads[i].cwiseAbs();
  for (const model::FixedPoint& fp : scene_.fixedPoints) {
    const int i = active_[fp.point.block];
    if (i < 0) continue;
    const Mat26 t = scene_.blocks[fp.point.block].tAt(fp.point.current);
    k[i] += penalty_ * t.transpose() * t;
    const Vec6 pull = penalty_ * t.transpose() * (fp.point.initial - fp.point.current);
    f[i] += pull;
    magnitude[i] += pull.cwiseAbs();
  }
}

Simulation::Attempt Simulation::tryStep(double dt, Regime regime, bool freezeCycling, bool holdSmallViolations) {
  Stopwatch sw;
  Attempt a;
  a.contacts = contacts_.contacts();
  AttemptKinematics kin(kinematics_);
  const double ps = penalty_ * scene_.settings.shearPenaltyRatio;

  std::vector<std::pair<int, int>> couplings;
  for (const Contact& c : a.contacts) {
    const int i = active_[c.key().vertexBlock], j = active_[c.key().edgeBlock];
    if (i >= 0 && j >= 0) couplings.emplace_back(i, j);
  }
  const int dof = scene_.settings.rigidBlocks ? 3 : 6;
  // The same contacts in the same order couple the same blocks: the pattern stands, and the
  // sort that normalises the list (a millisecond at 2000 blocks) is skipped.
  if (couplings != lastCouplings_ || matrix_.patternVersion() == 0 || matrix_.blockSize() != dof ||
      matrix_.size() != dof * nActive_) {
    lastCouplings_ = couplings;
    couplings = assembly::BlockSparseMatrix::normalise(std::move(couplings));
    if (!matrix_.hasPattern(nActive_, couplings, dof)) matrix_.setPattern(nActive_, couplings, dof);
  }

  std::vector<Mat6> blockK;
  std::vector<Vec6> blockF, blockMagnitude;
  assembleBlockTerms(dt, regime, blockK, blockF, a.loads, blockMagnitude, &a.groundLoads);
  stats_.times.assembly += sw.lap();

  const auto ends = [&](const Contact& c) {
    return std::pair{active_[c.key().vertexBlock], active_[c.key().edgeBlock]};
  };
  Eigen::VectorXd rhs(6 * nActive_);
  const auto addForce = [&](const Contact& c, double s, const Vec12& v) {
    const auto [i, j] = ends(c);
    if (i >= 0) rhs.segment<6>(6 * i) += s * v.head<6>();
    if (j >= 0) rhs.segment<6>(6 * j) += s * v.tail<6>();
  };
  const auto gather = [&](const Contact& c) {
    const auto [i, j] = ends(c);
    Vec12 d = Vec12::Zero();
    if (i >= 0) d.head<6>() = a.d.segment<6>(6 * i);
    if (j >= 0) d.tail<6>() = a.d.segment<6>(6 * j);
    return d;
  };

  // Last resort against cycling (load passed back and forth between coupled contacts): when
  // allowed, a contact that changed state kFlipsBeforeFreeze times in this step keeps its state
  // for the rest of it; an open one may still close. Steps accepted so are counted.
  constexpr int kFlipsBeforeFreeze = 4;
  // Sudden loading (gravity switched on at step 1) sets the blocks ringing: a wave crosses a
  // 0.5 m brick in 0.25 ms, so within a 1 ms step a lightly loaded contact (a brick corner at a
  // T-junction) is closed part of the time and open part of it, and no single state satisfies
  // its law; the states cycle (open → locked → sliding → open, period 2-4) and cutting Δt does
  // not end it. Holding such a contact in its state is an error in its law; it is accepted
  // early (before any cut) only while that error is below this fraction of the largest contact
  // force of the iterate (violation() below). (Shi's DDA keeps every contact closed up to a
  // separation of 2e-7·w0, so that a contact can carry a tension of the order of the largest
  // contact force: docs/performance.md, "Known limitations".) A hold must not anchor a block
  // either: a locked contact kept closed in tension counts its whole shear (its strength is nil),
  // or a block sliding on a plane is held by its unloaded heel and topples (BenchmarkA7). Contacts
  // whose law a hold would break by more still cut Δt, and are frozen unconditionally only after
  // two cuts.
  constexpr double kHeldViolation = 1e-2;
  std::vector<int> flips(a.contacts.size(), 0);
  // Round-off guard: the larger of the penalty force of a round-off displacement and 1e-9 of the
  // largest contact force of the last solve (forces are only known to that relative precision).
  // The displacement stays below 1e-3 of the lightest block's own penetration under its weight,
  // or a millimetre block in a 10 m model could never change state.
  const double noise = std::min(scene_.settings.contactStateTolerance * w0_, lightestPenetration_);
  double largestForce = 0;
  for (const Contact& c : a.contacts) largestForce = std::max(largestForce, std::abs(c.normalForce));
  const contact::StateTolerance stateTolerance{std::max(penalty_ * noise, 1e-9 * largestForce), noise};
  bool stiffnessChanged = true;
  bool nextSolveStrict = false;
  StateCycleDetector cycles;
  // A large system's factor follows the contact state changes by low-rank update/downdate
  // (solver/factor_springs.hpp) instead of being redone; small systems refactorise, which is
  // cheap there and keeps the round-off that the shipped cases' documented results carry.
  const bool followFactor = factorFollowing_ && largeSystem();
  // Nested dissection orders a large wall's factor with less fill than AMD and a shallower tree,
  // whose paths each update/downdate of a spring walks. Small systems keep AMD, and their round-off.
  linearSolver_.setOrdering(followFactor ? FillOrdering::NestedDissection : FillOrdering::MinimumDegree);
  linearSolver_.setSimplicialSolves(followFactor);
  linearSolver_.setPanelSolves(followFactor && panelSolves_);
  assembly::SystemTerms terms;
  TermsOnDemand lazySystem(terms, matrix_);
  const AssembledSystem assembledSystem(matrix_);
  const SystemOperator& system = followFactor ? static_cast<const SystemOperator&>(lazySystem) : assembledSystem;
  // The right-hand side is a sum of forces that nearly cancel in a scene at rest (weights against
  // contact preloads and stresses: in a large wall the terms are some eight orders of magnitude
  // above their sum), so it is known only to the round-off of those terms. A large system's solve
  // stops there instead of at a residual 1e-12 of the sum, which only conjugate-gradient
  // iterations on round-off would reach. Small systems keep the strict rule and their results.
  const bool residualAtRoundOff = followFactor;
  // With that looser target a factor far from K (an equilibrium's) would converge within the
  // small systems' budget of CG iterations, which it misses at the strict target (and is then
  // redone), and stay in use at several iterations per step. A near-exact factor (one that follows
  // the states) converges in 0-3: a large system redoes a factor that needs more than 4.
  linearSolver_.setMaxIterations(followFactor ? kLargeSystemCgIterations : LinearSolverSettings{}.maxIterations);
  // A factor made for other block terms (the equilibrium's static steps, without strain damping,
  // at the analysis Δt) would stay within CG's budget at a few iterations per step for the whole
  // run: it is redone at once instead.
  const FactorBlockTerms blockTerms{dt, (regime == Regime::Analysis || regime == Regime::Settling) &&
                                            scene_.settings.mode == model::AnalysisMode::Dynamic};
  if (followFactor && linearSolver_.hasFactor() && !blockTerms.sameAs(factorBlockTerms_)) {
    linearSolver_.discardFactor();
    factorSprings_.invalidate();
  }
  Eigen::VectorXd magnitude;
  const auto addMagnitude = [&](const Contact& c, double s, const Vec12& v) {
    const auto [i, j] = ends(c);
    if (i >= 0) magnitude.segment<6>(6 * i) += std::abs(s) * v.head<6>().cwiseAbs();
    if (j >= 0) magnitude.segment<6>(6 * j) += std::abs(s) * v.tail<6>().cwiseAbs();
  };
  std::vector<SparseCholesky::Column> added, removed;
  const auto contactSprings = [&] {
    std::vector<ContactSprings> out;
    out.reserve(a.contacts.size());
    for (size_t q = 0; q < a.contacts.size(); ++q) {
      const Contact& c = a.contacts[q];
      if (!c.closed()) continue;
      const auto [i, j] = ends(c);
      ContactSprings sp{c.key(), i, j, penalty_, 0, kin[q].normal, Vec12::Zero()};
      if (c.state == ContactState::Locked) sp.shearK = ps, sp.shear = kin[q].shearLocked;
      out.push_back(sp);
    }
    return out;
  };
  const int maxIterations = std::max(1, scene_.settings.openCloseMaxIterations);
  for (a.iterations = 1; a.iterations <= maxIterations; ++a.iterations) {
    sw.lap();
    if (stiffnessChanged) terms.reset(dof, blockK);
    for (int i = 0; i < nActive_; ++i) rhs.segment<6>(6 * i) = blockF[i];
    if (residualAtRoundOff) {
      magnitude.resize(rhs.size());
      for (int i = 0; i < nActive_; ++i) magnitude.segment<6>(6 * i) = blockMagnitude[i];
    }
    const auto addTerm = [&](const Contact& c, double s, const Vec12& v) {
      addForce(c, s, v);
      if (residualAtRoundOff) addMagnitude(c, s, v);
    };
    // K's springs and b's contact terms in one pass over the contacts (a large scene's contacts
    // are read from memory, not the cache), each summed in the contacts' order.
    const std::vector<double> friction = slidingFriction(a.contacts);
    for (size_t q = 0; q < a.contacts.size(); ++q) {
      const Contact& c = a.contacts[q];
      if (!c.closed()) continue;
      if (stiffnessChanged) {
        const auto [i, j] = ends(c);
        terms.addSpring(i, j, penalty_, kin[q].normal);
        if (c.state == ContactState::Locked) terms.addSpring(i, j, ps, kin[q].shearLocked);
      }
      addTerm(c, -penalty_ * kin[q].penetration0, kin[q].normal);
      if (c.state == ContactState::Locked) {
        addTerm(c, -ps * kin[q].shearLocked0, kin[q].shearLocked);
      } else {
        // Friction N tanφ (plus c·L while a softening bond lasts) opposite to the slip, as a pair
        // of point loads: K stays symmetric.
        addTerm(c, -c.slideDirection * friction[q], kin[q].shearStep());
      }
    }
    // A large system assembles K only if a factorisation asks for it; a small one at once, and
    // multiplies by the assembled K, whose round-off the shipped cases' documented results carry.
    if (stiffnessChanged) {
      if (followFactor)
        lazySystem.changed();
      else
        terms.assembleInto(matrix_);
    }
    stats_.times.assembly += sw.lap();
    if (followFactor && stiffnessChanged && factorSprings_.valid() && !factorSprings_.holdsSame(a.contacts)) {
      factorSprings_.changes(contactSprings(), matrix_.blockSize(), added, removed);
      const size_t rank = added.size() + removed.size();
      if (rank > kMaxFactorModificationRank || !linearSolver_.modifyFactor(matrix_, added, removed))
        factorSprings_.invalidate();
      else
        stats_.factorColumns += static_cast<long>(rank);
      stats_.times.factorUpdate += sw.lap();
    }
    if (stiffnessChanged) linearSolver_.matrixChanged();
    const long factorisationsBefore = linearSolver_.stats().factorisations;
    // 16 units of round-off of the terms' sizes: what b itself is known to.
    // (Rigid blocks solve for their first three unknowns only.)
    double magnitudeNorm2 = 0;
    if (residualAtRoundOff)
      for (int i = 0; i < nActive_; ++i) magnitudeNorm2 += magnitude.segment(6 * i, dof).squaredNorm();
    const double roundOff = 16 * std::numeric_limits<double>::epsilon() * std::sqrt(magnitudeNorm2);
    // A large system solves only to kJudgingResidual while its contact states still change:
    // those states are judged again on the next solution anyway. An iteration after one that
    // changed no state solves to the full target, and only such a solution ends the iteration.
    const double floor = followFactor && !nextSolveStrict ? std::max(roundOff, kJudgingResidual * rhs.norm()) : roundOff;
    const bool solved = nActive_ == 0 || solveSystem(system, rhs, a.d, floor);
    const bool solvedStrictly = nActive_ == 0 || linearSolver_.lastSolveWithin(roundOff);
    if (followFactor && linearSolver_.stats().factorisations > factorisationsBefore) {
      factorSprings_.reset(contactSprings());
      factorBlockTerms_ = blockTerms;
    }
    // Time in a refactorising solve counts as factorisation, the rest as solve.
    (linearSolver_.stats().factorisations > factorisationsBefore ? stats_.times.factorisation
                                                                 : stats_.times.solve) += sw.lap();
    if (!solved) {
      a.failure = "global matrix not positive definite";
      return a;
    }
    if (nActive_ == 0) a.d.resize(0);
    if (!a.d.allFinite()) {
      a.failure = "solution not finite";
      return a;
    }

    // Judge every contact against the new solution.
    std::vector<contact::ContactResponse> response(a.contacts.size());
    parallelFor(static_cast<int>(a.contacts.size()), threads_, [&](int k) {
      const size_t q = static_cast<size_t>(k);
      const Vec12 d = gather(a.contacts[q]);
      response[q].normalForce = penalty_ * kin[q].penetration(d);
      response[q].lockedShear = ps * kin[q].shearFromAnchor(d);
      response[q].slip = kin[q].slip(d);
    });
    const std::vector<contact::ContactJudgement> verdict = judgeContacts(a.contacts, response, regime, stateTolerance);
    double largestNormal = 0;
    for (size_t q = 0; q < a.contacts.size(); ++q)
      if (a.contacts[q].closed()) largestNormal = std::max(largestNormal, std::abs(response[q].normalForce));
    // By how much holding contact q in its state breaks its law, against the judgement j: the
    // tension it keeps, plus, if locked, the shear its spring keeps above the strength (all of
    // it in tension: a locked heel held closed also anchors the block against sliding), or, if
    // sliding against a reversed slip, the shear spring force of that slip.
    const auto violation = [&](size_t q, const contact::ContactJudgement& j) {
      const Contact& c = a.contacts[q];
      const contact::ContactResponse& r = response[q];
      if (c.state == ContactState::Sliding && j.state == ContactState::Sliding) return double(INFINITY);
      if (c.state == ContactState::Sliding)
        return std::max(0.0, -r.normalForce) + (j.state == ContactState::Locked ? ps * std::abs(r.slip) : 0.0);
      const auto excess = [&](size_t k) {
        const Contact& h = a.contacts[k];
        return std::abs(response[k].lockedShear) - contact::shearStrength(h.bonded, response[k].normalForce, strengthOf(h));
      };
      // An edge-to-edge pair slides as a whole: count its other half's excess too.
      const int p = partner_[q];
      const double shear = excess(q) + (p >= 0 && a.contacts[p].state == ContactState::Locked ? excess(p) : 0.0);
      return std::max(0.0, -r.normalForce) + std::max(0.0, shear);
    };
    bool stateChanged = false, bondChanged = false;
    double frictionDrift = 0, forceScale = 0;
    for (size_t q = 0; q < a.contacts.size(); ++q) {
      Contact& c = a.contacts[q];
      const contact::ContactResponse& r = response[q];
      contact::ContactJudgement j = verdict[q];
      // Before t = 0 a contact pulled open by the start (gravity switched on at once) keeps its
      // bond, as slip then does not soften: that is the slope's loading history, not damage.
      // Only an open contact: it carries nothing either way, so a rest found so is a rest under
      // the analysis law too. (Keeping the bond of a closed contact, e.g. the pivot half of a
      // brittle edge-to-edge contact whose other half opens, would let settling lean on a
      // strength the first analysis step removes: the planar multi-block slide then "rested" at
      // 122 kPa and ran away at t = 0. Such a brittle pair loses its bond, as in original DDA.)
      if (scene_.settings.settleDynamically && (regime == Regime::Relaxation || regime == Regime::Settling))
        j.bonded = j.bonded || (c.bonded && j.state == ContactState::Open);
      if (j.state != c.state || j.direction != c.slideDirection) {
        const bool closing = c.state == ContactState::Open;
        const double allowed = kHeldViolation * largestNormal;
        if (flips[q] >= kFlipsBeforeFreeze && !closing &&
            (freezeCycling || (holdSmallViolations && violation(q, j) <= allowed))) {
          j = {c.state, c.slideDirection, j.bonded && c.bonded};
          a.frozeContacts = true;
        } else if (holdSmallViolations && flips[q] >= kFlipsBeforeFreeze && c.state == ContactState::Locked &&
                   j.state == ContactState::Open && -response[q].normalForce <= allowed) {
          // A locked contact whose shear breaks its law by more is still kept touching in the
          // small tension, but with its shear released: sliding, its friction max(0, N)·tanφ.
          j = {ContactState::Sliding, response[q].lockedShear > 0 ? 1 : -1, j.bonded && c.bonded};
          a.frozeContacts = true;
        } else {
          ++flips[q];
        }
      }
      if (c.state == ContactState::Sliding && j.state == ContactState::Sliding)
        frictionDrift = std::max(frictionDrift, std::abs(r.normalForce - c.normalForce));
      if (j.state != ContactState::Open) forceScale = std::max(forceScale, std::abs(r.normalForce));
      if (j.state != c.state || j.direction != c.slideDirection) stateChanged = true;
      if (j.state != c.state)
        ++((j.state == ContactState::Open || c.state == ContactState::Open) ? stats_.openCloseChanges
                                                                              : stats_.stickSlipChanges);
      if (j.bonded != c.bonded) bondChanged = true;
      if (j.state == ContactState::Locked && c.state != ContactState::Locked) {
        // The locked spring starts at the step-start position; a contact that sticks after
        // sliding keeps the friction force it carried (force continuity), or the load it drops
        // would jump onto its neighbours and break them.
        c.lockRatio = c.geometry.ratio;
        if (c.state == ContactState::Sliding)
          c.lockRatio -= c.slideDirection * friction[q] / (ps * edgeLength(c));
        kin.replace(q, assembly::linearise(scene_.blocks[c.key().vertexBlock], scene_.blocks[c.key().edgeBlock], c));
      }
      // A brittle joint's contact drops to its residual strength the moment it slides.
      if (j.state == ContactState::Sliding && *scene_.joints[c.joint].weakeningDistance <= 0) c.intact = 0;
      c.stepSlip = j.state == ContactState::Sliding ? r.slip : 0.0;
      c.state = j.state;
      c.slideDirection = j.direction;
      c.bonded = j.bonded;
      c.normalForce = r.normalForce;
      c.shearForce = c.state == ContactState::Locked ? r.lockedShear : 0.0;
    }
    stats_.times.stateChecks += sw.lap();
    if (const int period = cycles.record(a.contacts); period > 0) {
      a.failure = "open-close iteration cycles: the contact states repeat every " + std::to_string(period) +
                  " iterations (from iteration " +
                  std::to_string(a.iterations - StateCycleDetector::kRepeats * period) + ")";
      ++stats_.cycles;
      return a;
    }
    stiffnessChanged = stateChanged;
    nextSolveStrict = !stateChanged;
    const bool frictionSettled = frictionDrift <= scene_.settings.frictionTolerance * forceScale;
    if (!stateChanged && !bondChanged && frictionSettled && solvedStrictly) {
      a.converged = true;
      break;
    }
  }
  if (!a.converged) {
    a.iterations = maxIterations;
    a.failure = "open-close iteration did not converge in " + std::to_string(maxIterations) + " iterations";
    return a;
  }
  // A sliding contact's shear spring stays stretched to the friction it slides against (once,
  // for the converged states: only the energy budget reads it).
  const std::vector<double> carried = slidingFriction(a.contacts);
  for (size_t q = 0; q < a.contacts.size(); ++q)
    if (a.contacts[q].state == ContactState::Sliding) a.contacts[q].shearForce = carried[q];
  // The step limit, checked exactly only for blocks whose cheap bound does not clear it (in a
  // quiet step, none).
  bool beyondLimit = false;
  for (size_t b = 0; b < scene_.blocks.size() && !beyondLimit; ++b) {
    if (active_[b] < 0) continue;
    const model::Block& blk = scene_.blocks[b];
    const Vec6 d = a.d.segment<6>(6 * active_[b]);
    beyondLimit = blk.vertexDisplacementBound(d) > stepLimit_ && blk.maxVertexDisplacement(d) > stepLimit_;
  }
  if (beyondLimit) {
    const double worst = largestVertexDisplacement(a);
    a.converged = false;
    std::ostringstream msg;
    msg << "largest vertex displacement " << worst << " m exceeds the step limit " << stepLimit_
        << " m (g2·w0, at most a tenth of the thinnest block)";
    a.failure = msg.str();
  }
  return a;
}

bool Simulation::solveSystem(const SystemOperator& k, const Eigen::VectorXd& rhs, Eigen::VectorXd& d,
                             double residualFloor) {
  const int dof = matrix_.blockSize();
  if (dof == 6) return linearSolver_.solve(k, rhs, d, residualFloor);
  // Rigid blocks: the matrix holds u0, v0, r0 of each block; the strains stay zero.
  Eigen::VectorXd reduced(dof * nActive_), x;
  for (int i = 0; i < nActive_; ++i) reduced.segment(dof * i, dof) = rhs.segment(6 * i, dof);
  if (!linearSolver_.solve(k, reduced, x, residualFloor)) return false;
  d = Eigen::VectorXd::Zero(6 * nActive_);
  for (int i = 0; i < nActive_; ++i) d.segment(6 * i, dof) = x.segment(dof * i, dof);
  return true;
}

void Simulation::commit(Attempt& a, double dt, bool weakens) {
  Stopwatch sw;
  const bool dynamic = scene_.settings.mode == model::AnalysisMode::Dynamic;
  const auto movePoint = [&](model::BlockPoint& p) {
    const int i = active_[p.block];
    if (i >= 0)
      p.current = model::displacedPoint(scene_.blocks[p.block].moments.centroid, p.current, a.d.segment<6>(6 * i));
  };
  for (auto& m : scene_.monitors) movePoint(m.point);
  for (auto& l : scene_.pointLoads) movePoint(l.point);
  for (auto& f : scene_.fixedPoints) movePoint(f.point);
  for (size_t b = 0; b < scene_.blocks.size(); ++b) {
    const int i = active_[b];
    if (i < 0) continue;
    model::Block& blk = scene_.blocks[b];
    const Vec6 d = a.d.segment<6>(6 * i);
    // V_{n+1} = 2D/Δt − V_n (Newmark γ = 1); static steps start from rest.
    blk.velocity = 2 * d / dt - (dynamic ? blk.velocity : Vec6::Zero());
    blk.stress += elasticity_[blk.material] * d.tail<3>();
    blk.applyDisplacement(d);
  }
  for (const Contact& c : a.contacts)
    if (c.closed()) stats_.maxPenetration = std::max(stats_.maxPenetration, c.normalForce / penalty_);
  contacts_.contacts() = std::move(a.contacts);
  a.contacts.clear();
  if (weakens)
    for (Contact& c : contacts_.contacts()) {
      // A softening joint loses strength with the slip accumulated by the accepted steps.
      c.slipDistance += std::abs(c.stepSlip);
      const model::JointProperties& j = scene_.joints[c.joint];
      if (*j.weakeningDistance > 0) c.intact = std::min(c.intact, contact::remainingStrength(j, c.slipDistance));
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

double Simulation::restAcceleration() const {
  // At rest when the acceleration a static step implies, 2|D|/Δt², is below 1e-6 g: a measure
  // of the out-of-balance force that does not depend on the Δt the step control ended up with.
  return 1e-6 * std::max(scene_.gravity.norm(), 1e-3);
}

Simulation::Rest Simulation::settle(Regime regime, double& dt, double largestDt) {
  // A scene that moves this far while settling is failing, not settling.
  const double failingTravel = scene_.settings.maxDisplacementRatio * w0_;
  double travel = 0;
  // Without stage 3 an unconfirmed rest is kept as a fallback while static steps from the
  // analysis Δt look for a confirmed one (many-block scenes near failure, e.g. Vajont, creep on).
  std::optional<std::pair<model::Scene, contact::ContactSet>> firstRest;
  constexpr int kConfirmationSteps = 30;
  int stepsSinceRest = 0;
  const auto fallBack = [&] {
    // Stage 3 settles a relaxation whose static steps ran out of budget or stopped converging
    // (contacts cycling in static steps: the chair slide with a block across its kink).
    if (regime == Regime::Relaxation && scene_.settings.settleDynamically) return Rest::Unsettled;
    if (!firstRest) return Rest::NotFound;
    scene_ = std::move(firstRest->first);
    contacts_ = std::move(firstRest->second);
    return Rest::Unconfirmed;
  };
  for (int s = 0; s < scene_.settings.equilibriumMaxSteps; ++s) {
    checkDeadline();
    if (firstRest && stepsSinceRest++ >= kConfirmationSteps) break;
    detectContacts(false);
    Attempt a = tryStep(dt, regime, true);
    bool cut = false;
    for (int k = 0; !a.converged && k < scene_.settings.maxStepCuts; ++k) {
      if (log_) log_("equilibrium Δt " + std::to_string(dt) + " s cut: " + a.failure);
      dt *= scene_.settings.stepCutFactor;
      a = tryStep(dt, regime, true);
      cut = true;
    }
    if (!a.converged) return fallBack();
    // Slip while the model settles under gravity switched on at once is an artefact of that start
    // (in nature the slope was loaded over its history), so it does not soften a joint; a brittle
    // bond that slides is still lost (original DDA).
    commit(a, dt, false);
    ++stats_.equilibriumSteps;
    const double worst = largestVertexDisplacement(a);
    stats_.equilibriumResidual = 2 * worst / (dt * dt) / std::max(scene_.gravity.norm(), 1e-3);
    travel += worst;
    if (regime == Regime::Relaxation) relaxationTravel_ = travel;
    if (log_) {
      std::ostringstream m;
      m << (regime == Regime::HeldEquilibrium ? "equilibrium (contacts held)" : "equilibrium (relaxation)")
        << " step " << s + 1 << ": Δt " << dt << " s, " << a.iterations << " open-close iterations, "
        << "out-of-balance " << stats_.equilibriumResidual << " g, travel " << travel << " m"
        << fastestBlockNote(a);
      log_(m.str());
    }
    if (2 * worst / (dt * dt) < restAcceleration()) {
      // Stage 1 holds every contact, so its rest is exact. A relaxation step may be accepted
      // with cycling contacts frozen against their own criteria (on the chair slide, bonded
      // contacts held locked in 150 MN/m of tension that their law opens), and at a static Δt of
      // seconds 2|D|/Δt² hides a residual force the stiffness takes up. The analysis would
      // release either dynamically, and on a slope near its strength that release slides and
      // softens joints. So the relaxed state is confirmed by one step from rest at the analysis
      // Δt with every contact judged by its real law; unconfirmed, stage 3 settles it.
      if (regime != Regime::Relaxation || confirmedAtRest(a, restAcceleration())) return Rest::Confirmed;
      if (scene_.settings.settleDynamically) return Rest::Unconfirmed;
      if (!firstRest) firstRest.emplace(scene_, contacts_);
      if (log_) log_("equilibrium (relaxation): rest not confirmed at the analysis Δt; settling on");
      dt = scene_.settings.timeStep;
      continue;
    }
    if (travel > failingTravel) return scene_.settings.settleDynamically ? Rest::NotFound : fallBack();
    // A cut Δt makes the static step a slow dynamic relaxation: grow it back once it passes.
    if (!cut) dt = std::min(largestDt, 3 * dt);
  }
  return fallBack();
}

bool Simulation::settleDynamically() {
  // Kinetic damping (Cundall's dynamic relaxation for explicit codes; here on the implicit
  // Newmark step): steps at the analysis Δt carry velocity, and whenever the kinetic energy has
  // passed a peak every velocity is set to zero, which removes the energy of the mode that
  // peaked while the out-of-balance force keeps pushing towards equilibrium. The scene is at rest
  // when a step started from zero velocity converges without freezing contacts and implies an
  // acceleration below restAcceleration(): the test confirmedAtRest() applies to stage 2.
  const double failingTravel = scene_.settings.maxDisplacementRatio * w0_;
  const int budget = kSettlingStepsPerEquilibriumStep * scene_.settings.equilibriumMaxSteps;
  const bool dynamic = scene_.settings.mode == model::AnalysisMode::Dynamic;
  // Releasing the held contacts sets a large scene ringing as a sudden load does, and its
  // lightly loaded contacts cycle at any Δt, so that the settling cuts Δt again and again. A large
  // system holds a contact whose cycling breaks its law by little, as its analysis steps do
  // (tryStep, kHeldViolation), and settles without those cuts. A step that held one never
  // confirms rest. Small systems and static analyses keep the strict rule: held contacts moved a
  // slope at its strength to another verdict (docs/performance.md, "Tried and dropped").
  const bool holdSmallViolations = largeSystem() && dynamic;
  // The travel of stage 2 counts: the two stages together may not move like a failing scene.
  double travel = relaxationTravel_, lastKinetic = 0;
  // Static steps leave no meaningful velocity (commit() sums 2D/Δt over them): start from rest.
  for (model::Block& b : scene_.blocks) b.velocity.setZero();
  bool fromRest = true;
  for (int s = 0; s < budget; ++s) {
    checkDeadline();
    detectContacts(false);
    double dt = scene_.settings.timeStep;
    Attempt a = tryStep(dt, Regime::Settling, false, holdSmallViolations);
    for (int k = 0; !a.converged && k < scene_.settings.maxStepCuts; ++k) {
      if (log_) log_("settling Δt " + std::to_string(dt) + " s cut: " + a.failure);
      dt *= scene_.settings.stepCutFactor;
      a = tryStep(dt, Regime::Settling, k >= 1, holdSmallViolations);
    }
    if (!a.converged) return false;
    commit(a, dt, false);
    ++stats_.settlingSteps;
    const double worst = largestVertexDisplacement(a);
    travel += worst;
    const double implied = 2 * worst / (dt * dt);
    if (log_) {
      std::ostringstream m;
      m << "settling step " << s + 1 << ": Δt " << dt << " s, " << a.iterations << " open-close iterations"
        << (fromRest ? ", from rest: " : ", ") << "implied acceleration " << implied / std::max(scene_.gravity.norm(), 1e-3)
        << " g, travel " << travel << " m" << fastestBlockNote(a);
      log_(m.str());
    }
    if (fromRest && !a.frozeContacts && implied < restAcceleration()) {
      stats_.equilibriumResidual = implied / std::max(scene_.gravity.norm(), 1e-3);
      return true;
    }
    if (travel > failingTravel) return false;
    double kinetic = 0;
    for (size_t b = 0; b < scene_.blocks.size(); ++b)
      if (active_[b] >= 0) kinetic += kineticEnergy(scene_.blocks[b], mass_[b]);
    // A static analysis carries no velocity: each of its steps starts from rest.
    fromRest = !dynamic || kinetic < lastKinetic;
    if (fromRest) {
      for (model::Block& b : scene_.blocks) b.velocity.setZero();
      kinetic = 0;
    }
    lastKinetic = kinetic;
  }
  return false;
}

void Simulation::polishRest(double staticDt) {
  // Kinetic damping stops once a step from rest implies less than 1e-6 g; a static step from
  // there, with the contact states settled, lands on the static equilibrium of those states. A
  // wall left at 1e-6 g rings slightly through the analysis, and each of its quiet steps then
  // needs a conjugate-gradient iteration that the single-precision factor of a wall at rest does
  // not (a second substitution). The static step is kept if it converges with no contact frozen
  // against its law and implies less than 1e-6 g at its Δt, and if a step from rest at the
  // analysis Δt under the real law then implies less than 1e-6 g (stage 3's own rest test, which
  // also leaves the analysis a factor of its block terms); otherwise the settled state stands.
  const model::Scene settledScene = scene_;
  const contact::ContactSet settledContacts = contacts_;
  const double settledPenetration = stats_.maxPenetration;
  const auto implied = [&](const Attempt& a, double dt) { return 2 * largestVertexDisplacement(a) / (dt * dt); };
  const auto atRest = [&](const Attempt& a, double dt) {
    return a.converged && !a.frozeContacts && implied(a, dt) < restAcceleration();
  };
  for (model::Block& b : scene_.blocks) b.velocity.setZero();
  detectContacts(false);
  Attempt polish = tryStep(staticDt, Regime::Relaxation, false);
  recordSolverStatistics();
  if (!atRest(polish, staticDt)) return;
  commit(polish, staticDt, false);
  for (model::Block& b : scene_.blocks) b.velocity.setZero();
  detectContacts(false);
  const double dt = scene_.settings.timeStep;
  const Attempt check = tryStep(dt, Regime::Settling, false);
  recordSolverStatistics();  // the check is not committed, but its factorisation counts here
  if (!atRest(check, dt)) {
    scene_ = settledScene;
    contacts_ = settledContacts;
    stats_.maxPenetration = settledPenetration;
    if (log_) log_("equilibrium: the static step from the settled state was not confirmed; the settled state stands");
    return;
  }
  ++stats_.equilibriumSteps;
  stats_.equilibriumResidual = implied(check, dt) / std::max(scene_.gravity.norm(), 1e-3);
  if (log_) {
    std::ostringstream m;
    m << "equilibrium: one static step from the settled state; a step from rest at the analysis Δt then implies "
      << stats_.equilibriumResidual << " g";
    log_(m.str());
  }
}

bool Simulation::largeSystem() const {
  return model::largeSystemPath(scene_.settings, (scene_.settings.rigidBlocks ? 3 : 6) * nActive_);
}

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

bool Simulation::confirmedAtRest(const Attempt& last, double restAcceleration) {
  if (last.frozeContacts) return false;
  const double dt = scene_.settings.timeStep;
  detectContacts(false);
  const Attempt check = tryStep(dt, Regime::Relaxation, false);
  if (!check.converged) return false;
  return 2 * largestVertexDisplacement(check) / (dt * dt) < restAcceleration;
}

std::vector<bool> Simulation::unsupportedBlocks() const {
  const size_t n = scene_.blocks.size();
  std::vector<bool> reached(n, false);
  std::vector<int> frontier;
  for (size_t b = 0; b < n; ++b)
    if (scene_.blocks[b].fixed) reached[b] = true;
  for (const model::FixedPoint& f : scene_.fixedPoints) reached[f.point.block] = true;
  for (size_t b = 0; b < n; ++b)
    if (reached[b]) frontier.push_back(static_cast<int>(b));
  while (!frontier.empty()) {
    const int b = frontier.back();
    frontier.pop_back();
    for (const Contact& c : contacts_.contacts()) {
      if (!c.closed()) continue;
      const int u = c.key().vertexBlock, v = c.key().edgeBlock;
      const int other = u == b ? v : (v == b ? u : -1);
      if (other >= 0 && !reached[other]) {
        reached[other] = true;
        frontier.push_back(other);
      }
    }
  }
  std::vector<bool> held(n);
  for (size_t b = 0; b < n; ++b) held[b] = !reached[b];
  return held;
}

HeldEquilibrium Simulation::holdEquilibrium() {
  HeldEquilibrium h;
  h.held = unsupportedBlocks();
  markActiveBlocks(h.held);
  if (nActive_ > 0) {
    // Static steps whose inertia term is 1e-8 of the contact stiffness: only a regularisation,
    // so a step solves the static problem almost exactly. A mechanism (a block free to turn)
    // trips the displacement limit, and each Δt cut raises the regularisation ~11-fold.
    double maxMass = 0;
    for (const model::Block& b : scene_.blocks)
      if (!b.fixed) maxMass = std::max(maxMass, scene_.materials[b.material].density * b.moments.area);
    h.dt = std::sqrt(2e8 * maxMass / penalty_);
    const int before = stats_.equilibriumSteps;
    h.converged = settle(Regime::HeldEquilibrium, h.dt, h.dt) != Rest::NotFound;
    h.steps = stats_.equilibriumSteps - before;
  }
  h.blocks = scene_.blocks;
  h.monitors = scene_.monitors;
  h.pointLoads = scene_.pointLoads;
  h.fixedPoints = scene_.fixedPoints;
  h.contacts = contacts_;
  markActiveBlocks({});
  return h;
}

void Simulation::bringToEquilibrium(const HeldEquilibrium* shared) {
  if (!scene_.settings.initialEquilibrium) {
    stats_.startedAtRest = false;  // not brought to rest: the analysis starts as the case is
    startSlidingWhereBlocksMove();
    return;
  }
  std::vector<Vec6> initialVelocity;
  for (const model::Block& b : scene_.blocks) initialVelocity.push_back(b.velocity);
  HeldEquilibrium own;
  if (shared) {
    DDASLOPE_ASSERT(shared->blocks.size() == scene_.blocks.size() && shared->monitors.size() == scene_.monitors.size(),
                    "a shared equilibrium must come from the same scene");
    scene_.blocks = shared->blocks;
    scene_.monitors = shared->monitors;
    scene_.pointLoads = shared->pointLoads;
    scene_.fixedPoints = shared->fixedPoints;
    contacts_ = shared->contacts;
    // The joints (strengths) are this scene's own; contacts keep their joint index.
  } else {
    own = holdEquilibrium();
    shared = &own;
  }
  stats_.equilibriumConverged = shared->converged;
  heldMonitors_.clear();
  for (const model::Monitor& m : shared->monitors) heldMonitors_.push_back(m.point.current);
  heldBlocks_ = shared->blocks;
  markActiveBlocks(shared->held);
  if (nActive_ > 0) {
    detectContacts(false);
    const model::Scene heldScene = scene_;
    const contact::ContactSet heldContacts = contacts_;
    // A large system settles dynamically (stage 3) straight from stage 1's state. Each static
    // step of stage 2 costs a factorisation per open-close iteration (Δt changing, and a large
    // scene's steps take tens of iterations), and a static step cannot settle a contact held at
    // its friction limit: its inertia is only a regulariser (1e-8 of the contact stiffness), so a
    // block whose driving force its friction just balances is all but free, and a large wall
    // creeps under the relaxation instead of coming to rest. Small systems keep stage 2: their
    // steps are cheap, and the shipped cases' figures were made with it. So does a static
    // analysis, whose stage 3 has no kinetic damping. Should stage 3 fail, the analysis starts
    // from stage 1's state.
    const bool skipStaticRelaxation = scene_.settings.settleDynamically && largeSystem() &&
                                      scene_.settings.mode == model::AnalysisMode::Dynamic;
    Rest rest = Rest::Unsettled;
    relaxationTravel_ = 0;
    if (!skipStaticRelaxation) {
      // Releasing every held contact at once in one huge static step rarely converges: start the
      // relaxation at the analysis Δt and let it grow.
      double relaxDt = std::min(shared->dt, scene_.settings.timeStep);
      rest = settle(Regime::Relaxation, relaxDt, shared->dt);
    }
    stats_.relaxationConverged = rest == Rest::Confirmed || rest == Rest::Unconfirmed;
    stats_.startedAtRest = rest == Rest::Confirmed;
    if (rest == Rest::NotFound) {
      scene_ = heldScene;
      contacts_ = heldContacts;
    } else if ((rest == Rest::Unconfirmed || rest == Rest::Unsettled) && scene_.settings.settleDynamically) {
      const model::Scene relaxedScene = scene_;
      const contact::ContactSet relaxedContacts = contacts_;
      if (log_)
        log_(skipStaticRelaxation ? "equilibrium: a large system settles dynamically from every contact held"
             : rest == Rest::Unsettled ? "equilibrium (relaxation): no static rest; settling dynamically"
                                     : "equilibrium (relaxation): rest not confirmed at the analysis Δt; settling dynamically");
      stats_.startedAtRest = settleDynamically();
      // Without stage 2, "relaxed" reports whether the real contact law found rest at all.
      if (skipStaticRelaxation) {
        stats_.relaxationConverged = stats_.startedAtRest;
        if (stats_.startedAtRest) polishRest(shared->dt);
      }
      if (!stats_.startedAtRest) {
        // Failing, or still moving after the budget: start from stage 2's rest, or from stage 1's
        // state if stage 2 found none, as without stage 3.
        const bool relaxed = rest == Rest::Unconfirmed;
        if (log_)
          log_(std::string("settling: no rest found; the analysis starts from the ") +
               (relaxed ? "relaxed state" : "state with every contact held"));
        scene_ = relaxed ? relaxedScene : heldScene;
        contacts_ = relaxed ? relaxedContacts : heldContacts;
      }
    }
  } else {
    // No block to settle: at rest unless blocks are held because nothing supports them.
    stats_.startedAtRest = std::none_of(shared->held.begin(), shared->held.end(), [](bool h) { return h; });
  }
  for (size_t b = 0; b < scene_.blocks.size(); ++b) scene_.blocks[b].velocity = initialVelocity[b];
  markActiveBlocks({});
  detectContacts(false);
  startSlidingWhereBlocksMove();
}

// The equilibrium leaves every closed contact locked at rest. A block the case launches along a
// contact (an initial velocity) would load that locked spring with a whole step's slip, a force
// thousands of times its weight. The iteration does find the contact sliding, but from an iterate
// thrown by that force, after cycles and Δt cuts whose spring forces brake the block and lift it
// off its base (docs/accuracy.md). Such a contact slides from the start, against its relative
// motion.
void Simulation::startSlidingWhereBlocksMove() {
  const double noise = scene_.settings.contactStateTolerance * w0_;
  std::vector<Contact>& cs = contacts_.contacts();
  for (size_t q = 0; q < cs.size(); ++q) {
    Contact& c = cs[q];
    if (c.state != ContactState::Locked) continue;
    Vec12 v;
    v.head<6>() = scene_.blocks[c.key().vertexBlock].velocity;
    v.tail<6>() = scene_.blocks[c.key().edgeBlock].velocity;
    const double slipInAStep = kinematics_[q].slip(v) * scene_.settings.timeStep;  // slip() is linear
    if (std::abs(slipInAStep) <= noise) continue;
    c.state = ContactState::Sliding;
    c.slideDirection = slipInAStep > 0 ? 1 : -1;
  }
}

bool Simulation::finished() const {
  return time_ >= scene_.settings.duration * (1 - 1e-12);
}

void Simulation::checkDeadline() const {
  if (!deadline_ || std::chrono::steady_clock::now() < *deadline_) return;
  std::ostringstream why;
  why << "stopped at t = " << time_ << " s after " << stats_.steps << " steps"
      << (stats_.steps == 0 ? " (still bringing the scene to equilibrium)" : "")
      << ": the budget analysis.wall_clock_limit (" << scene_.settings.wallClockLimit << " s) is spent";
  throw BudgetExceededError(why.str());
}

StepRecord Simulation::advance() {
  checkDeadline();
  detectContacts(false);
  const double remaining = scene_.settings.duration - time_;
  double dt = stepSize_.proposal(remaining);
  const double first = dt;
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
      time_ = (dt == remaining) ? scene_.settings.duration : time_ + dt;
      // A step accepted only by freezing cycling contacts was not cured by its cuts: the next
      // starts from the Δt before them, or a cycle met at rest would shrink Δt step after step
      // without end.
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
  EnergyBudget e = storedEnergy(scene_, mass_, elasticity_, contacts_.contacts(), penalty_,
                                penalty_ * scene_.settings.shearPenaltyRatio);
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

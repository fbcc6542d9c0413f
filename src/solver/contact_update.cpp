// The contact update before each step: the broad and narrow phases, the persistent contact set,
// the halves of edge-to-edge contacts paired, and every contact's kinematics linearised.
#include <algorithm>
#include <array>
#include <functional>
#include <utility>
#include <vector>

#include "ddaslope/contact/broad_phase.hpp"
#include "ddaslope/contact/contact_law.hpp"
#include "ddaslope/contact/joint_strength.hpp"
#include "ddaslope/contact/narrow_phase.hpp"
#include "ddaslope/core/block_order.hpp"
#include "ddaslope/core/parallel.hpp"
#include "ddaslope/solver/simulation.hpp"
#include "stopwatch.hpp"

namespace ddaslope::solver {

using contact::Contact;
using contact::ContactState;

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

  contact::NarrowPhaseSettings nps{searchDistance_, degToRad(scene_.settings.edgeParallelToleranceDeg)};
  if (!flatCorners_.empty()) nps.flatCorners = &flatCorners_;
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
    stats_.pairsUncertified += pairCache_.uncertified();
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
        pairCache_.find(k, polygons, nps, known, found[static_cast<size_t>(chunk)], &boxes);
      else {
        const std::array<geometry::Aabb, 2> pairBoxes{boxes[static_cast<size_t>(p.a)], boxes[static_cast<size_t>(p.b)]};
        contact::findContacts(p.a, scene_.blocks[p.a].vertices, p.b, scene_.blocks[p.b].vertices, nps, known,
                              found[static_cast<size_t>(chunk)], nullptr, &pairBoxes);
      }
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
  contacts_.update(
      std::move(candidates), joints, bondedIfNew,
      [&](int b) { return static_cast<int>(scene_.blocks[static_cast<size_t>(b)].vertices.size()); },
      [&](int b) { return scene_.blocks[static_cast<size_t>(b)].fixed; },
      [&](int j) { return contact::separatesWithBond(contact::contactStrength(jointStrength_[static_cast<size_t>(j)], 1, 0)); });
  if (pairCacheOn_) pairCache_.finish(contacts_.keyVersion());

  if (initial) {
    // Contacts touching at the start are closed and intact (bonded); the spring's zero is at
    // the initial gap, so that coordinates rounded in the case file do not preload it.
    const double tol = scene_.touchingGap();
    for (Contact& c : contacts_.contacts()) {
      if (c.geometry.gap > tol) continue;
      if (c.geometry.gap > 1e-6 * w0_) {
        ++stats_.closedAcrossGaps;
        stats_.widestClosedGap = std::max(stats_.widestClosedGap, c.geometry.gap);
      }
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

}  // namespace ddaslope::solver

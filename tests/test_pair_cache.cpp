// The reuse of narrow-phase decisions between steps (contact/pair_cache.hpp): a search certifies
// how far the vertices may move before any of its decisions could change, and the runs with and
// without the reuse must be the same bit for bit.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <set>

#include "ddaslope/contact/contact_set.hpp"
#include "ddaslope/contact/narrow_phase.hpp"
#include "ddaslope/io/case_reader.hpp"
#include "ddaslope/model/wall_scene.hpp"
#include "ddaslope/solver/simulation.hpp"

using namespace ddaslope;

namespace {

std::vector<Vec2> rectangle(Vec2 lo, double w, double h, double turn) {
  const Vec2 c = lo + Vec2(w / 2, h / 2);
  std::vector<Vec2> v = {lo, lo + Vec2(w, 0), lo + Vec2(w, h), lo + Vec2(0, h)};
  const double cs = std::cos(turn), sn = std::sin(turn);
  for (Vec2& p : v) {
    const Vec2 d = p - c;
    p = c + Vec2(cs * d.x() - sn * d.y(), sn * d.x() + cs * d.y());
  }
  return v;
}

std::vector<contact::ContactKey> keys(const std::vector<contact::ContactCandidate>& cs) {
  std::vector<contact::ContactKey> k;
  for (const auto& c : cs) k.push_back(c.key);
  return k;
}

}  // namespace

// The certificate's claim (narrow_phase.hpp, SearchMargin), tested where its decisions are close
// calls: pairs of blocks as a wall and a slope put them (edge on edge with an offset, corner on
// corner, side by side), turned and shifted at random by up to a few search distances, and a
// slope's triangle and hexagon corners. Every vertex of both blocks is then moved at random by less
// than the certified slack, in the worst direction of the Lipschitz bounds as often as chance gives
// it, and a new search, asked the same questions, must return the same contacts in the same order.
// Half the searches must certify something (the test would pass vacuously if the slack were always
// 0), moving by three times the slack must change a decision somewhere (the bounds are close),
// and a brick resting on another must certify at least 1e-5 m: the reuse would be worthless below
// what a slope at rest creeps in a step.
TEST(PairCache, CertifiedDecisionsHoldWithinTheSlack) {
  std::mt19937 rng(20261124);
  std::uniform_real_distribution<double> unit(0, 1), sym(-1, 1);
  const contact::NarrowPhaseSettings s{0.0625, 1.0 * M_PI / 180};
  int certified = 0, trials = 0, moves = 0, changedBeyond = 0;
  for (int t = 0; t < 3000; ++t) {
    const int shape = t % 4;
    std::vector<Vec2> a, b;
    const double jitter = s.searchDistance * (t % 3 == 0 ? 2 * sym(rng) : 1e-3 * sym(rng));
    const double turn = (t % 5 == 0 ? 0.05 : 1e-4) * sym(rng);
    if (shape == 0) {  // running bond: a brick on two, offset by half
      a = rectangle({0, 0}, 1, 0.5, 0);
      b = rectangle({0.5 + jitter, 0.5 + 0.3 * jitter}, 1, 0.5, turn);
    } else if (shape == 1) {  // corner on corner: stacked bricks
      a = rectangle({0, 0}, 1, 0.5, 0);
      b = rectangle({jitter, 0.5 + 0.2 * jitter * sym(rng)}, 1, 0.5, turn);
    } else if (shape == 2) {  // side by side
      a = rectangle({0, 0}, 1, 0.5, 0);
      b = rectangle({1 + 0.3 * jitter, jitter}, 1, 0.5, turn);
    } else {  // a triangle's corner near a hexagon's corner and edge
      for (int k = 0; k < 6; ++k) a.push_back(Vec2(std::cos(k * M_PI / 3), std::sin(k * M_PI / 3)));
      const Vec2 tip = a[1] + Vec2(jitter, 0.5 * jitter * sym(rng));
      b = {tip, tip + Vec2(0.8, 0.9 + turn), tip + Vec2(-0.3, 1.0)};
    }
    // Last step's contacts: the keys of a first search, so that the ties it keeps are exercised.
    std::vector<contact::ContactCandidate> first;
    const auto none = [](const contact::ContactKey &) { return false; };
    contact::findContacts(0, a, 1, b, s, none, first);
    std::set<contact::ContactKey> last;
    for (const auto& c : first) last.insert(c.key);
    const auto known = [&](const contact::ContactKey& k) { return last.count(k) > 0; };
    std::vector<contact::ContactCandidate> found;
    contact::SearchMargin margin;
    contact::findContacts(0, a, 1, b, s, known, found, &margin);
    ++trials;
    if (shape == 0 && std::abs(jitter) < 1e-3 * s.searchDistance && std::abs(turn) < 1e-3) {
      EXPECT_GE(margin.slack, 1e-5) << "a brick at rest on two others, trial " << t;
    }
    if (!(margin.slack > 0) || margin.tooManyQuestions) continue;
    ++certified;
    for (int m = 0; m < 20; ++m) {
      std::vector<Vec2> a2 = a, b2 = b;
      for (auto* poly : {&a2, &b2})
        for (Vec2& p : *poly) {
          const double angle = 2 * M_PI * unit(rng);
          // Up to the whole slack (the cache uses half); often right at it.
          const double r = margin.slack * (m % 2 == 0 ? 0.999 : unit(rng));
          p += r * Vec2(std::cos(angle), std::sin(angle));
        }
      std::vector<contact::ContactCandidate> moved;
      contact::findContacts(0, a2, 1, b2, s, known, moved);
      ASSERT_EQ(keys(moved), keys(found)) << "trial " << t << ", move " << m << ", slack " << margin.slack;
      ++moves;
    }
    // The bounds are close: three times the slack, in some trials, changes a decision.
    std::vector<Vec2> a3 = a, b3 = b;
    for (auto* poly : {&a3, &b3})
      for (Vec2& p : *poly) {
        const double angle = 2 * M_PI * unit(rng);
        p += 3 * margin.slack * Vec2(std::cos(angle), std::sin(angle));
      }
    std::vector<contact::ContactCandidate> far;
    contact::findContacts(0, a3, 1, b3, s, known, far);
    changedBeyond += keys(far) != keys(found);
  }
  EXPECT_GE(certified, trials / 2);
  EXPECT_GT(moves, 0);
  EXPECT_GT(changedBeyond, 0) << "no decision changed at three times the slack: the bounds are loose";

  // A block with a vertex that is not finite certifies nothing, and neither do blocks far from the
  // origin whose decisions are within the round-off of their coordinates (64 ulps of 1e12 m).
  const auto none = [](const contact::ContactKey&) { return false; };
  for (const Vec2& shift : {Vec2(0, 0), Vec2(1e12, 0)}) {
    std::vector<Vec2> a = rectangle(shift, 1, 0.5, 0), b = rectangle(shift + Vec2(0.5, 0.5), 1, 0.5, 0);
    if (shift.x() == 0) b[2].x() = NAN;
    std::vector<contact::ContactCandidate> out;
    contact::SearchMargin margin;
    contact::findContacts(0, a, 1, b, s, none, out, &margin);
    EXPECT_EQ(margin.slack, 0) << "shift " << shift.x();
  }
}

namespace {

/// Vertices, velocities and contact states and forces after a run: every number that a change of
/// the contacts found would move.
std::vector<double> stateAfter(solver::Simulation& sim) {
  std::vector<double> state;
  for (const auto& b : sim.scene().blocks) {
    for (const Vec2& v : b.vertices) state.insert(state.end(), {v.x(), v.y()});
    for (int i = 0; i < 6; ++i) state.push_back(b.velocity[i]);
  }
  for (const auto& c : sim.contacts().contacts())
    state.insert(state.end(), {double(c.state), c.normalForce, c.shearForce, double(c.key().vertex)});
  return state;
}

void expectSameRun(const std::vector<double>& with, const std::vector<double>& without) {
  ASSERT_EQ(with.size(), without.size());
  size_t differing = 0;
  for (size_t i = 0; i < with.size(); ++i) differing += with[i] != without[i];
  EXPECT_EQ(differing, 0u) << "values that differ with and without the pair cache";
}

}  // namespace

// The reuse changes nothing but the time: runs with and without it are the same bit for bit. A wall
// at rest (most pairs reused), the same wall started with full gravity at step 1 (every block
// moving: pairs searched, certificates running out and anchors renewed, pairs searched without
// certifying after certificates lapsed unused), and the toppling slope, whose columns rotate
// corner over corner through the vertex-to-vertex rules and its ties.
TEST(PairCache, RunsAreTheSameWithAndWithoutIt) {
  for (const bool sudden : {false, true}) {
    SCOPED_TRACE(sudden ? "sudden gravity" : "wall at rest");
    std::vector<std::vector<double>> finals;
    std::vector<long> reused, uncertified;
    for (const bool cache : {true, false}) {
      solver::Simulation sim(model::makeAnchorWall(10, sudden));
      sim.setPairCache(cache);
      sim.bringToEquilibrium();
      for (int k = 0; k < 30; ++k) sim.advance();
      finals.push_back(stateAfter(sim));
      reused.push_back(sim.statistics().pairsReused);
      uncertified.push_back(sim.statistics().pairsUncertified);
    }
    expectSameRun(finals[0], finals[1]);
    EXPECT_EQ(reused[1], 0);
    if (!sudden) {
      EXPECT_GT(reused[0], 0) << "a wall at rest reuses its pairs";
    } else {
      EXPECT_GT(uncertified[0], 0) << "pairs whose certificates lapse unused search without one for a while";
    }
  }
  std::vector<std::vector<double>> finals;
  std::vector<long> uncertified;
  for (const bool cache : {true, false}) {
    solver::Simulation sim(io::readCase(DDASLOPE_SOURCE_DIR "/cases/toppling_slope.json"));
    sim.setPairCache(cache);
    sim.bringToEquilibrium();
    for (int k = 0; k < 300; ++k) sim.advance();
    finals.push_back(stateAfter(sim));
    uncertified.push_back(sim.statistics().pairsUncertified);
  }
  expectSameRun(finals[0], finals[1]);
  EXPECT_GT(uncertified[0], 0);
}

// A pair whose blocks keep moving is searched without a certificate for a while (Entry::reuses):
// a brick resting on another, moved 2 cm along it at every detection (twice the certified 1 % of
// its shortest edge), certifies its first search, then, after each certificate its blocks moved
// beyond unused, searches 1, 3 and 7 times without one; each search finds the same contacts as a
// plain search. The brick stops where the certified search after the 7 finds it (its blocks
// anchored anew there), and that certificate is used at every detection after it.
TEST(PairCache, APairThatKeepsMovingSearchesWithoutACertificateForAWhile) {
  const contact::NarrowPhaseSettings s{0.0625, 1.0 * M_PI / 180};
  const std::vector<Vec2> lower = rectangle({0, 0}, 1, 0.5, 0);
  std::vector<Vec2> upper;
  const contact::PairCache::Polygons polygons{&lower, &upper};
  const std::vector<contact::BlockPair> pairs{{0, 1}};
  contact::PairCache cache;
  std::set<contact::ContactKey> last;
  const contact::PairCache::Known known = [&](const contact::ContactKey& k) { return last.count(k) > 0; };
  std::vector<long> uncertified, reused;
  for (int d = 0; d < 22; ++d) {
    const double x = 0.3 + (d < 15 ? 0.02 * (d % 2) : 0.0);  // at rest from detection 14 on
    upper = rectangle({x, 0.5}, 1, 0.5, 0);
    cache.prepare(polygons, pairs, s, 1);
    std::vector<contact::ContactCandidate> found, plain;
    cache.find(0, polygons, s, known, found);
    cache.finish(1);
    contact::findContacts(0, lower, 1, upper, s, known, plain);
    EXPECT_EQ(keys(found), keys(plain)) << "detection " << d;
    uncertified.push_back(cache.uncertified());
    reused.push_back(cache.reused());
    last.clear();
    for (const auto& c : found) last.insert(c.key);
  }
  const std::vector<long> waits = {0, 1, 0, 1, 1, 1, 0, 1, 1, 1, 1, 1, 1, 1, 0};
  for (size_t d = 0; d < waits.size(); ++d) {
    EXPECT_EQ(uncertified[d], waits[d]) << "detection " << d;
    EXPECT_EQ(reused[d], 0) << "detection " << d;
  }
  for (size_t d = waits.size(); d < reused.size(); ++d) {
    EXPECT_EQ(reused[d], 1) << "detection " << d;
    EXPECT_EQ(uncertified[d], 0) << "detection " << d;
  }
}

// The contact set's update when a scene at rest finds the same contacts again (the keys in the same
// order): each contact takes its candidate's geometry and keeps its state, as the merge would give;
// the key version stands while the keys do, the pairing version moves when a paired edge does, and
// a set restored from a copy keeps the versions it had (so that the pair cache and the edge-to-edge
// pairing see it is not the latest).
TEST(ContactSet, SameContactsRefreshTheirGeometryOnly) {
  const auto candidate = [](contact::ContactKey k, double gap, int paired) {
    contact::ContactCandidate c;
    c.key = k, c.gap = gap, c.pairedEdge = paired;
    return c;
  };
  const contact::ContactKey k1{0, 1, 1, 2}, k2{1, 3, 0, 0};
  contact::ContactSet set;
  // k2 found from both blocks: one contact.
  set.update({candidate(k2, 0.1, 1), candidate(k1, 0.2, -1), candidate(k2, 0.1, 1)}, {0, 0, 0}, {0, 0, 0});
  ASSERT_EQ(set.contacts().size(), 2u);
  set.contacts()[0].state = contact::ContactState::Locked;  // k1 (sorted first)
  const long keys = set.keyVersion(), pairing = set.pairingVersion();
  const contact::ContactSet saved = set;

  set.update({candidate(k2, 0.3, 1), candidate(k1, 0.4, -1), candidate(k2, 0.3, 1)}, {0, 0, 0}, {0, 0, 0});
  ASSERT_EQ(set.contacts().size(), 2u);
  EXPECT_EQ(set.contacts()[0].key(), k1);
  EXPECT_EQ(set.contacts()[0].geometry.gap, 0.4);
  EXPECT_EQ(set.contacts()[0].state, contact::ContactState::Locked);
  EXPECT_EQ(set.contacts()[1].geometry.gap, 0.3);
  EXPECT_EQ(set.keyVersion(), keys);
  EXPECT_EQ(set.pairingVersion(), pairing);

  set.update({candidate(k2, 0.3, -1), candidate(k1, 0.4, -1), candidate(k2, 0.3, -1)}, {0, 0, 0}, {0, 0, 0});
  EXPECT_EQ(set.keyVersion(), keys);
  EXPECT_NE(set.pairingVersion(), pairing) << "k2's paired edge changed";

  set.update({candidate(k1, 0.4, -1)}, {0}, {0});
  ASSERT_EQ(set.contacts().size(), 1u);
  EXPECT_EQ(set.contacts()[0].state, contact::ContactState::Locked);
  EXPECT_NE(set.keyVersion(), keys);
  set = saved;
  EXPECT_EQ(set.keyVersion(), keys);
  EXPECT_EQ(set.pairingVersion(), pairing);
  EXPECT_EQ(set.contacts().size(), 2u);
}

// A vertex that slid from one edge of a block onto the next (vertex 2 of block 1 from edge 3 of
// block 0 onto its edge 2) keeps the joint's history: its slip, bond and softening. It goes on
// closed if it touches the next edge (a concave bend: gap ≤ 0), open if it stands clear of it
// (past a convex bend: gap > 0), so that no spring pulls it down across the gap.
TEST(ContactSet, AVertexPassingOntoTheNextEdgeIsClosedOnlyIfItTouchesIt) {
  for (const double gap : {-1e-6, 0.0, 1e-6}) {
    contact::ContactSet set;
    contact::ContactCandidate c;
    c.key = {1, 2, 0, 3};
    set.update({c}, {0}, {1});
    contact::Contact& old = set.contacts()[0];
    old.state = contact::ContactState::Sliding, old.slideDirection = 1, old.slipDistance = 0.25, old.intact = 0.5;
    old.bonded = false, old.normalForce = 1e6;
    c.key = {1, 2, 0, 2};
    c.gap = gap;
    set.update({c}, {0}, {1});
    ASSERT_EQ(set.contacts().size(), 1u);
    const contact::Contact& now = set.contacts()[0];
    EXPECT_EQ(now.state, gap > 0 ? contact::ContactState::Open : contact::ContactState::Sliding) << "gap " << gap;
    EXPECT_EQ(now.slideDirection, gap > 0 ? 0 : 1) << "gap " << gap;
    EXPECT_EQ(now.normalForce, gap > 0 ? 0.0 : 1e6) << "gap " << gap;
    EXPECT_EQ(now.slipDistance, 0.25) << "gap " << gap;
    EXPECT_EQ(now.intact, 0.5) << "gap " << gap;
    EXPECT_FALSE(now.bonded) << "gap " << gap;  // new contacts of this joint start bonded
  }
  // Opened so, a bonded contact keeps its bond as one the iteration pulls open would: only if its
  // joint has no tensile strength to crack.
  for (const bool survives : {false, true}) {
    contact::ContactSet set;
    contact::ContactCandidate c;
    c.key = {1, 2, 0, 3};
    set.update({c}, {0}, {1});
    set.contacts()[0].state = contact::ContactState::Locked;
    set.contacts()[0].bonded = true;
    c.key = {1, 2, 0, 2};
    c.gap = 1e-6;
    set.update({c}, {0}, {0}, {}, {}, [&](int joint) { return joint == 0 && survives; });
    EXPECT_EQ(set.contacts()[0].state, contact::ContactState::Open);
    EXPECT_EQ(set.contacts()[0].bonded, survives);
  }
}

// The hand-over of an edge-to-edge contact whose measuring corner changes blocks. Block 0 (the
// base, 4 vertices) has edge 2 from its vertex 2 to 3; block 1 (the slider, 4 vertices) lies with
// its edge 0 (vertex 0 to 1) against it, antiparallel, so the slider's vertex 0 (the paired edge's
// start) sits at the base edge's end, vertex 3. Last step the base's vertex 3 sat on the slider's
// edge 0, sliding; now the slider's vertex 0 sits on the base's edge 2. It inherits the sliding
// state (and its gap's zero) only from that corner, only if that contact is gone, and only once.
TEST(ContactSet, AContactWhoseMeasuringCornerChangesBlocksKeepsItsState) {
  const auto candidate = [](contact::ContactKey k, int paired) {
    contact::ContactCandidate c;
    c.key = k, c.pairedEdge = paired;
    return c;
  };
  const auto fourVertices = [](int) { return 4; };
  const contact::ContactKey oldKey{0, 3, 1, 0}, farCorner{0, 2, 1, 0}, newKey{1, 0, 0, 2};
  const auto start = [&](contact::ContactKey k) {
    contact::ContactSet set;
    set.update({candidate(k, 1)}, {0}, {0}, fourVertices);
    set.contacts()[0].state = contact::ContactState::Sliding;
    set.contacts()[0].slideDirection = -1;
    set.contacts()[0].normalOffset = 1e-4;
    return set;
  };
  contact::ContactSet set = start(oldKey);
  set.update({candidate(newKey, 0)}, {0}, {0}, fourVertices);
  ASSERT_EQ(set.contacts().size(), 1u);
  EXPECT_EQ(set.contacts()[0].state, contact::ContactState::Sliding);
  EXPECT_EQ(set.contacts()[0].slideDirection, -1);
  EXPECT_EQ(set.contacts()[0].normalOffset, 1e-4);
  // The base's other corner of the edge did not measure this end: nothing inherited.
  set = start(farCorner);
  set.update({candidate(newKey, 0)}, {0}, {0}, fourVertices);
  EXPECT_EQ(set.contacts()[0].state, contact::ContactState::Open);
  // The old contact goes on beside the new one: each keeps its own state.
  set = start(oldKey);
  set.update({candidate(oldKey, 1), candidate(newKey, 0)}, {0, 0}, {0, 0}, fourVertices);
  ASSERT_EQ(set.contacts().size(), 2u);
  EXPECT_EQ(set.contacts()[0].state, contact::ContactState::Sliding);  // oldKey sorts first
  EXPECT_EQ(set.contacts()[1].state, contact::ContactState::Open);
  // Without the blocks' vertex counts, no hand-over.
  set = start(oldKey);
  set.update({candidate(newKey, 0)}, {0}, {0});
  EXPECT_EQ(set.contacts()[0].state, contact::ContactState::Open);
}

// Contact kinematics, narrow phase and state law.
#include <gtest/gtest.h>

#include <cmath>

#include "ddaslope/assembly/contact_terms.hpp"
#include "ddaslope/contact/contact_law.hpp"
#include "ddaslope/contact/narrow_phase.hpp"

using namespace ddaslope;
using contact::ContactState;

namespace {
model::Block square(double x, double y, double s) {
  model::Block b;
  b.vertices = {{x, y}, {x + s, y}, {x + s, y + s}, {x, y + s}};
  b.moments = geometry::computeMoments(b.vertices);
  return b;
}
const auto none = [](const contact::ContactKey&) { return false; };
}  // namespace

// The linearised penetration must match the exact one (vertex moved by the exact update) to
// second order: for D of size ε the error is O(ε²) (Shi eq. 2.52 drops only that term).
TEST(ContactTerms, PenetrationLinearisationIsFirstOrderExact) {
  const model::Block base = square(0, 0, 4), top = square(1, 4.001, 1);
  contact::Contact c;
  c.geometry.key = {1, 0, 0, 2};  // vertex 0 of top on edge 2 of base (its top edge, 4,4 → 0,4)
  c.geometry.ratio = 0.75;
  c.lockRatio = 0.75;
  const auto kin = assembly::linearise(top, base, c);
  EXPECT_NEAR(kin.penetration0, -0.001, 1e-12);
  for (double eps : {1e-4, 1e-5}) {
    Vec6 di;
    di << 0.3, -1.0, 0.2, 0.1, -0.2, 0.05;
    di *= eps;
    Vec12 d = Vec12::Zero();
    d.head<6>() = di;
    const Vec2 p = model::displacedPoint(top.moments.centroid, top.vertices[0], di);
    const double exact = 4.0 - p.y();  // penetration below the line y = 4
    EXPECT_NEAR(kin.penetration(d), exact, 10 * eps * eps);
  }
}

// A block lying on a longer base: exactly two vertex-to-edge contacts, both recognised as the
// ends of one edge-to-edge contact of overlap b.
TEST(NarrowPhase, BlockOnBaseGivesTwoEdgeContacts) {
  const model::Block base = square(0, -10, 10), top = square(3, 0, 2);
  std::vector<contact::ContactCandidate> out;
  contact::findContacts(0, base.vertices, 1, top.vertices, {0.05, 0.0175}, none, out);
  ASSERT_EQ(out.size(), 2u);
  for (const auto& c : out) {
    EXPECT_EQ(c.key.vertexBlock, 1);
    EXPECT_EQ(c.key.edgeBlock, 0);
    EXPECT_NEAR(c.gap, 0, 1e-12);
    EXPECT_NEAR(c.overlap, 2.0, 1e-12);
  }
}

// Two equal blocks stacked with coincident corners: one contact per corner pair, not two.
TEST(NarrowPhase, StackedCornersGiveOneContactEach) {
  const model::Block lower = square(0, 0, 1), upper = square(0, 1, 1);
  std::vector<contact::ContactCandidate> out;
  contact::findContacts(0, lower.vertices, 1, upper.vertices, {0.05, 0.0175}, none, out);
  ASSERT_EQ(out.size(), 2u);
  for (const auto& c : out) EXPECT_NEAR(c.overlap, 1.0, 1e-12);
}

// Far apart: nothing.
TEST(NarrowPhase, DistantBlocksGiveNoContact) {
  const model::Block a = square(0, 0, 1), b = square(0, 1.2, 1);
  std::vector<contact::ContactCandidate> out;
  contact::findContacts(0, a.vertices, 1, b.vertices, {0.05, 0.0175}, none, out);
  EXPECT_TRUE(out.empty());
}

// An acute corner P hooked over a corner Q (the wedge of test_energy.cpp as it reaches the
// bench): P lies 4 cm behind the line of the bench's vertical face but above the bench top, and Q
// 2.3 cm outside the wedge's lower face. Both entrances are allowed by the angles, P on the face
// the better; the new contact must be the open one, Q on the wedge's face (the entrance
// penetrated least, Shi's shortest distance), not P 4 cm "deep" behind the face's extension.
TEST(NarrowPhase, CornerOverACornerTakesTheSeparatingEntrance) {
  const double rise = std::tan(30 * M_PI / 180), face = 56 * M_PI / 180;
  const std::vector<Vec2> bench = {{-10, -2}, {12, -2}, {12, 0}, {0, 0}, {0, 2}, {-10, 2 + 10 * rise}};
  const Vec2 p(-0.04, 2.1);
  const std::vector<Vec2> wedge = {p, p + 2 * Vec2(std::cos(face), -std::sin(face)), p + Vec2(2, 0)};
  std::vector<contact::ContactCandidate> out;
  contact::findContacts(0, bench, 1, wedge, {0.1375, 0.0175}, none, out);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].key, (contact::ContactKey{0, 4, 1, 0}));  // Q on the wedge's edge P → lower vertex
  EXPECT_NEAR(out[0].gap, 0.1 * std::cos(face) - 0.04 * std::sin(face), 1e-12);
  EXPECT_GT(out[0].gap, 0);
}

// Mohr-Coulomb judgement of one vertex-to-edge contact (dda-method.md §4).
TEST(ContactLaw, VertexRule) {
  const contact::ContactStrength s{std::tan(30 * M_PI / 180), 100, 50};
  // Locked, bonded: holds up to c·L + N tanφ = 100 + 1000·0.57735.
  EXPECT_EQ(contact::judgeVertexContact(ContactState::Locked, 0, true, {1000, 677, 0}, s).state, ContactState::Locked);
  const auto slid = contact::judgeVertexContact(ContactState::Locked, 0, true, {1000, -678, 0}, s);
  EXPECT_EQ(slid.state, ContactState::Sliding);
  EXPECT_EQ(slid.direction, -1);
  EXPECT_FALSE(slid.bonded);  // cohesion lost for good
  // Unbonded: friction only.
  EXPECT_EQ(contact::judgeVertexContact(ContactState::Locked, 0, false, {1000, 578, 0}, s).state, ContactState::Sliding);
  // Tension: held by the bond up to σt·L, then open and unbonded.
  EXPECT_EQ(contact::judgeVertexContact(ContactState::Locked, 0, true, {-49, 0, 0}, s).state, ContactState::Locked);
  const auto opened = contact::judgeVertexContact(ContactState::Locked, 0, true, {-51, 0, 0}, s);
  EXPECT_EQ(opened.state, ContactState::Open);
  EXPECT_FALSE(opened.bonded);
  // Sliding stops (locks) when the slip reverses against the friction direction.
  EXPECT_EQ(contact::judgeVertexContact(ContactState::Sliding, 1, false, {1000, 0, -1e-6}, s).state, ContactState::Locked);
  EXPECT_EQ(contact::judgeVertexContact(ContactState::Sliding, 1, false, {1000, 0, 1e-6}, s).state, ContactState::Sliding);
  // Open closes (locked) on penetration.
  EXPECT_EQ(contact::judgeVertexContact(ContactState::Open, 0, false, {1, 0, 0}, s).state, ContactState::Locked);
  // ... sliding if a lock could not hold the step's relative motion: the shear a lock would take
  // (lockedShear of an open contact) beyond N tanφ = 577.35.
  EXPECT_EQ(contact::judgeVertexContact(ContactState::Open, 0, false, {1000, 577, 0}, s).state, ContactState::Locked);
  const auto landed = contact::judgeVertexContact(ContactState::Open, 0, false, {1000, -578, 0}, s);
  EXPECT_EQ(landed.state, ContactState::Sliding);
  EXPECT_EQ(landed.direction, -1);
  // Bonded, it holds up to c·L + N tanφ = 677.35, and a brittle bond is lost once sliding.
  EXPECT_EQ(contact::judgeVertexContact(ContactState::Open, 0, true, {1000, 677, 0}, s).state, ContactState::Locked);
  EXPECT_FALSE(contact::judgeVertexContact(ContactState::Open, 0, true, {1000, 678, 0}, s).bonded);
}

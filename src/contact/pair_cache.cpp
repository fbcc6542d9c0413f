#include "ddaslope/contact/pair_cache.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace ddaslope::contact {

namespace {

constexpr std::uint32_t kVertexOnB = 1u << 31;
constexpr int kFieldLimit = 1 << 15;  ///< vertex numbers are packed in 15 bits, edge numbers in 16

bool pairLess(const BlockPair& x, const BlockPair& y) { return x.a != y.a ? x.a < y.a : x.b < y.b; }

}  // namespace

bool PairCache::holds(const Entry& e) const {
  // Every vertex has moved from where the search saw it by at most its drift then plus its drift
  // now (both from the same anchor). Half the slack: a margin for the round-off of the drifts and
  // of the slack itself.
  const Anchor& a = anchors_[static_cast<size_t>(e.pair.a)];
  const Anchor& b = anchors_[static_cast<size_t>(e.pair.b)];
  return e.slack > 0 && e.epochA == a.epoch && e.epochB == b.epoch && e.driftA + a.drift <= 0.5 * e.slack &&
         e.driftB + b.drift <= 0.5 * e.slack;
}

void PairCache::prepare(const Polygons& blocks, const std::vector<BlockPair>& pairs, const NarrowPhaseSettings& s,
                        long knownVersion) {
  if (knownVersion != expectedVersion_ || s.searchDistance != searchDistance_ ||
      s.sinParallelTolerance != sinParallelTolerance_ || anchors_.size() != blocks.size()) {
    entries_.clear();
    anchors_.assign(blocks.size(), Anchor{});
    searchDistance_ = s.searchDistance;
    sinParallelTolerance_ = s.sinParallelTolerance;
  }
  // Each block's drift from its anchor; a block whose vertices changed in number is anchored anew.
  std::vector<char> reanchor(blocks.size(), 0);
  for (size_t b = 0; b < blocks.size(); ++b) {
    Anchor& an = anchors_[b];
    const std::vector<Vec2>& v = *blocks[b];
    if (an.vertices.size() != v.size()) {
      reanchor[b] = 1;
      continue;
    }
    double drift = 0;
    for (size_t k = 0; k < v.size(); ++k) {
      const double d = (v[k] - an.vertices[k]).norm();
      drift = std::isfinite(d) ? std::max(drift, d) : INFINITY;  // a vertex not finite: never reused
    }
    an.drift = drift;
  }
  // Match this detection's pairs with the last one's (both sorted). A pair whose certificate has
  // run out anchors its blocks anew: searched on the new anchors, its next certificate starts from
  // a drift of 0. So does a pair whose searches without a certificate (Entry::reuses) end now.
  // (A new pair, or one that could not be certified, is searched as it is.)
  previous_.assign(pairs.size(), -1);
  prior_.assign(pairs.size(), -1);
  movedAway_.assign(pairs.size(), 0);
  size_t old = 0;
  for (size_t k = 0; k < pairs.size(); ++k) {
    while (old < entries_.size() && pairLess(entries_[old].pair, pairs[k])) ++old;
    if (old == entries_.size() || !(entries_[old].pair == pairs[k])) continue;
    prior_[k] = static_cast<int>(old);
    const Entry& e = entries_[old];
    const size_t a = static_cast<size_t>(pairs[k].a), b = static_cast<size_t>(pairs[k].b);
    if (!e.certified && e.wait == 0) reanchor[a] = reanchor[b] = 1;
    const bool held = holds(e);
    if (reanchor[a] || reanchor[b] || !held) {
      // Its blocks moved beyond the certificate (not only anchored anew for another pair).
      movedAway_[k] = !held && e.slack > 0 && e.epochA == anchors_[a].epoch && e.epochB == anchors_[b].epoch;
      if (e.slack > 0) reanchor[a] = reanchor[b] = 1;
      continue;
    }
    previous_[k] = static_cast<int>(old);
  }
  for (size_t b = 0; b < blocks.size(); ++b) {
    if (!reanchor[b]) continue;
    Anchor& an = anchors_[b];
    an.vertices = *blocks[b];
    an.drift = 0;
    ++an.epoch;
  }
  // A pair matched above whose block was anchored anew since (for another pair) is searched too.
  reused_ = searched_ = 0;
  for (size_t k = 0; k < pairs.size(); ++k) {
    if (previous_[k] >= 0 && !holds(entries_[static_cast<size_t>(previous_[k])])) previous_[k] = -1;
    ++(previous_[k] >= 0 ? reused_ : searched_);
  }
  next_.assign(pairs.size(), Entry{});
  waited_ = 0;
  for (size_t k = 0; k < pairs.size(); ++k) {
    Entry& e = next_[k];
    e.pair = pairs[k];
    // Whether a pair searched anew certifies its search (Entry::reuses), from its last search.
    e.certified = true;
    if (previous_[k] >= 0 || prior_[k] < 0) continue;
    const Entry& last = entries_[static_cast<size_t>(prior_[k])];
    e.level = last.level;
    if (last.wait > 0) {
      e.certified = false;
      e.wait = static_cast<std::uint8_t>(last.wait - 1);
    } else if (last.certified && last.slack > 0 && last.reuses > 0) {
      e.level = 0;
    } else if (last.certified && (!(last.slack > 0) || movedAway_[k])) {  // not given, or lapsed unused
      e.level = static_cast<std::uint8_t>(std::min(last.level + 1, kMaxLevel));
      e.certified = false;
      e.wait = static_cast<std::uint8_t>((1 << e.level) - 2);
    }
    waited_ += !e.certified;
  }
}

void PairCache::find(int k, const Polygons& blocks, const NarrowPhaseSettings& s, const Known& known,
                     std::vector<ContactCandidate>& out, const std::vector<geometry::Aabb>* boxes) {
  Entry& e = next_[static_cast<size_t>(k)];
  const int a = e.pair.a, b = e.pair.b;
  const std::vector<Vec2>& pa = *blocks[static_cast<size_t>(a)];
  const std::vector<Vec2>& pb = *blocks[static_cast<size_t>(b)];
  if (const int old = previous_[static_cast<size_t>(k)]; old >= 0) {
    e = entries_[static_cast<size_t>(old)];
    ++e.reuses;
    for (int q = 0; q < e.count; ++q) {
      const Found f = e.found[q];
      const int v = static_cast<int>((f >> 16) & 0x7fff), edge = static_cast<int>(f & 0xffff);
      out.push_back((f & kVertexOnB) ? contactCandidate(b, pb, v, a, pa, edge, s)
                                     : contactCandidate(a, pa, v, b, pb, edge, s));
    }
    return;
  }
  const size_t first = out.size();
  std::array<geometry::Aabb, 2> pairBoxes;
  if (boxes) pairBoxes = {(*boxes)[static_cast<size_t>(a)], (*boxes)[static_cast<size_t>(b)]};
  const std::array<geometry::Aabb, 2>* given = boxes ? &pairBoxes : nullptr;
  if (!e.certified) {
    // The same contacts as a certified search finds, without a certificate: not reused.
    findContacts(a, pa, b, pb, s, known, out, nullptr, given);
    e.slack = 0;
    return;
  }
  SearchMargin margin;
  findContacts(a, pa, b, pb, s, known, out, &margin, given);
  const Anchor& anA = anchors_[static_cast<size_t>(a)];
  const Anchor& anB = anchors_[static_cast<size_t>(b)];
  e.epochA = anA.epoch, e.epochB = anB.epoch;
  e.driftA = anA.drift, e.driftB = anB.drift;
  e.slack = margin.tooManyQuestions || out.size() - first > static_cast<size_t>(kMaxFound) ? 0 : margin.slack;
  e.count = 0;
  for (size_t q = first; q < out.size() && e.slack > 0; ++q) {
    const ContactKey& key = out[q].key;
    if (key.vertex >= kFieldLimit || key.edge >= 2 * kFieldLimit) e.slack = 0;
    e.found[e.count++] = (key.vertexBlock == b ? kVertexOnB : 0u) | static_cast<std::uint32_t>(key.vertex) << 16 |
                         static_cast<std::uint32_t>(key.edge);
  }
  // The search's answers from `known` must be those it will get at the next step, when the
  // contact set is the one this detection makes: a key was known iff this search finds it.
  for (int q = 0; q < margin.askedCount && e.slack > 0; ++q) {
    const auto& [key, answer] = margin.asked[static_cast<size_t>(q)];
    const bool found = std::any_of(out.begin() + static_cast<long>(first), out.end(),
                                   [&](const ContactCandidate& c) { return c.key == key; });
    if (found != answer) e.slack = 0;
  }
  if (!(e.slack > 0)) e.slack = 0;
}

void PairCache::finish(long knownVersion) {
  entries_.swap(next_);
  expectedVersion_ = knownVersion;
}

}  // namespace ddaslope::contact

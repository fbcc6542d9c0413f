#pragma once
// The pair cache's certification of a narrow-phase search (contact/pair_cache.hpp): for each
// decision the search takes (a vertex inside the contact region, a corner convex, an edge within
// reach, the entrance chosen), how far the blocks' vertices may move before it could change. The
// search calls these hooks beside its geometric tests; without a SearchMargin they are inert and
// the search is the plain geometry (narrow_phase.cpp). Private to narrow_phase.cpp.
#include <cmath>
#include <functional>
#include <initializer_list>
#include <limits>

#include "ddaslope/contact/narrow_phase.hpp"

namespace ddaslope::contact::detail {

struct Poly {
  int block;
  const std::vector<Vec2>& p;
  /// Per vertex, NarrowPhaseSettings::flatCorners' flags: kFlatCorner, kInternalEdge (the edge
  /// from the vertex).
  const std::vector<char>* flat = nullptr;
  int n() const { return static_cast<int>(p.size()); }
  bool flatAt(int k) const { return flat && ((*flat)[static_cast<size_t>(wrap(k))] & kFlatCorner); }
  bool internalEdge(int e) const { return flat && ((*flat)[static_cast<size_t>(wrap(e))] & kInternalEdge); }
  /// Vertex k, for k from −1 to n (every caller steps at most one past either end): a wrap
  /// without the two divisions of a general modulo, which the hot loops below paid per access.
  int wrap(int k) const { return k < 0 ? k + n() : k >= n() ? k - n() : k; }
  const Vec2& at(int k) const { return p[static_cast<size_t>(wrap(k))]; }
  bool convex(int k) const { return !flatAt(k) && cross(at(k) - at(k - 1), at(k + 1) - at(k)) > 0; }
};

/// Records how far each decision of one search is from changing (SearchMargin); inert without
/// a margin, so that a search that certifies nothing pays for nothing.
class Certifier {
 public:
  Certifier(SearchMargin* m, const Poly& A, const Poly& B) : m_(m) {
    if (!m_) return;
    double shortest = INFINITY, extent = 0;
    bool finite = true;
    for (const Poly* P : {&A, &B})
      for (int k = 0; k < P->n(); ++k) {
        shortest = std::min(shortest, (P->at(k + 1) - P->at(k)).norm());
        extent = std::max(extent, P->at(k).cwiseAbs().maxCoeff());
        finite = finite && std::isfinite(P->at(k).x()) && std::isfinite(P->at(k).y());
      }
    unitRate = 5 / shortest;
    cornerRate = 4 * 0.01 * shortest;
    // Every quantity is computed from coordinates as large as `extent`, so it is known only to a
    // few units of round-off of them: a decision closer than that to its threshold is a tie.
    noise_ = 64 * std::numeric_limits<double>::epsilon() * extent;
    hold(finite && shortest > 0 ? 0.01 * shortest : 0);
  }
  /// The slack the search certifies: none if a decision was within round-off of changing.
  ~Certifier() {
    if (m_ && !(m_->slack > noise_)) m_->slack = 0;
  }
  bool on() const { return m_ != nullptr; }
  /// A decision that must not change, `slack` (m of vertex motion) from changing.
  void hold(double slack) {
    if (m_) m_->slack = std::min(m_->slack, slack);
  }
  /// known(k), recorded.
  bool ask(const std::function<bool(const ContactKey&)>& known, const ContactKey& k) {
    const bool answer = known(k);
    if (m_) {
      if (m_->askedCount < static_cast<int>(m_->asked.size()))
        m_->asked[static_cast<size_t>(m_->askedCount++)] = {k, answer};
      else
        m_->tooManyQuestions = true;
    }
    return answer;
  }
  /// Rate of change of a unit edge direction per metre of vertex motion (SearchMargin).
  double unitRate = 0;
  /// The second-order part of a corner's cross product: 4δ² with δ at most its cap.
  double cornerRate = 0;

 private:
  SearchMargin* m_;
  double noise_ = 0;
};

/// "Skip if T1 || T2 || …", tested in order. A skip holds while its first true test stays true;
/// going on (to a contact) holds while every test stays false. A slack is computed only when
/// the search certifies.
class SkipChain {
 public:
  explicit SkipChain(Certifier& c) : c_(c) {}
  template <class Slack>
  bool skipIf(bool test, const Slack& slack) {
    if (!c_.on()) return test;
    if (test) {
      c_.hold(slack());
      return true;
    }
    pending_ = std::min(pending_, slack());
    return false;
  }
  /// A contact came out of the tests: each must stay false.
  void passed() { c_.hold(pending_); }

 private:
  Certifier& c_;
  double pending_ = INFINITY;
};

/// The slack of "every d ≥ 0" (each d changing at `rate`): the smallest d if all are, else the
/// largest shortfall (any negative d that stays negative keeps the answer).
inline double allNonNegativeSlack(std::initializer_list<double> d, double rate) {
  double smallest = INFINITY, shortfall = 0;
  for (double x : d) {
    smallest = std::min(smallest, x);
    if (x < 0) shortfall = std::max(shortfall, -x);
  }
  return (smallest >= 0 ? smallest : shortfall) / rate;
}

/// The slack of V.convex(k): its cross product over the rate 2(|e1| + |e2|) + 4δ².
inline double convexSlack(const Poly& V, int k, const Certifier& cert) {
  if (V.flatAt(k)) return INFINITY;  // set by the scene, not by the vertex's position
  const Vec2 e1 = V.at(k) - V.at(k - 1), e2 = V.at(k + 1) - V.at(k);
  return std::abs(cross(e1, e2)) / (2 * (e1.norm() + e2.norm()) + cert.cornerRate);
}

/// How fast the gap of vertex p on the edge from a changes: 2 + |p − a| · the unit rate.
inline double gapRate(const Vec2& p, const Vec2& a, const Certifier& cert) { return 2 + (p - a).norm() * cert.unitRate; }

/// The slack of nearestVertex's choice: the margin of every other vertex's distance over the
/// nearest one's (each distance changes at rate 2).
inline double nearestSlack(const Vec2& p, const Poly& B, int nearest) {
  const double dn = (p - B.at(nearest)).norm();
  double slack = INFINITY;
  for (int q = 0; q < B.n(); ++q)
    if (q != nearest) slack = std::min(slack, std::abs((p - B.at(q)).norm() - dn) / 4);
  return slack;
}

}  // namespace ddaslope::contact::detail

#include "ddaslope/solver/factor_springs.hpp"

#include <algorithm>
#include <cmath>

namespace ddaslope::solver {

namespace {

/// √k·v over the global unknowns: the first `dof` entries of each free block's half of v.
SparseCholesky::Column column(const ContactSprings& c, double k, const Vec12& v, int dof) {
  SparseCholesky::Column col;
  const double s = std::sqrt(k);
  for (int side = 0; side < 2; ++side) {
    const int block = side == 0 ? c.blockI : c.blockJ;
    if (block < 0) continue;
    for (int e = 0; e < dof; ++e) {
      col.rows[col.count] = dof * block + e;
      col.values[col.count] = s * v[6 * side + e];
      ++col.count;
    }
  }
  return col;
}

void sortByKey(std::vector<ContactSprings>& v) {
  const auto less = [](const ContactSprings& a, const ContactSprings& b) { return a.key < b.key; };
  if (!std::is_sorted(v.begin(), v.end(), less)) std::sort(v.begin(), v.end(), less);
}

}  // namespace

void FactorSprings::record(std::vector<ContactSprings> springs) {
  recorded_ = std::move(springs);
  switched_.resize(recorded_.size());
  for (size_t r = 0; r < recorded_.size(); ++r)
    switched_[r] = {recorded_[r].key, recorded_[r].normalK > 0, recorded_[r].shearK > 0};
}

void FactorSprings::reset(std::vector<ContactSprings> inFactor) {
  sortByKey(inFactor);
  record(std::move(inFactor));
  valid_ = true;
}

bool FactorSprings::holdsSame(const std::vector<contact::Contact>& contacts) const {
  size_t r = 0;
  for (const contact::Contact& c : contacts) {
    if (!c.closed()) continue;
    if (r == switched_.size() || !(switched_[r].key == c.key()) || !switched_[r].normal ||
        switched_[r].shear != (c.state == contact::ContactState::Locked))
      return false;
    ++r;
  }
  return r == switched_.size();
}

void FactorSprings::changes(std::vector<ContactSprings> now, int dof, std::vector<SparseCholesky::Column>& added,
                            std::vector<SparseCholesky::Column>& removed) {
  added.clear();
  removed.clear();
  sortByKey(now);
  const auto leave = [&](const ContactSprings& old) {
    if (old.normalK > 0) removed.push_back(column(old, old.normalK, old.normal, dof));
    if (old.shearK > 0) removed.push_back(column(old, old.shearK, old.shear, dof));
  };
  // Merge the two key-sorted lists.
  size_t r = 0;
  for (ContactSprings& c : now) {
    while (r < recorded_.size() && recorded_[r].key < c.key) leave(recorded_[r++]);  // gone since the record
    const ContactSprings* old = r < recorded_.size() && recorded_[r].key == c.key ? &recorded_[r++] : nullptr;
    const bool normalWas = old && old->normalK > 0, shearWas = old && old->shearK > 0;
    if (normalWas && !(c.normalK > 0)) removed.push_back(column(*old, old->normalK, old->normal, dof));
    if (c.normalK > 0 && !normalWas) added.push_back(column(c, c.normalK, c.normal, dof));
    if (shearWas && !(c.shearK > 0)) removed.push_back(column(*old, old->shearK, old->shear, dof));
    if (c.shearK > 0 && !shearWas) added.push_back(column(c, c.shearK, c.shear, dof));
    // A spring that stays on keeps the vector the factor holds.
    if (normalWas && c.normalK > 0) c.normal = old->normal, c.normalK = old->normalK;
    if (shearWas && c.shearK > 0) c.shear = old->shear, c.shearK = old->shearK;
  }
  while (r < recorded_.size()) leave(recorded_[r++]);
  record(std::move(now));
}

}  // namespace ddaslope::solver

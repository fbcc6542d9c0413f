#pragma once
// A support's terms in the DDA equations (docs/supports.md): an axial spring between the head
// point of one block and the end point of another, Shi's bolt. With n the unit vector from head
// to end and T(x) a block's displacement matrix at x, the step's elongation is linear in the
// step's unknowns,
//   Δe = v·[D_head; D_end],  v = [−T_head(x_h)ᵀ n; T_end(x_e)ᵀ n],
// and the support's potential N0·Δe + ½ k Δe² (N0 its force at the step's start, k its stiffness
// while elastic) adds k·v·vᵀ to K (coupling the two blocks like a contact spring) and −N0·v to b.
#include "ddaslope/core/types.hpp"
#include "ddaslope/model/block.hpp"
#include "ddaslope/model/support.hpp"

namespace ddaslope::assembly {

/// v of support s on its blocks' present geometry (head's six entries, then the end's).
Vec12 supportElongationVector(const model::Support& s, const model::Block& head, const model::Block& end);

}  // namespace ddaslope::assembly

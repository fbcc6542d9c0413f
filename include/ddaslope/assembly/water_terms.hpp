#pragma once
// Water pressure on a block's edges as generalised forces (dda-method.md §2: ∫ Tᵀ n p along the
// edge, Gauss points; exact because T and the hydrostatic p are linear between breakpoints).
#include "ddaslope/core/types.hpp"
#include "ddaslope/model/block.hpp"
#include "ddaslope/model/water.hpp"

namespace ddaslope::assembly {

/// Generalised force of the water pressure on all edges of the block (pressure pushes along the
/// inward normal of a counter-clockwise polygon).
Vec6 waterForce(const model::Block& block, const model::WaterTable& water);

/// Resultant force of the water on one edge a → b of a counter-clockwise polygon (N/m).
Vec2 edgeWaterResultant(const Vec2& a, const Vec2& b, const model::WaterTable& water);

}  // namespace ddaslope::assembly

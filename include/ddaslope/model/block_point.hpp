#pragma once
#include "ddaslope/core/types.hpp"

namespace ddaslope::model {

/// A point carried by a block (monitor, load point, fixed point, support end): it moves with the
/// block.
struct BlockPoint {
  int block = 0;
  Vec2 initial{0, 0};
  Vec2 current{0, 0};
};

}  // namespace ddaslope::model

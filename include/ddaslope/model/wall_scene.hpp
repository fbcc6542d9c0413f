#pragma once
// A running-bond brick wall on a fixed base, built in code: the step-cost benchmark's scene
// (bench/bench_steps.cpp) and the 2000-block extreme of the test suite.
#include "ddaslope/model/scene.hpp"

namespace ddaslope::model {

/// About n bricks (2 m × 1 m, E = 10 GPa, ρ = 2600, joints φ = 35°) in running bond on a fixed
/// base: odd rows start and end with a half brick, so both ends are straight and no brick
/// overhangs (a stable wall). Δt = 1 ms, no monitors.
Scene makeBrickWall(int n);

}  // namespace ddaslope::model

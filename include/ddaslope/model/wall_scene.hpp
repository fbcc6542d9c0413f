#pragma once
// A running-bond brick wall on a fixed base, built in code: the step-cost benchmark's scene
// (bench/bench_steps.cpp) and the 2000-block extreme of the test suite.
#include "ddaslope/model/scene.hpp"

namespace ddaslope::model {

/// About n bricks (2 m × 1 m, E = 10 GPa, ρ = 2600, joints φ = 35°) in running bond on a fixed
/// base: odd rows start and end with a half brick, so both ends are straight and no brick
/// overhangs (a stable wall). Δt = 1 ms, no monitors.
Scene makeBrickWall(int n);

/// The side-by-side wall timed against Shi's DDA (ntdda) in ../shared/ntdda (make_wall.py and
/// wall_case.py there): `rows` rows of 1 m × 0.5 m bricks, `rows` per even row, odd rows offset
/// by half a brick (rows 22, 31, 45, 71 give 495, 976, 2047, 5076 bricks), ρ 2500, E 10 GPa,
/// ν 0.25, joints φ 30° without cohesion, penalty 1e11 N/m fixed, Δt 1 ms. `sudden`: no initial
/// equilibrium, full gravity at step 1 (ntdda's start).
Scene makeAnchorWall(int rows, bool sudden);

}  // namespace ddaslope::model

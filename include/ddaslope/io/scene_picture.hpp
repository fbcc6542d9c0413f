#pragma once
// Pictures of a running scene (PNG through cairo): blocks coloured by displacement, contact
// states marked, monitors, water. One file per requested time.
#include <string>
#include <vector>

#include "ddaslope/geometry/polygon.hpp"
#include "ddaslope/solver/simulation.hpp"

namespace ddaslope::io {

struct PictureFrame {
  geometry::Aabb view;                  ///< world window, fixed for all pictures of a run
  geometry::Aabb whole;                 ///< the whole scene, drawn as an inset when the view is zoomed
  bool zoomed = false;                  ///< the view shows the free blocks, not the whole scene
  std::vector<Vec2> initialCentroids;   ///< per block, to colour by displacement
};

/// Frames the scene as it is now: its free blocks with a margin (what can move), when they take
/// up less than a quarter of it (a slab on a large base), else the whole scene with a 5 % margin.
PictureFrame frameScene(const model::Scene& scene);

/// What a picture shows of a simulation at one moment, kept apart from it: a search keeps the
/// final state of its trials and draws only those at its bracket's ends.
struct SceneState {
  model::Scene scene;  ///< blocks where they are, supports in their states
  struct ContactMark {
    int block = 0, vertex = 0;  ///< the contact's vertex
    bool locked = true;         ///< locked or sliding (open contacts are not kept)
  };
  std::vector<ContactMark> contacts;
  double time = 0;
};
SceneState captureState(const solver::Simulation& sim);

/// Draws the simulation's current state to `path` (PNG, 1000 px wide).
void writeScenePicture(const solver::Simulation& sim, const PictureFrame& frame, const std::string& path,
                       const std::string& title);
/// `displacementScale` (m): the colour bar's and arrows' full scale is at least this (a search's
/// failure displacement), so that a block at rest is not drawn as the most moved.
void writeScenePicture(const SceneState& state, const PictureFrame& frame, const std::string& path,
                       const std::string& title, double displacementScale = 0);

}  // namespace ddaslope::io

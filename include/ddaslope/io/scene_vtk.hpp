#pragma once
// A running scene as VTK grids for ParaView (docs/case-format.md, "VTK series"): blocks as
// polygons, contacts as lines, the water table as a polyline. Each kind is a series of its own
// (<kind>_<label>.vtu files listed in <kind>.pvd), as DEM codes write particles and their
// interactions apart (Yade's VTKRecorder), so that each is coloured by its own arrays.
#include <string>
#include <vector>

#include "ddaslope/io/vtk_writer.hpp"
#include "ddaslope/solver/simulation.hpp"

namespace ddaslope::io {

/// One polygon per block, in the case's order. Cell data: block_id, material, fixed,
/// displacement and velocity of the centroid, rotation, angular_velocity, stress (σx, σy, τxy).
/// Displacement and rotation count from the case's geometry (`initialCentroids`), as
/// history.csv's monitors do. Field data: block_names, material_names.
VtkGrid blocksGrid(const solver::Simulation& sim, const std::vector<Vec2>& initialCentroids);

/// One line per contact of the last accepted step (open ones too), drawn from the contact vertex
/// into its block along the normal of the edge it touches, 0.15 √(smaller block area) long: the
/// contact sits where it acts and shows at any zoom, where the vertex-to-edge gap (µm) would not.
/// Cell data: state (0 open, 1 sliding, 2 locked), normal_force, shear_force, bonded, joint,
/// vertex_block, edge_block, edge_to_edge, slip. Field data: joint_names.
VtkGrid contactsGrid(const solver::Simulation& sim);

/// The water table at the simulation's time as one polyline across the blocks' current extent
/// (flat beyond the phreatic line's ends); no cell without water.
VtkGrid waterGrid(const solver::Simulation& sim);

/// Writes frames of the three series into one folder. Thread-safe: the trials of a search write
/// their final states from their own threads.
class VtkRecorder {
 public:
  /// `scene`: the case as read (displacements count from it). Creates `dir` and removes the
  /// files of an earlier series there.
  VtkRecorder(const std::string& dir, const model::Scene& scene);
  /// blocks_<label>.vtu, contacts_<label>.vtu (and water_<label>.vtu when the scene has water,
  /// supports_<label>.vtu when it has supports), then their entries at `timestep` in blocks.pvd,
  /// contacts.pvd, water.pvd, supports.pvd. `notes`: more field
  /// data for every file of the frame (a trial's value and verdict).
  void write(const solver::Simulation& sim, double timestep, const std::string& label,
             const std::vector<VtkArray>& notes = {});
  const std::string& dir() const { return dir_; }

 private:
  std::string dir_;
  std::vector<Vec2> initialCentroids_;
  bool water_ = false, supports_ = false;
  PvdCollection blocks_, contacts_, waterSeries_, supportSeries_;
};

/// True when everything a frame writes is finite (a diverged run's last state is not).
bool finiteState(const solver::Simulation& sim);

/// Removes the files a VtkRecorder writes in `dir` (nothing else), and `dir` if it is then empty:
/// a run's outputs must not sit beside a stale series that contradicts them.
void removeVtkSeries(const std::string& dir);

}  // namespace ddaslope::io

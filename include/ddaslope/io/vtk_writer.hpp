#pragma once
// VTK XML files, the only place that knows the format ("VTK File Formats", VTK User's Guide
// ch. 19, docs.vtk.org): an UnstructuredGrid piece (.vtu) whose arrays are raw binary appended
// data with UInt64 size headers, and the Collection (.pvd) that makes files a time series for
// ParaView. A grid here is planar: its points are written with z = 0.
#include <cstdint>
#include <mutex>
#include <string>
#include <variant>
#include <vector>

#include "ddaslope/core/types.hpp"

namespace ddaslope::io {

/// VTK's cell type codes (vtkCellType.h).
enum class VtkCellType : std::uint8_t { Vertex = 1, Line = 3, PolyLine = 4, Polygon = 7 };

/// A named array of cell data (one tuple per cell) or field data (any number of tuples).
/// Float64 and Int32 numbers; strings in field data only (VTK's vtkStringArray).
struct VtkArray {
  std::string name;
  int components = 1;
  std::vector<std::string> componentNames;  ///< optional: ParaView labels the components with them
  std::variant<std::vector<double>, std::vector<std::int32_t>, std::vector<std::string>> values;
  size_t tuples() const;
};

struct VtkGrid {
  std::vector<Vec2> points;                 ///< written as (x, y, 0)
  std::vector<std::int64_t> connectivity;   ///< point indices of every cell, one cell after the other
  std::vector<std::int64_t> offsets;        ///< end of each cell in connectivity (VTK's convention)
  std::vector<std::uint8_t> types;          ///< VtkCellType per cell
  std::vector<VtkArray> cellData, fieldData;

  /// Appends a cell made of new points, in order.
  void addCell(VtkCellType type, const std::vector<Vec2>& cellPoints);
  size_t cells() const { return types.size(); }
};

/// The whole .vtu file. Every cell array must have one tuple per cell and Float64 values must be
/// finite (an internal error otherwise: a file must never promise a number and hold NaN).
std::string vtuBytes(const VtkGrid& grid);
/// Writes `path` through `path.tmp` and a rename, so that a reader never sees half a file.
void writeVtu(const std::string& path, const VtkGrid& grid);

struct PvdEntry {
  double timestep = 0;  ///< the series' time axis: simulated time, or a search's trial value
  std::string file;     ///< relative to the .pvd
};
/// A Collection file listing `entries` by increasing timestep.
std::string pvdText(std::vector<PvdEntry> entries);

/// A .pvd that lists exactly the files written so far after every entry added, so that an
/// interrupted run leaves a valid series: an entry after the last is written over the closing
/// tags in one write; any other (a search's trials come in any order) rewrites the file through a
/// temporary file and a rename. Thread-safe.
class PvdCollection {
 public:
  explicit PvdCollection(std::string path) : path_(std::move(path)) {}
  void add(double timestep, const std::string& file);

 private:
  std::string path_;
  std::vector<PvdEntry> entries_;
  std::mutex mutex_;
};

/// `text` with & < > " as XML (and HTML) entities.
std::string xmlEscaped(const std::string& text);

}  // namespace ddaslope::io

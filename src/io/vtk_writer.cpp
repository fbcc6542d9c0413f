#include "ddaslope/io/vtk_writer.hpp"

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "ddaslope/core/errors.hpp"

namespace ddaslope::io {
namespace {

/// Shortest text that reads back as the same double, whatever the locale.
std::string number(double v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}


/// The appended block: each array is a UInt64 byte count followed by its bytes in the
/// machine's byte order (the file's byte_order attribute says which).
class AppendedData {
 public:
  /// Appends an array's bytes and returns its offset (from the character after the '_').
  size_t add(const void* data, size_t bytes) {
    const size_t offset = data_.size();
    const std::uint64_t header = bytes;
    data_.append(reinterpret_cast<const char*>(&header), sizeof header);
    if (bytes > 0) data_.append(static_cast<const char*>(data), bytes);
    return offset;
  }
  template <class T>
  size_t add(const std::vector<T>& v) {
    return add(v.data(), v.size() * sizeof(T));
  }
  const std::string& bytes() const { return data_; }

 private:
  std::string data_;
};

const char* vtkTypeName(const VtkArray& a) {
  switch (a.values.index()) {
    case 0: return "Float64";
    case 1: return "Int32";
    default: return "String";
  }
}

/// One array's XML element (its data goes to `appended`).
std::string arrayElement(const VtkArray& a, AppendedData& appended, bool field, const std::string& indent) {
  size_t offset = 0;
  if (const auto* d = std::get_if<std::vector<double>>(&a.values)) {
    DDASLOPE_ASSERT(std::all_of(d->begin(), d->end(), [](double v) { return std::isfinite(v); }),
                    "VTK array \"" + a.name + "\" holds a value that is not finite");
    offset = appended.add(*d);
  } else if (const auto* i = std::get_if<std::vector<std::int32_t>>(&a.values)) {
    offset = appended.add(*i);
  } else {
    // vtkStringArray: the strings one after the other, each ended by a NUL.
    std::string joined;
    for (const std::string& s : std::get<std::vector<std::string>>(a.values)) joined.append(s.c_str(), s.size() + 1);
    offset = appended.add(joined.data(), joined.size());
  }
  const bool strings = a.values.index() == 2;
  std::string e = indent + (strings ? "<Array" : "<DataArray") + " type=\"" + vtkTypeName(a) + "\" Name=\"" +
                  xmlEscaped(a.name) + "\"";
  if (a.components != 1) e += " NumberOfComponents=\"" + std::to_string(a.components) + "\"";
  for (size_t k = 0; k < a.componentNames.size(); ++k)
    e += " ComponentName" + std::to_string(k) + "=\"" + xmlEscaped(a.componentNames[k]) + "\"";
  if (field) e += " NumberOfTuples=\"" + std::to_string(a.tuples()) + "\"";
  e += " format=\"appended\" offset=\"" + std::to_string(offset) + "\"/>\n";
  return e;
}

constexpr const char* kPvdEnd = "  </Collection>\n</VTKFile>\n";

std::string pvdLine(const PvdEntry& e) {
  return "    <DataSet timestep=\"" + number(e.timestep) + "\" part=\"0\" file=\"" + xmlEscaped(e.file) + "\"/>\n";
}

void renameInto(const std::string& tmp, const std::string& path) {
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) throw InputError(path, "", "cannot write the file: " + ec.message());
}

}  // namespace

size_t VtkArray::tuples() const {
  const size_t n = std::visit([](const auto& v) { return v.size(); }, values);
  return values.index() == 2 ? n : n / static_cast<size_t>(components);
}

void VtkGrid::addCell(VtkCellType type, const std::vector<Vec2>& cellPoints) {
  for (const Vec2& p : cellPoints) {
    connectivity.push_back(static_cast<std::int64_t>(points.size()));
    points.push_back(p);
  }
  offsets.push_back(static_cast<std::int64_t>(connectivity.size()));
  types.push_back(static_cast<std::uint8_t>(type));
}

std::string vtuBytes(const VtkGrid& g) {
  static_assert(std::endian::native == std::endian::little || std::endian::native == std::endian::big);
  const char* order = std::endian::native == std::endian::little ? "LittleEndian" : "BigEndian";
  for (const VtkArray& a : g.cellData)
    DDASLOPE_ASSERT(a.values.index() != 2 && a.tuples() == g.cells() &&
                        std::visit([](const auto& v) { return v.size(); }, a.values) == a.tuples() * a.components,
                    "VTK cell array \"" + a.name + "\" must hold one number tuple per cell");
  AppendedData appended;
  std::string xml = "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"" +
                    std::string(order) + "\" header_type=\"UInt64\">\n  <UnstructuredGrid>\n";
  if (!g.fieldData.empty()) {
    xml += "    <FieldData>\n";
    for (const VtkArray& a : g.fieldData) xml += arrayElement(a, appended, true, "      ");
    xml += "    </FieldData>\n";
  }
  xml += "    <Piece NumberOfPoints=\"" + std::to_string(g.points.size()) + "\" NumberOfCells=\"" +
         std::to_string(g.cells()) + "\">\n";
  if (!g.cellData.empty()) {
    xml += "      <CellData>\n";
    for (const VtkArray& a : g.cellData) xml += arrayElement(a, appended, false, "        ");
    xml += "      </CellData>\n";
  }
  std::vector<double> xyz;
  xyz.reserve(3 * g.points.size());
  for (const Vec2& p : g.points) xyz.insert(xyz.end(), {p.x(), p.y(), 0.0});
  xml += "      <Points>\n" +
         arrayElement({"Points", 3, {}, std::move(xyz)}, appended, false, "        ") + "      </Points>\n";
  xml += "      <Cells>\n";
  const auto cellArray = [&](const char* name, const char* type, size_t offset) {
    xml += std::string("        <DataArray type=\"") + type + "\" Name=\"" + name +
           "\" format=\"appended\" offset=\"" + std::to_string(offset) + "\"/>\n";
  };
  cellArray("connectivity", "Int64", appended.add(g.connectivity));
  cellArray("offsets", "Int64", appended.add(g.offsets));
  cellArray("types", "UInt8", appended.add(g.types));
  xml += "      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n  <AppendedData encoding=\"raw\">\n   _";
  xml += appended.bytes();
  xml += "\n  </AppendedData>\n</VTKFile>\n";
  return xml;
}

void writeVtu(const std::string& path, const VtkGrid& grid) {
  const std::string bytes = vtuBytes(grid);
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    if (!out) throw InputError(path, "", "cannot write the file");
  }
  renameInto(tmp, path);
}

std::string pvdText(std::vector<PvdEntry> entries) {
  std::stable_sort(entries.begin(), entries.end(),
                   [](const PvdEntry& a, const PvdEntry& b) { return a.timestep < b.timestep; });
  std::string xml = "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n  <Collection>\n";
  for (const PvdEntry& e : entries) xml += pvdLine(e);
  return xml + kPvdEnd;
}

void PvdCollection::add(double timestep, const std::string& file) {
  const std::lock_guard<std::mutex> lock(mutex_);
  // The same file again (a value tried twice) leaves its old place.
  const bool replaced = std::erase_if(entries_, [&](const PvdEntry& e) { return e.file == file; }) > 0;
  const bool last = !replaced && (entries_.empty() || timestep >= entries_.back().timestep);
  // Kept in timestep order, as listed (a search's trials come in any order).
  const auto at = std::upper_bound(entries_.begin(), entries_.end(), timestep,
                                   [](double t, const PvdEntry& e) { return t < e.timestep; });
  entries_.insert(at, {timestep, file});
  if (last && entries_.size() > 1 && std::filesystem::exists(path_)) {
    // A run's next frame: written over the closing tags in one write, so that a long series costs
    // each frame one line instead of the whole file (10 000 frames would write 3.5 GB per series).
    std::fstream out(path_, std::ios::in | std::ios::out | std::ios::binary);
    out.seekp(-static_cast<std::streamoff>(std::strlen(kPvdEnd)), std::ios::end);
    const std::string tail = pvdLine(entries_.back()) + kPvdEnd;
    out.write(tail.data(), static_cast<std::streamsize>(tail.size()));
    if (!out) throw InputError(path_, "", "cannot write the file");
    return;
  }
  const std::string tmp = path_ + ".tmp";
  {
    std::ofstream out(tmp);
    out << pvdText(entries_);
    if (!out) throw InputError(path_, "", "cannot write the file");
  }
  renameInto(tmp, path_);
}

std::string xmlEscaped(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

}  // namespace ddaslope::io

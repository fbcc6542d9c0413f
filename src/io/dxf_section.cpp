#include "ddaslope/io/dxf_section.hpp"

#include <dxflib/dl_creationadapter.h>
#include <dxflib/dl_dxf.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <mutex>
#include <sstream>
#include <string_view>

#include "ddaslope/core/errors.hpp"
#include "ddaslope/geometry/polyline_chain.hpp"
#include "ddaslope/io/input_file.hpp"
#include "ddaslope/model/input_limits.hpp"

namespace ddaslope::io {
namespace {

// ---------------------------------------------------------------------------------------------
// Units: $INSUNITS codes of the DXF reference. Those no slope section is drawn in (microinches,
// ångströms, parsecs, …) have no short name: a drawing declaring them is refused.

struct Unit {
  int code;
  const char* name;      ///< as the case writes it (section.dxf.units); empty: refused
  const char* longName;
  double metres;
};

constexpr std::array<Unit, 22> kUnits{{{0, "", "no units", 0},
                                       {1, "in", "inches", 0.0254},
                                       {2, "ft", "feet", 0.3048},
                                       {3, "mi", "miles", 1609.344},
                                       {4, "mm", "millimetres", 1e-3},
                                       {5, "cm", "centimetres", 1e-2},
                                       {6, "m", "metres", 1},
                                       {7, "km", "kilometres", 1e3},
                                       {8, "", "microinches", 0},
                                       {9, "", "mils", 0},
                                       {10, "yd", "yards", 0.9144},
                                       {11, "", "ångströms", 0},
                                       {12, "", "nanometres", 0},
                                       {13, "", "microns", 0},
                                       {14, "dm", "decimetres", 0.1},
                                       {15, "dam", "decametres", 10},
                                       {16, "hm", "hectometres", 100},
                                       {17, "", "gigametres", 0},
                                       {18, "", "astronomical units", 0},
                                       {19, "", "light years", 0},
                                       {20, "", "parsecs", 0},
                                       {21, "us_ft", "US survey feet", 1200.0 / 3937.0}}};

const Unit* unitByCode(int code) {
  for (const Unit& u : kUnits)
    if (u.code == code) return &u;
  return nullptr;
}

const Unit* unitByName(const std::string& name) {
  for (const Unit& u : kUnits)
    if (*u.name && name == u.name) return &u;
  return nullptr;
}

std::string unitNames() {
  std::string list;
  for (const Unit& u : kUnits)
    if (*u.name) list += (list.empty() ? "" : ", ") + std::string(u.name);
  return list;
}

/// Every error names the case file, a JSON path under section.dxf, and the drawing.
struct Refusal {
  std::string caseFile, base, dxf;
  [[noreturn]] void operator()(const std::string& key, const std::string& what) const {
    throw InputError(caseFile, base + "." + key, dxf + ": " + what);
  }
};

std::string shown(double v) {
  std::ostringstream s;
  s.precision(12);
  s << v;
  return s.str();
}

// ---------------------------------------------------------------------------------------------
// The text before dxflib sees it. dxflib trusts its input: it reads lines into a 1024-byte
// buffer (a longer line shifts every later pair), and allocates an LWPOLYLINE's, SPLINE's or
// LEADER's arrays from the count the file gives (an overflowing count overruns them).

constexpr size_t kLongestLine = 1022;   // dxflib's buffer less the newline and the terminator
constexpr long kLargestCount = 1000000;  // vertices or points of one entity

std::string_view stripped(std::string_view s, bool spaces) {
  while (!s.empty() && (s.back() == '\r' || (spaces && (s.back() == ' ' || s.back() == '\t')))) s.remove_suffix(1);
  while (spaces && !s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  return s;
}

bool integer(std::string_view s, long& v) {
  s = stripped(s, true);
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  return ec == std::errc() && end == s.data() + s.size() && !s.empty();
}

void checkText(const std::string& text, const Refusal& refuse) {
  if (text.rfind("AutoCAD Binary DXF", 0) == 0) refuse("file", "a binary DXF: save the drawing as ASCII DXF");
  if (text.find('\0') != std::string::npos) refuse("file", "not a DXF file: it holds binary data (NUL bytes)");
  size_t at = 0, line = 0;
  const auto nextLine = [&](std::string_view& out) {
    if (at >= text.size()) return false;
    const size_t end = std::min(text.find('\n', at), text.size());
    out = std::string_view(text).substr(at, end - at);
    at = end + 1;
    if (out.size() > kLongestLine)
      refuse("file", "line " + std::to_string(line + 1) + " is longer than the " + std::to_string(kLongestLine) +
                         " characters a DXF reader takes: not a DXF file, or a damaged one");
    ++line;
    return true;
  };
  std::string_view codeText, value, type;
  long code = 0;
  bool begun = false, ended = false;
  while (!ended && nextLine(codeText)) {
    if (!integer(codeText, code))
      refuse("file", "not a DXF file: line " + std::to_string(line) + " should be a group code (an integer), found \"" +
                         std::string(stripped(codeText, true).substr(0, 40)) + "\"");
    if (!nextLine(value)) refuse("file", "the file ends inside a group (line " + std::to_string(line) + "): truncated");
    value = stripped(value, false);
    if (!begun && code != 999) {
      if (code != 0 || stripped(value, true) != "SECTION")
        refuse("file", "not a DXF file: it does not begin with a section (group 0, SECTION)");
      begun = true;
    }
    if (code == 0) type = value;
    const bool count = (type == "LWPOLYLINE" && code == 90) || (type == "LEADER" && code == 76) ||
                       (type == "SPLINE" && code >= 72 && code <= 74);
    long n = 0;
    if (count && !(integer(value, n) && n >= 0 && n <= kLargestCount))
      refuse("file", "line " + std::to_string(line) + ": group " + std::to_string(code) + " of " + std::string(type) +
                         " gives a count of \"" + std::string(value.substr(0, 40)) +
                         "\": expected a whole number of at most " + std::to_string(kLargestCount));
    ended = code == 0 && stripped(value, true) == "EOF";
  }
  if (!begun) refuse("file", "not a DXF file: it is empty or holds only comments");
  if (!ended) refuse("file", "the drawing ends before its end-of-file marker (group 0, EOF): truncated");
  // dxflib would read on past the marker, unchecked; blank lines are all that may follow it.
  if (text.find_first_not_of(" \t\r\n", at) != std::string::npos)
    refuse("file", "text after the end-of-file marker (group 0, EOF) at line " + std::to_string(line));
}

// ---------------------------------------------------------------------------------------------
// The drawing as dxflib reports it. The group pairs name each entity (type, layer, handle);
// dxflib's callbacks give its geometry. dxflib reports an entity when the next one begins, so
// the callbacks belong to the entity whose pairs came just before (`finishing_`).

struct Entity {
  std::string type, layer = "0", handle;  // without group 8 an entity is on layer 0
  bool paperSpace = false;
  int index = 0;                 ///< among the model-space entities on its layer, from 1
  std::vector<Vec2> points;      ///< as drawn: WCS for LINE, the entity's own plane for polylines
  std::vector<double> z;
  int flags = 0;                 ///< POLYLINE / LWPOLYLINE group 70
  double elevation = 0;
  std::array<double, 3> extrusion{0, 0, 1};
  int bulgeAt = -1;              ///< first vertex starting an arc segment
  long declaredVertices = -1;    ///< LWPOLYLINE group 90
  long countedVertices = 0;      ///< LWPOLYLINE group 10s
};

struct Drawing {
  int insUnits = 0;  ///< absent: 0 (unitless)
  std::vector<std::string> tableLayers;
  std::vector<Entity> entities;  ///< the ENTITIES section, in file order
};

class DrawingReader : public DL_CreationAdapter {
 public:
  using DL_CreationAdapter::processCodeValuePair;
  using DL_CreationAdapter::setVariableInt;

  Drawing drawing;

  void processCodeValuePair(unsigned int code, const std::string& value) override {
    if (code == 0) {
      finishing_ = current_;
      current_ = -1;
      sectionNext_ = value == "SECTION";
      if (value == "ENDSEC") {
        section_.clear();
      } else if (section_ == "ENTITIES" && value != "VERTEX" && value != "SEQEND") {
        drawing.entities.emplace_back().type = value;
        current_ = static_cast<int>(drawing.entities.size()) - 1;
      }
      return;
    }
    if (sectionNext_ && code == 2) {
      section_ = value;
      sectionNext_ = false;
      return;
    }
    if (current_ < 0) return;
    Entity& e = drawing.entities[current_];
    long n = 0;
    if (code == 8) e.layer = value;
    else if (code == 5) e.handle = std::string(stripped(value, true));
    else if (code == 67) e.paperSpace = integer(value, n) && n == 1;
    else if (e.type == "LWPOLYLINE" && code == 90 && integer(value, n)) e.declaredVertices = n;
    else if (e.type == "LWPOLYLINE" && code == 10) ++e.countedVertices;
  }
  void addLayer(const DL_LayerData& d) override { drawing.tableLayers.push_back(d.name); }
  void setVariableInt(const std::string& key, int value, int) override {
    if (key == "$INSUNITS") drawing.insUnits = value;
  }
  void addLine(const DL_LineData& d) override {
    if (finishing_ < 0) return;  // in a block definition or outside ENTITIES
    Entity& e = drawing.entities[finishing_];
    e.points = {{d.x1, d.y1}, {d.x2, d.y2}};
    e.z = {d.z1, d.z2};
  }
  void addPolyline(const DL_PolylineData& d) override {
    polyline_ = finishing_;
    if (polyline_ < 0) return;
    Entity& e = drawing.entities[polyline_];
    e.flags = d.flags;
    const DL_Extrusion* x = getExtrusion();
    e.extrusion = {x->getDirection()[0], x->getDirection()[1], x->getDirection()[2]};
    e.elevation = x->getElevation();
  }
  void addVertex(const DL_VertexData& v) override {
    if (polyline_ < 0) return;
    Entity& e = drawing.entities[polyline_];
    if (v.bulge != 0 && e.bulgeAt < 0) e.bulgeAt = static_cast<int>(e.points.size());
    e.points.push_back({v.x, v.y});
    e.z.push_back(v.z);
  }

 private:
  std::string section_;
  bool sectionNext_ = false;
  int current_ = -1, finishing_ = -1, polyline_ = -1;
};

std::string upper(std::string s) {
  for (char& c : s) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return s;
}

Drawing readDrawing(const std::string& path, const Refusal& refuse) {
  checkText(readInputFile(path, kMaxDxfFileBytes, refuse.caseFile, refuse.base + ".file"), refuse);
  // dxflib counts lines in a function-static variable and swaps the global locale while it
  // reads: one drawing at a time (cases are read on several threads by back-analyses).
  static std::mutex oneAtATime;
  const std::lock_guard lock(oneAtATime);
  DL_Dxf dxf;
  DrawingReader reader;
  if (!dxf.in(path, &reader)) refuse("file", "cannot open the file");
  std::vector<std::pair<std::string, int>> counts;
  for (Entity& e : reader.drawing.entities) {
    if (e.paperSpace) continue;
    const std::string key = upper(e.layer);
    auto it = std::find_if(counts.begin(), counts.end(), [&](const auto& c) { return c.first == key; });
    if (it == counts.end()) it = counts.insert(counts.end(), {key, 0});
    e.index = ++it->second;
  }
  return reader.drawing;
}

// ---------------------------------------------------------------------------------------------
// Layers to lines.

std::string describe(const Entity& e) {
  return "layer \"" + e.layer + "\", " + e.type + " #" + std::to_string(e.index) +
         (e.handle.empty() ? "" : " (handle " + e.handle + ")");
}

/// An entity's points in the drawing's XY plane (drawing units).
struct Piece {
  std::vector<Vec2> points;
  const Entity* entity;
};

/// The model-space lines and polylines on a layer (named case-insensitively, as CAD does),
/// each checked to be a 2-D, straight-segmented, open line.
std::vector<Piece> piecesOnLayer(const Drawing& d, const std::string& layer, const std::string& key,
                                 const std::string& what, const Refusal& refuse) {
  std::vector<Piece> pieces;
  bool named = false;  // by the layer table or by an entity, in model or paper space
  for (const std::string& l : d.tableLayers) named |= upper(l) == upper(layer);
  for (const Entity& e : d.entities) {
    named |= upper(e.layer) == upper(layer);
    if (e.paperSpace || upper(e.layer) != upper(layer)) continue;
    const auto bad = [&](const std::string& why) { refuse(key, describe(e) + ": " + why); };
    const bool lw = e.type == "LWPOLYLINE", poly = e.type == "POLYLINE";
    if (e.type != "LINE" && !lw && !poly)
      bad("an entity of type " + e.type + " where " + what +
          " is drawn: only LINE, LWPOLYLINE and POLYLINE of straight segments are read (explode blocks, "
          "draw arcs and splines as polylines, move text and other entities to another layer)");
    if (lw && e.declaredVertices != e.countedVertices)
      bad("declares " + std::to_string(e.declaredVertices) + " vertices (group 90) but has " +
          std::to_string(e.countedVertices) + ": a damaged file");
    if (poly && (e.flags & (16 | 64))) bad("a polygon or polyface mesh, not a line");
    if ((lw || poly) && (e.flags & (2 | 4)))
      bad("a curve- or spline-fit polyline: its drawn curve is not its vertices; remove the fit (PEDIT Decurve)");
    if (e.bulgeAt >= 0)
      bad("vertex " + std::to_string(e.bulgeAt + 1) + " starts an arc segment (bulge): draw it with straight segments");
    if (e.points.size() < 2) bad("fewer than two points");
    // A 2-D polyline lies in the plane of its extrusion direction; (0, 0, −1) is the XY plane
    // seen from below, its x mirrored (the DXF reference's arbitrary axis algorithm).
    const bool planar = lw || (poly && !(e.flags & 8));
    double mirror = 1;
    if (planar) {
      const auto& n = e.extrusion;
      if (std::abs(n[0]) > 1e-12 || std::abs(n[1]) > 1e-12 || std::abs(std::abs(n[2]) - 1) > 1e-12)
        bad("drawn in a tilted plane (extrusion direction (" + shown(n[0]) + ", " + shown(n[1]) + ", " + shown(n[2]) +
            ")): draw the section in the XY plane");
      mirror = n[2] < 0 ? -1 : 1;
    }
    for (size_t i = 0; i < e.z.size(); ++i) {
      const double z = e.z[i] + (planar ? e.elevation : 0);
      if (z != 0)
        bad("point " + std::to_string(i + 1) + " is at z = " + shown(z) +
            ": a section is drawn in the XY plane at z = 0 (a 3-D drawing is refused, not flattened: flatten it "
            "in CAD if its projection is the section)");
    }
    if (e.flags & 1) bad("a closed polyline, where " + what + " is an open line across the section");
    Piece p{e.points, &e};
    for (Vec2& v : p.points) v.x() *= mirror;
    pieces.push_back(std::move(p));
  }
  if (pieces.empty()) {
    if (named) refuse(key, "layer \"" + layer + "\" holds no lines or polylines in model space");
    std::vector<std::string> names = d.tableLayers;
    for (const Entity& e : d.entities)
      if (std::find(names.begin(), names.end(), e.layer) == names.end()) names.push_back(e.layer);
    std::string list;
    for (const std::string& n : names) list += (list.empty() ? "" : ", ") + ("\"" + n + "\"");
    refuse(key, "no layer \"" + layer + "\" in the drawing (its layers: " + list + ")");
  }
  return pieces;
}

double extentOf(const std::vector<Piece>& pieces) {
  Vec2 lo(INFINITY, INFINITY), hi(-INFINITY, -INFINITY);
  for (const Piece& p : pieces)
    for (const Vec2& v : p.points) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
  return (hi - lo).maxCoeff();
}

/// A drawn line with, for each point, the entity it came from.
struct DrawnLine {
  std::vector<Vec2> points;
  std::vector<const Entity*> from;
};

/// The pieces on a layer joined into one open line, turned to run with x increasing.
DrawnLine oneLine(const std::vector<Piece>& pieces, const std::string& key, const std::string& what,
                  const Refusal& refuse) {
  std::vector<std::vector<Vec2>> points;
  for (const Piece& p : pieces) points.push_back(p.points);
  const double tol = 1e-9 * extentOf(pieces);
  const geometry::Chain c = geometry::joinEndToEnd(points, tol);
  if (c.stray >= 0)
    refuse(key, describe(*pieces[c.stray].entity) +
                    ": does not meet the other entities on the layer end to end (a gap or a branch); " + what +
                    " is one line: snap its pieces together, or move this one to another layer");
  if (c.closed)
    refuse(key, describe(*pieces.front().entity) +
                    (pieces.size() > 1 ? " and the other entities on the layer close into a loop" : ": its ends meet") +
                    ", where " + what + " is an open line across the section");
  // A vertex doubled in place (a common CAD artefact) is one point of the line.
  DrawnLine line;
  for (size_t i = 0; i < c.points.size(); ++i)
    if (line.points.empty() || (c.points[i] - line.points.back()).norm() > tol) {
      line.points.push_back(c.points[i]);
      line.from.push_back(pieces[c.pieceOf[i]].entity);
    }
  if (line.points.size() < 2)
    refuse(key, describe(*pieces.front().entity) + ": its points all coincide, where " + what +
                    " is a line of at least two distinct points");
  if (line.points.front().x() > line.points.back().x()) {
    std::reverse(line.points.begin(), line.points.end());
    std::reverse(line.from.begin(), line.from.end());
  }
  return line;
}

}  // namespace

DxfSection readDxfSection(const DxfSectionSource& src, const std::string& caseFile, const std::string& jsonPath) {
  const Refusal refuse{caseFile, jsonPath, src.file};
  const Unit* asked = src.units.empty() ? nullptr : unitByName(src.units);
  if (!src.units.empty() && !asked)
    throw InputError(caseFile, jsonPath + ".units", "expected one of " + unitNames() + ", found \"" + src.units + "\"");
  const Drawing drawing = readDrawing(src.file, refuse);

  // The drawing's declared units win over nothing and must agree with the case's; a drawing
  // without units takes the case's, and one of neither is refused rather than guessed.
  const Unit* declared = drawing.insUnits == 0 ? nullptr : unitByCode(drawing.insUnits);
  const std::string header = "$INSUNITS = " + std::to_string(drawing.insUnits);
  if (drawing.insUnits != 0 && !(declared && *declared->name))
    refuse("units", "the drawing declares its units as " + std::string(declared ? declared->longName : "an unknown code") +
                        " (" + header + "): not a unit ddaslope reads a section in (" + unitNames() + ")");
  if (declared && asked && declared != asked)
    refuse("units", "the drawing declares its units as " + std::string(declared->longName) + " (" + header +
                        "), the case says \"" + src.units + "\": correct the one that is wrong");
  if (!declared && !asked)
    refuse("units", "the drawing declares no units ($INSUNITS 0 or absent): give section.dxf.units (" + unitNames() + ")");
  const Unit& unit = asked ? *asked : *declared;
  const double metresPerUnit = unit.metres * src.scale;

  DxfSection out;
  std::ostringstream summary;
  summary << "section drawn in " << src.file << " (" << unit.longName
          << (declared ? ", declared by the drawing" : ", as the case says") << "; scale " << shown(src.scale) << "):";
  const auto pointFrom = [&](const DrawnLine& l, size_t i) {
    return src.file + ": " + describe(*l.from[i]) + " at (" + shown(l.points[i].x()) + ", " + shown(l.points[i].y()) +
           ") " + unit.name;
  };
  const auto inMetres = [&](const std::vector<Vec2>& drawn) {
    std::vector<Vec2> m;
    for (const Vec2& v : drawn) m.push_back(v * metresPerUnit);
    return m;
  };
  const auto typesOf = [](const std::vector<Piece>& pieces) {
    std::string types;
    for (const char* t : {"LINE", "LWPOLYLINE", "POLYLINE"}) {
      const auto n = std::count_if(pieces.begin(), pieces.end(), [&](const Piece& p) { return p.entity->type == t; });
      if (n > 0) types += (types.empty() ? "" : " + ") + std::to_string(n) + " " + t;
    }
    return types;
  };
  const auto line = [&](const std::string& layer, const std::string& key, const std::string& what,
                        std::vector<Vec2>& points, std::vector<std::string>* from) {
    const std::vector<Piece> pieces = piecesOnLayer(drawing, layer, key, what, refuse);
    const DrawnLine l = oneLine(pieces, key, what, refuse);
    points = inMetres(l.points);
    if (from)
      for (size_t i = 0; i < l.points.size(); ++i) from->push_back(pointFrom(l, i));
    summary << " " << what.substr(4) << " " << l.points.size() << " points from " << typesOf(pieces) << " on \""
            << layer << "\";";
    return l;
  };
  line(src.groundLayer, "layers.ground", "the ground", out.ground, &out.groundFrom);
  line(src.slidingSurfaceLayer, "layers.sliding_surface", "the sliding surface", out.slidingSurface,
       &out.slidingSurfaceFrom);
  if (!src.jointsLayer.empty()) {
    const std::vector<Piece> pieces = piecesOnLayer(drawing, src.jointsLayer, "layers.joints", "a joint", refuse);
    for (const Piece& p : pieces) {
      // A joint is a straight line (the cut extends it through the mass): a polyline of more
      // points must keep to the line through its ends.
      const Vec2 a = p.points.front(), b = p.points.back();
      const double length = (b - a).norm();
      for (size_t i = 1; i + 1 < p.points.size(); ++i)
        if (!(std::abs(cross((b - a) / length, p.points[i] - a)) <= 1e-6 * length))
          refuse("layers.joints", describe(*p.entity) + ": bends at point " + std::to_string(i + 1) +
                                      ": a joint is one straight line (draw each joint as its own LINE)");
      out.joints.emplace_back(a * metresPerUnit, b * metresPerUnit);
      out.jointFrom.push_back(src.file + ": " + describe(*p.entity));
    }
    summary << " " << pieces.size() << (pieces.size() == 1 ? " joint" : " joints") << " from " << typesOf(pieces)
            << " on \"" << src.jointsLayer << "\";";
  }
  if (!src.waterLineLayer.empty()) {
    const DrawnLine l = line(src.waterLineLayer, "layers.water_line", "the water line", out.waterLine, nullptr);
    for (size_t i = 1; i < l.points.size(); ++i)
      if (!(l.points[i].x() > l.points[i - 1].x()))
        refuse("layers.water_line", describe(*l.from[i]) + " at (" + shown(l.points[i].x()) + ", " +
                                        shown(l.points[i].y()) + ") " + unit.name +
                                        ": expected x increasing along the water line (one height at each x)");
  }

  // Units or a scale that are wrong by a factor of 1000 put the section outside what a scene may
  // be; say so here, where the cause is, rather than at the blocks.
  Vec2 lo = out.ground.front(), hi = lo;
  for (const auto* pts : {&out.ground, &out.slidingSurface})
    for (const Vec2& v : *pts) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
  const double size = (hi - lo).maxCoeff();
  if (!(size >= model::limits::kMinSceneSize && size <= model::limits::kMaxSceneSize))
    refuse(src.scale != 1 ? "scale" : "units",
           "the ground and sliding surface span " + shown(size) + " m read in " + unit.longName + " at scale " +
               shown(src.scale) + ": outside the 1 mm to 1000 km a scene may be; are the units or the scale wrong?");
  std::string text = summary.str();
  text.pop_back();  // the last semicolon
  out.summary = text;
  return out;
}

}  // namespace ddaslope::io

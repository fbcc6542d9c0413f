// Reading ntdda's geometry and analysis files (DDAML and the original text form). The DDAML
// elements are flat and simple, so a small XML reader of our own serves (no new dependency).
#include "ddaslope/io/ntdda_model.hpp"

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <map>
#include <sstream>

#include "ddaslope/core/errors.hpp"
#include "ddaslope/io/input_file.hpp"

namespace ddaslope::io {

std::string NtddaSource::where() const {
  return "line " + std::to_string(line) + (element.empty() ? std::string() : ": <" + element + ">");
}

namespace {

/// ntdda's largest models have tens of thousands of joint lines: a few MB.
constexpr std::uintmax_t kMaxNtddaFileBytes = 64u << 20;
constexpr int kMaxXmlDepth = 64;
/// The case's limit is 50 000 blocks; a few lines per block.
constexpr size_t kMaxJointLines = 200'000;
constexpr double kMaxCoordinate = 1e9;

struct XmlNode {
  std::string name;  ///< without its namespace prefix ("Berkeley:Geometry" → "Geometry")
  std::map<std::string, std::string> attributes;
  std::string text;  ///< the element's own character data, children's left out
  std::vector<XmlNode> children;
  int line = 0;
};

class XmlReader {
 public:
  XmlReader(const std::string& text, std::string file) : s_(text), file_(std::move(file)) {}

  XmlNode document() {
    skipMisc();
    if (pos_ >= s_.size() || s_[pos_] != '<') fail("an XML element", "no element");
    XmlNode root = element(0);
    skipMisc();
    if (pos_ < s_.size()) fail("the end of the file after </" + root.name + ">", "more content");
    return root;
  }

 private:
  [[noreturn]] void fail(const std::string& expected, const std::string& found) const {
    throw InputError(file_, "line " + std::to_string(line_), "malformed XML: expected " + expected + ", found " + found);
  }
  bool startsWith(const char* p) const { return s_.compare(pos_, std::char_traits<char>::length(p), p) == 0; }
  void advance(size_t n) {
    for (size_t i = 0; i < n && pos_ < s_.size(); ++i) line_ += s_[pos_++] == '\n';
  }
  void skipTo(const char* end, const std::string& what) {
    const size_t at = s_.find(end, pos_);
    if (at == std::string::npos) fail(std::string("\"") + end + "\" closing " + what, "the end of the file");
    advance(at - pos_ + std::char_traits<char>::length(end));
  }
  void skipSpace() {
    while (pos_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[pos_]))) advance(1);
  }
  /// Declarations, comments, a DOCTYPE (with any internal subset) and white space.
  void skipMisc() {
    for (;;) {
      skipSpace();
      if (startsWith("<?")) skipTo("?>", "a processing instruction");
      else if (startsWith("<!--")) skipTo("-->", "a comment");
      else if (startsWith("<!DOCTYPE")) {
        int depth = 0;
        for (; pos_ < s_.size(); advance(1)) {
          if (s_[pos_] == '[') ++depth;
          else if (s_[pos_] == ']') --depth;
          else if (s_[pos_] == '>' && depth <= 0) break;
        }
        if (pos_ >= s_.size()) fail("'>' closing <!DOCTYPE", "the end of the file");
        advance(1);
      } else return;
    }
  }
  std::string name() {
    const size_t start = pos_;
    while (pos_ < s_.size() && (std::isalnum(static_cast<unsigned char>(s_[pos_])) || s_[pos_] == ':' ||
                                s_[pos_] == '_' || s_[pos_] == '-' || s_[pos_] == '.'))
      advance(1);
    if (pos_ == start) fail("a name", pos_ < s_.size() ? std::string("'") + s_[pos_] + "'" : "the end of the file");
    return s_.substr(start, pos_ - start);
  }
  std::string decoded(const std::string& raw) const {
    std::string out;
    for (size_t i = 0; i < raw.size(); ++i) {
      if (raw[i] != '&') {
        out += raw[i];
        continue;
      }
      const size_t semi = raw.find(';', i);
      const std::string ent = semi == std::string::npos ? "" : raw.substr(i + 1, semi - i - 1);
      static const std::map<std::string, char> named{{"lt", '<'}, {"gt", '>'}, {"amp", '&'}, {"quot", '"'}, {"apos", '\''}};
      if (const auto it = named.find(ent); it != named.end()) out += it->second;
      else if (ent.size() > 1 && ent[0] == '#') {
        const long code = ent[1] == 'x' ? std::strtol(ent.c_str() + 2, nullptr, 16) : std::strtol(ent.c_str() + 1, nullptr, 10);
        out += code > 0 && code < 128 ? static_cast<char>(code) : '?';
      } else fail("an entity (&lt; &gt; &amp; &quot; &apos; &#N;)", "'&" + ent.substr(0, 20) + "'");
      i = semi;
    }
    return out;
  }
  static std::string localName(const std::string& n) {
    const size_t colon = n.rfind(':');
    return colon == std::string::npos ? n : n.substr(colon + 1);
  }

  XmlNode element(int depth) {
    if (depth > kMaxXmlDepth) fail("elements nested at most " + std::to_string(kMaxXmlDepth) + " deep", "deeper ones");
    XmlNode node;
    node.line = line_;
    advance(1);  // '<'
    const std::string qname = name();
    node.name = localName(qname);
    for (;;) {
      skipSpace();
      if (startsWith("/>")) {
        advance(2);
        return node;
      }
      if (startsWith(">")) {
        advance(1);
        break;
      }
      const std::string attr = localName(name());
      skipSpace();
      if (!startsWith("=")) fail("'=' after attribute " + attr + " of <" + qname + ">", "something else");
      advance(1);
      skipSpace();
      if (pos_ >= s_.size() || (s_[pos_] != '"' && s_[pos_] != '\''))
        fail("a quoted value of attribute " + attr + " of <" + qname + ">", "no quote");
      const char quote = s_[pos_];
      advance(1);
      const size_t end = s_.find(quote, pos_);
      if (end == std::string::npos) fail("the closing quote of attribute " + attr, "the end of the file");
      node.attributes[attr] = decoded(s_.substr(pos_, end - pos_));
      advance(end - pos_ + 1);
    }
    for (;;) {
      if (pos_ >= s_.size()) fail("</" + qname + "> closing the element of line " + std::to_string(node.line), "the end of the file");
      if (startsWith("<!--")) skipTo("-->", "a comment");
      else if (startsWith("<![CDATA[")) {
        advance(9);
        const size_t end = s_.find("]]>", pos_);
        if (end == std::string::npos) fail("]]> closing CDATA", "the end of the file");
        node.text += s_.substr(pos_, end - pos_);
        advance(end - pos_ + 3);
      } else if (startsWith("<?")) skipTo("?>", "a processing instruction");
      else if (startsWith("</")) {
        advance(2);
        const std::string closing = name();
        skipSpace();
        if (closing != qname) fail("</" + qname + "> closing the element of line " + std::to_string(node.line), "</" + closing + ">");
        if (!startsWith(">")) fail("'>'", "something else");
        advance(1);
        return node;
      } else if (s_[pos_] == '<') node.children.push_back(element(depth + 1));
      else {
        const size_t end = s_.find('<', pos_);
        const size_t stop = end == std::string::npos ? s_.size() : end;
        node.text += decoded(s_.substr(pos_, stop - pos_));
        advance(stop - pos_);
      }
    }
  }

  const std::string& s_;
  std::string file_;
  size_t pos_ = 0;
  int line_ = 1;
};

std::string quoted(const std::string& text) {
  std::string t = text;
  for (char& c : t)
    if (c == '\n' || c == '\r' || c == '\t') c = ' ';
  const size_t a = t.find_first_not_of(' '), b = t.find_last_not_of(' ');
  t = a == std::string::npos ? "" : t.substr(a, b - a + 1);
  if (t.size() > 60) t = t.substr(0, 57) + "...";
  return t.empty() ? "nothing" : "\"" + t + "\"";
}

/// One whitespace-separated number: finite, and nothing else in the token.
bool parseNumber(const std::string& token, double* v) {
  if (token.empty()) return false;
  char* end = nullptr;
  *v = std::strtod(token.c_str(), &end);
  return end == token.c_str() + token.size() && std::isfinite(*v);
}

/// Exactly `n` finite numbers in `text`.
std::vector<double> numbers(const std::string& text, size_t n, const std::string& file, const NtddaSource& src,
                            const std::string& what) {
  std::istringstream in(text);
  std::vector<double> v;
  std::string tok;
  while (in >> tok) {
    double x = 0;
    if (!parseNumber(tok, &x))
      throw InputError(file, src.where(), "expected " + what + " (" + std::to_string(n) + " finite numbers), found " + quoted(text));
    v.push_back(x);
  }
  if (v.size() != n)
    throw InputError(file, src.where(), "expected " + what + " (" + std::to_string(n) + " finite numbers), found " + quoted(text));
  return v;
}

double attributeNumber(const XmlNode& n, const std::string& attr, const std::string& file) {
  const NtddaSource src{n.line, n.name};
  const auto it = n.attributes.find(attr);
  if (it == n.attributes.end()) throw InputError(file, src.where(), "expected the attribute " + attr + ", found none");
  double v = 0;
  const size_t a = it->second.find_first_not_of(" \t\r\n"), b = it->second.find_last_not_of(" \t\r\n");
  if (a == std::string::npos || !parseNumber(it->second.substr(a, b - a + 1), &v))
    throw InputError(file, src.where(), "expected " + attr + " to be a finite number, found \"" + it->second + "\"");
  return v;
}

int typeAttribute(const XmlNode& n, const std::string& file, int fallback) {
  if (!n.attributes.count("type")) {
    if (fallback > 0) return fallback;
    throw InputError(file, NtddaSource{n.line, n.name}.where(), "expected the attribute type (a whole number from 1), found none");
  }
  const double t = attributeNumber(n, "type", file);
  if (t < 1 || t > 1e6 || t != std::floor(t))
    throw InputError(file, NtddaSource{n.line, n.name}.where(),
                     "expected type to be a whole number from 1, found \"" + n.attributes.at("type") + "\"");
  return static_cast<int>(t);
}

bool flag(const XmlNode& n, const std::string& attr = "flag") {
  const auto it = n.attributes.find(attr);
  return it != n.attributes.end() && it->second == "yes";
}

XmlNode parseDdaml(const std::string& path, const std::string& section) {
  const std::string text = readInputFile(path, kMaxNtddaFileBytes);
  XmlNode root = XmlReader(text, path).document();
  if (root.name != "DDA")
    throw InputError(path, NtddaSource{root.line, root.name}.where(), "expected the root element <Berkeley:DDA>, found <" + root.name + ">");
  for (XmlNode& c : root.children)
    if (c.name == section) return std::move(c);
  throw InputError(path, NtddaSource{root.line, root.name}.where(), "expected a <" + section + "> element, found none");
}

void readGeometryXml(NtddaGeometry& g) {
  const XmlNode geo = parseDdaml(g.file, "Geometry");
  const auto lineOf = [&](const XmlNode& n, int type) {
    const NtddaSource src{n.line, n.name};
    const auto v = numbers(n.text, 4, g.file, src, "x1 y1 x2 y2");
    return NtddaLine{{v[0], v[1]}, {v[2], v[3]}, type, src};
  };
  const auto pointOf = [&](const XmlNode& n) {
    const NtddaSource src{n.line, n.name};
    const auto v = numbers(n.text, 2, g.file, src, "x y");
    return NtddaPoint{{v[0], v[1]}, src};
  };
  const auto expectOnly = [&](const XmlNode& list, const char* child) {
    for (const XmlNode& c : list.children)
      if (c.name != child)
        throw InputError(g.file, NtddaSource{c.line, c.name}.where(),
                         "expected <" + std::string(child) + "> in <" + list.name + ">, found <" + c.name + ">");
  };
  for (const XmlNode& n : geo.children) {
    if (n.name == "Edgenodedist") {
      g.edgeNodeDistance = attributeNumber(n, "distance", g.file);
      if (g.edgeNodeDistance < 0 || g.edgeNodeDistance > 0.5)
        throw InputError(g.file, NtddaSource{n.line, n.name}.where(),
                         "expected distance in [0, 0.5] (a fraction of the model's scale), found " + n.attributes.at("distance"));
    } else if (n.name == "Jointlist") {
      expectOnly(n, "Joint");
      for (const XmlNode& c : n.children) g.joints.push_back(lineOf(c, typeAttribute(c, g.file, 0)));
    } else if (n.name == "Fixedpointlist") {
      for (const XmlNode& c : n.children) {
        if (c.name == "Point") g.fixedPoints.push_back(pointOf(c));
        else if (c.name == "Line") g.fixedLines.push_back(lineOf(c, 0));
        else throw InputError(g.file, NtddaSource{c.line, c.name}.where(), "expected <Point> or <Line> in <Fixedpointlist>, found <" + c.name + ">");
      }
    } else if (n.name == "Measuredpointlist" || n.name == "Loadpointlist" || n.name == "Holepointlist" ||
               n.name == "Seismicpointlist") {
      expectOnly(n, "Point");
      auto& list = n.name[0] == 'M' ? g.measuredPoints : n.name[0] == 'L' ? g.loadPoints : n.name[0] == 'H' ? g.holePoints : g.seismicPoints;
      for (const XmlNode& c : n.children) list.push_back(pointOf(c));
    } else if (n.name == "Boltlist") {
      expectOnly(n, "Bolt");
      for (const XmlNode& c : n.children) g.bolts.push_back(lineOf(c, typeAttribute(c, g.file, 1)));
    } else if (n.name == "Matlinelist") {
      expectOnly(n, "Line");
      for (const XmlNode& c : n.children) g.materialLines.push_back(lineOf(c, typeAttribute(c, g.file, 0)));
    } else if (n.name == "Boundlist") {
      expectOnly(n, "Line");
      for (const XmlNode& c : n.children) g.boundaryLines.push_back(lineOf(c, 0));
    } else {
      g.unmapped.push_back({n.line, n.name});
    }
  }
}

/// The original text form: whitespace-separated numbers, each known with its line.
class TextNumbers {
 public:
  TextNumbers(const std::string& text, std::string file) : file_(std::move(file)) {
    std::istringstream in(text);
    std::string lineText;
    for (int line = 1; std::getline(in, lineText); ++line) {
      std::istringstream words(lineText);
      std::string w;
      while (words >> w) tokens_.push_back({w, line});
    }
  }
  double next(const std::string& what) {
    if (at_ >= tokens_.size())
      throw InputError(file_, "line " + std::to_string(tokens_.empty() ? 1 : tokens_.back().second),
                       "expected " + what + ", found the end of the file");
    const auto& [tok, line] = tokens_[at_++];
    double v = 0;
    if (!parseNumber(tok, &v))
      throw InputError(file_, "line " + std::to_string(line), "expected " + what + " (a finite number), found \"" + tok + "\"");
    return v;
  }
  int count(const std::string& what, int most) {
    const double v = next(what);
    if (v < 0 || v > most || v != std::floor(v))
      throw InputError(file_, "line " + std::to_string(line()), "expected " + what + " (a whole number in [0, " +
                                                                   std::to_string(most) + "]), found " + tokens_[at_ - 1].first);
    return static_cast<int>(v);
  }
  int line() const { return at_ == 0 ? 1 : tokens_[at_ - 1].second; }
  bool done() const { return at_ >= tokens_.size(); }

 private:
  std::vector<std::pair<std::string, int>> tokens_;
  size_t at_ = 0;
  std::string file_;
};

constexpr int kMaxCount = 10'000'000;

void readGeometryText(NtddaGeometry& g, const std::string& text) {
  g.xml = false;
  TextNumbers in(text, g.file);
  g.edgeNodeDistance = in.next("the edge-node distance e00");
  const int nJoints = in.count("the number of joint lines", kMaxCount);
  in.count("the number of boundary lines", kMaxCount);  // ntdda reads it and uses none of it
  const int nMat = in.count("the number of material lines", kMaxCount);
  const int nBolts = in.count("the number of bolts", kMaxCount);
  const int boltsLine = in.line();
  const int nFixed = in.count("the number of fixed points", kMaxCount);
  const int nLoad = in.count("the number of load points", kMaxCount);
  const int nMeasured = in.count("the number of measured points", kMaxCount);
  const int nHole = in.count("the number of hole points", kMaxCount);
  if (nBolts > 0)
    g.notes.push_back("line " + std::to_string(boltsLine) + ": " + std::to_string(nBolts) +
                      " bolts counted, but the text form holds no bolt lines (ntdda reads none): not mapped");
  const auto line = [&](const char* what, bool typed) {
    NtddaLine l;
    const std::string w = std::string(what) + " x1 y1 x2 y2" + (typed ? " type" : "");
    l.a.x() = in.next(w);
    l.source = {in.line(), what};
    l.a.y() = in.next(w), l.b.x() = in.next(w), l.b.y() = in.next(w);
    if (typed) {
      const double t = in.next(w);
      if (t < 1 || t != std::floor(t) || t > 1e6)
        throw InputError(g.file, "line " + std::to_string(in.line()), std::string("expected the ") + what + "'s type (a whole number from 1), found " + std::to_string(t));
      l.type = static_cast<int>(t);
    }
    return l;
  };
  const auto point = [&](const char* what) {
    NtddaPoint p;
    p.p.x() = in.next(std::string(what) + " x y");
    p.source = {in.line(), what};
    p.p.y() = in.next(std::string(what) + " x y");
    return p;
  };
  for (int i = 0; i < nJoints; ++i) g.joints.push_back(line("joint line", true));
  for (int i = 0; i < nMat; ++i) g.materialLines.push_back(line("material line", true));
  for (int i = 0; i < nFixed; ++i) {
    NtddaLine l = line("fixed line", false);
    if (l.a == l.b) g.fixedPoints.push_back({l.a, {l.source.line, "fixed point"}});
    else g.fixedLines.push_back(l);
  }
  for (int i = 0; i < nLoad; ++i) g.loadPoints.push_back(point("load point"));
  for (int i = 0; i < nMeasured; ++i) g.measuredPoints.push_back(point("measured point"));
  for (int i = 0; i < nHole; ++i) g.holePoints.push_back(point("hole point"));
}

bool looksLikeXml(const std::string& text) {
  const size_t first = text.find_first_not_of(" \t\r\n\xEF\xBB\xBF");
  return first != std::string::npos && text[first] == '<';
}

void readAnalysisXml(NtddaAnalysis& a) {
  const XmlNode an = parseDdaml(a.file, "Analysis");
  for (const XmlNode& n : an.children) {
    const NtddaSource src{n.line, n.name};
    const auto text = [&](const XmlNode& c, const std::string& what) {
      return numbers(c.text, 1, a.file, NtddaSource{c.line, c.name}, what)[0];
    };
    if (n.name == "Analysistype") a.dynamic = n.attributes.count("type") && n.attributes.at("type") == "dynamic";
    else if (n.name == "Gravity") a.gravityPhase = flag(n);
    else if (n.name == "Gravaccel") a.gravity = attributeNumber(n, "value", a.file);
    else if (n.name == "Planestrain") a.planeStrain = flag(n);
    else if (n.name == "Autotimestep") {
      // A fixed step is ddaslope's own (a nominal Δt, cut when a step fails).
      if (flag(n)) a.notes.push_back(src.where() + ": ntdda's automatic time step: the case runs Maxtimestep as its nominal step");
    }
    else if (n.name == "Numtimesteps") {
      const double s = attributeNumber(n, "timesteps", a.file);
      if (s < 1 || s > 1e9 || s != std::floor(s))
        throw InputError(a.file, src.where(), "expected timesteps to be a whole number in [1, 1e9], found " + n.attributes.at("timesteps"));
      a.steps = static_cast<int>(s);
    } else if (n.name == "Maxtimestep") a.timeStep = attributeNumber(n, "maxtimestep", a.file);
    else if (n.name == "Maxdisplacement") a.maxDisplacement = attributeNumber(n, "maxdisplacement", a.file);
    else if (n.name == "Autopenalty") {
      a.autoPenalty = flag(n);
      if (n.attributes.count("pfactor")) a.penaltyFactor = attributeNumber(n, "pfactor", a.file);
    } else if (n.name == "Blockmaterial") {
      NtddaMaterial m;
      m.source = src;
      for (const XmlNode& c : n.children) {
        const NtddaSource cs{c.line, c.name};
        if (c.name == "Unitmass") m.unitMass = text(c, "the unit mass");
        else if (c.name == "Unitweight") m.unitWeight = text(c, "the unit weight");
        else if (c.name == "Youngsmod") m.youngModulus = text(c, "Young's modulus");
        else if (c.name == "Poissonratio") m.poissonRatio = text(c, "Poisson's ratio");
        else if (c.name == "Damping") m.damping = text(c, "the damping");
        else if (c.name == "Istress" || c.name == "Istrain" || c.name == "Ivelocity") {
          const auto v = numbers(c.text, 3, a.file, cs, "three initial values");
          double* into = c.name == "Istress" ? m.stress : c.name == "Istrain" ? m.strain : m.velocity;
          for (int k = 0; k < 3; ++k) into[k] = v[k];
        } else a.unmapped.push_back(cs);
      }
      a.materials.push_back(m);
    } else if (n.name == "Jointproperties") {
      NtddaJointType j;
      j.source = src;
      for (const XmlNode& c : n.children) {
        if (c.name == "Friction") j.friction = text(c, "the friction angle (degrees)");
        else if (c.name == "Cohesion") j.cohesion = text(c, "the cohesion");
        else if (c.name == "Tensile") j.tensile = text(c, "the tensile strength");
        else a.unmapped.push_back({c.line, c.name});
      }
      a.joints.push_back(j);
    } else if (n.name == "Loadpointlist") {
      for (const XmlNode& c : n.children) {
        const NtddaSource cs{c.line, c.name};
        if (c.name != "Loadpoint")
          throw InputError(a.file, cs.where(), "expected <Loadpoint> in <Loadpointlist>, found <" + c.name + ">");
        NtddaLoadHistory h;
        h.source = cs;
        std::istringstream records(c.text);
        std::string record;
        while (std::getline(records, record, ';')) {
          if (record.find_first_not_of(" \t\r\n") == std::string::npos) continue;
          const auto v = numbers(record, 3, a.file, cs, "a record t fx fy");
          h.records.push_back({v[0], v[1], v[2]});
        }
        if (h.records.empty()) throw InputError(a.file, cs.where(), "expected records \"t fx fy;\", found " + quoted(c.text));
        a.loads.push_back(h);
      }
    } else if (n.name == "Boltproperties") {
      const auto v = numbers(n.text, 3, a.file, src, "stiffness strength pretension");
      a.bolts.push_back({v[0], v[1], v[2], src});
    } else if (n.name == "Rotation" && n.attributes.count("type") && n.attributes.at("type") == "linear") {
      // Shi's linear rotation; ddaslope updates vertices by the exact rotation (block.hpp), which
      // differs from it by O(r0²) per step only.
    } else {
      a.unmapped.push_back(src);
    }
  }
}

void readAnalysisText(NtddaAnalysis& a, const std::string& text) {
  a.xml = false;
  TextNumbers in(text, a.file);
  a.dynamic = in.next("the analysis type (0 static, 1 dynamic)") != 0;
  a.steps = in.count("the number of time steps", 1'000'000'000);
  const int nMat = in.count("the number of block materials", 100000);
  const int nJoint = in.count("the number of joint types", 100000);
  a.maxDisplacement = in.next("the maximum displacement ratio g2");
  a.timeStep = in.next("the maximum time step");
  // No load history in this form: ntdda takes every fixed and load point as constant.
  for (int i = 0; i < nMat; ++i) {
    NtddaMaterial m;
    const std::string w = "material " + std::to_string(i + 1) + ": unit mass, unit weight, E, ν, 3 stresses, 3 strains, 3 velocities";
    m.unitMass = in.next(w);
    m.source = {in.line(), "material " + std::to_string(i + 1)};
    m.unitWeight = in.next(w), m.youngModulus = in.next(w), m.poissonRatio = in.next(w);
    for (double& s : m.stress) s = in.next(w);
    for (double& s : m.strain) s = in.next(w);
    for (double& v : m.velocity) v = in.next(w);
    a.materials.push_back(m);
  }
  for (int i = 0; i < nJoint; ++i) {
    NtddaJointType j;
    const std::string w = "joint type " + std::to_string(i + 1) + ": friction angle, cohesion, tensile strength";
    j.friction = in.next(w);
    j.source = {in.line(), "joint type " + std::to_string(i + 1)};
    j.cohesion = in.next(w), j.tensile = in.next(w);
    a.joints.push_back(j);
  }
  if (!in.done()) a.notes.push_back("line " + std::to_string(in.line()) + ": values after the joint types are not read");
  // ntdda's text form: automatic penalty of 50 × E and gravity from the first material.
  a.penaltyFactor = 50;
  a.autoPenalty = true;
  a.notes.push_back("the text form's time step is the largest of ntdda's automatic ones: the case runs it as its nominal step");
  if (!a.materials.empty() && a.materials[0].unitMass > 0) a.gravity = a.materials[0].unitWeight / a.materials[0].unitMass;
}

}  // namespace

NtddaGeometry readNtddaGeometry(const std::string& path) {
  NtddaGeometry g;
  g.file = path;
  const std::string text = readInputFile(path, kMaxNtddaFileBytes);
  if (looksLikeXml(text)) readGeometryXml(g);
  else readGeometryText(g, text);
  if (g.joints.empty()) throw InputError(path, "", "expected joint lines, found none");
  if (g.joints.size() > kMaxJointLines)
    throw InputError(path, "", "expected at most " + std::to_string(kMaxJointLines) + " joint lines, found " + std::to_string(g.joints.size()));
  // Beyond any national grid; products of such coordinates stay far from overflow.
  const auto farOff = [](const Vec2& p) { return std::abs(p.x()) > kMaxCoordinate || std::abs(p.y()) > kMaxCoordinate; };
  const auto refuse = [&](const NtddaSource& s, const Vec2& p) {
    throw InputError(path, s.where(), "expected coordinates within ±1e9 m, found (" + std::to_string(p.x()) + ", " + std::to_string(p.y()) + ")");
  };
  for (const auto* lines : {&g.joints, &g.materialLines, &g.fixedLines, &g.bolts, &g.boundaryLines})
    for (const NtddaLine& l : *lines)
      if (farOff(l.a) || farOff(l.b)) refuse(l.source, farOff(l.a) ? l.a : l.b);
  for (const auto* points : {&g.fixedPoints, &g.measuredPoints, &g.loadPoints, &g.holePoints, &g.seismicPoints})
    for (const NtddaPoint& p : *points)
      if (farOff(p.p)) refuse(p.source, p.p);
  for (const NtddaLine& l : g.joints)
    if (l.a == l.b) throw InputError(path, l.source.where(), "expected a joint line of non-zero length, found both ends at the same point");
  return g;
}

NtddaAnalysis readNtddaAnalysis(const std::string& path) {
  NtddaAnalysis a;
  a.file = path;
  const std::string text = readInputFile(path, kMaxNtddaFileBytes);
  if (looksLikeXml(text)) readAnalysisXml(a);
  else readAnalysisText(a, text);
  if (a.materials.empty()) throw InputError(path, "", "expected at least one block material, found none");
  if (a.joints.empty()) throw InputError(path, "", "expected at least one joint type, found none");
  if (a.steps <= 0) throw InputError(path, "", "expected the number of time steps (Numtimesteps), found none");
  if (!(a.timeStep > 0)) throw InputError(path, "", "expected a positive time step (Maxtimestep), found " + std::to_string(a.timeStep));
  return a;
}

double ntddaScale(const std::vector<NtddaLine>& joints) {
  Vec2 lo = joints.front().a, hi = lo;
  for (const NtddaLine& l : joints)
    for (const Vec2& p : {l.a, l.b}) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  // dc02: the half height, widened when the model is much wider than tall, plus 2 %.
  double w0 = (hi.y() - lo.y()) / 2;
  if ((hi.x() - lo.x()) / 2 > 1.3 * w0) w0 = (hi.x() - lo.x()) / 2 / 1.3;
  return 1.02 * w0;
}

}  // namespace ddaslope::io

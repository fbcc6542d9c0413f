#pragma once
// The mutators of the fuzz tests (test_fuzz.cpp, test_fuzz_surfaces.cpp): random changes of a
// JSON document and of a text file, driven by the caller's seeded generator so that a failure
// reproduces.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

namespace fuzz {

using nlohmann::json;

inline size_t uniform(std::mt19937& rng, size_t lo, size_t hi) {
  return std::uniform_int_distribution<size_t>(lo, hi)(rng);
}

template <class T>
const T& pick(std::mt19937& rng, const std::vector<T>& from) {
  return from[uniform(rng, 0, from.size() - 1)];
}

/// Every node of the document (its JSON pointer), for the mutator to choose from.
inline void collectPointers(const json& j, const json::json_pointer& at, std::vector<json::json_pointer>& out) {
  out.push_back(at);
  if (j.is_object())
    for (const auto& [k, v] : j.items()) collectPointers(v, at / k, out);
  if (j.is_array())
    for (size_t i = 0; i < j.size(); ++i) collectPointers(j[i], at / i, out);
}

/// Values a careless or hostile user might put anywhere: extremes, wrong types, odd strings.
inline json oddValue(std::mt19937& rng) {
  static const std::vector<json> odd = {
      0, -1, 1e-300, 1e300, -1e300, 1e-12, 1e12, 1e308, -1e308, 0.5, 3, 1e6, -1e6, 1e-9, 100000,
      "x", "", "a,b", "\n", std::string(300, 'y'), nullptr, true, false, json::array(), json::object(),
      json::array({1, 2}), json::array({json::array({0, 0}), json::array({1, 0}), json::array({0, 1})}),
      json::array({1e308, -1e308}), json::object({{"unknown", 1}})};
  return odd[std::uniform_int_distribution<size_t>(0, odd.size() - 1)(rng)];
}

/// One random change of the document: a value replaced, scaled, removed, duplicated or added.
inline void mutateJson(json& doc, std::mt19937& rng) {
  std::vector<json::json_pointer> nodes;
  collectPointers(doc, json::json_pointer(), nodes);
  const json::json_pointer at = nodes[std::uniform_int_distribution<size_t>(1, nodes.size() - 1)(rng)];
  json& node = doc[at];
  json& parent = doc[at.parent_pointer()];
  switch (std::uniform_int_distribution<int>(0, 5)(rng)) {
    case 0:
      node = oddValue(rng);
      break;
    case 1:  // scale a number by a power of ten
      if (node.is_number()) node = node.get<double>() * std::pow(10.0, std::uniform_int_distribution<int>(-12, 12)(rng));
      else node = oddValue(rng);
      break;
    case 2:  // remove it
      if (parent.is_object()) parent.erase(at.back());
      else if (parent.is_array()) parent.erase(std::stoul(at.back()));
      break;
    case 3:  // duplicate an array element
      if (parent.is_array()) parent.push_back(node);
      else node = oddValue(rng);
      break;
    case 4:  // negate
      if (node.is_number()) node = -node.get<double>();
      else node = oddValue(rng);
      break;
    default:  // an extra key
      if (node.is_object()) node["fuzz"] = oddValue(rng);
      else node = oddValue(rng);
  }
}

/// Numbers as a record, a drawing or a samples file might hold them after a bad edit or export:
/// not numbers, overflows, extremes, subnormals, half-numbers.
inline const std::vector<std::string>& oddNumbers() {
  static const std::vector<std::string> odd = {
      "nan", "NaN", "-nan", "inf", "-inf", "Infinity", "1e400", "-1e400", "1e308", "-1e308",
      "1.7976931348623157e308", "4.9e-324", "1e-320", "0", "-0", "", " ", "x", "1,2", "0x1p3", "1e", "--1",
      "+", ".", "123456789012345678901234567890", "1e-9", "-1", "1e6", "1e30", "-1e30", "2147483648", "1e5"};
  return odd;
}

/// The text's lines, each with its line end (the last may have none).
inline std::vector<std::string> splitLines(const std::string& text) {
  std::vector<std::string> out;
  size_t at = 0;
  while (at < text.size()) {
    const size_t end = text.find('\n', at);
    const size_t next = end == std::string::npos ? text.size() : end + 1;
    out.push_back(text.substr(at, next - at));
    at = next;
  }
  return out;
}

inline std::string joinLines(const std::vector<std::string>& lines) {
  std::string out;
  for (const auto& l : lines) out += l;
  return out;
}

/// The [begin, end) spans of the number tokens of a text: a digit run with its sign, point and
/// exponent, not part of a word.
inline std::vector<std::pair<size_t, size_t>> numberSpans(const std::string& t) {
  std::vector<std::pair<size_t, size_t>> out;
  const auto numeric = [](char c) { return std::isdigit(static_cast<unsigned char>(c)) || c == '.' || c == 'e' || c == 'E' || c == '+' || c == '-'; };
  for (size_t i = 0; i < t.size();) {
    const bool starts = std::isdigit(static_cast<unsigned char>(t[i])) &&
                        (i == 0 || !std::isalpha(static_cast<unsigned char>(t[i - 1])));
    if (!starts) {
      ++i;
      continue;
    }
    size_t b = i;
    while (b > 0 && (t[b - 1] == '-' || t[b - 1] == '.')) --b;
    size_t e = i;
    while (e < t.size() && numeric(t[e])) ++e;
    out.emplace_back(b, e);
    i = e;
  }
  return out;
}

/// One random change of a text file: what a copy cut short, a careless edit, an export from
/// another program or a damaged disk leaves behind.
inline std::string mutateText(std::string t, std::mt19937& rng) {
  std::vector<std::string> lines = splitLines(t);
  const auto someLine = [&] { return uniform(rng, 0, lines.size() - 1); };
  switch (uniform(rng, 0, 10)) {
    case 0:  // cut short anywhere
      t.resize(uniform(rng, 0, t.size()));
      return t;
    case 1:  // one byte changed to any value
      if (!t.empty()) t[uniform(rng, 0, t.size() - 1)] = static_cast<char>(uniform(rng, 0, 255));
      return t;
    case 2:  // a line lost
      if (!lines.empty()) lines.erase(lines.begin() + static_cast<long>(someLine()));
      return joinLines(lines);
    case 3:  // a line twice
      if (!lines.empty()) {
        const size_t k = someLine();
        lines.insert(lines.begin() + static_cast<long>(k), lines[k]);
      }
      return joinLines(lines);
    case 4:  // two lines swapped
      if (!lines.empty()) std::swap(lines[someLine()], lines[someLine()]);
      return joinLines(lines);
    case 5:
    case 6: {  // a number replaced by an odd one
      const auto spans = numberSpans(t);
      if (spans.empty()) return t + pick(rng, oddNumbers());
      const auto [b, e] = pick(rng, spans);
      return t.replace(b, e - b, pick(rng, oddNumbers()));
    }
    case 7: {  // binary garbage
      std::string junk(uniform(rng, 1, 64), '\0');
      for (char& c : junk) c = static_cast<char>(uniform(rng, 0, 255));
      return t.insert(uniform(rng, 0, t.size()), junk);
    }
    case 8:  // a very long line
      if (!lines.empty()) lines[someLine()] = std::string(uniform(rng, 1000, 5000), pick(rng, std::vector<char>{'9', 'x', ' ', ','})) + "\n";
      return joinLines(lines);
    case 9: {  // a separator, a carriage return, a space or a line end slipped in
      static const std::vector<std::string> bits = {",", "\r", " ", "\t", "\n", ",,", "\r\n", "-", "."};
      return t.insert(uniform(rng, 0, t.size()), pick(rng, bits));
    }
    default:  // nothing left, or nothing but a line end
      return uniform(rng, 0, 1) ? std::string() : std::string("\n");
  }
}

}  // namespace fuzz

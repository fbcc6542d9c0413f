#include "json_input.hpp"

#include <filesystem>
#include <fstream>
#include <sstream>
#include <system_error>

#include <nlohmann/json.hpp>

#include "ddaslope/core/errors.hpp"

namespace ddaslope::io {
namespace {

std::string megabytes(std::uintmax_t bytes) {
  std::ostringstream s;
  s.precision(3);
  s << static_cast<double>(bytes) / (1u << 20) << " MB";
  return s.str();
}

}  // namespace

std::string readInputFile(const std::string& path, std::uintmax_t maxBytes, const std::string& referrer,
                          const std::string& referrerPath) {
  const auto fail = [&](const std::string& what) -> std::string {
    if (referrer.empty()) throw InputError(path, "", what);
    throw InputError(referrer, referrerPath, path + ": " + what);
  };
  std::error_code ec;
  const std::filesystem::file_status st = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(st)) return fail("cannot open the file: it does not exist");
  // A device, FIFO or directory could block the read or never end (/dev/zero).
  if (!std::filesystem::is_regular_file(st)) return fail("expected a regular file, found a directory or special file");
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) return fail("cannot read the file's size");
  if (size > maxBytes)
    return fail("the file is " + megabytes(size) + ", more than the " + megabytes(maxBytes) + " an input may be");
  std::ifstream in(path, std::ios::binary);
  if (!in) return fail("cannot open the file");
  std::string text(static_cast<size_t>(size), '\0');
  in.read(text.data(), static_cast<std::streamsize>(size));
  if (in.gcount() != static_cast<std::streamsize>(size)) return fail("cannot read the whole file");
  return text;
}

nlohmann::json parseJsonText(const std::string& text, const std::string& file) {
  using nlohmann::json;
  // Depth is measured on the text before parsing, which keeps the parser's own stack and the
  // document's destruction bounded. (nlohmann's callback parser would do it in passing, but it
  // rescans an object's members at each member's end: a case with 50 000 materials took minutes.)
  int depth = 0;
  bool inString = false;
  for (size_t i = 0; i < text.size(); ++i) {
    const char ch = text[i];
    if (inString) {
      if (ch == '\\') ++i;
      else if (ch == '"') inString = false;
    } else if (ch == '"') {
      inString = true;
    } else if (ch == '{' || ch == '[') {
      if (++depth > kMaxJsonDepth)
        throw InputError(file, "", "JSON nested more than " + std::to_string(kMaxJsonDepth) + " levels deep");
    } else if (ch == '}' || ch == ']') {
      --depth;
    }
  }
  try {
    return json::parse(text);
  } catch (const json::parse_error& e) {
    throw InputError(file, "", std::string("invalid JSON: ") + e.what());
  } catch (const json::out_of_range& e) {
    // A number token the double cannot hold (1e400).
    throw InputError(file, "", std::string("invalid JSON: ") + e.what());
  }
}

nlohmann::json readJsonFile(const std::string& path) {
  return parseJsonText(readInputFile(path, kMaxJsonFileBytes), path);
}

}  // namespace ddaslope::io

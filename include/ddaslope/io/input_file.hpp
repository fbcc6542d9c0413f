#pragma once
// Files a user hands to ddaslope (case, job, CSV series, DXF drawing): read with limits, so that
// no input can crash the parser, exhaust memory or block a read. Every failure is an InputError
// naming the file (and, for a file another one refers to, the referring file and JSON path).
#include <cstdint>
#include <string>

namespace ddaslope::io {

/// Case and job files: a section of a few hundred blocks is tens of kB, and the largest sensible
/// explicit case (20 000 blocks) stays below 8 MB.
constexpr std::uintmax_t kMaxJsonFileBytes = 16u << 20;
/// CSV series (water levels, load histories): a million rows.
constexpr std::uintmax_t kMaxCsvFileBytes = 64u << 20;
/// DXF drawings (a section, or a site plan with contours holding one): a section of a few
/// hundred lines is tens of kB.
constexpr std::uintmax_t kMaxDxfFileBytes = 64u << 20;
/// No case or job nests deeper than 6; a limit well above that still stops a hostile file
/// (100 000 nested arrays) before it costs memory and recursion.
constexpr int kMaxJsonDepth = 64;

/// The whole content of a regular file of at most `maxBytes`. `referrer`/`referrerPath` name the
/// file and JSON path that pointed to it (empty for a file named on the command line).
std::string readInputFile(const std::string& path, std::uintmax_t maxBytes, const std::string& referrer = "",
                          const std::string& referrerPath = "");

}  // namespace ddaslope::io

#include "ddaslope/io/progress.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "ddaslope/core/errors.hpp"

namespace ddaslope::io {

namespace {

/// A JSON string literal (the events hold paths, rule names and text of ours).
std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (const char c : s) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", c);
      out += buf;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

/// A JSON number; null where JSON has no number (an infinite misfit, a NaN).
std::string number(double v) {
  if (!std::isfinite(v)) return "null";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);  // round-trips: a script reads the value itself
  return buf;
}

}  // namespace

std::string formatDuration(double s) {
  char buf[32];
  if (s < 60)
    std::snprintf(buf, sizeof buf, "%.1f s", s);
  else if (s < 3600)
    std::snprintf(buf, sizeof buf, "%d min %02d s", static_cast<int>(s / 60), static_cast<int>(s) % 60);
  else
    std::snprintf(buf, sizeof buf, "%d h %02d min", static_cast<int>(s / 3600), static_cast<int>(s / 60) % 60);
  return buf;
}

double remainingTime(double elapsed, int done, int planned) {
  if (done <= 0 || planned <= 0 || done > planned) return -1;
  return elapsed * (planned - done) / done;
}

ProgressLog::ProgressLog(std::string command, bool terminal, const std::string& jsonPath, bool minuteLines,
                         double lineInterval)
    : command_(std::move(command)),
      terminal_(terminal),
      minuteLines_(minuteLines && !terminal),
      lineInterval_(lineInterval),
      start_(std::chrono::steady_clock::now()) {
  if (!jsonPath.empty()) {
    json_ = std::fopen(jsonPath.c_str(), "w");
    if (!json_) throw InputError("--log-json", jsonPath, "cannot write the file");
    std::fprintf(json_, "{\"event\": \"start\", \"command\": %s, \"t\": 0}\n", quoted(command_).c_str());
    std::fflush(json_);
  }
  // Off a terminal the line comes from a clock of its own: a trial may run for minutes, and long
  // work must not be silent between trials.
  if (minuteLines_)
    ticker_ = std::thread([this] {
      std::unique_lock<std::mutex> lock(mutex_);
      const auto tick = std::chrono::duration<double>(std::min(1.0, lineInterval_ / 4));
      while (!finished_) {
        wake_.wait_for(lock, tick);
        if (finished_) break;
        const double t = elapsed();
        if (t - lastLine_ < lineInterval_) continue;
        lastLine_ = t;
        const std::string text = hasLast_ ? lineOf(last_, t) : "working, no trial finished yet, " + formatDuration(t);
        std::fprintf(stderr, "  %s %s\n", command_.c_str(), text.c_str());
        std::fflush(stderr);
      }
    });
}

ProgressLog::~ProgressLog() {
  finish(false, "ended before its result");  // nothing if it has finished
  if (json_) std::fclose(json_);
}

std::string ProgressLog::lineOf(const ProgressEvent& e, double t) const {
  std::string text = e.stage + ": " + std::to_string(e.done);
  if (e.planned > 0) text += " of " + std::string(e.stage == "narrow" ? "~" : "") + std::to_string(e.planned);
  if (!e.detail.empty()) text += ", " + e.detail;
  text += ", " + formatDuration(t);
  const double left = remainingTime(t, e.done, e.planned);
  if (left >= 0) text += ", ~" + formatDuration(left) + " left";
  return text;
}

double ProgressLog::elapsed() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

void ProgressLog::report(const ProgressEvent& e) {
  const std::lock_guard<std::mutex> lock(mutex_);
  const double t = elapsed();
  const double left = remainingTime(t, e.done, e.planned);
  if (json_) {
    std::ostringstream line;
    line << "{\"event\": \"progress\", \"command\": " << quoted(command_) << ", \"t\": " << number(t)
         << ", \"stage\": " << quoted(e.stage) << ", \"done\": " << e.done << ", \"planned\": ";
    line << (e.planned > 0 ? std::to_string(e.planned) : "null") << ", \"remaining_s\": " << (left >= 0 ? number(left) : "null");
    for (const auto& [name, v] : e.values) line << ", " << quoted(name) << ": " << number(v);
    line << ", \"detail\": " << quoted(e.detail) << "}\n";
    std::fputs(line.str().c_str(), json_);
    std::fflush(json_);
  }
  last_ = e;
  hasLast_ = true;
  if (terminal_ && (t - lastDrawn_ >= 0.1 || (e.planned > 0 && e.done >= e.planned))) {
    lastDrawn_ = t;
    std::string text = "  " + lineOf(e, t);
    // Pad over the longer line before it, so no tail of it stays on screen.
    const size_t width = text.size();
    if (text.size() < lineWidth_) text.append(lineWidth_ - text.size(), ' ');
    lineWidth_ = width;
    std::fprintf(stderr, "\r%s", text.c_str());
    std::fflush(stderr);
  }
}

void ProgressLog::finish(bool ok, const std::string& summary) {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (finished_) return;
    finished_ = true;
  }
  wake_.notify_all();
  if (ticker_.joinable()) ticker_.join();
  const std::lock_guard<std::mutex> lock(mutex_);
  if (terminal_ && lineWidth_ > 0) std::fprintf(stderr, "\n");
  if (json_) {
    std::fprintf(json_, "{\"event\": \"end\", \"command\": %s, \"t\": %s, \"ok\": %s, \"summary\": %s}\n",
                 quoted(command_).c_str(), number(elapsed()).c_str(), ok ? "true" : "false", quoted(summary).c_str());
    std::fflush(json_);
  }
}

}  // namespace ddaslope::io

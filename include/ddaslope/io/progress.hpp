#pragma once
// Progress of a long command: the searches, sweeps, back-analyses and probability
// studies report events (what stage, how many trials of how many, the current bracket or best
// misfit); ProgressLog shows them on one terminal line and/or writes them as JSON lines for
// scripts and notebooks (--log-json FILE). Events never reach stdout, so results stay clean.
#include <chrono>
#include <cstdio>
#include <functional>
#include <memory>
#include <condition_variable>
#include <mutex>
#include <thread>
#include <string>
#include <utility>
#include <vector>

namespace ddaslope::io {

struct ProgressEvent {
  /// What is being done: "bracket", "narrow" (a search), "points", "samples", "global",
  /// "local", "map", "precision" …
  std::string stage;
  int done = 0;     ///< trials (forward runs, evaluations, samples, points) finished
  int planned = 0;  ///< of how many (an estimate while a search narrows); 0: not known yet
  std::string detail;  ///< for people: "stable at F 1.10, fails at 1.15"
  /// For scripts: named numbers (stable_end, failing_end, best_misfit, probability_of_failure …).
  std::vector<std::pair<std::string, double>> values;
};

using ProgressSink = std::function<void(const ProgressEvent&)>;

class ProgressLog {
 public:
  /// `terminal`: show a line on stderr (the caller decides: a terminal, and no --quiet);
  /// `jsonPath`: "" for none; `minuteLines`: off a terminal, write the progress as a line of
  /// stderr once every `lineInterval` seconds at most, the first after one interval (a log file,
  /// a batch job: long work is not silent). Throws InputError if the JSON file cannot be written.
  ProgressLog(std::string command, bool terminal, const std::string& jsonPath, bool minuteLines = false,
              double lineInterval = 60);
  ~ProgressLog();
  ProgressLog(const ProgressLog&) = delete;
  ProgressLog& operator=(const ProgressLog&) = delete;

  /// Thread-safe. The terminal line is redrawn at most 10 times a second (and for the last
  /// trial); every event goes to the JSON log.
  void report(const ProgressEvent& e);
  ProgressSink sink() {
    return [this](const ProgressEvent& e) { report(e); };
  }
  /// The command's end: a last JSON line {"event": "end", "ok": …, "summary": …}.
  void finish(bool ok, const std::string& summary);
  bool active() const { return terminal_ || json_ || minuteLines_; }

 private:
  double elapsed() const;
  /// The event as a line of text at time t: stage, done of planned, detail, elapsed, time left.
  std::string lineOf(const ProgressEvent& e, double t) const;
  std::string command_;
  bool terminal_;
  bool minuteLines_;
  double lineInterval_;
  double lastLine_ = 0;
  std::FILE* json_ = nullptr;
  std::chrono::steady_clock::time_point start_;
  double lastDrawn_ = -1;
  size_t lineWidth_ = 0;
  bool finished_ = false;
  ProgressEvent last_;  ///< the latest event, for the lines off a terminal
  bool hasLast_ = false;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::thread ticker_;  ///< writes those lines (minuteLines)
};

/// "1.5 s", "2 min 05 s", "1 h 03 min": a duration for the terminal line.
std::string formatDuration(double seconds);
/// Seconds left at a steady pace: elapsed × (planned − done) / done; negative if not known.
double remainingTime(double elapsed, int done, int planned);

/// A sink that is silent when `log` is null (a command run without progress).
inline ProgressSink sinkOf(ProgressLog* log) { return log && log->active() ? log->sink() : ProgressSink{}; }

}  // namespace ddaslope::io

#include "crack_search.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>

#include "ddaslope/core/byte_record.hpp"
#include "ddaslope/core/task_farm.hpp"

namespace ddaslope::cli {

namespace {

/// No answer because every trial failed: the scene fails at every value the search tried.
bool failsThroughout(bool found, const std::vector<calibration::TrialRecord>& trials) {
  return !found && !trials.empty() && std::all_of(trials.begin(), trials.end(), [](const calibration::TrialRecord& t) {
           return !t.result.stable && !t.result.undecided;
         });
}

}  // namespace

CrackValue crackValueOf(const calibration::CriticalResult& r) {
  return {r.found, r.critical, r.runs, r.message, failsThroughout(r.found, r.trials)};
}

CrackValue crackValueOf(const calibration::FactorOfSafetyResult& r) {
  return {r.found, r.factor, r.runs, r.message, failsThroughout(r.found, r.trials)};
}

std::vector<io::CaseOverride> crackAt(double x) {
  // A crack given by its depth is moved by its position.
  return {io::CaseOverride::removal("section.tension_crack.depth"), io::CaseOverride("section.tension_crack.x", x)};
}

CrackSearch searchCrackPosition(const std::string& casePath, const Overrides& o, const model::Scene& scene, int threads,
                                bool maximise, double precision, const std::string& quantity, const ProgressOptions& progress,
                                const std::function<CrackValue(const model::Scene&)>& valueAt) {
  const auto t0 = std::chrono::steady_clock::now();
  const auto log = startProgress("tension crack search", progress, false);
  const std::unique_ptr<TaskFarm> farm = makeTaskFarm(threads);
  CrackSearch out;
  int done = 0;
  const auto evaluate = [&](const std::vector<double>& xs) {
    std::vector<calibration::PositionSample> samples(xs.size());
    std::vector<int> indices(xs.size());
    for (size_t i = 0; i < xs.size(); ++i) indices[i] = static_cast<int>(i);
    farm->run(
        indices,
        [&](int i) {
          const CrackValue v = valueAt(loadCase(casePath, o, crackAt(xs[i])));
          BytePacker b;
          b.put(v.found).put(v.value).put(v.runs).put(v.message).put(v.fails);
          return b.bytes();
        },
        [&](int i, const TaskResult& bytes) {
          ByteUnpacker b(bytes);
          calibration::PositionSample& s = samples[i];
          s.x = xs[i];
          s.found = b.get<bool>();
          s.value = b.get<double>();
          out.runs += b.get<int>();
          s.message = b.getString();
          s.fails = b.get<bool>();
          if (log->active())
            log->report({"positions", ++done, 0,
                         "crack at x = " + std::to_string(xs[i]) + ": " + quantity + " " +
                             (s.found ? std::to_string(s.value) : "not found"),
                         {{"x", xs[i]}, {"value", s.found ? s.value : NAN}}});
        });
    return samples;
  };
  out.result = calibration::searchLeastSafePosition(scene.crackSearch->first, scene.crackSearch->second, 9, maximise,
                                                    precision, evaluate);
  out.wallTime = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  log->finish(true, out.result.found ? "least safe crack at x = " + std::to_string(out.result.best)
                                      : "no position gave " + quantity);
  return out;
}

std::optional<CrackSearch> placeCrack(const std::string& casePath, const Overrides& o, model::Scene& scene, int threads,
                                      bool maximise, double precision, const std::string& quantity,
                                      const ProgressOptions& progress, bool json,
                                      const std::function<CrackValue(const model::Scene&)>& valueAt) {
  if (!scene.crackSearch) return std::nullopt;
  CrackSearch crack = searchCrackPosition(casePath, o, scene, threads, maximise, precision, quantity, progress, valueAt);
  if (crack.result.found) scene = loadCase(casePath, o, crackAt(crack.result.best));
  if (!json) printCrackSearch(crack, scene, quantity);
  return crack;
}

PointCrack leastSafeCrackOnThisThread(const model::Scene& scene, bool maximise, double precision,
                                      const std::function<model::Scene(double)>& read,
                                      const std::function<CrackValue(const model::Scene&)>& valueAt, int& runs) {
  const calibration::PositionSearchResult r = calibration::searchLeastSafePosition(
      scene.crackSearch->first, scene.crackSearch->second, 9, maximise, precision, [&](const std::vector<double>& xs) {
        std::vector<calibration::PositionSample> samples;
        for (double x : xs) {
          const CrackValue v = valueAt(read(x));
          runs += v.runs;
          samples.push_back({x, v.value, v.found, v.message, v.fails});
        }
        return samples;
      });
  return r.found ? PointCrack{r.best, true, false, r.fails} : PointCrack{scene.tensionCrack->x, false, r.tied, false};
}

std::string pointCrackText(bool found, bool tied, bool fails, double x, double caseX, const std::string& quantity) {
  char text[200];
  if (found && fails)
    std::snprintf(text, sizeof text, ", least safe crack at x = %.4g m, where the slope fails at every value tried", x);
  else if (found)
    std::snprintf(text, sizeof text, ", least safe crack at x = %.4g m", x);
  else
    std::snprintf(text, sizeof text, ", no crack position is least safe (%s): the crack at the case's x = %.4g m",
                  tied ? ("every one gave the same " + quantity).c_str() : ("none gave " + quantity).c_str(), caseX);
  return text;
}

std::string noCrackPositionNote(const model::Scene& scene, const std::string& quantity, bool tied) {
  char text[400];
  std::snprintf(text, sizeof text,
                tied ? "every crack position in x = [%g, %g] m gave the same %s, so none is least safe: the crack stays at "
                       "the case's x = %g m (%s)"
                     : "no crack position in x = [%g, %g] m gave an answer (%s), so none is least safe: the crack stays at "
                       "the case's x = %g m (%s)",
                scene.crackSearch->first, scene.crackSearch->second, quantity.c_str(), scene.tensionCrack->x,
                crackPlacement(scene).c_str());
  return text;
}

std::string crackPlacement(const model::Scene& scene) {
  return scene.tensionCrack && scene.tensionCrack->placedByDepth ? "where section.tension_crack.depth puts it"
                                                                  : "section.tension_crack.x";
}

std::string forwardRunsText(int answerRuns, const std::optional<CrackSearch>& crack) {
  if (!crack) return std::to_string(answerRuns) + " forward runs";
  return std::to_string(answerRuns + crack->runs) + " forward runs (" + std::to_string(crack->runs) +
         " of them searching the crack's position)";
}

int totalRuns(int answerRuns, const std::optional<CrackSearch>& crack) { return answerRuns + (crack ? crack->runs : 0); }

double totalWallTime(double answerWallTime, const std::optional<CrackSearch>& crack) {
  return answerWallTime + (crack ? crack->wallTime : 0);
}

void printCrackSearch(const CrackSearch& s, const model::Scene& scene, const std::string& quantity) {
  const auto& r = s.result;
  std::printf("tension crack position searched in x = [%g, %g] m (%zu positions, %d forward runs, %.2f s wall):\n",
              scene.crackSearch->first, scene.crackSearch->second, r.samples.size(), s.runs, s.wallTime);
  bool missing = false;
  int failing = 0;
  for (const auto& p : r.samples) {
    // A position's reason in brief (its first clause): the answer's own message gives it in full.
    const std::string brief = p.message.substr(0, p.message.find(": "));
    std::printf("  x = %-10.4g %s %s\n", p.x, quantity.c_str(), p.found ? std::to_string(p.value).c_str() : ("none: " + brief).c_str());
    missing |= !p.found && !p.fails;
    failing += p.fails;
  }
  const model::CrackGeometry& c = *scene.tensionCrack;
  if (r.fails) {
    std::printf("least safe crack: x = %.4g m, %.4g m deep, water %.4g m deep, where the slope fails at every value "
                "tried (%d of the %zu positions, x in [%.4g, %.4g] m): there is no %s\n",
                c.x, c.depth(), c.waterDepth(), failing, r.samples.size(), r.flatLo, r.flatHi, quantity.c_str());
    std::fflush(stdout);
    return;
  }
  if (!r.found) {
    std::printf("%s, %.4g m deep, water %.4g m deep\n", noCrackPositionNote(scene, quantity, r.tied).c_str(), c.depth(),
                c.waterDepth());
    std::fflush(stdout);
    return;
  }
  std::printf("least safe crack: x = %.4g m, %.4g m deep, water %.4g m deep (%s); %s within the search's width for x "
              "in [%.4g, %.4g] m\n",
              c.x, c.depth(), c.waterDepth(), r.fitted ? "the vertex of a parabola through the nearest positions" : "the best position tried",
              quantity.c_str(), r.flatLo, r.flatHi);
  if (missing)
    std::printf("  note: some positions gave no %s (above) without failing, as held at every value tried or undecided: "
                "they are left out\n",
                quantity.c_str());
  if (r.atEnd)
    std::printf("  note: the least safe position lies at an end of the range: widen section.tension_crack.search to "
                "look beyond it\n");
  std::fflush(stdout);  // before an error on stderr about the answer at this crack
}

void appendCrackSearch(io::JsonRecord& j, const CrackSearch& s, const model::Scene& scene, const std::string& quantity) {
  const model::CrackGeometry& c = *scene.tensionCrack;
  io::JsonRecord t;
  t.set("x", c.x).set("depth", c.depth()).set("water_depth", c.waterDepth()).set("water_fraction", c.waterFraction);
  if (scene.crackSearch) {
    const auto& r = s.result;
    std::vector<double> xs, values;
    for (const auto& p : r.samples) xs.push_back(p.x), values.push_back(p.found ? p.value : NAN);
    t.set("searched", std::vector<double>{scene.crackSearch->first, scene.crackSearch->second});
    t.set("positions", xs).set("values", values).set("fitted", r.fitted).set("at_end", r.atEnd);
    t.set("within_width", std::vector<double>{r.flatLo, r.flatHi}).set("position_width", r.precision);
    t.set("position_found", r.found).set("position_fails", r.fails);
    if (!r.found) t.set("note", noCrackPositionNote(scene, quantity, r.tied));
    t.set("forward_runs", s.runs).set("wall_time_s", s.wallTime);
  }
  j.set("tension_crack", t);
}

}  // namespace ddaslope::cli

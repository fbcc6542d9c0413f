#include "ddaslope/calibration/backanalysis.hpp"

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <exception>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <sstream>
#include <system_error>
#include <thread>

#include "ddaslope/calibration/minimiser.hpp"
#include "ddaslope/calibration/precision.hpp"
#include "ddaslope/calibration/strength_search.hpp"
#include "ddaslope/core/byte_record.hpp"
#include "ddaslope/core/cancellation.hpp"
#include "ddaslope/core/errors.hpp"
#include "ddaslope/io/case_reader.hpp"
#include "ddaslope/io/run_case.hpp"

namespace ddaslope::calibration {
namespace {

int jointNamed(const model::Scene& s, const std::string& name, const std::string& file, const std::string& path) {
  std::string known;
  for (size_t j = 0; j < s.joints.size(); ++j) {
    if (s.joints[j].name == name) return static_cast<int>(j);
    known += (known.empty() ? "" : ", ") + s.joints[j].name;
  }
  throw InputError(file, path, "no joint named \"" + name + "\" in the case (it has: " + known + ")");
}

std::vector<double> physical(const io::BackanalysisJob& job, const std::vector<double>& u) {
  std::vector<double> x(u.size());
  for (size_t i = 0; i < u.size(); ++i) x[i] = job.parameters[i].min + u[i] * (job.parameters[i].max - job.parameters[i].min);
  return x;
}

/// Profile of the misfit map along one axis: for each value of parameter `axis`, the least misfit
/// over the other parameter, refined by a parabola through the best cell and its neighbours
/// (exact when the observation is linear in that parameter, as a factor of safety is in c).
std::vector<double> profile(const BackanalysisResult& r, int axis) {
  const size_t n = axis == 0 ? r.axis0.size() : r.axis1.size(), m = axis == 0 ? r.axis1.size() : r.axis0.size();
  std::vector<double> out(n);
  for (size_t k = 0; k < n; ++k) {
    const auto at = [&](size_t i) { return axis == 0 ? r.map[k][i] : r.map[i][k]; };
    size_t best = 0;
    for (size_t i = 1; i < m; ++i)
      if (at(i) < at(best)) best = i;
    double v = at(best);
    if (best > 0 && best + 1 < m) {
      const double a = at(best - 1), b = at(best), c = at(best + 1), curvature = a - 2 * b + c;
      if (curvature > 0) v = std::max(0.0, b - (a - c) * (a - c) / (8 * curvature));
    }
    out[k] = v;
  }
  return out;
}

/// The data constrain only a line when, along one parameter, the profile stays within one
/// standard deviation of the optimum (misfit + 1 per unit weight) over at least 40 % of the
/// search range: many values of that parameter explain the data equally well.
void judgeConstraint(const io::BackanalysisJob& job, BackanalysisResult& r) {
  double weights = 0;
  for (const auto& o : job.observations) weights += o.weight;
  const std::vector<double> p0 = profile(r, 0), p1 = profile(r, 1);
  double best = r.misfit;
  for (double v : p0) best = std::min(best, v);
  for (double v : p1) best = std::min(best, v);
  const auto flatSpan = [&](const std::vector<double>& p) {
    int first = -1, last = -1;
    for (size_t k = 0; k < p.size(); ++k)
      if (p[k] <= best + weights) {
        if (first < 0) first = static_cast<int>(k);
        last = static_cast<int>(k);
      }
    return first < 0 ? 0.0 : double(last - first) / (p.size() - 1);
  };
  const double span0 = flatSpan(p0), span1 = flatSpan(p1);
  r.lineOnly = std::max(span0, span1) >= 0.4;
  std::ostringstream s;
  if (r.lineOnly)
    s << "The observations constrain only a line of (" << r.names[0] << ", " << r.names[1] << ") pairs, not both: "
      << "within one standard deviation of the best fit, " << r.names[span0 >= span1 ? 0 : 1] << " ranges over "
      << static_cast<int>(100 * std::max(span0, span1)) << " % of its search range (see misfit_map.png). "
      << "The estimate is one point of that line; add an observation that separates the two (a displacement or "
         "velocity history) or fix one of them.";
  else {
    // A span within one node of the map's grid is below what the grid resolves: said as such.
    const auto spanText = [](double span, size_t nodes) {
      const int step = nodes > 1 ? static_cast<int>(std::ceil(100.0 / static_cast<double>(nodes - 1))) : 100;
      return span > 0 ? std::to_string(static_cast<int>(100 * span)) + " %"
                      : "under " + std::to_string(step) + " % (one step of misfit_map.png's grid)";
    };
    s << "The observations constrain both " << r.names[0] << " and " << r.names[1]
      << ": within one standard deviation of the best fit they span " << spanText(span0, p0.size()) << " and "
      << spanText(span1, p1.size()) << " of their search ranges.";
  }
  r.statement = s.str();
}

}  // namespace

model::Scene sceneAt(const io::BackanalysisJob& job, const std::vector<double>& x) {
  std::vector<io::CaseOverride> overrides = job.caseOverrides;
  for (size_t i = 0; i < x.size(); ++i)
    if (!job.parameters[i].jsonPath.empty()) overrides.emplace_back(job.parameters[i].jsonPath, x[i]);
  for (const model::SettingsOverride& o : job.model)
    for (auto& m : io::caseOverridesFor(o)) overrides.push_back(std::move(m));
  model::Scene s = io::parseCase(job.caseText, job.casePath, overrides);
  for (size_t i = 0; i < x.size(); ++i) {
    const io::ParameterSpec& p = job.parameters[i];
    if (p.joint.empty()) continue;
    model::JointProperties& j = s.joints[jointNamed(s, p.joint, job.jobPath, "parameters[" + std::to_string(i) + "].joint")];
    // A residual above the peak is used as the peak (model::JointProperties), so the two can be
    // searched over overlapping ranges.
    if (p.property == "cohesion") j.cohesion = x[i];
    else if (p.property == "friction_angle") j.frictionAngle = degToRad(x[i]);
    else if (p.property == "tensile_strength") j.tensileStrength = x[i];
    else if (p.property == "residual_cohesion") j.residualCohesion = x[i];
    else if (p.property == "residual_friction_angle") j.residualFrictionAngle = degToRad(x[i]);
    else j.weakeningDistance = x[i];
  }
  return s;
}

double misfitAt(const io::BackanalysisJob& job, const std::vector<double>& x, int* runs,
                const solver::HeldEquilibrium* shared, int searchThreads, std::vector<ObservationFit>* fit) {
  return misfitOf(job, sceneAt(job, x), runs, shared, searchThreads, fit);
}

double misfitOf(const io::BackanalysisJob& job, const model::Scene& scene, int* runs,
                const solver::HeldEquilibrium* shared, int searchThreads, std::vector<ObservationFit>* fit) {
  if (fit) fit->clear();
  double total = 0;
  bool needTrace = false;
  for (const auto& o : job.observations) needTrace |= o.kind != io::ObservationSpec::Kind::FactorOfSafety;
  // A series observed after the run's end would be compared with the run's last state.
  for (size_t k = 0; k < job.observations.size(); ++k)
    for (const double t : job.observations[k].times)
      if (t > scene.settings.duration * (1 + 1e-9)) {
        std::ostringstream m;
        m << "an observation at t = " << t << " s, after the run's end (the case's analysis.duration, "
          << scene.settings.duration << " s): lengthen the run or drop the later rows";
        throw InputError(job.jobPath, "observations[" + std::to_string(k) + "].csv", m.str());
      }
  io::RunOutcome run;
  if (needTrace) {
    io::RunOptions options;
    options.sharedEquilibrium = shared;
    options.energy = false;  // the misfit reads monitors only
    run = io::runScene(scene, options);
    if (runs) ++*runs;
  }
  for (const auto& o : job.observations) {
    double sum = 0;
    int count = 0;
    ObservationFit met{o.label, NAN, o.target, o.sigma, o.kind == io::ObservationSpec::Kind::Series, true, {}};
    if (o.kind == io::ObservationSpec::Kind::FactorOfSafety) {
      std::vector<int> joints;
      for (const auto& n : o.joints) joints.push_back(jointNamed(scene, n, job.jobPath, "observations: joints"));
      SearchSettings s;
      s.threads = std::max(1, searchThreads);
      const FactorOfSafetyResult f = factorOfSafety(scene, joints, 0.2 * o.sigma, s);
      if (runs) *runs += f.runs;
      met.simulated = f.found ? f.factor : 0.0;
      met.trials = f.trials;
      const double d = (met.simulated - o.target) / o.sigma;
      sum = d * d;
      count = 1;
    } else if (!run.completed) {
      met.converged = false;
      sum = 1e6;  // a run that did not converge explains nothing
      count = 1;
    } else {
      model::Expectation e;
      e.monitor = o.monitor;
      e.quantity = o.quantity;
      if (run.trace.monitorIndex(o.monitor) < 0) {
        std::string known;
        for (const auto& id : run.trace.monitorIds) known += (known.empty() ? "" : ", ") + id;
        throw InputError(job.jobPath, "observations", "no monitor \"" + o.monitor + "\" in the case (it has: " +
                                                          (known.empty() ? std::string("none") : known) + ")");
      }
      if (o.kind == io::ObservationSpec::Kind::Runout) {
        met.simulated = io::measure(run.trace, e);
        const double d = (met.simulated - o.target) / o.sigma;
        sum = d * d;
        count = 1;
      } else {
        for (size_t k = 0; k < o.times.size(); ++k) {
          e.time = o.times[k];
          const double d = (io::measure(run.trace, e) - o.values[k]) / o.sigma;
          sum += d * d;
          ++count;
        }
        met.simulated = o.sigma * std::sqrt(sum / std::max(1, count));
        met.observed = 0;
      }
    }
    if (fit) fit->push_back(met);
    total += o.weight * sum / std::max(1, count);
  }
  return total;
}

namespace {

/// Misfits at parameter vectors (physical units), spread over the farm (one thread per point, so
/// a point's misfit is the same on any farm); on the root, values[k], and the forward runs taken.
std::vector<double> misfitsAt(const io::BackanalysisJob& job, const std::vector<std::vector<double>>& points,
                              const solver::HeldEquilibrium* shared, TaskFarm& farm, std::atomic<int>& runs,
                              const std::function<void(double)>& finished) {
  std::vector<double> values(points.size(), HUGE_VAL);
  std::vector<int> indices(points.size());
  for (size_t k = 0; k < points.size(); ++k) indices[k] = static_cast<int>(k);
  farm.run(
      indices,
      [&](int k) {
        int m = 0;
        const double v = misfitAt(job, points[k], &m, shared);
        return BytePacker().put(v).put(m).bytes();
      },
      [&](int k, const TaskResult& bytes) {
        ByteUnpacker b(bytes);
        values[k] = b.get<double>();
        runs += b.get<int>();
        finished(values[k]);
      });
  return values;
}

/// n values per parameter evenly over its range, every combination, the last parameter fastest:
/// the misfit map's points for two parameters. `unit`: the same points in the unit box.
std::vector<std::vector<double>> parameterGrid(const io::BackanalysisJob& job, int n,
                                               std::vector<std::vector<double>>* unit = nullptr) {
  const size_t dims = job.parameters.size();
  size_t total = 1;
  for (size_t d = 0; d < dims; ++d) total *= static_cast<size_t>(n);
  std::vector<std::vector<double>> points(total, std::vector<double>(dims));
  if (unit) unit->assign(total, std::vector<double>(dims));
  for (size_t k = 0; k < total; ++k) {
    size_t rest = k;
    for (size_t d = dims; d-- > 0;) {
      const int i = static_cast<int>(rest % n);
      rest /= n;
      const io::ParameterSpec& p = job.parameters[d];
      points[k][d] = p.min + (p.max - p.min) * i / (n - 1);
      if (unit) (*unit)[k][d] = static_cast<double>(i) / (n - 1);
    }
  }
  return points;
}

/// The optimisers' misfits, kept by exact point, with DIRECT's next point run ahead on a spare
/// thread. The optimisers ask for one point at a time, and a point asked again (the local stage
/// starts at the global stage's best) is not run again. DIRECT divides a box at two points
/// symmetric about its centre c along one axis and asks for c - d, then c + d. While the first
/// runs, the second runs ahead: the asked point mirrored about the nearest point known above it
/// on the one axis where they differ, c + (c - x), which in floating point is DIRECT's c + d for
/// all but a few pairs. A guess that the next ask does not take is stopped then. A value is used
/// only for the exact point it was made for, so an optimiser sees the values it would see
/// without running ahead.
class Evaluations {
 public:
  struct Value {
    double misfit = 0;
    int runs = 0;
    std::vector<ObservationFit> fit;
  };
  using Compute = std::function<Value(const std::vector<double>&)>;

  explicit Evaluations(Compute compute) : compute_(std::move(compute)) {}
  ~Evaluations() { stopRunningAhead(); }
  Evaluations(const Evaluations&) = delete;
  Evaluations& operator=(const Evaluations&) = delete;

  /// Whether the points asked from now on have their mirrors run ahead (a DIRECT stage).
  void runAheadFrom(bool on) { runAhead_ = on; }

  /// The value at u; `fresh`: u was not asked before (its runs count once).
  Value at(const std::vector<double>& u, bool& fresh) {
    std::unique_lock<std::mutex> lock(mutex_);
    if (const auto it = entries_.find(u); it != entries_.end()) {
      const std::shared_ptr<Entry> e = it->second;
      done_.wait(lock, [&] { return e->done; });
      if (!e->cancelled) {
        fresh = !e->taken;
        if (fresh && e->ahead) ++takenAhead_;
        e->taken = true;
        if (e->error) std::rethrow_exception(e->error);
        return e->value;
      }
    }
    // A new point: a guess run ahead for another one was wrong, and its thread is wanted.
    const bool wrongGuess = guess_ && !guess_->done && !guess_->taken;
    if (wrongGuess) guess_->cancel = true;
    lock.unlock();
    if (wrongGuess && spare_.joinable()) spare_.join();
    lock.lock();
    auto e = std::make_shared<Entry>();
    e->taken = true;
    entries_[u] = e;
    startAhead(u);
    lock.unlock();
    Value v;
    std::exception_ptr error;
    try {
      v = compute_(u);
    } catch (const Cancelled&) {
      lock.lock();
      forget(u, e);
      throw;
    } catch (...) {
      error = std::current_exception();
    }
    lock.lock();
    e->value = v;
    e->error = error;
    e->done = true;
    done_.notify_all();
    fresh = true;
    if (error) std::rethrow_exception(error);
    return v;
  }

  /// Stops a run ahead that no one has asked for and waits for the spare thread: what follows
  /// needs the cores.
  void stopRunningAhead() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (guess_ && !guess_->done) guess_->cancel = true;
    }
    if (spare_.joinable()) spare_.join();
  }

  /// Runs made ahead (to the end), and those of them no optimiser asked for.
  int madeAhead() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return madeAhead_;
  }
  int unusedAhead() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return madeAhead_ - takenAhead_;
  }

 private:
  struct Entry {
    bool ahead = false, done = false, taken = false, cancelled = false;
    Value value;
    std::exception_ptr error;
    std::atomic<bool> cancel{false};
  };

  /// A run stopped before its end: its point is not known after all. Under the lock.
  void forget(const std::vector<double>& u, const std::shared_ptr<Entry>& e) {
    e->cancelled = e->done = true;
    if (const auto it = entries_.find(u); it != entries_.end() && it->second == e) entries_.erase(it);
    done_.notify_all();
  }

  /// The mirror of u about the nearest point known above it on the one axis they differ on, if
  /// it lies in the unit box and is not known yet. Under the lock.
  std::optional<std::vector<double>> mirror(const std::vector<double>& u) const {
    std::optional<std::vector<double>> best;
    double nearest = INFINITY;
    for (const auto& [c, e] : entries_) {
      int axis = -1, differing = 0;
      for (size_t i = 0; i < u.size(); ++i)
        if (c[i] != u[i]) axis = static_cast<int>(i), ++differing;
      if (differing != 1) continue;
      const size_t i = static_cast<size_t>(axis);
      const double above = c[i] - u[i];
      if (!(above > 0) || above >= nearest) continue;
      std::vector<double> m = u;
      m[i] = c[i] + above;
      if (!(m[i] <= 1.0)) continue;
      nearest = above;
      best = std::move(m);
    }
    if (best && entries_.count(*best)) best.reset();
    return best;
  }

  /// Starts the run ahead of u's mirror on the spare thread, if it is free. Under the lock.
  void startAhead(const std::vector<double>& u) {
    if (!runAhead_ || spareBusy_) return;
    const std::optional<std::vector<double>> next = mirror(u);
    if (!next) return;
    if (spare_.joinable()) spare_.join();  // finished: spareBusy_ is false
    auto e = std::make_shared<Entry>();
    e->ahead = true;
    entries_[*next] = e;
    guess_ = e;
    spareBusy_ = true;
    try {
      spare_ = std::thread([this, x = *next, e] { runAhead(x, e); });
    } catch (const std::system_error&) {  // no thread to be had: run nothing ahead
      entries_.erase(*next);
      guess_.reset();
      spareBusy_ = false;
    }
  }

  void runAhead(const std::vector<double>& x, const std::shared_ptr<Entry>& e) {
    Value v;
    std::exception_ptr error;
    bool cancelled = false;
    try {
      const CancellationScope scope(e->cancel);
      v = compute_(x);
    } catch (const Cancelled&) {
      cancelled = true;
    } catch (...) {
      error = std::current_exception();
    }
    std::lock_guard<std::mutex> lock(mutex_);
    if (cancelled) {
      forget(x, e);
    } else {
      e->value = std::move(v);
      e->error = error;
      e->done = true;
      ++madeAhead_;
      done_.notify_all();
    }
    spareBusy_ = false;
  }

  Compute compute_;
  bool runAhead_ = false;
  mutable std::mutex mutex_;
  std::condition_variable done_;
  std::map<std::vector<double>, std::shared_ptr<Entry>> entries_;
  std::shared_ptr<Entry> guess_;  ///< the last run started ahead
  std::thread spare_;
  bool spareBusy_ = false;
  int madeAhead_ = 0, takenAhead_ = 0;
};

}  // namespace

std::string directSearchCommand(const io::BackanalysisJob& job) {
  if (job.parameters.size() != 1 || job.observations.size() != 1) return {};
  const io::ParameterSpec& p = job.parameters[0];
  const io::ObservationSpec& o = job.observations[0];
  // F = 1 reduces no strength, so the joints the observation names do not matter.
  if (o.kind != io::ObservationSpec::Kind::FactorOfSafety || o.target != 1.0 || p.joint.empty()) return {};
  const std::string solve = p.property == "cohesion" ? "cohesion" : p.property == "friction_angle" ? "friction" : "";
  if (solve.empty()) return {};
  return "ddaslope critical " + job.casePath + " --joint " + p.joint + " --solve " + solve;
}

BackanalysisResult runBackanalysis(const io::BackanalysisJob& job, TaskFarm* farm, const io::ProgressSink& progress) {
  const auto t0 = std::chrono::steady_clock::now();
  std::unique_ptr<TaskFarm> own;
  if (!farm) own = makeThreadFarm(job.threads), farm = own.get();
  // Under MPI the other ranks take part in the grid stages only (the optimisers' evaluations
  // depend on one another); the root runs the rest.
  const bool root = farm->isRoot();
  BackanalysisResult r;
  for (const auto& p : job.parameters) r.names.push_back(p.name);
  std::atomic<int> runs{0};
  // When every parameter is a joint strength, all trials share the first equilibrium stage.
  bool strengthsOnly = true;
  for (const auto& p : job.parameters) strengthsOnly &= p.jsonPath.empty();
  std::optional<solver::HeldEquilibrium> held;
  if (strengthsOnly) {
    const model::Scene base = sceneAt(job, physical(job, std::vector<double>(job.parameters.size(), 0.5)));
    if (base.settings.initialEquilibrium) held = solver::Simulation(base).holdEquilibrium();
  }
  const solver::HeldEquilibrium* shared = held ? &*held : nullptr;
  double bestSeen = HUGE_VAL;
  // Progress: evaluations of the current stage out of its budget, and the best misfit so far.
  std::string stage;
  int stageDone = 0, stagePlanned = 0;
  double stageBest = HUGE_VAL;
  const auto beginStage = [&](const std::string& name, int planned) {
    stage = name, stageDone = 0, stagePlanned = planned, stageBest = HUGE_VAL;
  };
  const auto evaluated = [&](double v) {
    ++stageDone;
    stageBest = std::min(stageBest, v);
    if (!progress) return;
    char text[96];
    std::snprintf(text, sizeof text, "best misfit %.4g (%d forward runs)", std::min(stageBest, bestSeen), runs.load());
    progress({stage, stageDone, stagePlanned, text, {{"best_misfit", std::min(stageBest, bestSeen)}}});
  };
  // A factor-of-safety observation's search already uses job.threads; a run-out's or a series'
  // forward run uses one, and the other runs the optimiser's next point ahead.
  bool searches = false;
  for (const auto& o : job.observations) searches |= o.kind == io::ObservationSpec::Kind::FactorOfSafety;
  Evaluations misfits([&](const std::vector<double>& u) {
    Evaluations::Value v;
    v.misfit = misfitAt(job, physical(job, u), &v.runs, shared, job.threads, &v.fit);
    return v;
  });
  const bool runAhead = job.threads >= 2 && !searches;
  // While the local stage polishes the global stage's best point, the spare thread starts the
  // precision study there: if the polish finds nothing better, that point is the estimate and
  // the study's runs are the ones it needs; if it moves, they are stopped.
  std::optional<PrecisionRuns> early;
  struct Spare {
    std::atomic<bool> stop{false};
    std::thread thread;
    void join() {
      if (thread.joinable()) thread.join();
    }
    ~Spare() {
      stop = true;
      join();
    }
  } spare;
  double earlyBest = HUGE_VAL;  // the misfit at the early study's point
  const std::function<double(const std::vector<double>&)> f = [&](const std::vector<double>& u) {
    bool fresh = false;
    Evaluations::Value v = misfits.at(u, fresh);
    if (fresh) runs += v.runs;
    // A better point: the estimate will move, and the early study is of no use.
    if (early && v.misfit < earlyBest) spare.stop = true;
    if (v.misfit < bestSeen) bestSeen = v.misfit, r.fit = std::move(v.fit);  // the optimisers call f one at a time
    evaluated(v.misfit);
    return v.misfit;
  };
  std::vector<double> u(job.parameters.size(), 0.5);
  for (size_t i = 0; i < u.size(); ++i)
    if (job.parameters[i].hasStart)
      u[i] = (job.parameters[i].start - job.parameters[i].min) / (job.parameters[i].max - job.parameters[i].min);
  double best = HUGE_VAL;
  const bool gridSearch = job.optimiser.global == io::kGridSearch;
  std::vector<double> gridValues;
  if (gridSearch) {
    // A global stage whose evaluations are independent: the misfit at grid_points per axis,
    // spread over the threads (or ranks); the best point starts the local polish.
    std::vector<std::vector<double>> unit;
    const std::vector<std::vector<double>> grid = parameterGrid(job, job.gridPoints, &unit);
    beginStage("grid", static_cast<int>(grid.size()));
    gridValues = misfitsAt(job, grid, shared, *farm, runs, evaluated);
    const size_t k = static_cast<size_t>(std::min_element(gridValues.begin(), gridValues.end()) - gridValues.begin());
    u = unit[k];
    best = gridValues[k];
    r.evaluations += static_cast<int>(grid.size());
    r.globalStatus = std::string(io::kGridSearch) + ": " + std::to_string(grid.size()) + " points";
  } else if (!job.optimiser.global.empty() && root) {
    beginStage("global", job.optimiser.globalEvaluations);
    misfits.runAheadFrom(runAhead && job.optimiser.global.find("DIRECT") != std::string::npos);
    const MinimiserResult g = minimise(job.optimiser.global, f, u, job.optimiser.globalEvaluations, job.optimiser.xtolRel);
    misfits.runAheadFrom(false);
    r.globalStatus = job.optimiser.global + ": " + g.status;
    r.evaluations += g.evaluations;
    u = g.x;
    best = g.value;
  }
  // (Without a global stage the local one starts at the job's start, which it nearly always leaves.)
  if (runAhead && job.precision.enabled && root && !job.optimiser.local.empty() &&
      (gridSearch || !job.optimiser.global.empty())) {
    misfits.stopRunningAhead();
    early.emplace(job, physical(job, u), shared);
    earlyBest = best;
    try {
      spare.thread = std::thread([&] {
        const CancellationScope scope(spare.stop);
        try {
          early->work();
        } catch (const Cancelled&) {
        }
      });
    } catch (const std::system_error&) {  // no thread to be had: the study runs after the polish
      early.reset();
    }
  }
  if (!job.optimiser.local.empty() && root) {
    beginStage("local", job.optimiser.localEvaluations);
    const MinimiserResult l = minimise(job.optimiser.local, f, u, job.optimiser.localEvaluations, job.optimiser.xtolRel);
    r.localStatus = job.optimiser.local + ": " + l.status;
    r.evaluations += l.evaluations;
    if (l.value <= best) u = l.x, best = l.value;
  }
  // The observations' fit at the estimate (the local stage recorded it if it ran from there).
  if (root && bestSeen > best) f(u), ++r.evaluations;
  misfits.stopRunningAhead();
  r.runsAhead = misfits.madeAhead();
  r.runsAheadUnused = misfits.unusedAhead();
  r.estimate = physical(job, u);
  r.misfit = best;
  if (job.precision.enabled && root) {
    if (progress) progress({"precision", 0, 0, "scanning the estimate's neighbourhood and Δt", {}});
    std::vector<double> simulated;
    for (const auto& f : r.fit) simulated.push_back(f.converged ? f.simulated : NAN);
    int n = 0;
    if (early && !spare.stop && early->estimate() == r.estimate) {
      // The same runs the study would make: this thread (and any other allowed) joins in.
      runOnThreads(job.threads - 1, job.threads - 1, [&](int) { early->work(); });
      spare.join();
      r.precision = early->summary(r.misfit, simulated, n);
      r.precisionStartedEarly = true;
    } else {
      spare.stop = true;
      spare.join();
      // Its finished runs were made ahead of need, for a point that is not the estimate.
      if (early) r.runsAhead += early->runsMade(), r.runsAheadUnused += early->runsMade();
      r.precision = measurePrecision(job, r.estimate, r.misfit, simulated, shared, n);
    }
    runs += n;
  }

  if (job.parameters.size() == 2 && job.gridPoints >= 3) {
    const int n = job.gridPoints;
    for (int i = 0; i < n; ++i) {
      r.axis0.push_back(job.parameters[0].min + (job.parameters[0].max - job.parameters[0].min) * i / (n - 1));
      r.axis1.push_back(job.parameters[1].min + (job.parameters[1].max - job.parameters[1].min) * i / (n - 1));
    }
    // The map is the grid search's own grid when there was one (the same points, last axis
    // fastest); else its n² evaluations are spread over the farm.
    std::vector<double> values = gridValues;
    if (!gridSearch) {
      beginStage("map", n * n);
      values = misfitsAt(job, parameterGrid(job, n), shared, *farm, runs, evaluated);
    }
    r.map.assign(n, std::vector<double>(n, 0));
    for (int k = 0; k < n * n; ++k) r.map[k / n][k % n] = values[k];
    if (root) judgeConstraint(job, r);
  }
  r.forwardRuns = runs;
  r.wallTime = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

}  // namespace ddaslope::calibration

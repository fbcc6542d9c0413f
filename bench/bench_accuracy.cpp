// The speed/accuracy trade, measured (issue #6): sweeps the time step, the displacement ratio g2,
// the penalty, the open-close iteration limit and rigid against deformable blocks over
// closed-form benchmarks and prints, per setting, the error against the
// closed form and the wall time, as CSV; marks the Pareto front (no other setting is both faster
// and more accurate) and writes a PNG of error against time.
//   build/ddaslope_accuracy [--out DIR]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "ddaslope/calibration/strength_search.hpp"
#include "ddaslope/io/extremes.hpp"
#include "ddaslope/io/case_reader.hpp"
#include "ddaslope/io/line_plot.hpp"
#include "ddaslope/io/run_case.hpp"
#include "ddaslope/model/incline_scene.hpp"

using namespace ddaslope;

namespace {

struct Knobs {
  double timeStep, g2, penaltyFactor;
  int openCloseLimit = 30;
  bool rigid = false;
};

struct Errors {
  double sliding = 0, stable = 0, cohesion = 0, fos = 0, toppling = 0, twoBlock = 0, worst = 0, seconds = 0;
  double twoBlockToe = 0;  ///< raw value; its error is taken against the finest setting
};

void apply(model::Scene& s, const Knobs& k) {
  s.settings.timeStep = k.timeStep;
  s.settings.maxDisplacementRatio = k.g2;
  s.settings.penaltyFactor = k.penaltyFactor;
  s.settings.openCloseMaxIterations = k.openCloseLimit;
  s.settings.rigidBlocks = k.rigid;
}

double measure(const io::Trace& t, const char* q, std::optional<double> time) {
  model::Expectation e;
  e.monitor = "centre";
  e.quantity = q;
  e.time = time;
  return io::measure(t, e);
}

/// Hoek & Bray planar failure (the geometry of cases/planar_failure.json), FS closed form.
std::pair<model::Scene, double> planar() {
  const double h = 20, xc = 20, gap = 0.05, psi = 35 * M_PI / 180, t = std::tan(psi), cot60 = 1 / std::tan(M_PI / 3);
  model::Scene s;
  s.materials.push_back({"rock", 2600, 10e9, 0.25});
  s.joints.push_back(model::JointProperties::coulomb("plane", 30 * M_PI / 180, 25e3));
  model::Block base, wedge;
  base.fixed = true;
  base.vertices = {{-10, -10}, {xc + 20, -10}, {xc + 20, h}, {xc + gap, h}, {xc + gap, (xc + gap) * t}, {0, 0}, {-5 * cot60, -5}, {-10, -5}};
  wedge.vertices = {{0, 0}, {xc, xc * t}, {xc, h}, {h * cot60, h}};
  for (auto* b : {&base, &wedge}) b->moments = geometry::computeMoments(b->vertices);
  s.blocks = {base, wedge};
  s.monitors.push_back({"centre", {1, wedge.moments.centroid, wedge.moments.centroid}});
  const double w = 2600 * 9.81 * wedge.moments.area, a = xc / std::cos(psi);
  return {s, (25e3 * a + w * std::cos(psi) * std::tan(M_PI / 6)) / (w * std::sin(psi))};
}

Errors evaluate(const Knobs& k) {
  Errors e;
  const auto t0 = std::chrono::steady_clock::now();
  {  // A2 sliding block: displacement at 1 s against a/2.
    model::InclineSpec spec{40, 10, 5, 20, 0, 2000, 10};
    model::Scene s = model::makeInclineScene(spec);
    apply(s, k);
    const io::RunOutcome o = io::runScene(s, {});
    const double want = model::slidingAcceleration(spec) / 2;
    e.sliding = o.completed ? std::abs(measure(o.trace, "displacement", 1.0) - want) / want : 1.0;
  }
  {  // A3 stable block: largest displacement over 2 s relative to the block size b (exact: 0).
    model::InclineSpec spec{40, 10, 10, 40.1, 0, 2000, 10};
    spec.duration = 2;
    model::Scene s = model::makeInclineScene(spec);
    apply(s, k);
    const io::RunOutcome o = io::runScene(s, {});
    e.stable = o.completed ? measure(o.trace, "displacement", std::nullopt) / spec.b : 1.0;
  }
  {  // B1 critical cohesion of the A2 block against 36.40 kPa.
    model::InclineSpec spec{40, 10, 5, 20, 0, 2000, 10};
    spec.duration = 0.5;
    model::Scene s = model::makeInclineScene(spec);
    apply(s, k);
    const auto r = calibration::criticalCohesion(s, 0, 20, 10);
    const double want = model::criticalCohesion(spec);
    e.cohesion = r.found ? std::abs(r.critical - want) / want : 1.0;
  }
  {  // C planar failure: strength-reduction F against Hoek & Bray.
    auto [s, want] = planar();
    apply(s, k);
    const auto r = calibration::factorOfSafety(s, {}, 0.005);
    e.fos = r.found ? std::abs(r.factor - want) / want : 1.0;
  }
  {  // A6 toppling: top-corner travel at 0.5 s against the small-angle rotation about the toe
     // (the 3 % of the shipped case is the closed form's own approximation; here the error).
    model::InclineSpec spec{30, 10, 25, 40, 0, 2600, 9.81};
    spec.duration = 0.5;
    model::Scene s = model::makeInclineScene(spec);
    apply(s, k);
    const io::RunOutcome o = io::runScene(s, {});
    const double a = M_PI / 6, acc = 1.5 * 9.81 * (25 * std::sin(a) - 10 * std::cos(a)) / (100 + 625);
    const double want = std::hypot(10.0, 25.0) * 0.5 * acc * 0.25;
    model::Expectation top{};
    top.monitor = "top";
    top.quantity = "displacement";
    top.time = 0.5;
    e.toppling = o.completed ? std::abs(io::measure(o.trace, top) - want) / want : 1.0;
  }
  {  // Two-block slide (calibration/two_block_slide geometry at phi = 9 deg): toe travel at 2 s.
    model::Scene s = io::readCase(std::string(DDASLOPE_SOURCE_DIR) + "/calibration/two_block_slide/case.json");
    apply(s, k);
    const io::RunOutcome o = io::runScene(s, {});
    const model::Expectation toe{.monitor = "toe", .quantity = "ux", .time = 2.0};
    e.twoBlockToe = o.completed ? io::measure(o.trace, toe) : NAN;
  }
  e.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return e;
}

}  // namespace

/// `--extremes`: the closed-form error, speed bound and energy balance of each extreme of issue #6
/// (io/extremes.hpp; the test suite asserts the same numbers), as a Markdown table.
int printExtremes() {
  std::printf("| extreme | b (m) | h/b | E (Pa) | ρ | φ (°) | c (Pa) | Δt (s) | slide: closed form | slide: DDA | error "
              "| peak speed / a t | energy rise / PE held | energy lost / friction work | wall (s) |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  bool allPassed = true;
  for (const io::ExtremeIncline& x : io::extremeInclines()) {
    const io::ExtremeResult r = io::runExtreme(x);
    const model::InclineSpec& s = x.spec;
    if (!r.completed || !r.finite) {
      std::printf("| %s | did not complete: %s |\n", x.name.c_str(), r.failure.c_str());
      allPassed = false;
      continue;
    }
    char closed[40], lost[40], speed[40];
    if (x.slides) std::snprintf(closed, sizeof closed, "%.6g m", r.closedFormSlide);
    else std::snprintf(closed, sizeof closed, "holds (< 1e-3 b)");
    std::snprintf(speed, sizeof speed, "%.4f", r.closedFormPeakSpeed > 0 ? r.peakSpeed / r.closedFormPeakSpeed : 0.0);
    if (x.slides && r.frictionWork > 0) std::snprintf(lost, sizeof lost, "%.4f", r.energyLost / r.frictionWork);
    else std::snprintf(lost, sizeof lost, "(no friction work)");
    std::printf("| %s | %g | %g | %g | %g | %g | %g | %g | %s | %.6g %s | %.2e | %s | %.1e | %s | %.3f |\n", x.name.c_str(), s.b,
                s.h / s.b, s.young, s.density, s.phiDeg, s.cohesion, s.timeStep, closed, r.slide, x.slides ? "m" : "b",
                r.slideError(), x.slides ? speed : "(held)", r.heldPotential > 0 ? r.energyGain / r.heldPotential : 0.0,
                lost, r.wallSeconds);
  }
  return allPassed ? 0 : 1;
}

int main(int argc, char** argv) {
  std::string out = "out/accuracy";
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--out") && i + 1 < argc) out = argv[++i];
    else if (!std::strcmp(argv[i], "--extremes")) return printExtremes();
  }
  std::vector<Knobs> knobs;
  for (double dt : {1e-2, 3e-3, 1e-3, 3e-4})
    for (double g2 : {0.002, 0.005, 0.01})
      for (double pf : {10.0, 40.0, 100.0})
        for (int limit : {30, 6})
          for (bool rigid : {false, true}) knobs.push_back({dt, g2, pf, limit, rigid});
  std::vector<Errors> errors;
  for (const Knobs& k : knobs) errors.push_back(evaluate(k));
  // The two-block slide has no closed form: its error is against the finest setting (smallest Δt,
  // then smallest g2, then largest penalty factor), which is the last in the sweep's order.
  size_t finest = 0;
  for (size_t i = 0; i < knobs.size(); ++i) {
    const Knobs &a = knobs[i], &b = knobs[finest];
    // ... with the default open-close limit and deformable blocks.
    if (a.openCloseLimit != 30 || a.rigid) continue;
    if (a.timeStep < b.timeStep || (a.timeStep == b.timeStep && (a.g2 < b.g2 || (a.g2 == b.g2 && a.penaltyFactor > b.penaltyFactor))))
      finest = i;
  }
  for (Errors& e : errors) {
    const double ref = errors[finest].twoBlockToe;
    e.twoBlock = std::isfinite(e.twoBlockToe) ? std::abs(e.twoBlockToe - ref) / std::abs(ref) : 1.0;
    e.worst = std::max({e.sliding, e.stable, e.cohesion, e.fos, e.toppling, e.twoBlock});
  }
  std::filesystem::create_directories(out);
  std::FILE* csv = std::fopen((out + "/accuracy.csv").c_str(), "w");
  const char* header = "time_step,max_displacement_ratio,penalty_factor,open_close_limit,blocks,sliding_error,stable_error,cohesion_error,fos_error,"
                       "toppling_error,two_block_error_vs_finest,worst_error,wall_s,pareto\n";
  std::fputs(header, csv);
  std::fputs(header, stdout);
  io::PlotSeries deformable{"deformable blocks", {}, {}, true, false}, rigid{"rigid blocks", {}, {}, true, false},
      front{"Pareto front", {}, {}, true};
  for (size_t i = 0; i < knobs.size(); ++i) {
    bool dominated = false;
    for (size_t j = 0; j < knobs.size(); ++j)
      dominated |= j != i && errors[j].worst <= errors[i].worst && errors[j].seconds <= errors[i].seconds &&
                   (errors[j].worst < errors[i].worst || errors[j].seconds < errors[i].seconds);
    const Errors& e = errors[i];
    for (std::FILE* f : {csv, stdout})
      std::fprintf(f, "%g,%g,%g,%d,%s,%.3e,%.3e,%.3e,%.3e,%.3e,%.3e,%.3e,%.3f,%d\n", knobs[i].timeStep, knobs[i].g2,
                   knobs[i].penaltyFactor, knobs[i].openCloseLimit, knobs[i].rigid ? "rigid" : "deformable", e.sliding, e.stable, e.cohesion, e.fos, e.toppling, e.twoBlock, e.worst,
                   e.seconds, !dominated);
    io::PlotSeries& all = knobs[i].rigid ? rigid : deformable;
    all.x.push_back(e.seconds);
    all.y.push_back(std::log10(std::max(e.worst, 1e-12)));
    if (!dominated) {
      front.x.push_back(e.seconds);
      front.y.push_back(std::log10(std::max(e.worst, 1e-12)));
    }
  }
  std::fclose(csv);
  // The front as a line from the fastest setting to the most accurate one.
  std::vector<size_t> order(front.x.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return front.x[a] < front.x[b]; });
  io::PlotSeries sorted{front.label, {}, {}, true};
  for (size_t i : order) sorted.x.push_back(front.x[i]), sorted.y.push_back(front.y[i]);
  io::writePng({"Worst relative error of 6 benchmarks against wall time", "wall time (s)",
                "log10 worst relative error", {deformable, rigid, sorted}},
               out + "/accuracy.png");
  std::fprintf(stderr, "wrote %s/accuracy.csv and accuracy.png\n", out.c_str());
  return 0;
}

// Step-cost benchmark: brick walls of N = 10 … 5000 blocks on a fixed base. Prints CSV: per-step
// time by phase, open-close iterations and Δt cuts. Speed targets live here, not in tests.
//   build/ddaslope_bench [--steps S] [--sizes 10,100,...] [--contact-treatment edge|vertex] [--blocks rigid|deformable]
//                        [--compare-search]  (also time the narrow phase on every pair, on stderr)
//                        [--no-pair-cache]  (search every block pair at every step, as before the
//                        pair cache: contact/pair_cache.hpp; the run is the same, bit for bit)
//                        [--double-factor-only]  (large systems substitute with CHOLMOD's double
//                        factor only, as before the panels, rounded or exact: solver/panel_factor.hpp)
//                        [--probe-solve-cache]  (time each timed step's first substitution, then
//                        the same substitution repeated at once with the factor in cache; on stderr;
//                        the repeats lengthen the steps, so time steps without it)
//   build/ddaslope_bench --anchor-rows 22,31,45 [--sudden] [--steps 100] [--blocks rigid|deformable]
//       the wall timed side by side with Shi's DDA (../shared/ntdda, issue #16): rows 22, 31, 45, 71,
//       100, 141 give 495, 976, 2047, 5076, 10050, 19951 bricks; --sudden starts it as ntdda does,
//       full gravity at step 1 without the initial equilibrium (sudden loading).
// One core, as the side-by-side table: run with OMP_NUM_THREADS=1.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

#include "ddaslope/contact/broad_phase.hpp"
#include "ddaslope/contact/narrow_phase.hpp"
#include "ddaslope/model/wall_scene.hpp"
#include "ddaslope/solver/simulation.hpp"

using namespace ddaslope;

namespace {

double ms(double s, int steps) { return 1e3 * s / steps; }

/// What the broad phase saves: one contact search over the candidate pairs of the sweep and
/// prune against the narrow phase run on every pair of blocks (ms each, and the pair counts).
void compareContactSearch(const model::Scene& scene, double searchDistance) {
  std::vector<geometry::Aabb> boxes;
  std::vector<bool> fixed;
  for (const model::Block& b : scene.blocks) {
    boxes.push_back(geometry::boundingBox(b.vertices));
    fixed.push_back(b.fixed);
  }
  const contact::NarrowPhaseSettings nps{searchDistance, 1.0 * M_PI / 180};
  const auto none = [](const contact::ContactKey&) { return false; };
  std::vector<contact::ContactCandidate> found;
  auto t0 = std::chrono::steady_clock::now();
  const auto pairs = contact::findCandidatePairs(boxes, fixed, searchDistance);
  for (const auto& p : pairs)
    contact::findContacts(p.a, scene.blocks[p.a].vertices, p.b, scene.blocks[p.b].vertices, nps, none, found);
  const double pruned = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const size_t withPruning = found.size();
  found.clear();
  t0 = std::chrono::steady_clock::now();
  size_t allPairs = 0;
  for (size_t a = 0; a < scene.blocks.size(); ++a)
    for (size_t b = a + 1; b < scene.blocks.size(); ++b) {
      if (fixed[a] && fixed[b]) continue;
      ++allPairs;
      contact::findContacts(a, scene.blocks[a].vertices, b, scene.blocks[b].vertices, nps, none, found);
    }
  const double all = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::fprintf(stderr, "contact search, %zu blocks: broad phase + narrow phase on %zu pairs %.2f ms; "
               "narrow phase on all %zu pairs %.2f ms (%zu and %zu contacts)\n",
               scene.blocks.size(), pairs.size(), 1e3 * pruned, allPairs, 1e3 * all, withPruning, found.size());
}

/// A memory figure of this process (MB) from /proc/self/status: "VmRSS" (resident now) or
/// "VmHWM" (peak resident since the last resetPeakResident).
double statusMb(const char* field) {
  std::FILE* f = std::fopen("/proc/self/status", "r");
  if (!f) return 0;
  char line[256], format[64];
  std::snprintf(format, sizeof format, "%s: %%lf kB", field);
  double kb = 0;
  while (std::fgets(line, sizeof line, f))
    if (std::sscanf(line, format, &kb) == 1) break;
  std::fclose(f);
  return kb / 1024;
}

/// Resets the peak resident set (Linux ≥ 4.0: "5" to /proc/self/clear_refs), so that each wall
/// size reports its own peak. Returns false where that is not allowed.
bool resetPeakResident() {
  std::FILE* f = std::fopen("/proc/self/clear_refs", "w");
  if (!f) return false;
  const bool ok = std::fputs("5", f) >= 0;
  return std::fclose(f) == 0 && ok;
}

}  // namespace

int main(int argc, char** argv) {
  int steps = 20;
  model::ContactTreatment treatment = model::ContactTreatment::Edge;
  bool rigid = false;
  bool allPairs = false;
  bool refactoriseOnly = false, pairCache = true, probeSolveCache = false, panels = true;
  bool sudden = false;
  int threads = 1;
  std::vector<int> sizes{10, 50, 100, 200, 500, 1000, 2000};
  std::vector<int> anchorRows;
  const auto list = [](const char* text) {
    std::vector<int> out;
    std::stringstream ss(text);
    for (std::string tok; std::getline(ss, tok, ',');) out.push_back(std::stoi(tok));
    return out;
  };
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--steps") && i + 1 < argc) steps = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--contact-treatment") && i + 1 < argc)
      treatment = std::strcmp(argv[++i], "vertex") ? model::ContactTreatment::Edge : model::ContactTreatment::Vertex;
    else if (!std::strcmp(argv[i], "--compare-search"))
      allPairs = true;
    else if (!std::strcmp(argv[i], "--refactorise-only"))
      refactoriseOnly = true;
    else if (!std::strcmp(argv[i], "--probe-solve-cache"))
      probeSolveCache = true;
    else if (!std::strcmp(argv[i], "--double-factor-only"))
      panels = false;
    else if (!std::strcmp(argv[i], "--no-pair-cache"))
      pairCache = false;
    else if (!std::strcmp(argv[i], "--blocks") && i + 1 < argc)
      rigid = !std::strcmp(argv[++i], "rigid");
    else if (!std::strcmp(argv[i], "--sizes") && i + 1 < argc)
      sizes = list(argv[++i]);
    else if (!std::strcmp(argv[i], "--anchor-rows") && i + 1 < argc)
      anchorRows = list(argv[++i]);
    else if (!std::strcmp(argv[i], "--sudden"))
      sudden = true;
    else if (!std::strcmp(argv[i], "--threads") && i + 1 < argc)
      threads = std::atoi(argv[++i]);
    else {
      std::fprintf(stderr, "usage: ddaslope_bench [--steps S] [--sizes 10,100,...] [--anchor-rows 22,31,... [--sudden]] [--threads T] [--contact-treatment edge|vertex] [--blocks rigid|deformable] [--compare-search] [--refactorise-only] [--no-pair-cache] [--probe-solve-cache] [--double-factor-only]\n");
      return 2;
    }
  }
  std::printf("blocks,contacts,unknowns,equilibrium_ms,step_ms,broad_phase_ms,contacts_ms,assembly_ms,"
              "factorisation_ms,solve_ms,state_checks_ms,update_ms,iterations_per_step,factorisations_per_step,"
              "cg_iterations_per_step,cuts,resident_mb,peak_resident_mb,simulated_s,wall_s,factor_update_ms,"
              "factor_columns_per_step,stick_slip_changes_per_step,open_close_changes_per_step,pairs_reused_share\n");
  std::vector<std::pair<int, double>> perStep;
  // The anchor wall by rows, or the bench's own wall by bricks.
  const std::vector<int>& runs = anchorRows.empty() ? sizes : anchorRows;
  for (int size : runs) {
    const bool peakReset = resetPeakResident();
    model::Scene scene = anchorRows.empty() ? model::makeBrickWall(size) : model::makeAnchorWall(size, sudden);
    const int n = static_cast<int>(scene.blocks.size()) - 1;
    scene.settings.contactTreatment = treatment;
    scene.settings.rigidBlocks = rigid;
    solver::Simulation sim(scene);
    sim.setFactorFollowing(!refactoriseOnly);
    sim.setPairCache(pairCache);
    sim.setPanelSolves(panels);
    sim.setThreads(threads);
    if (std::getenv("DDASLOPE_BENCH_VERBOSE")) sim.setLog([](const std::string& l) { std::fprintf(stderr, "%s\n", l.c_str()); });
    if (allPairs) compareContactSearch(scene, sim.searchDistance());
    auto t0 = std::chrono::steady_clock::now();
    sim.bringToEquilibrium();
    const double eq = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const solver::RunStatistics before = sim.statistics();
    const solver::PhaseTimes& e = before.times;
    std::fprintf(stderr,
                 "%d blocks, equilibrium: %.2f s; contacts %.2f, assembly %.2f, factorisation %.2f, solve %.2f, "
                 "state checks %.2f s; %ld factorisations, %ld factor updates, %ld CG iterations, %d steps\n",
                 n, eq, e.contacts + e.broadPhase, e.assembly, e.factorisation, e.solve, e.stateChecks, before.factorisations,
                 before.factorUpdates, before.cgIterations, before.equilibriumSteps);
    sim.setSolveCacheProbe(probeSolveCache);
    t0 = std::chrono::steady_clock::now();
    // Simulated time, not a step count: steps whose Δt was cut take several (sudden loading).
    const double simulated = steps * scene.settings.timeStep;
    int accepted = 0;
    for (; sim.time() < simulated * (1 - 1e-9); ++accepted) sim.advance();
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const solver::RunStatistics& a = sim.statistics();
    const auto d = [&](double solver::PhaseTimes::*f) { return ms(a.times.*f - before.times.*f, accepted); };
    std::printf("%d,%zu,%d,%.1f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.2f,%.2f,%.2f,%d,%.1f,%.1f,%.4f,%.3f,%.3f,%.1f,%.1f,%.1f,%.3f\n", n,
                sim.contacts().contacts().size(), (rigid ? 3 : 6) * n, 1e3 * eq, ms(wall, accepted),
                d(&solver::PhaseTimes::broadPhase), d(&solver::PhaseTimes::contacts),
                d(&solver::PhaseTimes::assembly), d(&solver::PhaseTimes::factorisation),
                d(&solver::PhaseTimes::solve), d(&solver::PhaseTimes::stateChecks),
                d(&solver::PhaseTimes::update), double(a.iterations - before.iterations) / accepted,
                double(a.factorisations - before.factorisations) / accepted,
                double(a.cgIterations - before.cgIterations) / accepted,
                a.cuts - before.cuts, statusMb("VmRSS"), peakReset ? statusMb("VmHWM") : NAN, sim.time(), wall,
                d(&solver::PhaseTimes::factorUpdate), double(a.factorColumns - before.factorColumns) / accepted,
                double(a.stickSlipChanges - before.stickSlipChanges) / accepted,
                double(a.openCloseChanges - before.openCloseChanges) / accepted,
                double(a.pairsReused - before.pairsReused) /
                    std::max(1.0, double(a.pairsReused - before.pairsReused + a.pairsSearched - before.pairsSearched)));
    std::fflush(stdout);
    // The final state in two numbers, to see that two settings give the same run.
    double sum = 0, fastest = 0;
    for (const auto& b : sim.scene().blocks) {
      sum += b.moments.centroid.x() + 3 * b.moments.centroid.y();
      fastest = std::max(fastest, b.velocity.head<2>().norm());
    }
    if (probeSolveCache) {
      const long probed = a.probedSubstitutions - before.probedSubstitutions;
      std::fprintf(stderr,
                   "%d blocks: factor of %.3g entries (%.1f MB with their row indices); %ld substitutions probed: "
                   "%.3f ms each as they ran, %.3f ms repeated at once\n",
                   n, a.factorEntries, 12e-6 * a.factorEntries, probed,
                   ms(a.probeFirstSeconds - before.probeFirstSeconds, static_cast<int>(std::max(1L, probed))),
                   ms(a.probeRepeatSeconds - before.probeRepeatSeconds, static_cast<int>(std::max(1L, probed))));
    }
    if (a.panelSubstitutions > before.panelSubstitutions)
      std::fprintf(stderr, "%d blocks: %ld substitutions with the factor's panels (%.1f MB; rounded to single precision from 1e6 entries, exact below)\n", n,
                   a.panelSubstitutions - before.panelSubstitutions, 1e-6 * a.panelBytes);
    std::fprintf(stderr, "%d blocks: state checksum %.12g, fastest block %.6g m/s\n", n, sum, fastest);
    perStep.emplace_back(n, wall / accepted);
  }
  // Growth of the step cost: exponent k in t ∝ N^k between consecutive sizes (on stderr, so
  // stdout stays plain CSV).
  for (size_t i = 1; i < perStep.size(); ++i)
    std::fprintf(stderr, "growth %d -> %d blocks: N^%.2f\n", perStep[i - 1].first, perStep[i].first,
                 std::log(perStep[i].second / perStep[i - 1].second) /
                     std::log(double(perStep[i].first) / perStep[i - 1].first));
  return 0;
}

// Step-cost benchmark: brick walls of N = 10 … 5000 blocks on a fixed base. Prints CSV: per-step
// time by phase, open-close iterations and Δt cuts. Speed targets live here, not in tests.
//   build/ddaslope_bench [--steps S] [--sizes 10,100,...]
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

#include "ddaslope/solver/simulation.hpp"

using namespace ddaslope;

namespace {

/// A running-bond wall of about n bricks (2 m × 1 m) on a fixed base: odd rows start and end
/// with a half brick, so both ends are straight and no brick overhangs (a stable wall).
model::Scene makeWall(int n) {
  model::Scene s;
  s.description = "benchmark wall";
  s.materials.push_back({"rock", 2600, 10e9, 0.25});
  s.joints.push_back({"joint", 35 * M_PI / 180, 0, 0});
  const int perRow = std::max(2, static_cast<int>(std::lround(std::sqrt(2.0 * n))));
  const double bw = 2, bh = 1, width = perRow * bw;
  const auto add = [&](std::string id, bool fixed, std::vector<Vec2> v) {
    model::Block b;
    b.id = std::move(id);
    b.fixed = fixed;
    b.vertices = std::move(v);
    b.moments = geometry::computeMoments(b.vertices);
    s.blocks.push_back(b);
  };
  add("base", true, {{-2, -2}, {width + 2, -2}, {width + 2, 0}, {-2, 0}});
  int made = 0;
  for (int r = 0; made < n; ++r) {
    const double y0 = r * bh;
    std::vector<std::pair<double, double>> spans;
    if (r % 2 == 0) {
      for (int k = 0; k < perRow; ++k) spans.emplace_back(k * bw, (k + 1) * bw);
    } else {
      spans.emplace_back(0, bw / 2);
      for (int k = 0; k + 1 < perRow; ++k) spans.emplace_back(bw / 2 + k * bw, bw / 2 + (k + 1) * bw);
      spans.emplace_back(width - bw / 2, width);
    }
    for (const auto& [x0, x1] : spans) {
      if (made == n) break;
      add("b" + std::to_string(made++), false, {{x0, y0}, {x1, y0}, {x1, y0 + bh}, {x0, y0 + bh}});
    }
  }
  s.settings.timeStep = 1e-3;
  s.settings.duration = 1e9;
  return s;
}

double ms(double s, int steps) { return 1e3 * s / steps; }

/// Resident memory of this process now (MB), from /proc/self/status.
double residentMb() {
  std::FILE* f = std::fopen("/proc/self/status", "r");
  if (!f) return 0;
  char line[256];
  double kb = 0;
  while (std::fgets(line, sizeof line, f))
    if (std::sscanf(line, "VmRSS: %lf kB", &kb) == 1) break;
  std::fclose(f);
  return kb / 1024;
}

}  // namespace

int main(int argc, char** argv) {
  int steps = 20;
  model::ContactTreatment treatment = model::ContactTreatment::Edge;
  bool rigid = false;
  std::vector<int> sizes{10, 50, 100, 200, 500, 1000, 2000};
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--steps") && i + 1 < argc) steps = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--contact-treatment") && i + 1 < argc)
      treatment = std::strcmp(argv[++i], "vertex") ? model::ContactTreatment::Edge : model::ContactTreatment::Vertex;
    else if (!std::strcmp(argv[i], "--blocks") && i + 1 < argc)
      rigid = !std::strcmp(argv[++i], "rigid");
    else if (!std::strcmp(argv[i], "--sizes") && i + 1 < argc) {
      sizes.clear();
      std::stringstream ss(argv[++i]);
      for (std::string tok; std::getline(ss, tok, ',');) sizes.push_back(std::stoi(tok));
    } else {
      std::fprintf(stderr, "usage: ddaslope_bench [--steps S] [--sizes 10,100,...] [--contact-treatment edge|vertex] [--blocks rigid|deformable]\n");
      return 2;
    }
  }
  std::printf("blocks,contacts,unknowns,equilibrium_ms,step_ms,broad_phase_ms,contacts_ms,assembly_ms,"
              "factorisation_ms,solve_ms,state_checks_ms,update_ms,iterations_per_step,factorisations_per_step,"
              "cg_iterations_per_step,cuts,resident_mb\n");
  std::vector<std::pair<int, double>> perStep;
  for (int n : sizes) {
    model::Scene scene = makeWall(n);
    scene.settings.contactTreatment = treatment;
    scene.settings.rigidBlocks = rigid;
    solver::Simulation sim(scene);
    if (std::getenv("DDASLOPE_BENCH_VERBOSE")) sim.setLog([](const std::string& l) { std::fprintf(stderr, "%s\n", l.c_str()); });
    auto t0 = std::chrono::steady_clock::now();
    sim.bringToEquilibrium();
    const double eq = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const solver::RunStatistics before = sim.statistics();
    t0 = std::chrono::steady_clock::now();
    for (int k = 0; k < steps; ++k) sim.advance();
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const solver::RunStatistics& a = sim.statistics();
    const auto d = [&](double solver::PhaseTimes::*f) { return ms(a.times.*f - before.times.*f, steps); };
    std::printf("%d,%zu,%d,%.1f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.2f,%.2f,%.2f,%d,%.1f\n", n,
                sim.contacts().contacts().size(), (rigid ? 3 : 6) * n, 1e3 * eq, ms(wall, steps),
                d(&solver::PhaseTimes::broadPhase), d(&solver::PhaseTimes::contacts),
                d(&solver::PhaseTimes::assembly), d(&solver::PhaseTimes::factorisation),
                d(&solver::PhaseTimes::solve), d(&solver::PhaseTimes::stateChecks),
                d(&solver::PhaseTimes::update), double(a.iterations - before.iterations) / steps,
                double(a.factorisations - before.factorisations) / steps,
                double(a.cgIterations - before.cgIterations) / steps,
                a.cuts - before.cuts, residentMb());
    std::fflush(stdout);
    perStep.emplace_back(n, wall / steps);
  }
  // Growth of the step cost: exponent k in t ∝ N^k between consecutive sizes (on stderr, so
  // stdout stays plain CSV).
  for (size_t i = 1; i < perStep.size(); ++i)
    std::fprintf(stderr, "growth %d -> %d blocks: N^%.2f\n", perStep[i - 1].first, perStep[i].first,
                 std::log(perStep[i].second / perStep[i - 1].second) /
                     std::log(double(perStep[i].first) / perStep[i - 1].first));
  return 0;
}

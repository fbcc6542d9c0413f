// One substitution with the factor of the side-by-side wall (issue #16), in seconds instead of the
// minutes the wall's equilibrium takes at 20 000 blocks. The factor's pattern is the wall's:
// every free brick is coupled to the bricks its bounding box touches (the couplings of its
// contacts), six unknowns each, ordered by CHOLMOD's nested dissection as the runs order it
// (1.45 million entries at 2047 bricks, 22.4 million at 19 951, as ddaslope_bench reports). The
// entries are made up (a diagonally dominant K of that pattern): a substitution's cost depends on
// the pattern, not on the values. Prints, per wall, the best and the median of `reps` timed
// substitutions through single-precision panels, for each kernel and with the back
// substitutions' prefetch on and off (solver/panel_factor.hpp), and a checksum of the solution,
// which must not depend on either choice. Two more rows per wall: CHOLMOD's own substitution with
// the double-precision factor (kernel "cholmod-double", its bytes with row indices as panel_mb),
// which a factor's first solves use, the regrouping into panels ("panel-build"), and one plain
// read of as many single-precision entries as the panels hold ("memory-read", forward and back:
// the floor, which a substitution, reading them twice, could reach at best).
//   build/ddaslope_substitution_bench [--anchor-rows 45,71,141] [--reps 40]
//   build/ddaslope_substitution_bench --anchor-rows 45,141 --orderings
//       instead, the factor's entries under CHOLMOD's orderings and nested dissection's settings
//       (the fill a different ordering would save).
// One core: run with OMP_NUM_THREADS=1.
#include <cholmod.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

#include "ddaslope/model/wall_scene.hpp"
#include "ddaslope/solver/panel_factor.hpp"

using namespace ddaslope;

namespace {

/// Free bricks whose bounding boxes touch (within 1 mm), each pair once (i < j).
std::vector<std::vector<int>> touchingBricks(const model::Scene& scene) {
  std::vector<std::array<double, 4>> boxes;  // x0, x1, y0, y1
  for (const model::Block& b : scene.blocks) {
    if (b.fixed) continue;
    std::array<double, 4> box{1e300, -1e300, 1e300, -1e300};
    for (const Vec2& v : b.vertices)
      box = {std::min(box[0], v.x()), std::max(box[1], v.x()), std::min(box[2], v.y()), std::max(box[3], v.y())};
    boxes.push_back(box);
  }
  const int n = static_cast<int>(boxes.size());
  std::vector<int> byLeft(n);
  for (int i = 0; i < n; ++i) byLeft[i] = i;
  std::sort(byLeft.begin(), byLeft.end(), [&](int a, int b) { return boxes[a][0] < boxes[b][0]; });
  constexpr double kTouch = 1e-3;
  std::vector<std::vector<int>> above(n);  // above[j]: the i < j coupled to j
  for (int a = 0; a < n; ++a)
    for (int b = a + 1; b < n; ++b) {
      const int i = byLeft[a], j = byLeft[b];
      if (boxes[j][0] > boxes[i][1] + kTouch) break;
      if (boxes[j][2] <= boxes[i][3] + kTouch && boxes[i][2] <= boxes[j][3] + kTouch)
        above[std::max(i, j)].push_back(std::min(i, j));
    }
  for (auto& v : above) std::sort(v.begin(), v.end());
  return above;
}

struct Pattern {
  int n = 0;
  std::vector<int> colStart{0}, rows;
  std::vector<double> values;
};

/// The upper triangle, column by column, of a K with dense 6 × 6 blocks on that graph: off-diagonal
/// entries 0.1, diagonal 100 (positive definite by dominance).
Pattern stiffnessPattern(const std::vector<std::vector<int>>& above) {
  constexpr int kDof = 6;
  Pattern p;
  p.n = kDof * static_cast<int>(above.size());
  for (size_t bj = 0; bj < above.size(); ++bj)
    for (int cj = 0; cj < kDof; ++cj) {
      for (const int bi : above[bj])
        for (int ci = 0; ci < kDof; ++ci) p.rows.push_back(kDof * bi + ci), p.values.push_back(0.1);
      for (int ci = 0; ci <= cj; ++ci)
        p.rows.push_back(kDof * static_cast<int>(bj) + ci), p.values.push_back(ci == cj ? 100.0 : 0.1);
      p.colStart.push_back(static_cast<int>(p.rows.size()));
    }
  return p;
}

cholmod_sparse viewOf(Pattern& k) {
  cholmod_sparse a{};
  a.nrow = a.ncol = static_cast<size_t>(k.n);
  a.nzmax = k.rows.size();
  a.p = k.colStart.data();
  a.i = k.rows.data();
  a.x = k.values.data();
  a.stype = 1;
  a.itype = CHOLMOD_INT;
  a.xtype = CHOLMOD_REAL;
  a.dtype = CHOLMOD_DOUBLE;
  a.sorted = a.packed = 1;
  return a;
}

/// Entries of L under each ordering (symbolic analysis only).
void surveyOrderings(int bricks, Pattern& k) {
  struct Choice {
    const char* name;
    int ordering, small, camd, compress;
  };
  const Choice choices[] = {{"nesdis (ddaslope)", CHOLMOD_NESDIS, 200, 1, 1},
                            {"nesdis nd_small 64", CHOLMOD_NESDIS, 64, 1, 1},
                            {"nesdis nd_small 600", CHOLMOD_NESDIS, 600, 1, 1},
                            {"nesdis nd_camd 0", CHOLMOD_NESDIS, 200, 0, 1},
                            {"nesdis nd_camd 2", CHOLMOD_NESDIS, 200, 2, 1},
                            {"nesdis nd_compress 0", CHOLMOD_NESDIS, 200, 1, 0},
                            {"metis", CHOLMOD_METIS, 200, 1, 1},
                            {"amd", CHOLMOD_AMD, 200, 1, 1}};
  cholmod_common common;
  cholmod_start(&common);
  common.print = 0;
  cholmod_sparse a = viewOf(k);
  for (const Choice& c : choices) {
    common.nmethods = 1;
    common.method[0].ordering = c.ordering;
    common.method[0].nd_small = static_cast<size_t>(c.small);
    common.method[0].nd_camd = c.camd;
    common.method[0].nd_compress = c.compress;
    cholmod_factor* f = cholmod_analyze(&a, &common);
    if (f) std::printf("%d,%s,%.0f\n", bricks, c.name, common.lnz);
    cholmod_free_factor(&f, &common);
  }
  cholmod_finish(&common);
}

std::vector<int> parseList(const char* s) {
  std::vector<int> out;
  std::stringstream ss(s);
  for (std::string item; std::getline(ss, item, ',');) out.push_back(std::atoi(item.c_str()));
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<int> anchorRows{45, 71, 141};
  int reps = 40;
  bool orderings = false;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--anchor-rows") && i + 1 < argc)
      anchorRows = parseList(argv[++i]);
    else if (!std::strcmp(argv[i], "--reps") && i + 1 < argc)
      reps = std::max(1, std::atoi(argv[++i]));
    else if (!std::strcmp(argv[i], "--orderings"))
      orderings = true;
    else {
      std::fprintf(stderr, "usage: ddaslope_substitution_bench [--anchor-rows 45,71,141] [--reps 40] [--orderings]\n");
      return 2;
    }
  }
  std::printf(orderings ? "bricks,ordering,factor_entries\n"
                        : "bricks,factor_entries,panel_mb,kernel,prefetch,best_ms,median_ms,checksum\n");
  for (const int rows : anchorRows) {
    const model::Scene scene = model::makeAnchorWall(rows, false);
    const auto above = touchingBricks(scene);
    Pattern k = stiffnessPattern(above);
    if (orderings) {
      surveyOrderings(static_cast<int>(above.size()), k);
      continue;
    }
    cholmod_common common;
    cholmod_start(&common);
    common.print = 0;
    common.supernodal = CHOLMOD_SUPERNODAL;
    common.nmethods = 1;
    common.method[0].ordering = CHOLMOD_NESDIS;  // as a large system orders its factor
    cholmod_sparse a = viewOf(k);
    cholmod_factor* f = cholmod_analyze(&a, &common);
    if (!f || !cholmod_factorize(&a, f, &common) || common.status != CHOLMOD_OK) {
      std::fprintf(stderr, "%d rows: CHOLMOD could not factorise the wall's K\n", rows);
      return 1;
    }
    // The simplicial LDLᵀ form the panels are built from (solver/sparse_cholesky.cpp).
    if (!cholmod_change_factor(CHOLMOD_REAL, false, false, true, true, f, &common)) {
      std::fprintf(stderr, "%d rows: CHOLMOD could not make the factor simplicial\n", rows);
      return 1;
    }
    solver::SimplicialFactorView view;
    view.n = k.n;
    view.perm = static_cast<const int*>(f->Perm);
    view.colStart = static_cast<const int*>(f->p);
    view.colCount = static_cast<const int*>(f->nz);
    view.rows = static_cast<const int*>(f->i);
    view.values = static_cast<const double*>(f->x);
    const double entries = common.lnz;
    Eigen::VectorXd b(k.n), x;
    for (int i = 0; i < k.n; ++i) b[i] = 1.0 + 1e-3 * (i % 17);
    // What a large system pays for a factor before its panels exist: CHOLMOD's substitution with
    // the double-precision simplicial factor (SparseCholesky before kSolvesBeforeRoundedPanels solves),
    // and the regrouping into rounded panels. A handful of each: the times hardly vary.
    solver::PanelFactor panels;
    {
      constexpr int kFew = 5;
      std::vector<double> solveMs, buildMs;
      double checksum = 0;
      cholmod_dense rhs{};
      rhs.nrow = rhs.nzmax = rhs.d = static_cast<size_t>(k.n);
      rhs.ncol = 1;
      rhs.x = b.data();
      rhs.xtype = CHOLMOD_REAL;
      rhs.dtype = CHOLMOD_DOUBLE;
      for (int r = 0; r < kFew; ++r) {
        const auto t0 = std::chrono::steady_clock::now();
        cholmod_dense* sol = cholmod_solve(CHOLMOD_A, f, &rhs, &common);
        solveMs.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
        if (!sol) {
          std::fprintf(stderr, "%d rows: CHOLMOD could not solve with its factor\n", rows);
          return 1;
        }
        checksum = Eigen::Map<const Eigen::VectorXd>(static_cast<const double*>(sol->x), k.n).sum();
        cholmod_free_dense(&sol, &common);
      }
      for (int r = 0; r < kFew; ++r) {
        const auto t0 = std::chrono::steady_clock::now();
        const bool built = panels.build(view, solver::PanelFactor::Precision::Single);
        buildMs.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
        if (!built) {
          std::fprintf(stderr, "%d rows: the factor did not make panels\n", rows);
          return 1;
        }
      }
      std::sort(solveMs.begin(), solveMs.end());
      std::sort(buildMs.begin(), buildMs.end());
      std::printf("%zu,%.0f,%.1f,cholmod-double,-,%.3f,%.3f,%.17g\n", above.size(), entries,
                  12 * entries / 1e6, solveMs.front(), solveMs[kFew / 2], checksum);
      std::printf("%zu,%.0f,%.1f,panel-build,-,%.3f,%.3f,\n", above.size(), entries, panels.bytes() / 1e6,
                  buildMs.front(), buildMs[kFew / 2]);
    }
    cholmod_free_factor(&f, &common);
    cholmod_finish(&common);
    // The floor: one plain read of as many single-precision entries, forward and back (kernel
    // "memory-read"); a substitution reads them twice.
    {
      std::vector<float> plain(static_cast<size_t>(entries), 1.0f);
      for (const bool forward : {true, false}) {
        std::vector<double> times;
        double sum = 0;
        // 32 independent sums (four vector registers' worth): the additions' latency, which one
        // register of 8 sums would wait on, stays below the memory's.
        constexpr size_t kSums = 32;
        for (int r = 0; r < reps; ++r) {
          const auto t0 = std::chrono::steady_clock::now();
          float s[kSums] = {};
          const size_t m = plain.size() / kSums * kSums;
          if (forward)
            for (size_t i = 0; i < m; i += kSums)
              for (size_t l = 0; l < kSums; ++l) s[l] += plain[i + l];
          else
            for (size_t i = m; i > 0; i -= kSums)
              for (size_t l = 0; l < kSums; ++l) s[l] += plain[i - kSums + l];
          times.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
          sum = 0;
          for (const float v : s) sum += v;
        }
        std::sort(times.begin(), times.end());
        std::printf("%zu,%.0f,%.1f,memory-read,%s,%.3f,%.3f,%.17g\n", above.size(), entries, 4 * entries / 1e6,
                    forward ? "forward" : "back", times.front(), times[times.size() / 2], sum);
      }
    }

    using solver::PanelFactor;
    double firstChecksum = NAN;
    for (const auto kernel : {PanelFactor::Kernel::Best, PanelFactor::Kernel::Portable})
      for (const auto prefetch : {PanelFactor::Prefetch::Always, PanelFactor::Prefetch::Never}) {
        panels.setKernel(kernel);
        panels.setPrefetch(prefetch);
        std::vector<double> times;
        for (int r = 0; r < reps; ++r) {
          const auto t0 = std::chrono::steady_clock::now();
          panels.solve(b, x);
          times.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
        }
        std::sort(times.begin(), times.end());
        const char* kernelName =
            kernel == PanelFactor::Kernel::Portable ? "portable" : (PanelFactor::avxAvailable() ? "avx" : "portable");
        std::printf("%zu,%.0f,%.1f,%s,%s,%.3f,%.3f,%.17g\n", above.size(), entries, panels.bytes() / 1e6, kernelName,
                    prefetch == PanelFactor::Prefetch::Always ? "on" : "off", times.front(), times[times.size() / 2],
                    x.sum());
        // Kernel and prefetch are promised not to change a bit of the solution.
        if (std::isnan(firstChecksum)) firstChecksum = x.sum();
        if (x.sum() != firstChecksum) {
          std::fprintf(stderr, "%d rows: the solution depends on the kernel or the prefetch\n", rows);
          return 1;
        }
      }
  }
  return 0;
}

#include "check_command.hpp"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "ddaslope/calibration/contact_comparison.hpp"
#include "ddaslope/calibration/probability.hpp"
#include "ddaslope/core/errors.hpp"
#include "ddaslope/io/case_reader.hpp"
#include "ddaslope/io/probability_reader.hpp"
#include "ddaslope/io/scene_picture.hpp"
#include "ddaslope/solver/simulation.hpp"
#include "scene_notes.hpp"

namespace ddaslope::cli {

int compareContactsCommand(bool deformable, const std::string& csvPath) {
  ddaslope::calibration::ComparisonSettings s;
  s.stiffBlocks = !deformable;
  const auto start = std::chrono::steady_clock::now();
  const auto rows = ddaslope::calibration::compareContactTreatments(s);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("| α (°) | h/b | φ (°) | closed form c_cr (kPa) | edge (kPa) | edge error | vertex (kPa) | vertex error |\n");
  std::printf("|---|---|---|---|---|---|---|---|\n");
  const auto err = [](double v, double ref) -> std::string {
    if (ref == 0) return v == 0 ? "0 (holds at c = 0)" : "c_cr = 0, found " + std::to_string(v / 1e3) + " kPa";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%+.2f %%", 100 * (v - ref) / ref);
    return buf;
  };
  int runs = 0;
  for (const auto& r : rows) {
    runs += r.runs;
    std::printf("| %.0f | %.2f | %.0f | %.2f | %.2f | %s | %.2f | %s |\n", r.alphaDeg, r.heightRatio, r.phiDeg,
                r.closedForm / 1e3, r.edge / 1e3, err(r.edge, r.closedForm).c_str(), r.vertex / 1e3,
                err(r.vertex, r.closedForm).c_str());
  }
  std::printf("\n%zu rows, %d forward runs, %.1f s wall (%s blocks, b = 10 m, ρ = 2000 kg/m³, g = 10 m/s², σt = c)\n",
              rows.size(), runs, wall, deformable ? "deformable (E = 5 GPa, p = 40 E)" : "stiff (E = 500 GPa, p = 200 GN/m)");
  if (!csvPath.empty()) {
    std::FILE* f = std::fopen(csvPath.c_str(), "w");
    if (!f) throw ddaslope::InputError(csvPath, "", "cannot write the file");
    std::fprintf(f, "alpha_deg,h_over_b,phi_deg,closed_form_pa,edge_pa,vertex_pa\n");
    for (const auto& r : rows)
      std::fprintf(f, "%g,%g,%g,%.6g,%.6g,%.6g\n", r.alphaDeg, r.heightRatio, r.phiDeg, r.closedForm, r.edge, r.vertex);
    std::fclose(f);
  }
  for (const auto& r : rows)
    if (!r.bracketed) return kExitNonConvergence;
  return kExitOk;
}

}  // namespace ddaslope::cli

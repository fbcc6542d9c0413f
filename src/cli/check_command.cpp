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

int checkCommand(const std::string& casePath, const Overrides& o) {
  ddaslope::model::Scene scene = loadCase(casePath, o);
  const ddaslope::solver::Simulation sim(scene);
  int closed = 0;
  for (const auto& c : sim.contacts().contacts()) closed += c.closed();
  std::printf("%s: valid. %zu blocks, %zu materials, %zu joints, %zu monitors; %zu contacts found at t = 0 "
              "(%d touching); w0 = %g m, penalty = %g N/m\n",
              casePath.c_str(), scene.blocks.size(), scene.materials.size(), scene.joints.size(),
              scene.monitors.size(), sim.contacts().contacts().size(), closed, sim.modelHalfSize(),
              scene.normalPenalty());
  const double g2w0 = scene.settings.maxDisplacementRatio * sim.modelHalfSize();
  std::printf("  step limit %g m per step (g2·w0 = %g m%s), contact search distance %g m\n", sim.stepLimit(), g2w0,
              sim.stepLimit() < g2w0 ? ", held to a tenth of the thinnest block" : "", sim.searchDistance());
  std::printf("  %s\n", settingsLine(scene).c_str());
  if (const std::string drawn = ddaslope::io::sectionDrawingSummary(casePath); !drawn.empty())
    std::printf("  %s\n", drawn.c_str());
  if (!scene.origin.isZero())
    std::printf("  coordinates: far from (0, 0) for the scene's size; computed relative to (%.17g, %.17g), written back "
                "in the case's coordinates\n",
                scene.origin.x(), scene.origin.y());
  printOutlineNotes(scene);
  printSeismicNote(scene);
  printKinkNotes(scene);
  if (ddaslope::io::hasProbabilitySection(casePath)) {
    const ddaslope::io::ProbabilityJob job = ddaslope::io::readProbabilityJob(casePath);
    std::printf("  probability section: %zu uncertain inputs, %d samples (%s, measure %s): valid; run it with "
                "ddaslope probability\n",
                job.spec.inputs.size(), job.spec.samples, ddaslope::calibration::name(job.spec.sampling),
                ddaslope::calibration::name(job.spec.measure));
  }
  return kExitOk;
}

int cutCommand(const std::string& casePath, const std::string& outDir) {
  const ddaslope::model::Scene scene = ddaslope::io::readCase(casePath);
  const std::string text = ddaslope::io::expandSection(casePath);
  std::filesystem::create_directories(outDir);
  const std::string blocks = outDir + "/blocks.json", picture = outDir + "/section.png";
  {
    std::ofstream out(blocks + ".tmp");
    out << text;
  }
  std::filesystem::rename(blocks + ".tmp", blocks);
  const ddaslope::solver::Simulation sim(scene);
  ddaslope::io::writeScenePicture(sim, ddaslope::io::frameScene(scene), picture, casePath + " (cut)");
  int slide = 0;
  for (const auto& b : scene.blocks) slide += !b.fixed;
  std::printf("%s: %zu blocks (%d free, %zu fixed), %zu contacts at t = 0\n  wrote %s and %s\n", casePath.c_str(),
              scene.blocks.size(), slide, scene.blocks.size() - slide, sim.contacts().contacts().size(), blocks.c_str(),
              picture.c_str());
  if (const std::string drawn = ddaslope::io::sectionDrawingSummary(casePath); !drawn.empty())
    std::printf("  %s\n", drawn.c_str());
  printKinkNotes(scene);
  return kExitOk;
}

}  // namespace ddaslope::cli

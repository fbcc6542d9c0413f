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

#include "convert_command.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>

#include "cli_common.hpp"
#include "ddaslope/core/errors.hpp"
#include "ddaslope/io/case_reader.hpp"
#include "ddaslope/io/ntdda_model.hpp"

namespace ddaslope::cli {
namespace {

/// Written whole or not at all: a temporary beside the target, then renamed.
void writeFile(const std::string& path, const std::string& text) {
  const std::filesystem::path p(path);
  if (p.has_parent_path()) std::filesystem::create_directories(p.parent_path());
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary);
    out << text;
    if (!out) throw InputError(path, "", "cannot write the file");
  }
  std::filesystem::rename(tmp, path);
}

void printNotes(const std::vector<std::string>& notes) {
  for (const std::string& n : notes) std::cerr << "ddaslope: note: " << n << "\n";
}

bool isCase(const std::string& path) {
  const std::string ext = std::filesystem::path(path).extension().string();
  return ext == ".json" || ext == ".JSON";
}

}  // namespace

void addConvertOptions(CLI::App* cmd, ConvertOptions& o) {
  cmd->add_option("input", o.input, "ntdda geometry (MODEL.geo, DDAML or Shi's text form) or a case (CASE.json)")->required();
  cmd->add_option("-o,--out", o.output, "the case to write (from a .geo), or the ntdda geometry (from a .json)")->required();
  cmd->add_option("--analysis", o.analysis, "ntdda analysis file (MODEL.ana) read with the geometry");
  cmd->add_option("--analysis-out", o.analysisOut, "ntdda analysis file written with the geometry (default: the -o name with .ana)");
}

int convertCommand(const ConvertOptions& o) {
  if (isCase(o.input)) {
    if (!o.analysis.empty()) throw InputError(o.input, "", "--analysis reads an ntdda analysis with a .geo; a case is converted with -o and --analysis-out");
    const model::Scene scene = io::readCase(o.input);
    const io::NtddaFiles files = io::writeNtddaModel(scene, std::filesystem::path(o.input).filename().string());
    const std::string anaPath =
        o.analysisOut.empty() ? std::filesystem::path(o.output).replace_extension(".ana").string() : o.analysisOut;
    if (anaPath == o.output) throw InputError(o.output, "", "the geometry and the analysis would be the same file; name the analysis with --analysis-out");
    writeFile(o.output, files.geometry);
    writeFile(anaPath, files.analysis);
    printNotes(files.notes);
    int fixed = 0;
    for (const auto& b : scene.blocks) fixed += b.fixed;
    std::printf("%s: %zu blocks (%d fixed) as %d joint lines\n  wrote %s and %s\n", o.input.c_str(), scene.blocks.size(), fixed,
                files.jointLines, o.output.c_str(), anaPath.c_str());
    return kExitOk;
  }
  if (!o.analysisOut.empty()) throw InputError(o.input, "", "--analysis-out writes an ntdda analysis from a case (.json); from a .geo, -o writes the case");
  if (!isCase(o.output)) throw InputError(o.output, "", "expected the case to write to be named .json, found \"" + o.output + "\"");
  const io::NtddaGeometry geometry = io::readNtddaGeometry(o.input);
  std::optional<io::NtddaAnalysis> analysis;
  if (!o.analysis.empty()) analysis = io::readNtddaAnalysis(o.analysis);
  const io::ConvertedModel model = io::convertNtddaModel(geometry, analysis ? &*analysis : nullptr);
  writeFile(o.output, model.caseJson);
  printNotes(model.notes);
  std::printf("%s%s%s: %zu joint lines (%s form) cut into %d blocks (%d fixed)\n  wrote %s; check it with ddaslope check %s\n",
              o.input.c_str(), analysis ? " + " : "", analysis ? o.analysis.c_str() : "", geometry.joints.size(),
              geometry.xml ? "DDAML" : "text", model.blocks, model.fixedBlocks, o.output.c_str(), o.output.c_str());
  return kExitOk;
}

}  // namespace ddaslope::cli

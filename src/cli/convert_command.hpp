#pragma once
// `ddaslope convert`: models of Shi's DDA (ntdda's .geo and .ana files) to a case, and a case
// back to them (io/ntdda_model.hpp).
#include <string>

#include <CLI/CLI.hpp>

namespace ddaslope::cli {

struct ConvertOptions {
  std::string input;        ///< MODEL.geo (to a case) or CASE.json (to ntdda)
  std::string output;       ///< CASE.json or MODEL.geo
  std::string analysis;     ///< MODEL.ana read with a geometry
  std::string analysisOut;  ///< MODEL.ana written with a geometry (default: the output's name, .ana)
};

void addConvertOptions(CLI::App* cmd, ConvertOptions& o);
int convertCommand(const ConvertOptions& o);

}  // namespace ddaslope::cli

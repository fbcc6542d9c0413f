#pragma once
// Reads a probability study (docs/probability.md): a "probability" section in a case
// file, or a probability job, a small file naming the case:
//   {"case": "../../cases/planar_failure.json", "preset": "fast", "probability": {...}}
// Plain data; calibration/ samples and runs it.
#include <string>

#include "ddaslope/model/settings_override.hpp"
#include "ddaslope/model/uncertainty.hpp"

namespace ddaslope::io {

struct ProbabilityJob {
  std::string file;      ///< the file read: the case itself, or the job
  std::string casePath;  ///< the case whose numbers the samples vary (a job's relative to the job)
  /// The case file's content, read once: every sample parses the same text.
  std::string caseText;
  model::ProbabilitySpec spec;
  /// A job's own "preset", "blocks" and "brittle_joints" (none for a section in a case).
  model::SettingsOverride model;
  /// A digest (16 hex digits, FNV-1a 64) of the case's JSON without its probability section,
  /// canonical (key order and spacing do not count): a resumed study checks it ran this case.
  std::string caseDigest;
};

/// Reads and checks the study: every key, every distribution (sd > 0, a lognormal's mean > 0,
/// bounds in order), the correlations (|ρ| < 1, between two inputs, a positive-definite matrix),
/// and that the case has a number at every input's path and accepts the input's median there.
/// Throws InputError (file, JSON path, what was expected and found). A case without a section
/// and a job without one are errors too.
ProbabilityJob readProbabilityJob(const std::string& path);

/// True when the case file has a "probability" section (`check` then validates it).
bool hasProbabilitySection(const std::string& casePath);

}  // namespace ddaslope::io

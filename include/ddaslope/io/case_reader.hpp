#pragma once
// Reads a case file (JSON, docs/case-format.md) into a Scene. Only this layer sees JSON.
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "ddaslope/model/scene.hpp"
#include "ddaslope/model/settings_override.hpp"

namespace ddaslope::io {

/// Throws InputError (file, JSON path, expected vs found) on any bad input.
model::Scene readCase(const std::string& path);
/// The case with its `section` cut into explicit blocks (and the joint pairs along the sliding
/// surface): a plain case file, as `ddaslope cut` writes it.
std::string expandSection(const std::string& path);

/// The unit a case value at a JSON path ("joints.base.cohesion", "water.level") is written in,
/// from its key, for labels of pictures and tables: "Pa", "°", "m", ...; empty when the value is
/// dimensionless or the key is not a physical quantity of the case format.
std::string unitOfCaseValue(const std::string& path);

/// Same, from text already loaded (`file` names it in errors).
model::Scene parseCase(const std::string& text, const std::string& file);

/// Refuses a run that cannot finish in reasonable time (duration / Δt beyond 1e7 steps, or more
/// than 1e10 block-steps), naming `file` and the setting to change. parseCase calls it; call it
/// again after changing the settings (command-line overrides).
void checkWorkload(const model::Scene& scene, const std::string& file);

/// A value to put at a JSON path of the case before it is read ("materials.rock.young_modulus",
/// "point_loads[0].rate[0]", "analysis.settle_dynamically", "analysis.preset"): how a
/// back-analysis varies any case value, and what `--set` does. A number unless `flag` or `text`
/// is given.
struct CaseOverride {
  CaseOverride() = default;
  CaseOverride(std::string path, double number) : jsonPath(std::move(path)), value(number) {}
  static CaseOverride boolean(std::string path, bool b) {
    CaseOverride o(std::move(path), 0);
    o.flag = b;
    return o;
  }
  static CaseOverride name(std::string path, std::string n) {
    CaseOverride o(std::move(path), 0);
    o.text = std::move(n);
    return o;
  }
  static CaseOverride removal(std::string path) {
    CaseOverride o(std::move(path), 0);
    o.erase = true;
    return o;
  }
  /// A path may hold one `*` standing for every key of an object ("joints.*.weakening_distance").
  std::string jsonPath;
  double value = 0;
  std::optional<bool> flag;          ///< a boolean setting (true / false)
  std::optional<std::string> text;   ///< a named choice ("rigid", "balanced")
  bool erase = false;                ///< remove the key, so that its default applies
  /// Where the time step came from when this sets analysis.time_step or analysis.preset
  /// ("--time-step", "job preset fast"); empty: the case key's own name.
  std::string origin;
};

/// The model choices of a command line or a job (preset, time step, blocks, contact treatment,
/// brittle joints) as overrides of the case, in that order: a preset wins over the case's own
/// time step, g2 and penalty (their keys are removed), an explicit time step over a preset.
std::vector<CaseOverride> caseOverridesFor(const model::SettingsOverride& o);
/// parseCase with overrides applied, in order, to its JSON before it is read (readCase's rules).
model::Scene parseCase(const std::string& text, const std::string& file, const std::vector<CaseOverride>& overrides);

/// A case's JSON parsed once and read many times with different overrides (a probability study's
/// samples): read(o) gives what parseCase(text, file, o) gives, without parsing the text again.
class ParsedCase {
 public:
  ParsedCase(const std::string& text, std::string file);
  model::Scene read(const std::vector<CaseOverride>& overrides) const;

 private:
  struct Document;
  std::shared_ptr<const Document> document_;
  std::string file_;
};
/// Reads the case with overrides applied, in order, to its JSON before it is read, so that every
/// value is checked, and the workload judged, once; a path that does not lead to a value of the
/// override's kind (or to a key the case may add) is an InputError.
model::Scene readCase(const std::string& path, const std::vector<CaseOverride>& overrides);

/// For a case whose section is drawn (section.dxf): one line saying what the drawing gave (units,
/// scale, points and entities per layer); empty for any other case.
std::string sectionDrawingSummary(const std::string& path);

}  // namespace ddaslope::io

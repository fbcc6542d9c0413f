#include "cli_common.hpp"

#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <tuple>
#include <iomanip>
#include <memory>
#include <sstream>

#include "ddaslope/calibration/verdict.hpp"
#include "ddaslope/core/errors.hpp"
#include "ddaslope/core/task_farm.hpp"
#include "ddaslope/io/scene_picture.hpp"
#include "ddaslope/io/scene_vtk.hpp"
#include "ddaslope/io/ground_motion.hpp"
#include "ddaslope/io/input_file.hpp"
#include "ddaslope/model/input_limits.hpp"

namespace ddaslope::cli {
namespace {

/// "softening", "brittle" (original DDA's bonds: a first-failure answer) or "mixed".
const char* jointKind(const ddaslope::model::Scene& scene) {
  int brittle = 0;
  for (const auto& j : scene.joints) brittle += j.weakeningDistance && *j.weakeningDistance == 0;
  return brittle == 0 ? "softening" : (brittle == static_cast<int>(scene.joints.size()) ? "brittle (first-failure)" : "mixed brittle/softening");
}

}  // namespace

/// A command-line number checked like a case number: finite (no nan, inf or overflow) and in
/// [lo, hi].
CLI::Validator finiteIn(double lo, double hi, const std::string& what) {
  return CLI::Validator(
      [=](std::string& text) -> std::string {
        char* end = nullptr;
        errno = 0;
        const double x = std::strtod(text.c_str(), &end);
        const bool ok = end != text.c_str() && *end == 0 && errno != ERANGE && std::isfinite(x) && x >= lo && x <= hi;
        return ok ? "" : "expected " + what + ", found " + text;
      },
      what);
}

std::optional<ValueRange> parseValueRange(const std::string& text, int maxCount) {
  const size_t a = text.find(':'), b = a == std::string::npos ? a : text.find(':', a + 1);
  if (b == std::string::npos || text.find(':', b + 1) != std::string::npos) return std::nullopt;
  // strtod alone would take "nan" and "inf" (a range that never ends), or "1e999" as inf.
  const auto number = [](const std::string& field, double& x) {
    char* end = nullptr;
    errno = 0;
    x = std::strtod(field.c_str(), &end);
    return !field.empty() && end == field.c_str() + field.size() && errno != ERANGE && std::isfinite(x);
  };
  ValueRange r;
  const std::string count = text.substr(b + 1);
  const auto [end, ec] = std::from_chars(count.data(), count.data() + count.size(), r.n);
  if (!number(text.substr(0, a), r.lo) || !number(text.substr(a + 1, b - a - 1), r.hi) || ec != std::errc() ||
      end != count.data() + count.size() || r.n < 2 || r.n > maxCount)
    return std::nullopt;
  return r;
}

/// The options every command that runs forward models shares.
void addModelOptions(CLI::App* cmd, Overrides& o) {
  cmd->add_option("--preset", o.model.preset, "fast, balanced or accurate: Δt, g2 and penalty (docs/accuracy.md)")
      ->check(CLI::IsMember({"fast", "balanced", "accurate"}));
  cmd->add_option("--time-step", o.model.timeStep, "override analysis.time_step (s)")
      ->check(finiteIn(ddaslope::model::limits::kMinTimeStep, ddaslope::model::limits::kMaxTimeStep,
                       "a time step in [1e-7, 10] s"));
  cmd->add_option("--blocks", o.model.blocks, "rigid (3 unknowns) or deformable (6)")
      ->check(CLI::IsMember({"rigid", "deformable"}));
  cmd->add_option("--contact-treatment", o.model.contactTreatment,
                  "edge (one state per edge-to-edge contact) or vertex (original DDA)")
      ->check(CLI::IsMember({"edge", "vertex"}));
  cmd->add_flag("--brittle-joints", o.model.brittleJoints,
                "every joint's bond lost the moment it slides (original DDA): the first-failure answer");
  cmd->add_option("--set", o.settings, "json.path=value: override a value of the case: a number, true, false or a string (repeatable)");
  // Pseudo-static seismic coefficients: shorthands for --set seismic.k_h=… (docs/seismic.md).
  const auto coefficient = [&o](const char* key) {
    return [&o, key](double k) {
      std::ostringstream v;
      v << std::setprecision(17) << k;
      o.settings.push_back(std::string("seismic.") + key + "=" + v.str());
    };
  };
  cmd->add_option_function<double>("--kh", coefficient("k_h"),
                                   "horizontal seismic coefficient: a force k_h·m·g along +x (negative: -x), part of the loads from the initial equilibrium on")
      ->check(finiteIn(-2, 2, "a coefficient in [-2, 2]"));
  cmd->add_option_function<double>("--kv", coefficient("k_v"), "vertical seismic coefficient: a force k_v·m·g upward, part of the loads from the initial equilibrium on")
      ->check(finiteIn(-2, 2, "a coefficient in [-2, 2]"));
}

/// "path=value" → an override, the value a JSON literal as the case file would hold it: a number
/// (parsed by std::stod, as always), true or false, or a string, quoted ("two words") or bare (a
/// word that is neither a number nor a boolean). The case reader then checks it as it checks the
/// file. A malformed one is bad input naming --set.
ddaslope::io::CaseOverride parseSetting(const std::string& text) {
  const size_t eq = text.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == text.size())
    throw ddaslope::InputError("--set", text,
                               "expected json.path=value, e.g. joints.clay.friction_angle=20, "
                               "analysis.settle_dynamically=false or analysis.blocks=rigid");
  ddaslope::io::CaseOverride o(text.substr(0, eq), 0);
  const std::string value = text.substr(eq + 1);
  if (value == "true" || value == "false") {
    o.flag = value == "true";
    return o;
  }
  if (value == "null")
    throw ddaslope::InputError("--set", text, "expected a number, true, false or a string, found null: a key "
                                              "cannot be unset from the command line (edit the case)");
  if (value.front() == '"') {
    // A JSON string: \" and \\ are the escapes a shell user needs; others are kept as written.
    std::string s;
    size_t k = 1;
    for (; k < value.size() && value[k] != '"'; ++k) {
      if (value[k] == '\\' && k + 1 < value.size() && (value[k + 1] == '"' || value[k + 1] == '\\')) ++k;
      s += value[k];
    }
    if (k + 1 != value.size())
      throw ddaslope::InputError("--set", text, "expected a string closed by its \" at the end, found " + value);
    o.text = s;
    return o;
  }
  try {
    size_t used = 0;
    o.value = std::stod(value, &used);
    if (used == value.size()) {
      if (!std::isfinite(o.value))
        throw ddaslope::InputError("--set", text, "expected a finite number, found " + value);
      return o;
    }
  } catch (const std::invalid_argument&) {
  } catch (const std::out_of_range&) {
    throw ddaslope::InputError("--set", text, "expected a finite number, found " + value);
  }
  // Not a number: a bare string (a choice such as analysis.blocks=rigid), unless it starts like a
  // number (20x, 1..2: a mistyped number, not a name); quoted, any text is a string.
  if (value.find_first_of("0123456789+-.") == 0)
    throw ddaslope::InputError("--set", text,
                               "expected a number, true, false or a string (quote a string that starts like a "
                               "number: =\"" + value + "\"), found " + value);
  o.text = value;
  return o;
}

/// Reads the case with every override of the command line in one pass: --set, any extra ones (a
/// sweep's value, a study's sample and its job's model choices), the model options, --duration.
ddaslope::model::Scene loadCase(const std::string& casePath, const Overrides& o,
                                std::vector<ddaslope::io::CaseOverride> extra) {
  return loadCaseText(ddaslope::io::readInputFile(casePath, ddaslope::io::kMaxJsonFileBytes), casePath, o,
                      std::move(extra));
}

namespace {

/// The command line's overrides and `extra`, in the order they apply: --set, extra, model options.
std::vector<ddaslope::io::CaseOverride> allOverrides(const Overrides& o, std::vector<ddaslope::io::CaseOverride> extra) {
  std::vector<ddaslope::io::CaseOverride> all;
  for (const auto& s : o.settings) all.push_back(parseSetting(s));
  all.insert(all.end(), extra.begin(), extra.end());
  for (auto& m : ddaslope::io::caseOverridesFor(o.model)) all.push_back(std::move(m));
  return all;
}

/// `run --duration` shortens a run after the case is read: the case's expected values at later
/// times stay valid (reported as not reached), and the shorter run's workload needs no new check.
void applyDuration(ddaslope::model::Scene& scene, const std::string& casePath, const Overrides& o) {
  if (o.duration > 0 && o.duration < scene.settings.duration) scene.settings.duration = o.duration;
  else if (o.duration > 0) {
    scene.settings.duration = o.duration;
    ddaslope::io::checkWorkload(scene, casePath);
  }
}

}  // namespace

ddaslope::model::Scene loadParsedCase(const ddaslope::io::ParsedCase& parsed, const std::string& casePath,
                                      const Overrides& o, std::vector<ddaslope::io::CaseOverride> extra) {
  ddaslope::model::Scene scene = parsed.read(allOverrides(o, std::move(extra)));
  applyDuration(scene, casePath, o);
  return scene;
}

ddaslope::model::Scene loadCaseText(const std::string& text, const std::string& casePath, const Overrides& o,
                                    std::vector<ddaslope::io::CaseOverride> extra) {
  ddaslope::model::Scene scene = ddaslope::io::parseCase(text, casePath, allOverrides(o, std::move(extra)));
  applyDuration(scene, casePath, o);
  return scene;
}

calibration::TrialStart trialStartOf(const std::string& word) {
  return word == "held" ? calibration::TrialStart::Held : calibration::TrialStart::Settled;
}

CLI::Option* addTrialStartOption(CLI::App* cmd, std::string& word) {
  return cmd
      ->add_option("--trial-start", word,
                   "where each trial's equilibrium starts: settled (from the rest at the case's own strengths, F = 1, "
                   "when it stands; as FLAC's and UDEC's strength reduction) or held (every contact held, each trial "
                   "settling with its own strengths); docs/calibration.md")
      ->capture_default_str()
      ->check(CLI::IsMember({"settled", "held"}));
}

std::string trialStartNote(const std::string& subject, calibration::TrialStart used, const std::string& asked) {
  if (used == calibration::TrialStart::Settled)
    return subject + " started from the rest at the case's own strengths (F = 1), the joints then weakened "
                     "(--trial-start settled)";
  if (asked == "held") return subject + " settled from every contact held with the reduced strengths (--trial-start held)";
  return subject + " settled from every contact held with the reduced strengths: the case fails at its own strengths, "
                   "so there is no rest at F = 1 to start from";
}

/// The settings every forward run of a command uses, and where Δt came from.
std::string settingsLine(const ddaslope::model::Scene& scene, bool trials) {
  const ddaslope::model::AnalysisSettings& s = scene.settings;
  char buf[320];
  std::snprintf(buf, sizeof buf, "Δt %g s (%s), g2 %g, penalty %g N/m, %s blocks, %s contacts, %s joints", s.timeStep,
                s.timeStepOrigin.c_str(), s.maxDisplacementRatio, scene.normalPenalty(),
                s.rigidBlocks ? "rigid" : "deformable",
                s.contactTreatment == ddaslope::model::ContactTreatment::Edge ? "edge" : "vertex",
                jointKind(scene));
  std::string line = buf;
  // The solver path is a numerical choice the model's size makes unless the case names it.
  const int unknowns = scene.freeUnknowns();
  const bool large = ddaslope::model::largeSystemPath(s, unknowns);
  std::snprintf(buf, sizeof buf, ", %s-system path (%s%d unknowns)", large ? "large" : "small",
                s.systemPath == ddaslope::model::SystemPath::Auto ? "auto: " : "analysis.system_path; ", unknowns);
  line += buf;
  if (!s.factorUpdates) line += ", factor refactorised at every state change (analysis.factor_updates)";
  // Quiet steps that grow (docs/accuracy.md): automatic only in a stability trial.
  // A record or a water-level history is followed at Δt: steps grow only once it has ended
  // (within the run: a trial run on past its duration may grow later), never under a load rate.
  const double settledFrom = scene.lastLoadChange();
  if (const double g = trials ? ddaslope::calibration::trialStepGrowth(s) : std::max(s.timeStepGrowth, 1.0);
      g > 1 && s.mode == ddaslope::model::AnalysisMode::Dynamic) {
    char after[64] = "";
    if (settledFrom > 0) std::snprintf(after, sizeof after, " after t = %g s, when the loads stop changing", settledFrom);
    if (settledFrom < s.duration) {
      std::snprintf(buf, sizeof buf, ", %s up to %g Δt%s (analysis.time_step_growth%s)",
                    s.timeStepGrowth > 0 ? "quiet steps" : "a trial's quiet steps", g, after,
                    s.timeStepGrowth > 0 ? "" : ": automatic");
      line += buf;
    } else if (s.timeStepGrowth > 1) {  // asked for, and not given: say why
      std::snprintf(buf, sizeof buf, ", steps kept at Δt: the loads change %s (analysis.time_step_growth %g unused)",
                    std::isfinite(settledFrom) ? "to the run's end" : "at a rate", g);
      line += buf;
    }
  }
  // The seismic loading a result was found under: F and critical strengths under a record or a
  // coefficient are not the static ones.
  const ddaslope::model::SeismicLoad& q = scene.seismic;
  if (q.kh != 0 || q.kv != 0) {
    std::snprintf(buf, sizeof buf, ", pseudo-static k_h %g (along %s), k_v %g", q.kh, q.kh < 0 ? "-x" : "+x", q.kv);
    line += buf;
  }
  if (q.ground.active()) {
    double peak = 0;
    for (double a : q.ground.horizontal) peak = std::max(peak, std::abs(a));
    for (double a : q.ground.vertical) peak = std::max(peak, std::abs(a));
    if (peak == 0)
      line += ", the ground-motion record scaled to 0 (no shaking: the static slope)";
    else {
      std::snprintf(buf, sizeof buf, ", under the ground-motion record (peak %.3g g; without it: --set "
                    "seismic.record.scale=0)", peak / ddaslope::io::kStandardGravity);
      line += buf;
    }
  }
  return line;
}

void recordTrialStates(calibration::SearchSettings& s, const std::string& dir, const model::Scene& scene) {
  if (dir.empty() || processRank() != 0) return;
  auto recorder = std::make_shared<io::VtkRecorder>(dir, scene);
  s.lookAhead = false;
  s.narrowInTurn = true;
  s.finalStates = [recorder](double value, const solver::Simulation& sim, const calibration::TrialResult& r) {
    char label[32];
    std::snprintf(label, sizeof label, "%.12g", value);
    recorder->write(sim, value, label,
                    {{"trial_value", 1, {}, std::vector<double>{value}},
                     {"stable", 1, {}, std::vector<std::int32_t>{r.stable ? 1 : 0}},
                     {"verdict", 1, {}, std::vector<std::string>{calibration::name(r.rule)}}});
  };
}

struct MechanismPictures::Kept {
  std::mutex mutex;
  io::PictureFrame frame;
  std::map<double, std::pair<io::SceneState, calibration::TrialResult>> states;
};

MechanismPictures::MechanismPictures(calibration::SearchSettings& s, const model::Scene& scene)
    : kept_(std::make_shared<Kept>()) {
  kept_->frame = io::frameScene(scene);
  auto before = std::move(s.finalStates);
  s.finalStates = [kept = kept_, before](double value, const solver::Simulation& sim, const calibration::TrialResult& r) {
    if (before) before(value, sim, r);
    io::SceneState state = io::captureState(sim);
    const std::lock_guard<std::mutex> lock(kept->mutex);
    kept->states[value] = {std::move(state), r};
  };
}

std::vector<std::string> MechanismPictures::write(const std::string& dir, const std::string& casePath,
                                                  const std::string& quantity, double stable, double failing) const {
  std::vector<std::string> written;
  std::filesystem::create_directories(dir);
  for (const auto& [value, file, verdict] : {std::tuple{stable, "mechanism_stable.png", "stable"},
                                            std::tuple{failing, "mechanism_failed.png", "fails"}}) {
    const auto found = kept_->states.find(value);
    if (found == kept_->states.end()) continue;
    const auto& [state, result] = found->second;
    // A bracket with no failing end (a slope stable without cohesion: both ends 0) draws no
    // failure: each picture only of a trial whose verdict it names.
    if (result.stable != (std::string(verdict) == "stable")) continue;
    // Rule (0) decides before t = 0: its motion is the settling's.
    const bool settling = result.rule == calibration::VerdictRule::MovedWhileSettling;
    char title[320];
    std::snprintf(title, sizeof title, "%s: %s = %.6g, %s (%s; a point moved %.3g m %s)", casePath.c_str(),
                  quantity.c_str(), value, verdict, calibration::name(result.rule),
                  settling ? result.settlingDisplacement : result.maxDisplacement,
                  settling ? "while the scene settled before t = 0" : "after t = 0");
    io::writeScenePicture(state, kept_->frame, dir + "/" + file, title, result.failureDisplacement);
    written.push_back(dir + "/" + file);
  }
  return written;
}

double MechanismPictures::horizontalMotion(double value, const model::Scene& initial) const {
  const auto found = kept_->states.find(value);
  if (found == kept_->states.end()) return 0;
  const model::Scene& moved = found->second.first.scene;
  if (moved.blocks.size() != initial.blocks.size()) return 0;
  double area = 0, dx = 0;
  for (size_t b = 0; b < initial.blocks.size(); ++b) {
    if (initial.blocks[b].fixed) continue;
    const double a = std::abs(initial.blocks[b].moments.area);
    area += a;
    dx += a * (moved.blocks[b].moments.centroid.x() - initial.blocks[b].moments.centroid.x());
  }
  return area > 0 ? dx / area : 0;
}

std::string csvField(double v, bool known) {
  if (!known || !std::isfinite(v)) return "";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

std::vector<double> bracketField(bool found, double first, double second) {
  return {found ? first : NAN, found ? second : NAN};
}

void writeResultFile(const std::string& path, const std::string& text) {
  const std::filesystem::path p(path);
  if (p.has_parent_path()) std::filesystem::create_directories(p.parent_path());
  const std::string temporary = path + "." + std::to_string(::getpid()) + ".tmp";
  {
    std::ofstream out(temporary, std::ios::binary);
    out << text;
    if (!out.flush()) throw InputError(path, "", "cannot write the file");
  }
  std::filesystem::rename(temporary, path);
}

int jointIndex(const ddaslope::model::Scene& scene, const std::string& name, const std::string& casePath) {
  for (size_t j = 0; j < scene.joints.size(); ++j)
    if (scene.joints[j].name == name) return static_cast<int>(j);
  std::string known;
  for (const auto& j : scene.joints) known += (known.empty() ? "" : ", ") + j.name;
  throw ddaslope::InputError(casePath, "joints", "no joint named \"" + name + "\" (the case has: " + known + ")");
}

void addProgressOptions(CLI::App* cmd, ProgressOptions& p) {
  cmd->add_flag("--quiet", p.quiet, "no progress line on stderr");
  cmd->add_option("--log-json", p.logJson, "write the progress events to FILE as JSON lines");
}

std::unique_ptr<ddaslope::io::ProgressLog> startProgress(const std::string& command, const ProgressOptions& p,
                                                         bool jsonResult) {
  const bool root = ddaslope::processRank() == 0;
  const bool terminal = root && !p.quiet && !jsonResult && isatty(STDERR_FILENO);
  // Off a terminal, long work still says how far it has got, once a minute.
  const bool minuteLines = root && !p.quiet && !isatty(STDERR_FILENO);
  return std::make_unique<ddaslope::io::ProgressLog>(command, terminal, root ? p.logJson : std::string(), minuteLines);
}

/// Where a search's --vtk went (text output).
void printTrialStatesNote(const std::string& dir, int runs) {
  if (!dir.empty())
    std::printf("  wrote %s: blocks.pvd, contacts.pvd: the final state of each of the %d trials, at the value it tried\n",
                dir.c_str(), runs);
}

/// Verdict warnings go to stderr, so a --json result on stdout stays clean.
void warnAboutTrials(const std::string& casePath, const std::string& warning) {
  if (!warning.empty())
    std::fprintf(stderr, "ddaslope: warning: %s: %s\n", casePath.c_str(), warning.c_str());
}

std::string shellWord(const std::string& text) {
  if (!text.empty() && text.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789_-./=:,+@%") ==
                           std::string::npos)
    return text;
  std::string quoted = "'";
  for (char c : text) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

}  // namespace ddaslope::cli

#include "ddaslope/calibration/minimiser.hpp"

#include <nlopt.hpp>

#include <exception>

#include "ddaslope/core/errors.hpp"

namespace ddaslope::calibration {
namespace {

struct Objective {
  const std::function<double(const std::vector<double>&)>* f;
  int evaluations = 0;
  std::vector<double> best;
  double bestValue = HUGE_VAL;
  /// What the objective threw: NLopt's wrapper would turn it into a bare failure status.
  std::exception_ptr error;
};

double trampoline(const std::vector<double>& x, std::vector<double>& /*grad*/, void* data) {
  auto* o = static_cast<Objective*>(data);
  ++o->evaluations;
  double v = 0;
  try {
    v = (*o->f)(x);
  } catch (...) {
    o->error = std::current_exception();
    throw nlopt::forced_stop();
  }
  if (v < o->bestValue) o->bestValue = v, o->best = x;
  return v;
}

}  // namespace

MinimiserResult minimise(const std::string& algorithm, const std::function<double(const std::vector<double>&)>& f,
                         const std::vector<double>& x0, int maxEvaluations, double xtolRel) {
  const nlopt_algorithm a = nlopt_algorithm_from_string(algorithm.c_str());
  if (static_cast<int>(a) < 0) throw InputError("optimiser", algorithm, "unknown NLopt algorithm name");
  const unsigned n = static_cast<unsigned>(x0.size());
  nlopt::opt opt(static_cast<nlopt::algorithm>(a), n);
  opt.set_lower_bounds(std::vector<double>(n, 0.0));
  opt.set_upper_bounds(std::vector<double>(n, 1.0));
  Objective o;
  o.f = &f;
  opt.set_min_objective(trampoline, &o);
  opt.set_maxeval(std::max(1, maxEvaluations));
  opt.set_xtol_rel(xtolRel);
  std::vector<double> x = x0;
  double value = 0;
  MinimiserResult r;
  try {
    r.status = nlopt_result_to_string(static_cast<nlopt_result>(opt.optimize(x, value)));
  } catch (const nlopt::roundoff_limited&) {
    r.status = "ROUNDOFF_LIMITED";
  } catch (const nlopt::forced_stop&) {
    r.status = "FORCED_STOP";
  } catch (const std::runtime_error& e) {
    r.status = std::string("FAILURE: ") + e.what();
  }
  // An error of the objective (a case that cannot run, say) is the caller's, not a status.
  if (o.error) std::rethrow_exception(o.error);
  r.x = o.best.empty() ? x0 : o.best;
  r.value = o.bestValue;
  r.evaluations = o.evaluations;
  return r;
}

}  // namespace ddaslope::calibration

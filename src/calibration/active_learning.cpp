#include "ddaslope/calibration/active_learning.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>

#include <nlopt.hpp>

#include "ddaslope/calibration/kriging.hpp"
#include "ddaslope/core/errors.hpp"
#include "ddaslope/core/task_farm.hpp"

namespace ddaslope::calibration {
namespace {

/// Population points predicted per block: bounds the n × block correlation matrices.
constexpr Eigen::Index kPredictBlock = 4096;

/// The state of a population point.
enum class Known : char { No, Fails, Stable, NotConverged };

class Learner {
 public:
  Learner(const ActiveLearningProblem& p, const ActiveLearningSettings& s)
      : p_(p), s_(s), n_(static_cast<int>(p.population.cols())), known_(static_cast<size_t>(n_), Known::No),
        mean_(n_), sd_(n_) {}

  ActiveLearningResult run() {
    r_.population = n_;
    const int d = static_cast<int>(p_.population.rows());
    const int initial = std::min(n_, s_.initial > 0 ? s_.initial : initialSearches(d));
    std::vector<int> first(static_cast<size_t>(initial));
    std::iota(first.begin(), first.end(), 0);
    search(first, LearnedRole::Initial);
    while (true) {
      if (static_cast<int>(trainX_.size()) < d + 2) {
        r_.message = "only " + std::to_string(trainX_.size()) + " of the first searches converged: at least " +
                     std::to_string(d + 2) + " are needed to fit the surrogate";
        break;
      }
      fitAndPredict();
      // Unsure points where the surrogate's own uncertainty still exceeds the searches'
      // resolution: a search there teaches it something. The other unsure points lie within the
      // resolution of F = 1, where no search can make the surrogate sure: a verdict decides them.
      int unsureCount = 0, learnable = 0;
      for (int k = 0; k < n_; ++k)
        if (u(k) < s_.stopU) ++unsureCount, learnable += sd_[k] > s_.resolution;
      if (s_.progress) s_.progress(r_.searches, r_.verdicts, unsureCount);
      if (learnable > 0 && unsureCount > s_.confirmations) {
        if (r_.searches >= s_.maxSearches) {
          r_.stoppedBy = "searches";
          break;
        }
        std::vector<int> next = batch(leastSure(64, true));
        next.resize(std::min(next.size(), static_cast<size_t>(s_.maxSearches - r_.searches)));
        search(next, LearnedRole::Learning);
        continue;
      }
      // The unsure points are judged by one forward run each (a search would cost ten), which
      // decides them; so are `confirmations` of the least sure of the others, which confirms the
      // surrogate where it claims to know. The verdict budget is for the whole learning.
      const int verdictRoom = std::max(0, s_.maxVerdicts - r_.verdicts);
      const int decide = std::min(unsureCount, verdictRoom);
      const std::vector<int> ordered = leastSure(static_cast<size_t>(unsureCount + s_.confirmations), false);
      std::vector<int> check(ordered.begin(), ordered.begin() + decide);
      const int sureChecks = std::min(s_.confirmations, verdictRoom - decide);
      for (size_t i = static_cast<size_t>(unsureCount); i < ordered.size() && static_cast<int>(check.size()) < decide + sureChecks; ++i)
        check.push_back(ordered[i]);
      const std::vector<int> wrong = confirm(check);
      if (decide < unsureCount) {  // the rest stay unsure, and bound Pf
        r_.stoppedBy = "verdicts";
        break;
      }
      if (wrong.empty()) {
        r_.learnt = true;
        break;
      }
      if (r_.searches >= s_.maxSearches) {
        r_.stoppedBy = "searches";
        break;
      }
      const size_t searchRoom = static_cast<size_t>(s_.maxSearches - r_.searches);
      search(std::vector<int>(wrong.begin(), wrong.begin() + std::min(searchRoom, wrong.size())), LearnedRole::Learning);
    }
    finish();
    return std::move(r_);
  }

 private:
  /// U of an unrun point: its margin's distance from 0 in standard deviations, the surrogate's
  /// own combined with the searches' resolution (the margins it learnt are known no better).
  double u(int k) const {
    if (known_[static_cast<size_t>(k)] != Known::No) return std::numeric_limits<double>::infinity();
    const double sd = std::hypot(sd_[k], s_.resolution);
    return sd > 0 ? std::abs(mean_[k]) / sd : std::numeric_limits<double>::infinity();
  }

  /// The `keep` unrun points of least U, least sure first (ties by index: deterministic); with
  /// `learnable`, only those whose predicted sd exceeds the searches' resolution.
  std::vector<int> leastSure(size_t keep, bool learnable) const {
    std::vector<int> order;
    for (int k = 0; k < n_; ++k)
      if (known_[static_cast<size_t>(k)] == Known::No && (!learnable || sd_[k] > s_.resolution)) order.push_back(k);
    keep = std::min(keep, order.size());
    std::partial_sort(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(keep), order.end(), [&](int a, int b) {
      const double ua = u(a), ub = u(b);
      return ua < ub || (ua == ub && a < b);
    });
    order.resize(keep);
    return order;
  }

  /// The least sure point, then each next least sure one at least `separation` from those chosen.
  std::vector<int> batch(const std::vector<int>& unsure) const {
    std::vector<int> chosen{unsure.front()};
    for (size_t i = 1; i < unsure.size() && static_cast<int>(chosen.size()) < s_.batch; ++i) {
      if (u(unsure[i]) >= s_.stopU) break;
      bool apart = true;
      for (int c : chosen) apart = apart && (p_.population.col(unsure[i]) - p_.population.col(c)).norm() >= s_.separation;
      if (apart) chosen.push_back(unsure[i]);
    }
    return chosen;
  }

  void search(const std::vector<int>& points, LearnedRole role) {
    std::vector<PerformanceValue> values(points.size());
    if (p_.evaluateAll)
      values = p_.evaluateAll(points);
    else
      runOnThreads(static_cast<int>(points.size()), s_.threads,
                   [&](int i) { values[static_cast<size_t>(i)] = p_.evaluate(points[static_cast<size_t>(i)]); });
    DDASLOPE_ASSERT(values.size() == points.size(), "a search per point");
    for (size_t i = 0; i < points.size(); ++i) {
      const int k = points[i];
      LearnedPoint lp;
      lp.index = k;
      lp.role = role;
      lp.value = values[i];
      if (role != LearnedRole::Initial) lp.predictedMean = mean_[k], lp.predictedSd = sd_[k];
      r_.points.push_back(lp);
      ++r_.searches;
      r_.searchRuns += values[i].runs;
      if (!values[i].converged) {
        // A point a verdict decided keeps it: only its margin stays unknown.
        if (known_[static_cast<size_t>(k)] == Known::No) known_[static_cast<size_t>(k)] = Known::NotConverged;
        continue;
      }
      known_[static_cast<size_t>(k)] = values[i].fails ? Known::Fails : Known::Stable;
      trainX_.push_back(k);
      trainY_.push_back(values[i].margin);
    }
  }

  /// Judges `points` by one forward run each; returns those whose verdict contradicts the surrogate.
  std::vector<int> confirm(const std::vector<int>& points) {
    std::vector<PointVerdict> verdicts(points.size());
    if (p_.judgeAll)
      verdicts = p_.judgeAll(points);
    else
      runOnThreads(static_cast<int>(points.size()), s_.threads,
                   [&](int i) { verdicts[static_cast<size_t>(i)] = p_.judge(points[static_cast<size_t>(i)]); });
    DDASLOPE_ASSERT(verdicts.size() == points.size(), "a verdict per point");
    std::vector<int> wrong;
    for (size_t i = 0; i < points.size(); ++i) {
      const int k = points[i];
      LearnedPoint lp;
      lp.index = k;
      lp.role = LearnedRole::Confirmation;
      lp.verdict = verdicts[i];
      lp.predictedMean = mean_[k];
      lp.predictedSd = sd_[k];
      ++r_.verdicts;
      if (verdicts[i] == PointVerdict::NotConverged) {
        known_[static_cast<size_t>(k)] = Known::NotConverged;
      } else {
        const bool fails = verdicts[i] == PointVerdict::Fails;
        lp.agrees = fails == (mean_[k] < 0);
        const bool sure = u(k) >= s_.stopU;
        lp.sure = sure;
        known_[static_cast<size_t>(k)] = fails ? Known::Fails : Known::Stable;
        if (!sure) {
          ++r_.decidedByVerdict;
        } else if (!lp.agrees) {
          // The surrogate was sure and wrong: it must learn there.
          ++r_.disagreements;
          wrong.push_back(k);
        }
      }
      r_.points.push_back(lp);
    }
    // A contradicted point keeps its verdict; it is searched next (budget allowing) so that the
    // surrogate learns its margin.
    return wrong;
  }

  void fitAndPredict() {
    const Eigen::Index d = p_.population.rows(), m = static_cast<Eigen::Index>(trainX_.size());
    Eigen::MatrixXd x(m, d);
    Eigen::VectorXd y(m);
    for (Eigen::Index i = 0; i < m; ++i) {
      x.row(i) = p_.population.col(trainX_[static_cast<size_t>(i)]).transpose();
      y[i] = trainY_[static_cast<size_t>(i)];
    }
    model_.fit(x, y);
    ++r_.rounds;
    const int blocks = static_cast<int>((n_ + kPredictBlock - 1) / kPredictBlock);
    parallelBlocks(blocks);
  }

  void parallelBlocks(int blocks) {
    runOnThreads(blocks, s_.threads, [&](int b) {
      const Eigen::Index begin = b * kPredictBlock, count = std::min<Eigen::Index>(kPredictBlock, n_ - begin);
      Eigen::VectorXd mean, sd;
      model_.predict(p_.population.middleCols(begin, count), mean, sd);
      mean_.segment(begin, count) = mean;
      sd_.segment(begin, count) = sd;
    });
  }

  void finish() {
    r_.fails.assign(static_cast<size_t>(n_), 0);
    r_.minU = std::numeric_limits<double>::infinity();
    const bool predicted = r_.rounds > 0;
    for (int k = 0; k < n_; ++k) {
      switch (known_[static_cast<size_t>(k)]) {
        case Known::Fails: r_.fails[static_cast<size_t>(k)] = 1; break;
        case Known::Stable: break;
        case Known::NotConverged: ++r_.notConverged; break;
        case Known::No:
          if (!predicted) break;
          r_.fails[static_cast<size_t>(k)] = mean_[k] < 0;
          r_.minU = std::min(r_.minU, u(k));
          if (u(k) < s_.stopU) ++(mean_[k] < 0 ? r_.unsureFailing : r_.unsureStable);
          break;
      }
      r_.failing += r_.fails[static_cast<size_t>(k)];
    }
    if (predicted) r_.surrogate = model_;
  }

  const ActiveLearningProblem& p_;
  const ActiveLearningSettings& s_;
  int n_;
  std::vector<Known> known_;
  Eigen::VectorXd mean_, sd_;
  std::vector<int> trainX_;
  std::vector<double> trainY_;
  Kriging model_;
  ActiveLearningResult r_;
};

}  // namespace

const char* name(LearnedRole role) {
  switch (role) {
    case LearnedRole::Initial: return "initial";
    case LearnedRole::Learning: return "learning";
    case LearnedRole::Confirmation: return "confirmation";
  }
  return "?";
}

int initialSearches(int dimensions) { return std::max(12, 2 * (dimensions + 2)); }

LearnedProbability probabilityOf(const ActiveLearningResult& r) {
  LearnedProbability p;
  p.converged = r.population - r.notConverged;
  if (p.converged <= 0) return p;
  p.pf = static_cast<double>(r.failing) / p.converged;
  p.interval = wilsonInterval(r.failing, p.converged);
  if (r.failing > 0) p.coefficientOfVariation = std::sqrt((1 - p.pf) / (p.pf * p.converged));
  p.beta = reliabilityIndex(p.pf);
  p.betaInterval = {reliabilityIndex(p.interval.high), reliabilityIndex(p.interval.low)};
  p.bounds = {wilsonInterval(r.failing - r.unsureFailing, r.population).low,
              wilsonInterval(r.failing + r.unsureStable + r.notConverged, r.population).high};
  p.bounds.low = std::min(p.bounds.low, p.interval.low);
  p.bounds.high = std::max(p.bounds.high, p.interval.high);
  return p;
}

DesignPoint surrogateDesignPoint(const ActiveLearningProblem& problem, const ActiveLearningResult& r) {
  DesignPoint d;
  const Eigen::Index dims = problem.population.rows();
  Eigen::Index start = -1;
  for (Eigen::Index k = 0; k < problem.population.cols(); ++k)
    if (r.fails[static_cast<size_t>(k)] &&
        (start < 0 || problem.population.col(k).squaredNorm() < problem.population.col(start).squaredNorm()))
      start = k;
  if (r.rounds == 0) {
    d.message = "no surrogate was fitted";
    return d;
  }
  if (start < 0) {
    d.message = "no population point fails";
    return d;
  }
  {
    // At the medians' side of the limit state only: a slope that fails at its medians has no
    // nearest failing point, and a direction taken there would be noise.
    Eigen::VectorXd mean, sd;
    r.surrogate.predict(Eigen::MatrixXd::Zero(dims, 1), mean, sd);
    if (mean[0] <= 0) {
      char text[96];
      std::snprintf(text, sizeof text, "the slope fails at the inputs' medians, where the surrogate's F is %.3f",
                    1 + mean[0]);
      d.message = text;
      return d;
    }
  }
  struct Data {
    const Kriging* model;
  } data{&r.surrogate};
  const auto margin = [](unsigned n, const double* x, double*, void* p) {
    const Eigen::MatrixXd at = Eigen::Map<const Eigen::MatrixXd>(x, n, 1);
    Eigen::VectorXd mean, sd;
    static_cast<Data*>(p)->model->predict(at, mean, sd);
    return mean[0];
  };
  const auto norm2 = [](const std::vector<double>& x, std::vector<double>&, void*) {
    double s = 0;
    for (double v : x) s += v * v;
    return s;
  };
  nlopt::opt opt(nlopt::LN_COBYLA, static_cast<unsigned>(dims));
  opt.set_min_objective(norm2, nullptr);
  opt.add_inequality_constraint(margin, &data, 1e-6);
  opt.set_xtol_abs(1e-4);
  opt.set_maxeval(2000);
  std::vector<double> u(problem.population.col(start).data(), problem.population.col(start).data() + dims);
  const std::vector<double> fallback = u;
  double value = 0;
  try {
    opt.optimize(u, value);
  } catch (const std::exception&) {
    // Round-off: keep the failing population point, a conservative (farther) estimate.
  }
  if (margin(static_cast<unsigned>(dims), u.data(), nullptr, &data) > 1e-4) u = fallback;
  d.found = true;
  d.converged = true;
  d.u = u;
  d.beta = std::sqrt(norm2(u, u, nullptr));
  d.alpha.resize(u.size());
  for (size_t i = 0; i < u.size(); ++i) d.alpha[i] = d.beta > 0 ? u[i] / d.beta : 0;
  return d;
}

ActiveLearningResult learnFailureDomain(const ActiveLearningProblem& problem, const ActiveLearningSettings& settings) {
  return Learner(problem, settings).run();
}

}  // namespace ddaslope::calibration

#include "fit/least_squares.hpp"

#include <ceres/ceres.h>
#include <glog/logging.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <mutex>

#include "core/error.hpp"
#include "core/interrupt.hpp"
#include "core/parallel_runner.hpp"

namespace shpb {
namespace {

// Residuals and Jacobian of all groups at one x, cached: Ceres asks each one-residual block in
// turn (single-threaded), the first ask evaluates every group (in parallel), the others read.
class Model {
 public:
  Model(const std::vector<LsParameter>& p, const std::vector<LsGroup>& g, const LsOptions& o)
      : params_(p), groups_(g), options_(o) {
    for (const auto& group : groups_) {
      offsets_.push_back(size_);
      size_ += group.loss_scale.size();
    }
  }
  std::size_t size() const { return size_; }
  std::size_t parameters() const { return params_.size(); }
  long evaluations() const { return evaluations_; }
  bool interrupted() const { return interrupted_; }
  const std::vector<double>& residuals() const { return r_; }
  const Eigen::MatrixXd& jacobian() const { return j_; }
  std::size_t offset(std::size_t group) const { return offsets_[group]; }  // its first residual

  std::vector<double> theta(const double* x) const {
    std::vector<double> t(params_.size());
    for (std::size_t i = 0; i < t.size(); ++i) t[i] = params_[i].to_theta(x[i]);
    return t;
  }

  // Makes residuals (and the Jacobian if asked) current at x; false if an evaluation failed.
  bool ensure(const double* x, bool jacobian) {
    const std::vector<double> xv(x, x + params_.size());
    if (!(have_r_ && xv == x_r_)) {
      have_r_ = have_j_ = false;
      if (!evaluate_all(xv, r_)) return false;
      x_r_ = xv, have_r_ = true;
    }
    if (jacobian && !(have_j_ && xv == x_j_)) {
      if (!jacobian_at(xv, options_.relative_step, j_)) return false;
      x_j_ = xv, have_j_ = true;
    }
    return true;
  }

  // Central (at a bound one-sided) differences with steps h_j = step · max(|x_j|, 1).
  bool jacobian_at(const std::vector<double>& x, double step, Eigen::MatrixXd& out) {
    struct Task {
      std::size_t group, column;
      double at;  // x_j of this evaluation
      std::vector<double> r;
    };
    std::vector<Task> tasks;
    std::vector<std::pair<double, double>> span(params_.size());  // x− and x+ used per column
    for (std::size_t j = 0; j < params_.size(); ++j) {
      const double lo = params_[j].to_x(params_[j].lower), hi = params_[j].to_x(params_[j].upper);
      const double h = step * std::max(std::abs(x[j]), 1.0);
      double minus = x[j] - h, plus = x[j] + h;
      if (plus > hi) plus = x[j];
      if (minus < lo) minus = x[j];
      span[j] = {minus, plus};
    }
    for (std::size_t g = 0; g < groups_.size(); ++g)
      for (std::size_t j : groups_[g].parameters)
        for (double at : {span[j].first, span[j].second})
          if (at != x[j]) tasks.push_back({g, j, at, {}});
    bool ok = true;
    std::mutex m;
    run_parallel(tasks.size(), options_.threads, [&](std::size_t k) {
      Task& t = tasks[k];
      std::vector<double> xt = x;
      xt[t.column] = t.at;
      if (!evaluate_group(t.group, xt, t.r)) {
        const std::lock_guard lock(m);
        ok = false;
      }
    });
    if (!ok) return false;
    out = Eigen::MatrixXd::Zero(static_cast<long>(size_), static_cast<long>(params_.size()));
    for (std::size_t g = 0; g < groups_.size(); ++g)
      for (std::size_t j : groups_[g].parameters) {
        const auto find = [&](double at) -> const std::vector<double>* {
          if (at == x[j]) return nullptr;
          for (const Task& t : tasks)
            if (t.group == g && t.column == j && t.at == at) return &t.r;
          return nullptr;
        };
        const std::vector<double>* rm = find(span[j].first);
        const std::vector<double>* rp = find(span[j].second);
        const double dx = span[j].second - span[j].first;
        for (std::size_t i = 0; i < groups_[g].loss_scale.size(); ++i) {
          const double base = r_[offsets_[g] + i];
          const double up = rp ? (*rp)[i] : base, down = rm ? (*rm)[i] : base;
          out(static_cast<long>(offsets_[g] + i), static_cast<long>(j)) = (up - down) / dx;
        }
      }
    return true;
  }

  const std::vector<double>& x_residuals() const { return x_r_; }

 private:
  bool evaluate_group(std::size_t g, const std::vector<double>& x, std::vector<double>& out) {
    try {
      out = groups_[g].residuals(theta(x.data()));
      ++evaluations_;
      for (double v : out)
        if (!std::isfinite(v)) return false;
      return out.size() == groups_[g].loss_scale.size();
    } catch (const NumericalError&) {
      ++evaluations_;
      return false;
    } catch (const Interrupted&) {
      interrupted_ = true;
      return false;
    }
  }

  bool evaluate_all(const std::vector<double>& x, std::vector<double>& out) {
    std::vector<std::vector<double>> parts(groups_.size());
    std::vector<char> ok(groups_.size(), 0);
    run_parallel(groups_.size(), options_.threads,
                 [&](std::size_t g) { ok[g] = evaluate_group(g, x, parts[g]); });
    if (std::find(ok.begin(), ok.end(), 0) != ok.end()) return false;
    out.clear();
    for (const auto& p : parts) out.insert(out.end(), p.begin(), p.end());
    return true;
  }

  const std::vector<LsParameter>& params_;
  const std::vector<LsGroup>& groups_;
  const LsOptions& options_;
  std::vector<std::size_t> offsets_;
  std::size_t size_ = 0;
  std::atomic<long> evaluations_{0};
  std::atomic<bool> interrupted_{false};
  std::vector<double> x_r_, r_, x_j_;
  bool have_r_ = false, have_j_ = false;
  Eigen::MatrixXd j_;
};

class SampleCost final : public ceres::CostFunction {
 public:
  SampleCost(Model& model, std::size_t index) : model_(model), index_(index) {
    set_num_residuals(1);
    mutable_parameter_block_sizes()->push_back(static_cast<int>(model.parameters()));
  }
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    const bool want_j = jacobians && jacobians[0];
    if (!model_.ensure(parameters[0], want_j)) return false;
    residuals[0] = model_.residuals()[index_];
    if (want_j)
      for (std::size_t j = 0; j < model_.parameters(); ++j)
        jacobians[0][j] = model_.jacobian()(static_cast<long>(index_), static_cast<long>(j));
    return true;
  }

 private:
  Model& model_;
  std::size_t index_;
};

class Progress final : public ceres::IterationCallback {
 public:
  Progress(const Model& model, const LsOptions& options) : model_(model), options_(options) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary& s) override {
    // A signal stops the solve here too when no evaluation saw it (the curve stage's groups run
    // no simulation that would notice).
    if (model_.interrupted() || interrupted()) return ceres::SOLVER_ABORT;
    if (options_.progress) {
      char line[200];
      std::snprintf(line, sizeof line, "iteration %2d  cost %.6g  %s  evaluations %ld", s.iteration,
                    s.cost, s.step_is_successful ? "step taken " : "step refused",
                    model_.evaluations());
      options_.progress(line);
    }
    return ceres::SOLVER_CONTINUE;
  }

 private:
  const Model& model_;
  const LsOptions& options_;
};

using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// Ceres' options for the bounded problem in scaled parameters.
ceres::Solver::Options solver_options(const LsOptions& options) {
  ceres::Solver::Options so;
  so.linear_solver_type = ceres::DENSE_QR;
  so.max_num_iterations = options.max_iterations;
  so.num_threads = 1;  // the model evaluates in parallel itself
  so.function_tolerance = 1e-7;
  so.parameter_tolerance = 1e-6;
  so.gradient_tolerance = 1e-12;
  so.logging_type = ceres::SILENT;
  // With bounds, Ceres follows each trust-region step by a projected line search whose trial
  // points ask for gradients, i.e. a whole Jacobian (2P simulations per test) each: on the LANL
  // test a refused step cost 40-53 simulations instead of one. The bounds are kept by projecting
  // the step onto the box alone.
  so.max_num_line_search_step_size_iterations = 0;
  return so;
}

// A group's clock error δt moves its residuals by δt ∂r/∂t, and the estimate by G δt with
// G = (JᵀJ)⁻¹ Jᵀ ∂r/∂t (Gauss–Newton): its variance adds σ_c² G Gᵀ. A free time shift of the same
// group absorbs it (G is then that parameter's unit vector).
// The residuals' covariance term Jᵀ S J with S the variance of each block of one noise level (a
// test's window: its own gauge's noise over its own peak), each block's s² = Σ r²/(N_b (1 − P/N)).
// The residuals are weighted by window, not by their variance, so the estimator's covariance is
// the sandwich (JᵀJ)⁻¹ Jᵀ S J (JᵀJ)⁻¹; with one variance for all it is s² (JᵀJ)⁻¹ (methods.md §9).
Eigen::MatrixXd block_meat(const Model& model, const std::vector<LsGroup>& groups, std::size_t p) {
  const Eigen::MatrixXd& jac = model.jacobian();
  const std::vector<double>& res = model.residuals();
  const double keep = std::max(1.0 / static_cast<double>(model.size()),
                               1.0 - static_cast<double>(p) / static_cast<double>(model.size()));
  Eigen::MatrixXd meat = Eigen::MatrixXd::Zero(static_cast<long>(p), static_cast<long>(p));
  for (std::size_t g = 0; g < groups.size(); ++g) {
    std::vector<std::size_t> blocks = groups[g].blocks;
    if (blocks.empty()) blocks.push_back(groups[g].loss_scale.size());
    std::size_t row = model.offset(g);
    for (std::size_t n : blocks) {
      if (n == 0) continue;
      double ss = 0;
      for (std::size_t i = row; i < row + n; ++i) ss += res[i] * res[i];
      const auto rows = jac.middleRows(static_cast<long>(row), static_cast<long>(n));
      meat += ss / (static_cast<double>(n) * keep) * rows.transpose() * rows;
      row += n;
    }
  }
  return meat;
}

void add_clock_errors(Model& model, const std::vector<LsGroup>& groups, std::vector<double>& x,
                      const RowMatrix& c, Eigen::MatrixXd& cov, LsResult& r,
                      long& clock_evaluations) {
  const std::size_t p = x.size();
  if (!model.ensure(x.data(), true)) return;
  const Eigen::MatrixXd& jac = model.jacobian();
  // An error of sd moving group g's residuals by sd·d moves the estimate by sd·(JᵀJ)⁻¹Jᵀd.
  const auto add = [&](std::size_t g, double sd, const std::vector<double>& d) {
    Eigen::VectorXd jtd = Eigen::VectorXd::Zero(static_cast<long>(p));
    for (std::size_t i = 0; i < d.size(); ++i)
      jtd += d[i] * jac.row(static_cast<long>(model.offset(g) + i)).transpose();
    const Eigen::VectorXd gain = c * jtd;
    cov += sd * sd * gain * gain.transpose();
  };
  for (std::size_t g = 0; g < groups.size(); ++g) {
    for (const LsCommonError& e : groups[g].common_errors)
      if (e.sd > 0 && e.sensitivity.size() == groups[g].loss_scale.size())
        add(g, e.sd, e.sensitivity);
    if (!(groups[g].clock_sd_s > 0) || !groups[g].clock_sensitivity) continue;
    std::vector<double> d;
    try {
      ++clock_evaluations;
      d = groups[g].clock_sensitivity(model.theta(x.data()));
    } catch (const NumericalError&) {
    }
    if (d.size() != groups[g].loss_scale.size()) {
      r.warnings.push_back("the standard errors leave out a clock error: its evaluation failed");
      continue;
    }
    add(g, groups[g].clock_sd_s, d);
  }
}

// The step against round-off: the Jacobian with half the step should agree.
void check_step(Model& model, std::vector<double>& x, const LsOptions& options, LsResult& r) {
  const std::size_t p = x.size();
  if (model.ensure(x.data(), true)) {
    const Eigen::MatrixXd jh = model.jacobian();
    r.jacobian = jh;
    Eigen::MatrixXd jh2;
    if (model.jacobian_at(x, options.relative_step / 2, jh2)) {
      r.step_check.resize(p);
      for (std::size_t j = 0; j < p; ++j) {
        const double norm = jh.col(static_cast<long>(j)).norm();
        r.step_check[j] = norm > 0 ? (jh - jh2).col(static_cast<long>(j)).norm() / norm : 0.0;
      }
    }
  }
}

}  // namespace

LsResult solve_least_squares(const std::vector<LsParameter>& parameters,
                             const std::vector<LsGroup>& groups, const LsOptions& options) {
  // Ceres reports through glog; shpb prints its own one-line messages, so glog stays quiet (set
  // once: bootstrap refits solve on several threads at a time).
  static std::once_flag quiet_glog;
  std::call_once(quiet_glog, [] { FLAGS_minloglevel = google::GLOG_FATAL; });
  Model model(parameters, groups, options);
  const std::size_t p = parameters.size();
  std::vector<double> x(p);
  for (std::size_t i = 0; i < p; ++i) x[i] = parameters[i].to_x(parameters[i].start);

  ceres::Problem::Options problem_options;
  ceres::Problem problem(problem_options);
  std::size_t index = 0;
  for (const auto& g : groups)
    for (double scale : g.loss_scale) {
      ceres::LossFunction* loss = nullptr;
      const double a = options.loss_delta * scale;
      if (options.loss == FitLoss::kHuber) loss = new ceres::HuberLoss(a);
      if (options.loss == FitLoss::kCauchy) loss = new ceres::CauchyLoss(a);
      problem.AddResidualBlock(new SampleCost(model, index++), loss, x.data());
    }
  for (std::size_t i = 0; i < p; ++i) {
    problem.SetParameterLowerBound(x.data(), static_cast<int>(i),
                                   parameters[i].to_x(parameters[i].lower));
    problem.SetParameterUpperBound(x.data(), static_cast<int>(i),
                                   parameters[i].to_x(parameters[i].upper));
  }

  ceres::Solver::Options so = solver_options(options);
  Progress progress(model, options);
  so.callbacks.push_back(&progress);
  // The simulator's residuals carry a small non-smooth part (docs/methods.md §9): a Jacobian
  // from differences is then a few tens of per cent off, Levenberg–Marquardt shrinks its trust
  // region after refused steps and stops on a tiny step. A restart from the point reached (a
  // fresh trust region) continues while it still lowers the cost by kRestartGain.
  constexpr double kRestartGain = 1e-3;
  constexpr int kMaxRestarts = 4;
  ceres::Solver::Summary summary, run;
  ceres::Solve(so, &problem, &summary);
  int iterations = static_cast<int>(summary.iterations.size());
  for (int k = 0; k < kMaxRestarts && !model.interrupted() && !interrupted() &&
                  summary.termination_type != ceres::FAILURE && iterations < options.max_iterations;
       ++k) {
    so.max_num_iterations = options.max_iterations - iterations;
    ceres::Solve(so, &problem, &run);
    iterations += static_cast<int>(run.iterations.size());
    const double gain = (summary.final_cost - run.final_cost) / summary.final_cost;
    summary.final_cost = run.final_cost;
    summary.termination_type = run.termination_type;
    summary.message = run.message;
    if (!(gain > kRestartGain)) break;
  }
  if (model.interrupted() || interrupted()) throw Interrupted();

  LsResult r;
  long clock_evaluations = 0;
  r.value = model.theta(x.data());
  r.cost_start = summary.initial_cost;
  r.cost = summary.final_cost;
  r.iterations = iterations;
  r.termination = summary.message;
  r.converged = summary.termination_type == ceres::CONVERGENCE;
  r.residuals = model.size();
  if (summary.termination_type == ceres::FAILURE)
    throw NumericalError("fit: the solver failed: " + summary.message);
  if (!r.converged)
    r.warnings.push_back("the solver stopped before converging: " + summary.message);

  // Covariance: Ceres' (JᵀJ)⁻¹ in x, times s², scaled back to θ. Ceres evaluates the Jacobian
  // at x for it and goes on when that evaluation fails (a SIGINT/SIGTERM, or a simulation that
  // breaks down there): with an empty Jacobian it then reads past its arrays. The residuals and
  // Jacobian at x are therefore made current here first; Ceres then reads them from the model's
  // cache and evaluates nothing, and the covariance is skipped when they cannot be had.
  const bool at_solution = model.ensure(x.data(), true);
  if (!at_solution && (model.interrupted() || interrupted())) throw Interrupted();
  ceres::Covariance::Options co;
  co.algorithm_type = ceres::DENSE_SVD;
  co.null_space_rank = -1;  // drop directions below min_reciprocal_condition_number
  co.num_threads = 1;
  ceres::Covariance covariance(co);
  std::vector<std::pair<const double*, const double*>> blocks = {{x.data(), x.data()}};
  RowMatrix c(p, p);
  if (at_solution && covariance.Compute(blocks, &problem) &&
      covariance.GetCovarianceBlock(x.data(), x.data(), c.data())) {
    Eigen::MatrixXd cov = c * block_meat(model, groups, p) * c;
    add_clock_errors(model, groups, x, c, cov, r, clock_evaluations);
    r.std_error.resize(p);
    r.correlation = Eigen::MatrixXd::Identity(static_cast<long>(p), static_cast<long>(p));
    for (std::size_t i = 0; i < p; ++i)
      r.std_error[i] = std::sqrt(std::max(0.0, cov(i, i))) * parameters[i].scale;
    for (std::size_t i = 0; i < p; ++i)
      for (std::size_t j = 0; j < p; ++j)
        if (cov(i, i) > 0 && cov(j, j) > 0)
          r.correlation(static_cast<long>(i), static_cast<long>(j)) =
              cov(i, j) / std::sqrt(cov(i, i) * cov(j, j));
  } else {
    r.warnings.push_back(at_solution
                             ? "no covariance: the Jacobian at the solution is rank-deficient"
                             : "no covariance: the Jacobian at the solution cannot be evaluated");
  }

  check_step(model, x, options, r);
  // A signal during the covariance or the step check leaves them incomplete: no result then.
  if (model.interrupted() || interrupted()) throw Interrupted();
  r.evaluations = model.evaluations() + clock_evaluations;
  return r;
}

}  // namespace shpb

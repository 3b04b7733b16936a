#include "optimize/ipopt_adapter.hpp"

#include <fmt/format.h>

#include <IpIpoptApplication.hpp>
#include <IpSolveStatistics.hpp>
#include <IpTNLP.hpp>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

#include "support/seconds_since.hpp"
#ifdef __GLIBC__
#include <malloc.h>
#endif

namespace lagrange::collocation {

namespace {

using Ipopt::Index;
using Ipopt::Number;

/// Ipopt's outcome in words.
std::string words(Ipopt::SolverReturn s) {
  switch (s) {
    case Ipopt::SUCCESS:
      return "optimal solution found";
    case Ipopt::MAXITER_EXCEEDED:
      return "maximum number of iterations exceeded";
    case Ipopt::CPUTIME_EXCEEDED:
      return "maximum CPU time exceeded";
    case Ipopt::STOP_AT_TINY_STEP:
      return "stopped at a tiny step (no progress)";
    case Ipopt::STOP_AT_ACCEPTABLE_POINT:
      return "solved to acceptable level only";
    case Ipopt::LOCAL_INFEASIBILITY:
      return "converged to a point of local infeasibility";
    case Ipopt::USER_REQUESTED_STOP:
      return "stopped on request";
    case Ipopt::FEASIBLE_POINT_FOUND:
      return "feasible point found";
    case Ipopt::DIVERGING_ITERATES:
      return "iterates diverging (problem unbounded?)";
    case Ipopt::RESTORATION_FAILURE:
      return "restoration phase failed (problem infeasible?)";
    case Ipopt::ERROR_IN_STEP_COMPUTATION:
      return "error in step computation";
    case Ipopt::INVALID_NUMBER_DETECTED:
      return "invalid number (NaN or Inf) in a function";
    case Ipopt::TOO_FEW_DEGREES_OF_FREEDOM:
      return "too few degrees of freedom";
    case Ipopt::INVALID_OPTION:
      return "invalid option";
    case Ipopt::OUT_OF_MEMORY:
      return "out of memory";
    default:
      return "internal error of Ipopt";
  }
}

class Adapter : public Ipopt::TNLP {
 public:
  Adapter(Transcription& nlp, IpoptOutcome& out, const std::atomic<bool>* interrupt,
          const IpoptOutcome* previous)
      : nlp_(nlp), out_(out), interrupt_(interrupt), previous_(previous) {}

  bool get_nlp_info(Index& n, Index& m, Index& nnz_jac, Index& nnz_h,
                    IndexStyleEnum& style) override {
    n = static_cast<Index>(nlp_.variables());
    m = static_cast<Index>(nlp_.constraints());
    nnz_jac = static_cast<Index>(nlp_.jacobian_pattern().size());
    nnz_h = static_cast<Index>(nlp_.has_hessian() ? nlp_.hessian_pattern().size() : 0);
    style = C_STYLE;
    return true;
  }
  bool get_bounds_info(Index, Number* xl, Number* xu, Index, Number* gl, Number* gu) override {
    nlp_.bounds(xl, xu, gl, gu);
    return true;
  }
  // The multipliers are asked for only under warm_start_init_point=yes: the previous solve's
  // when there is one of this size, else Ipopt's own cold values (bounds' 1, constraints' 0).
  bool get_starting_point(Index n, bool init_x, Number* x, bool init_z, Number* z_lower,
                          Number* z_upper, Index m, bool init_lambda, Number* lambda) override {
    if (n != static_cast<Index>(nlp_.variables())) return false;
    if (init_x) {
      const std::vector<double>& g = nlp_.guess();
      std::copy(g.begin(), g.end(), x);
    }
    if (!init_z && !init_lambda) return true;
    if (previous_ == nullptr || previous_->z_lower.size() != static_cast<size_t>(n) ||
        previous_->lambda.size() != static_cast<size_t>(m)) {
      if (init_z) {
        std::fill(z_lower, z_lower + n, 1.0);
        std::fill(z_upper, z_upper + n, 1.0);
      }
      if (init_lambda) std::fill(lambda, lambda + m, 0.0);
      return true;
    }
    if (init_z) {
      std::copy(previous_->z_lower.begin(), previous_->z_lower.end(), z_lower);
      std::copy(previous_->z_upper.begin(), previous_->z_upper.end(), z_upper);
    }
    if (init_lambda) std::copy(previous_->lambda.begin(), previous_->lambda.end(), lambda);
    return true;
  }
  // The nominal magnitudes' scaling, used with --ipopt nlp_scaling_method=user-scaling
  // (docs/theory.md §10, "Scaling": measured, it does not beat Ipopt's gradient-based default).
  bool get_scaling_parameters(Number& obj_scaling, bool& use_x_scaling, Index, Number* x_scaling,
                              bool& use_g_scaling, Index, Number* g_scaling) override {
    nlp_.scaling(x_scaling, g_scaling, obj_scaling);
    use_x_scaling = use_g_scaling = true;
    return true;
  }
  bool eval_f(Index, const Number* x, bool, Number& f) override {
    return timed([&] {
      f = nlp_.objective(x);
      if (!std::isfinite(f)) note_invalid(f, "the objective");
    });
  }
  bool eval_grad_f(Index n, const Number* x, bool, Number* g) override {
    return timed([&] {
      nlp_.gradient(x, g);
      for (Index i = 0; i < n; ++i)
        if (!std::isfinite(g[i]))
          note_invalid(g[i], "the objective's gradient in " + nlp_.describe_variable(i, x));
    });
  }
  bool eval_g(Index, const Number* x, bool, Index m, Number* g) override {
    return timed([&] {
      nlp_.constraint_values(x, g);
      for (Index r = 0; r < m; ++r)
        if (!std::isfinite(g[r])) note_invalid(g[r], nlp_.describe(static_cast<size_t>(r), x));
    });
  }
  bool eval_jac_g(Index, const Number* x, bool, Index, Index, Index* rows, Index* cols,
                  Number* values) override {
    if (values == nullptr) {
      const auto& nz = nlp_.jacobian_pattern();
      for (size_t e = 0; e < nz.size(); ++e) {
        rows[e] = static_cast<Index>(nz[e].first);
        cols[e] = static_cast<Index>(nz[e].second);
      }
      return true;
    }
    return timed([&] {
      nlp_.jacobian(x, values);
      const auto& nz = nlp_.jacobian_pattern();
      for (size_t e = 0; e < nz.size(); ++e)
        if (!std::isfinite(values[e]))
          note_invalid(values[e], "the derivative of " + nlp_.describe(nz[e].first, x) + " in " +
                                      nlp_.describe_variable(nz[e].second, x));
    });
  }
  bool eval_h(Index, const Number* x, bool, Number sigma, Index, const Number* y, bool, Index,
              Index* rows, Index* cols, Number* values) override {
    if (values == nullptr) {
      const auto& nz = nlp_.hessian_pattern();
      for (size_t e = 0; e < nz.size(); ++e) {
        rows[e] = static_cast<Index>(nz[e].first);
        cols[e] = static_cast<Index>(nz[e].second);
      }
      return true;
    }
    return timed([&] {
      nlp_.hessian(x, sigma, y, values);
      const auto& nz = nlp_.hessian_pattern();
      for (size_t e = 0; e < nz.size(); ++e)
        if (!std::isfinite(values[e]))
          note_invalid(values[e], "the Hessian of the Lagrangian in " +
                                      nlp_.describe_variable(nz[e].first, x) + " and " +
                                      nlp_.describe_variable(nz[e].second, x));
    });
  }
  // After each iteration: false stops Ipopt (USER_REQUESTED_STOP) at the current iterate.
  bool intermediate_callback(Ipopt::AlgorithmMode, Index, Number, Number, Number, Number, Number,
                             Number, Number, Number, Index, const Ipopt::IpoptData*,
                             Ipopt::IpoptCalculatedQuantities*) override {
    if (interrupt_ != nullptr && interrupt_->load()) out_.interrupted = true;
    return !out_.interrupted;
  }
  void finalize_solution(Ipopt::SolverReturn status, Index n, const Number* x,
                         const Number* z_lower, const Number* z_upper, Index m, const Number*,
                         const Number* lambda, Number, const Ipopt::IpoptData*,
                         Ipopt::IpoptCalculatedQuantities*) override {
    out_.optimal = status == Ipopt::SUCCESS;
    out_.status = words(status);
    // Where the last NaN or Inf was met: Ipopt stops on it (invalid number) or, when it is in a
    // derivative, fails to factorise and ends in restoration.
    if (!out_.optimal && !invalid_.empty()) out_.status += "; " + invalid_;
    out_.x.assign(x, x + n);
    out_.z_lower.assign(z_lower, z_lower + n);
    out_.z_upper.assign(z_upper, z_upper + n);
    out_.lambda.assign(lambda, lambda + m);
  }

 private:
  /// Runs f, adding its time; a failure of the model's evaluation (a singular matrix) makes
  /// Ipopt shorten the step instead of aborting.
  template <class F>
  bool timed(F&& f) {
    const auto start = std::chrono::steady_clock::now();
    bool ok = true;
    try {
      f();
    } catch (const std::runtime_error&) {
      ok = false;
    }
    out_.function_seconds += seconds_since(start);
    return ok;
  }
  /// Records where a value is not finite; the last such place is reported.
  void note_invalid(double value, const std::string& where) {
    invalid_ = fmt::format("{} is {}", where, value);
  }
  std::string invalid_;
  Transcription& nlp_;
  IpoptOutcome& out_;
  const std::atomic<bool>* interrupt_;
  const IpoptOutcome* previous_;
};

/// MUMPS allocates its factorisation's workspace (with Ipopt's mumps_mem_percent, ten times its
/// estimate) and frees it again at every factorisation. glibc serves such large blocks by fresh
/// mappings (over its mmap threshold) or returns them to the system (over its trim threshold),
/// so each factorisation page-faults and zeroes the workspace anew: 15 % of the AP2 power
/// cycle's solve time (docs/benchmarks.md). Both thresholds raised once for the process keep the
/// blocks in the heap for reuse; the process keeps the largest workspace until it ends.
void keep_large_blocks() {
#ifdef __GLIBC__
  static const bool once = [] {
    constexpr int kBytes = 1 << 30;
    mallopt(M_MMAP_THRESHOLD, kBytes);
    mallopt(M_TRIM_THRESHOLD, kBytes);
    return true;
  }();
  (void)once;
#endif
}

/// Sets one option by the form of its value: an integer, a number, else a word.
bool set_option(Ipopt::OptionsList& list, const std::string& key, const std::string& value) {
  char* end = nullptr;
  const long i = std::strtol(value.c_str(), &end, 10);
  if (!value.empty() && *end == '\0') return list.SetIntegerValue(key, static_cast<Index>(i));
  const double d = std::strtod(value.c_str(), &end);
  if (!value.empty() && *end == '\0') return list.SetNumericValue(key, d);
  return list.SetStringValue(key, value);
}

}  // namespace

IpoptOutcome solve_with_ipopt(Transcription& nlp,
                              const std::vector<std::pair<std::string, std::string>>& options,
                              bool verbose, const std::atomic<bool>* interrupt,
                              const IpoptOutcome* previous) {
  IpoptOutcome out;
  keep_large_blocks();
  Ipopt::SmartPtr<Ipopt::IpoptApplication> app = IpoptApplicationFactory();
  Ipopt::OptionsList& list = *app->Options();
  list.SetStringValue("sb", "yes");
  list.SetIntegerValue("print_level", verbose ? 5 : 0);
  list.SetStringValue("hessian_approximation", nlp.has_hessian() ? "exact" : "limited-memory");
  list.SetStringValue("linear_solver", "mumps");
  list.SetNumericValue("tol", 1e-8);
  list.SetIntegerValue("max_iter", 1000);
  for (const auto& [key, value] : options)
    if (!set_option(list, key, value))
      throw std::invalid_argument("Ipopt rejected the option " + key + "=" + value);
  std::string approximation;
  list.GetStringValue("hessian_approximation", approximation, "");
  out.exact_hessian = approximation == "exact";
  if (app->Initialize() != Ipopt::Solve_Succeeded)
    throw std::runtime_error("Ipopt could not be initialised");
  Ipopt::SmartPtr<Ipopt::TNLP> tnlp = new Adapter(nlp, out, interrupt, previous);
  app->OptimizeTNLP(tnlp);
  if (Ipopt::IsValid(app->Statistics())) out.iterations = app->Statistics()->IterationCount();
  if (out.x.empty()) {
    out.x = nlp.guess();
    if (out.status.empty()) out.status = "Ipopt stopped before its first iterate";
  }
  return out;
}

}  // namespace lagrange::collocation

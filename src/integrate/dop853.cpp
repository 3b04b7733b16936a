// DOP853: Dormand and Prince's explicit Runge–Kutta pair of order 8 with Hairer's error estimate,
// step-size control and continuous extension of order 7 (docs/theory.md §8, "DOP853").

#include "integrate/dop853.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "integrate/keeping_stats.hpp"
#include "integrate/methods.hpp"
#include "integrate/solver_errors.hpp"
#include "integrate/walk_grid.hpp"
#include "lagrange/error.hpp"

namespace lagrange::integration {

namespace {

// Hairer's step-size control with his stabilisation (a PI controller): after an accepted step
// h_new = h · clamp(0.9 · err^(−(1/8 − 0.2β)) · err_prev^β, 1/3, 6), at most h after a rejected
// one. Hairer's code offers β as an option (0 by default in DOP853, 0.04 recommended for DOPRI5);
// β = 0.04 saved 5–18 % of the evaluations at equal error on the work–precision chains and
// rejects fewer steps (docs/theory.md §8, DOP853).
constexpr double kBeta = 0.04;
constexpr double kSafety = 0.9;
constexpr double kSmallestFactor = 0.333;
constexpr double kLargestFactor = 6.0;
constexpr size_t kStages = 12;     // stage 13, f(t + h, y₁), is the next step's first
constexpr size_t kAllStages = 16;  // and stages 14–16 serve the dense output

/// Root mean square of v[i] / scale[i].
double rms(const std::vector<double>& v, const std::vector<double>& scale) {
  double sum = 0.0;
  for (size_t i = 0; i < v.size(); ++i) sum += (v[i] / scale[i]) * (v[i] / scale[i]);
  return std::sqrt(sum / static_cast<double>(v.size()));
}

}  // namespace

Dop853::Dop853(const OdeProblem& problem, const IntegratorOptions& options, std::vector<double>& y,
               double t_end)
    : problem_(problem),
      options_(options),
      table_(dop853()),
      n_(y.size()),
      t_end_(t_end),
      y_(y),
      k_(kAllStages, std::vector<double>(n_)),
      y_old_(n_),
      y_new_(n_),
      stage_(n_),
      scale_(n_),
      dense_(7, std::vector<double>(n_)) {}

void Dop853::start(double t, bool keep_step) {
  t_ = t;
  f(t, y_.data(), k_[0]);
  first_is_last_ = false;
  if (keep_step && h_ > 0.0) return;
  h_ = options_.step > 0.0 ? options_.step : initial_step();
  previous_error_ = 1e-4;
}

double Dop853::step() {
  if (first_is_last_) k_[0].swap(k_[kStages]);  // f(t, y) from the last step's end
  first_is_last_ = false;
  y_old_ = y_;
  t_old_ = t_;
  const bool fixed = options_.step > 0.0;
  double h = h_;
  for (;;) {
    const bool last = t_ + (fixed ? (1.0 + 1e-9) * h : 1.01 * h) >= t_end_;
    const double wanted = h;  // the step a shortened last one replaces, kept for the next
    if (last) h = t_end_ - t_;
    if (!(h > 16.0 * std::numeric_limits<double>::epsilon() * std::abs(t_)) || !(h > 0.0))
      throw SimulationError(
          t_, fmt::format("dop853: the step size fell to {:.3g} at t = {:.17g}, below the "
                          "rounding of t ({} error-test failures in this step); the equations "
                          "may be stiff or singular here: try --integrator cvode",
                          h, t_, rejections_));
    stages(h);
    if (fixed) {
      accept(h, last, wanted);
      return t_;
    }
    const double err = error(h);
    const double grow = std::pow(err, 0.125 - 0.2 * kBeta);  // err ~ h⁸
    if (err <= 1.0) {
      const double shrink = grow / std::pow(previous_error_, kBeta) / kSafety;
      double h_next = h / std::clamp(shrink, 1.0 / kLargestFactor, 1.0 / kSmallestFactor);
      if (rejections_ > 0) h_next = std::min(h_next, h);  // no growth right after a rejection
      previous_error_ = std::max(err, 1e-4);
      accept(h, last, last ? std::max(h_next, wanted) : h_next);
      return t_;
    }
    ++stats_.failed_steps;
    ++rejections_;
    h /= std::min(1.0 / kSmallestFactor, grow / kSafety);
  }
}

void Dop853::interpolate(double t, double* out) {
  if (!dense_ready_) build_dense();
  const double s = (t - t_old_) / h_old_, s1 = 1.0 - s;
  const std::vector<double>* d = dense_.data();
  for (size_t i = 0; i < n_; ++i) {
    const double inner = d[3][i] + s * (d[4][i] + s1 * (d[5][i] + s * d[6][i]));
    out[i] = y_old_[i] + s * (d[0][i] + s1 * (d[1][i] + s * (d[2][i] + s1 * inner)));
  }
}

void Dop853::f(double t, const double* y, std::vector<double>& out) {
  problem_.rhs(t, y, out.data());
  ensure_finite(t, out.data(), n_, "right-hand side ydot");
  ++stats_.rhs_evals;
}

/// stage_ = y_old + h Σⱼ a[j] kⱼ over the row's stages.
void Dop853::stage_state(const std::vector<double>& a, double h) {
  stage_ = y_old_;
  for (size_t j = 0; j < a.size(); ++j) {
    if (a[j] == 0.0) continue;
    const double w = h * a[j];
    const double* kj = k_[j].data();
    for (size_t i = 0; i < n_; ++i) stage_[i] += w * kj[i];
  }
}

/// Stages 2–12 and the eighth-order solution y_new.
void Dop853::stages(double h) {
  const ButcherCoefficients& m = table_.main;
  for (size_t s = 1; s < kStages; ++s) {
    stage_state(m.a[s], h);
    f(t_ + m.c[s] * h, stage_.data(), k_[s]);
  }
  y_new_ = y_old_;
  for (size_t j = 0; j < kStages; ++j) {
    if (m.b[j] == 0.0) continue;
    for (size_t i = 0; i < n_; ++i) y_new_[i] += h * m.b[j] * k_[j][i];
  }
}

// docs/theory.md §8, DOP853: err = |h| ‖e₅‖² / √(‖e₅‖² + 0.01 ‖e₃‖²) in the root-mean-square norm
// scaled by atol + rtol · max(|y₀|, |y₁|).
double Dop853::error(double h) {
  double sum5 = 0.0, sum3 = 0.0;
  for (size_t i = 0; i < n_; ++i) {
    double e5 = 0.0, e3 = 0.0;
    for (size_t j = 0; j < kStages; ++j) {
      e5 += table_.e5[j] * k_[j][i];
      e3 += table_.e3[j] * k_[j][i];
    }
    const double sk = weight(i, std::max(std::abs(y_old_[i]), std::abs(y_new_[i])));
    sum5 += (e5 / sk) * (e5 / sk);
    sum3 += (e3 / sk) * (e3 / sk);
  }
  double denominator = sum5 + 0.01 * sum3;
  if (denominator <= 0.0) denominator = 1.0;
  return std::abs(h) * sum5 / std::sqrt(static_cast<double>(n_) * denominator);
}

/// The scale atol + rtol · size of component i's error; with atol = 0 a component that is 0
/// has none, and the run stops saying so rather than dividing by it.
double Dop853::weight(size_t i, double size) const {
  const double w = options_.atol + options_.rtol * size;
  if (!(w > 0.0))
    throw SimulationError(t_, fmt::format("dop853: y[{}] = 0 with atol = 0 leaves its error "
                                          "nothing to be relative to: give atol > 0",
                                          i));
  return w;
}

void Dop853::accept(double h, bool last, double h_next) {
  y_ = y_new_;
  t_ = last ? t_end_ : t_old_ + h;
  f(t_, y_.data(), k_[kStages]);
  test_stiffness(h);
  first_is_last_ = true;
  h_old_ = h;
  h_ = h_next;
  rejections_ = 0;
  dense_ready_ = false;
  ++stats_.steps;
}

// docs/theory.md §5.6, "Noticing stiffness during the run": stage 12 and the solution both sit
// at t + h, so h‖f(y₁) − f(Y₁₂)‖ / ‖y₁ − Y₁₂‖ estimates h·ρ along the difference (Hairer's
// dop853.f). Here every accepted step is tested (two sums of n terms).
void Dop853::test_stiffness(double h) {
  if (stiff()) return;
  double num = 0.0, den = 0.0;
  const std::vector<double>& f_new = k_[kStages];
  const std::vector<double>& f_stage = k_[kStages - 1];
  for (size_t i = 0; i < n_; ++i) {
    num += (f_new[i] - f_stage[i]) * (f_new[i] - f_stage[i]);
    den += (y_[i] - stage_[i]) * (y_[i] - stage_[i]);
  }
  if (!(den > 0.0)) return;
  if (h * std::sqrt(num / den) > kStabilityBoundary) {
    soft_tests_ = 0;
    if (++stiff_tests_ == kStiffSteps) stiff_since_ = t_;
  } else if (++soft_tests_ == kSoftSteps) {
    stiff_tests_ = 0;
  }
}

// Hairer's starting step: an Euler step of 0.01 in the scaled norm, refined by the change of f
// over it so that the first local error is about 0.01 (h⁸ ∼ 0.01 / ‖f'‖); at most 100 times
// the Euler guess and at most the whole interval.
double Dop853::initial_step() {
  const double span = t_end_ - t_;
  for (size_t i = 0; i < n_; ++i) scale_[i] = weight(i, std::abs(y_[i]));
  const double d0 = rms(y_, scale_), d1 = rms(k_[0], scale_);
  double h = (d0 < 1e-5 || d1 < 1e-5) ? 1e-6 : 0.01 * d0 / d1;
  h = std::min(h, span);
  for (size_t i = 0; i < n_; ++i) stage_[i] = y_[i] + h * k_[0][i];
  f(t_ + h, stage_.data(), k_[1]);
  for (size_t i = 0; i < n_; ++i) stage_[i] = k_[1][i] - k_[0][i];
  const double d2 = rms(stage_, scale_) / h;
  const double d12 = std::max(d2, d1);
  const double h1 = d12 <= 1e-15 ? std::max(1e-6, h * 1e-3) : std::pow(0.01 / d12, 0.125);
  return std::min({100.0 * h, h1, span});
}

// docs/theory.md §8, DOP853: y(t₀ + θh) = y₀ + θ(F₀ + (1−θ)(F₁ + θ(F₂ + (1−θ)(F₃ + θ(F₄ +
// (1−θ)(F₅ + θF₆)))))) with F₀ = Δy, F₁ = h f₀ − Δy, F₂ = 2Δy − h(f₀ + f₁) and
// F₃…F₆ = h Σⱼ dⱼ kⱼ over the 16 stages.
void Dop853::build_dense() {
  const double h = h_old_;
  for (size_t s = 0; s < table_.extra_c.size(); ++s) {
    stage_state(table_.extra_a[s], h);
    f(t_old_ + table_.extra_c[s] * h, stage_.data(), k_[kStages + 1 + s]);
  }
  const std::vector<double>& f0 = k_[0];
  const std::vector<double>& f1 = k_[kStages];
  for (size_t i = 0; i < n_; ++i) {
    const double dy = y_[i] - y_old_[i];
    dense_[0][i] = dy;
    dense_[1][i] = h * f0[i] - dy;
    dense_[2][i] = 2.0 * dy - h * (f0[i] + f1[i]);
  }
  for (size_t r = 0; r < table_.dense.size(); ++r) {
    std::vector<double>& out = dense_[3 + r];
    std::fill(out.begin(), out.end(), 0.0);
    for (size_t j = 0; j < kAllStages; ++j) {
      const double w = table_.dense[r][j];
      if (w == 0.0) continue;
      for (size_t i = 0; i < n_; ++i) out[i] += h * w * k_[j][i];
    }
  }
  dense_ready_ = true;
}

IntegratorStats integrate_dop853(const OdeProblem& problem, const IntegratorOptions& options,
                                 const OutputGrid& grid, std::vector<double>& y,
                                 const Observer& observer, Handover* handover) {
  Dop853 method(problem, options, y, grid.time(grid.intervals()));
  size_t sample = 0;
  // With a handover, a sample observed once the stiffness test has concluded is the last.
  const Observer watch = [&](double t, double* yy, double* yp) {
    const ObserverAction action = observer ? observer(t, yy, yp) : ObserverAction::Continue;
    const size_t k = sample++;
    if (action != ObserverAction::Continue || !method.stiff() || k == grid.intervals())
      return action;
    *handover = {true, method.stiff_since(), k, std::vector<double>(yy, yy + y.size())};
    return ObserverAction::Stop;
  };
  method.start(grid.time(0), false);
  StepBudget budget(options.max_steps);
  double t_reached = grid.time(0);
  const auto step = [&](double t_next) {
    budget.spend(t_next, t_reached, "dop853", "TOO_MUCH_WORK");
    t_reached = method.step();
    return t_reached;
  };
  const auto interpolate = [&](double t, double* out) { method.interpolate(t, out); };
  // A correction after a step keeps the step size (f is evaluated at the corrected state); a new
  // state from the observer starts afresh, as a run from there would.
  const auto restart = [&](double t, bool keep_step) {
    t_reached = t;
    method.start(t, keep_step);
  };
  keeping_stats(
      [&] {
        walk_dense(grid, handover ? watch : observer, options.after_step, false, y, step,
                   interpolate, restart);
      },
      [&] { return method.stats(); });
  return method.stats();
}

}  // namespace lagrange::integration

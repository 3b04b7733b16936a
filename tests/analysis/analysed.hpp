#pragma once
// A model derived, compiled and differentiated, at its consistent initial state: what the
// analysis tests start from.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "lagrange/analysis.hpp"
#include "lagrange/reader.hpp"
#include "support/harness.hpp"

namespace lagrange::testing {

struct Analysed {
  std::unique_ptr<Model> model;  // on the heap: `eq` points into it
  Equations eq;
  std::shared_ptr<const CompiledModel> cm;
  std::unique_ptr<Dynamics> dyn;
  std::unique_ptr<DynamicsJacobian> jac;
  std::vector<double> q, v;

  /// Set a plain coordinate's value and make the state consistent again.
  void set(const std::string& name, double value) {
    const auto it = std::find(cm->coordinate_names.begin(), cm->coordinate_names.end(), name);
    if (it == cm->coordinate_names.end()) throw std::invalid_argument("no coordinate " + name);
    q[static_cast<size_t>(it - cm->coordinate_names.begin())] = value;
    if (cm->m > 0) dyn->project(0.0, q.data(), v.data(), cm->fixed);
  }
  LinearModel linear(const std::vector<std::string>& outputs = {}) {
    return linearize(*jac, *dyn, 0.0, q.data(), v.data(), outputs);
  }
};

/// `model` analysed with derivatives with respect to `inputs` (model inputs or parameters).
inline Analysed analyse(std::unique_ptr<Model> model, const std::vector<std::string>& inputs = {},
                        const std::vector<std::string>& outputs = {}) {
  Analysed a;
  a.model = std::move(model);
  a.eq = derive(*a.model);
  a.cm = compile(a.eq);
  a.dyn = std::make_unique<Dynamics>(a.cm, a.cm->parameter_defaults);
  a.dyn->set_baumgarte(baumgarte_rate(a.model->stabilization, a.model->simulate.integrator));
  a.jac = std::make_unique<DynamicsJacobian>(a.eq, a.cm, inputs, outputs);
  a.q = a.cm->q0;
  a.v = a.cm->v0;
  if (a.cm->m > 0) a.dyn->project(0.0, a.q.data(), a.v.data(), a.cm->fixed);
  return a;
}

inline Analysed analyse_example(const std::string& name,
                                const std::vector<std::string>& inputs = {}) {
  return analyse(std::make_unique<Model>(read_model_file(example_path(name))), inputs);
}

inline Analysed analyse_string(const std::string& yaml, const std::vector<std::string>& inputs = {},
                               const std::vector<std::string>& outputs = {}) {
  return analyse(std::make_unique<Model>(read_model_string(yaml, "<test>")), inputs, outputs);
}

/// The reference an implicit method is checked against: DOP853 at rtol 1e-12 over `so`'s span and
/// output grid, from the analysed start (its method and tolerances are set here).
inline Trajectory dop853_reference(Analysed& s, SimulationOptions so) {
  so.integrator.method = "dop853";
  so.integrator.rtol = 1e-12;
  so.integrator.atol = 1e-14;
  s.dyn->set_baumgarte(baumgarte_rate(s.model->stabilization, "dop853"));
  return simulate(*s.dyn, so, s.q, s.v);
}

/// The largest difference of any coordinate at any sample of two runs on the same grid.
inline double worst_coordinate_difference(const Analysed& s, const Trajectory& a,
                                          const Trajectory& b) {
  double worst = 0.0;
  for (size_t r = 0; r < a.rows() && r < b.rows(); ++r)
    for (const std::string& name : s.cm->coordinate_names)
      worst = std::max(worst, std::abs(a.at(r, name) - b.at(r, name)));
  return worst;
}

/// One run of an implicit method (cvode:jacobian or ida:jacobian, on `s`'s exact Jacobian) at
/// rtol (atol = rtol·1e-2) and BDF order at most max_order on `so`'s grid against `ref`: its
/// steps and worst coordinate error.
struct OrderPoint {
  long steps = 0;
  double error = 0.0;
};

inline OrderPoint implicit_run(Analysed& s, SimulationOptions so, const std::string& method,
                               double rtol, int max_order, const Trajectory& ref) {
  so.integrator.method = method;
  so.integrator.max_order = max_order;
  so.integrator.rtol = rtol;
  so.integrator.atol = rtol * 1e-2;
  s.dyn->set_baumgarte(baumgarte_rate(s.model->stabilization, method));
  std::vector<double> y0 = s.q;
  y0.insert(y0.end(), s.v.begin(), s.v.end());
  if (method == "cvode:jacobian") so.jacobian = ode_jacobian(*s.jac, *s.dyn, so.t0, y0);
  so.jacobian_source.dae = [&s](Dynamics& dyn, double t0, const std::vector<double>& y) {
    return dae_jacobian(*s.jac, dyn, t0, y);
  };
  const Trajectory tr = simulate(*s.dyn, so, s.q, s.v);
  if (tr.status != Trajectory::Status::Complete || tr.rows() != ref.rows())
    throw std::runtime_error(method + " failed: " + tr.message);
  return {tr.stats.steps, worst_coordinate_difference(s, tr, ref)};
}

/// The order p of error ∝ steps^(−p): the least-squares slope of log error against log steps
/// over `runs` (docs/theory.md §5.8).
inline double fitted_order(const std::vector<OrderPoint>& runs) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double n = static_cast<double>(runs.size());
  for (const OrderPoint& r : runs) {
    const double x = std::log(static_cast<double>(r.steps)), y = std::log(r.error);
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
  }
  return -(n * sxy - sx * sy) / (n * sxx - sx * sx);
}

/// implicit_run of `example` over 2 s with samples every output_step at each of `rtols`, against
/// DOP853 at rtol 1e-12.
inline std::vector<OrderPoint> implicit_runs(const std::string& example, const std::string& method,
                                             int max_order, const std::vector<double>& rtols,
                                             double output_step) {
  Analysed s = analyse_example(example);
  SimulationOptions so;
  so.t_end = 2.0;
  so.output_step = output_step;
  const Trajectory ref = dop853_reference(s, so);
  std::vector<OrderPoint> runs;
  for (double rtol : rtols) runs.push_back(implicit_run(s, so, method, rtol, max_order, ref));
  return runs;
}

/// Decade-spaced rtols at which BDF held at order k (1 to 3) is in its asymptotic range on the
/// pendulums over 2 s, at a few thousand steps at most.
inline std::vector<double> order_tolerances(int k) {
  if (k == 1) return {1e-3, 1e-4, 1e-5};
  if (k == 2) return {1e-4, 1e-5, 1e-6, 1e-7};
  return {1e-4, 1e-5, 1e-6, 1e-7, 1e-8};
}

/// docs/theory.md §5.8: `method` held at order k = 1, 2, 3 on `example` converges at order k —
/// the fitted slope of error against steps lies in [k − 0.4, k + 0.7].
inline void expect_fixed_order_convergence(const std::string& example, const std::string& method,
                                           double output_step) {
  for (int k : {1, 2, 3}) {
    const double p =
        fitted_order(implicit_runs(example, method, k, order_tolerances(k), output_step));
    EXPECT_GT(p, k - 0.4) << example << ", " << method << ", order " << k;
    EXPECT_LT(p, k + 0.7) << example << ", " << method << ", order " << k;
  }
}

/// At the default (variable order up to 5) the error of `method` on the double pendulum follows
/// the tolerance: 100 times tighter, 10 to 1000 times smaller.
inline void expect_error_follows_tolerance(const std::string& method) {
  const auto runs = implicit_runs("double_pendulum.yaml", method, 5, {1e-4, 1e-6, 1e-8}, 0.05);
  for (size_t i = 0; i + 1 < runs.size(); ++i) {
    EXPECT_GT(runs[i].error / runs[i + 1].error, 10.0) << method << ", " << i;
    EXPECT_LT(runs[i].error / runs[i + 1].error, 1000.0) << method << ", " << i;
  }
}

}  // namespace lagrange::testing

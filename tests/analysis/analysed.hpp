#pragma once
// A model derived, compiled and differentiated, at its consistent initial state: what the
// analysis tests start from.

#include <algorithm>
#include <cmath>
#include <memory>
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

}  // namespace lagrange::testing

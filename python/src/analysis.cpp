#include "analysis.hpp"

#include <pybind11/complex.h>
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "analysis/jacobian_limit.hpp"
#include "arrays.hpp"
#include "cli/commands.hpp"
#include "cli/trim_setup.hpp"
#include "lagrange/analysis.hpp"

namespace py = pybind11;

namespace lagrange::python {

namespace {

/// The Lagrangian form of a loaded model (the exact Jacobians need it; a model loaded in the
/// recursive form is derived again, once per call), with a workspace at the model's parameters.
struct LagrangianForm {
  std::shared_ptr<const Equations> equations;
  std::shared_ptr<const CompiledModel> compiled;
  std::unique_ptr<Dynamics> dynamics;
};

LagrangianForm lagrangian_form(const cli::Prepared& p) {
  LagrangianForm f;
  if (p.equations.recursive) {
    f.equations = std::make_shared<const Equations>(derive(*p.model, Formulation::Lagrangian));
    f.compiled = compile(*f.equations);
  } else {
    f.equations = std::shared_ptr<const Equations>(&p.equations, [](const Equations*) {});
    f.compiled = p.compiled;
  }
  f.dynamics = std::make_unique<Dynamics>(f.compiled, p.dynamics->parameters());
  f.dynamics->set_baumgarte(p.dynamics->baumgarte());
  return f;
}

/// The operating point: the model's consistent initial state, or the caller's (q, v) made
/// consistent with the constraints as a run's start is.
void operating_point(const cli::Prepared& p, Dynamics& dyn, double t,
                     const std::optional<py::object>& q_in, const std::optional<py::object>& v_in,
                     std::vector<double>& q, std::vector<double>& v) {
  const CompiledModel& cm = dyn.model();
  q = p.q;
  v = p.v;
  if (q_in && !q_in->is_none()) {
    const DoubleArray a = q_in->cast<DoubleArray>();
    const double* d = vector_data(a, cm.nq, "q");
    q.assign(d, d + cm.nq);
  }
  if (v_in && !v_in->is_none()) {
    const DoubleArray a = v_in->cast<DoubleArray>();
    const double* d = vector_data(a, cm.nv, "v");
    v.assign(d, d + cm.nv);
  }
  if (cm.m == 0 || (!q_in && !v_in)) return;
  const InitialConsistency ic = make_initial_state_consistent(dyn, t, q, v);
  if (!ic.consistent)
    throw py::value_error("the operating point cannot be put on the constraints: " + ic.note());
}

/// Parameters and model inputs at the caller's `values` in `dyn` (inputs held, as a trimmed input
/// is); a name that is neither is a ValueError listing both.
void apply_values(Dynamics& dyn, const std::map<std::string, double>& values) {
  const CompiledModel& cm = dyn.model();
  std::vector<double> params = dyn.parameters();
  const auto index = [](const std::vector<std::string>& names, const std::string& name) {
    return static_cast<size_t>(std::find(names.begin(), names.end(), name) - names.begin());
  };
  const auto listed = [](const std::vector<std::string>& names) {
    std::string out;
    for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
    return out.empty() ? std::string("none") : out;
  };
  for (const auto& [name, value] : values) {
    if (!std::isfinite(value))
      throw py::value_error("values: expected a finite number for '" + name + "'");
    if (const size_t i = index(cm.parameter_names, name); i < cm.parameter_names.size()) {
      params[i] = value;
    } else if (const size_t j = index(cm.input_names, name); j < cm.input_names.size()) {
      dyn.hold_input(j, value);
    } else {
      throw py::value_error("values: no parameter or model input '" + name +
                            "' (parameters: " + listed(cm.parameter_names) +
                            "; inputs: " + listed(cm.input_names) + ")");
    }
  }
  if (params != dyn.parameters()) dyn.set_parameters(params);
}

py::object mode_dicts(const std::vector<Mode>& ms) {
  py::list out;
  for (const Mode& mode : ms) {
    py::list shape;
    for (const auto& c : mode.shape) shape.append(py::make_tuple(c.name, c.magnitude, c.phase_deg));
    out.append(py::dict(py::arg("eigenvalue") = mode.eigenvalue,
                        py::arg("frequency_hz") = mode.frequency_hz,
                        py::arg("damping") = mode.damping,
                        py::arg("time_constant") = mode.time_constant, py::arg("shape") = shape));
  }
  return std::move(out);
}

py::object namespace_of(const py::dict& fields) {
  return py::module_::import("types").attr("SimpleNamespace")(**fields);
}

}  // namespace

// docs/theory.md §5.3–5.4 through the library: the CLI's `linearize` and this share linearize(),
// modes() and discretize().
py::object linearize_model(const PyModel& m, std::optional<py::object> q_in,
                           std::optional<py::object> v_in, const std::vector<std::string>& inputs,
                           const std::vector<std::string>& outputs, std::optional<double> discrete,
                           double t, const std::map<std::string, double>& values,
                           const TrimFirst& first) {
  if (discrete && !(*discrete > 0)) throw py::value_error("discrete: expected a positive dt");
  if (!first.at_trim && (!first.free.empty() || !first.fix.empty() || !first.steady.empty()))
    throw py::value_error("free, fix and steady choose what trim varies: give at_trim=True too");
  const cli::Prepared& p = *m.prepared;
  LagrangianForm f = lagrangian_form(p);
  std::vector<std::string> model_outputs;  // only the named model outputs are differentiated
  for (const auto& name : outputs)
    if (std::count(f.compiled->output_names.begin(), f.compiled->output_names.end(), name) &&
        !std::count(model_outputs.begin(), model_outputs.end(), name))
      model_outputs.push_back(name);
  std::unique_ptr<DynamicsJacobian> jac;
  try {
    jac = std::make_unique<DynamicsJacobian>(*f.equations, f.compiled, inputs, model_outputs);
  } catch (const std::invalid_argument& e) {
    throw py::value_error(std::string("inputs: ") + e.what());
  }
  apply_values(*f.dynamics, values);
  std::vector<double> q, v;
  operating_point(p, *f.dynamics, t, q_in, v_in, q, v);
  py::object trimmed = py::none();
  if (first.at_trim) {  // as run_linearize: trim on the same Jacobian, free inputs held after it
    cli::Options opt;
    opt.free = first.free;
    opt.fix = first.fix;
    opt.steady = first.steady;
    opt.tol = first.tol;
    const TrimOptions options = cli::trim_options(*f.compiled, q, v, opt, jac->input_names());
    const TrimResult r = trim(*jac, *f.dynamics, t, q, v, options);
    q = r.q;
    v = r.v;
    py::dict found;
    for (size_t k = 0, j = 0; j < options.free_inputs.size(); ++j)
      if (options.free_inputs[j]) found[py::str(jac->input_names()[j])] = r.inputs[k++];
    trimmed = namespace_of(
        py::dict(py::arg("iterations") = r.iterations, py::arg("residual") = r.residual,
                 py::arg("tolerance") = r.tolerance, py::arg("inputs") = found,
                 py::arg("steady") = !first.steady.empty(), py::arg("drift") = r.drift));
  }
  LinearModel lin;
  try {
    lin = linearize(*jac, *f.dynamics, t, q.data(), v.data(), outputs);
  } catch (const std::invalid_argument& e) {
    throw py::value_error(std::string("outputs: ") + e.what());
  }
  const std::vector<Mode> ms = modes(lin);
  if (discrete) lin = discretize(lin, *discrete);
  return namespace_of(py::dict(
      py::arg("A") = lin.A, py::arg("B") = lin.B, py::arg("C") = lin.C, py::arg("D") = lin.D,
      py::arg("states") = lin.state_names, py::arg("inputs") = lin.input_names,
      py::arg("outputs") = lin.output_names, py::arg("dt") = lin.dt,
      py::arg("modes") = mode_dicts(ms), py::arg("full_states") = lin.full_state_names,
      py::arg("basis") = lin.basis, py::arg("dependent") = lin.dependent,
      py::arg("equilibrium_residual") = lin.equilibrium_residual, py::arg("q") = to_array(q),
      py::arg("v") = to_array(v), py::arg("trim") = trimmed));
}

// docs/theory.md §5.5 through the library, as `lagrange trim` (the same option handling,
// cli::trim_options; its usage errors become ValueError).
py::object trim_model(const PyModel& m, std::optional<py::object> q_in,
                      const std::vector<std::string>& free, const std::vector<std::string>& fix,
                      double tol, int max_iterations, double t,
                      const std::vector<std::string>& steady, std::optional<py::object> v_in) {
  const cli::Prepared& p = *m.prepared;
  LagrangianForm f = lagrangian_form(p);
  std::vector<double> q, v;
  operating_point(p, *f.dynamics, t, q_in, v_in, q, v);
  const CompiledModel& cm = *f.compiled;
  cli::Options opt;
  opt.free = free;
  opt.fix = fix;
  opt.steady = steady;
  opt.tol = tol;
  const std::vector<std::string> inputs = cli::trim_inputs(cm, opt);
  TrimOptions options = cli::trim_options(cm, q, v, opt, inputs);
  options.max_iterations = max_iterations;
  const DynamicsJacobian jac(*f.equations, f.compiled, inputs);
  const TrimResult r = trim(jac, *f.dynamics, t, q, v, options);
  py::dict found;  // the free parameters' or inputs' values
  for (size_t k = 0, j = 0; j < inputs.size(); ++j)
    if (options.free_inputs[j]) found[py::str(inputs[j])] = r.inputs[k++];
  return namespace_of(
      py::dict(py::arg("q") = to_array(r.q), py::arg("v") = to_array(r.v),
               py::arg("coordinates") = cm.coordinate_names, py::arg("iterations") = r.iterations,
               py::arg("residual") = r.residual, py::arg("tolerance") = r.tolerance,
               py::arg("not_isolated") = r.not_isolated, py::arg("inputs") = found,
               py::arg("drift") = r.drift, py::arg("pseudo_transient") = r.pseudo_transient));
}

// docs/theory.md §5.1 through the library: DynamicsJacobian::evaluate and ::implicit.
py::object jacobian_model(const PyModel& m, std::optional<py::object> q_in,
                          std::optional<py::object> v_in, const std::vector<std::string>& inputs,
                          double t) {
  const cli::Prepared& p = *m.prepared;
  LagrangianForm f = lagrangian_form(p);
  std::unique_ptr<DynamicsJacobian> jac;
  try {
    jac = std::make_unique<DynamicsJacobian>(*f.equations, f.compiled, inputs);
  } catch (const std::invalid_argument& e) {
    throw py::value_error(std::string("inputs: ") + e.what());
  }
  std::vector<double> q, v;
  operating_point(p, *f.dynamics, t, q_in, v_in, q, v);
  const StateJacobian J = jac->evaluate(*f.dynamics, t, q.data(), v.data());
  // The implicit form's ∂Φ/∂x with a removable 0/0 (drag at rest) as its limit, as evaluate's.
  const ImplicitJacobian I = jac->implicit(*f.dynamics, t, q.data(), v.data());
  Eigen::MatrixXd Phi_x(I.Phi_x);
  std::vector<double> y = q;
  y.insert(y.end(), v.begin(), v.end());
  analysis_detail::fill_limits(
      {&Phi_x},
      [&](const double* moved) {
        return std::vector<Eigen::MatrixXd>{
            Eigen::MatrixXd(jac->implicit(*f.dynamics, t, moved, moved + q.size()).Phi_x)};
      },
      y.data(), y.size(), t);
  return namespace_of(
      py::dict(py::arg("a") = J.a, py::arg("qdot") = J.qdot, py::arg("lam") = J.lambda,
               py::arg("a_q") = J.a_q, py::arg("a_v") = J.a_v, py::arg("a_w") = J.a_w,
               py::arg("qdot_q") = J.qdot_q, py::arg("qdot_v") = J.qdot_v, py::arg("G") = J.G,
               py::arg("C_q") = J.C_q, py::arg("inputs") = jac->input_names(),
               py::arg("K") = Eigen::MatrixXd(I.K), py::arg("Phi_x") = Phi_x,
               py::arg("nonzeros") = jac->nonzeros(), py::arg("q") = to_array(q),
               py::arg("v") = to_array(v)));
}

}  // namespace lagrange::python

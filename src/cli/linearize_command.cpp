// `lagrange linearize MODEL [--at …|--at-trim …] [--inputs …] [--outputs …] [--format …]
// [--discrete DT]` (README.md, "Linearise and trim"): A, B, C, D on the constraint manifold and
// the modes, at the given state or at the equilibrium or steady state trim finds from it.

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "cli/commands.hpp"
#include "cli/prepare.hpp"
#include "cli/trim_setup.hpp"
#include "lagrange/analysis.hpp"

namespace lagrange::cli {

namespace {

// Text and CSV print matrices up to this many columns; larger ones only in JSON or CSV.
constexpr long kTextMatrixLimit = 24;

std::string join(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
  return s;
}

std::string text_matrix(const std::string& title, const Eigen::MatrixXd& X,
                        const std::vector<std::string>& rows,
                        const std::vector<std::string>& cols) {
  if (X.size() == 0) return fmt::format("{} ({}×{}): empty\n", title, X.rows(), X.cols());
  if (X.cols() > kTextMatrixLimit || X.rows() > 4 * kTextMatrixLimit)
    return fmt::format("{} ({}×{}): too large for text; use --format csv or json\n", title,
                       X.rows(), X.cols());
  size_t w = 0, cw = 12;
  for (const auto& r : rows) w = std::max(w, r.size());
  for (const auto& c : cols) cw = std::max(cw, c.size());
  std::string out = fmt::format("{} ({}×{})\n  {:<{}}", title, X.rows(), X.cols(), "", w);
  for (const auto& c : cols) out += fmt::format(" {:>{}}", c, cw);
  out += "\n";
  for (long i = 0; i < X.rows(); ++i) {
    out += fmt::format("  {:<{}}", rows[static_cast<size_t>(i)], w);
    for (long j = 0; j < X.cols(); ++j) out += fmt::format(" {:>{}.6g}", X(i, j) + 0.0, cw);
    out += "\n";
  }
  return out;
}

std::string csv_matrix(const std::string& title, const Eigen::MatrixXd& X,
                       const std::vector<std::string>& rows, const std::vector<std::string>& cols) {
  std::string out = title;
  for (const auto& c : cols) out += "," + c;
  out += "\n";
  for (long i = 0; i < X.rows(); ++i) {
    out += rows[static_cast<size_t>(i)];
    for (long j = 0; j < X.cols(); ++j) out += fmt::format(",{:.17g}", X(i, j) + 0.0);
    out += "\n";
  }
  return out + "\n";
}

std::string eigenvalue_text(std::complex<double> z) {
  if (z.imag() == 0.0) return fmt::format("{:.6g}", z.real() + 0.0);
  return fmt::format("{:.6g} ± {:.6g}i", z.real() + 0.0, z.imag());
}

std::string shape_text(const Mode& mode) {
  std::string s;
  for (const auto& c : mode.shape)
    s += fmt::format("{}{} {:.3g}{}", s.empty() ? "" : ", ", c.name, c.magnitude,
                     std::abs(c.phase_deg) > 0.5 ? fmt::format("∠{:.0f}°", c.phase_deg) : "");
  return s;
}

// What the text output says about an operating point that came from trim.
struct TrimmedAt {
  const TrimResult* result = nullptr;
  bool steady = false;
  double tol = 0.0;
  std::vector<std::pair<std::string, double>> inputs;  ///< the free inputs trim found
};

std::string format_text(const Prepared& p, const LinearModel& lin, const std::vector<Mode>& ms,
                        const TrimmedAt& trimmed) {
  const CompiledModel& cm = *p.compiled;
  std::string out = fmt::format("{}: linearised at t = 0{}\n", p.model->name,
                                lin.dt > 0 ? fmt::format(", zero-order hold dt = {}", lin.dt) : "");
  if (trimmed.result)
    out += fmt::format("operating point from trim: {}\n",
                       trim_summary(*trimmed.result, trimmed.steady, trimmed.tol));
  std::string point;
  for (size_t i = 0; i < cm.plain; ++i)
    point +=
        fmt::format("{}{} = {:.9g}", point.empty() ? "" : ", ", cm.coordinate_names[i], p.q[i]);
  for (size_t i = 0; i < cm.plain; ++i)
    if (p.v[i] != 0.0) point += fmt::format(", {} = {:.9g}", cm.velocity_names[i], p.v[i]);
  for (const auto& [name, value] : trimmed.inputs)
    point += fmt::format("{}{} = {:.9g}", point.empty() ? "" : ", ", name, value);
  if (!point.empty()) out += "operating point: " + point + "\n";
  if (trimmed.steady)
    out +=
        "note: a steady motion (held rates): A, B describe perturbations of the state about it\n";
  else if (lin.equilibrium_residual >  // held to trim's own tolerance when trim found the point
           (trimmed.result ? std::max(1e-8, trimmed.result->tolerance) : 1e-8))
    out += fmt::format(
        "note: not an equilibrium (max |q_dot|, |acceleration| = {:.3g}): a first-order Taylor "
        "approximation; `lagrange trim` finds an equilibrium\n",
        lin.equilibrium_residual);
  if (!lin.dependent.empty())
    out += fmt::format(
        "on the constraint manifold: {} (and their rates) follow from the states below\n",
        join(lin.dependent));
  out += fmt::format("states ({}): {}\n", lin.state_names.size(), join(lin.state_names));
  out += fmt::format("inputs ({}): {}\n", lin.input_names.size(),
                     lin.input_names.empty() ? "none" : join(lin.input_names));
  out += fmt::format("outputs ({}): {}\n", lin.output_names.size(), join(lin.output_names));
  out += text_matrix("A", lin.A, lin.state_names, lin.state_names);
  if (!lin.input_names.empty()) out += text_matrix("B", lin.B, lin.state_names, lin.input_names);
  out += text_matrix("C", lin.C, lin.output_names, lin.state_names);
  if (!lin.input_names.empty()) out += text_matrix("D", lin.D, lin.output_names, lin.input_names);
  if (lin.dt > 0) {
    out += "eigenvalues of A (discrete):";
    Eigen::EigenSolver<Eigen::MatrixXd> es(lin.A, false);
    for (long k = 0; k < lin.A.rows(); ++k)
      if (es.eigenvalues()[k].imag() >= 0) out += " " + eigenvalue_text(es.eigenvalues()[k]);
    out += "\n";
  }
  out += "modes (continuous time)\n";
  out += fmt::format("  {:<26} {:>12} {:>10} {:>14}  {}\n", "eigenvalue [1/s]", "freq [Hz]",
                     "damping", "time const [s]", "shape (largest components)");
  for (const Mode& m : ms)
    out +=
        fmt::format("  {:<26} {:>12.6g} {:>10.4g} {:>14.6g}  {}\n", eigenvalue_text(m.eigenvalue),
                    m.frequency_hz, m.damping, m.time_constant, shape_text(m));
  if (!p.initial.was_consistent) out += fmt::format("note: {}\n", p.initial.note());
  return out;
}

nlohmann::json json_matrix(const Eigen::MatrixXd& X) {
  nlohmann::json rows = nlohmann::json::array();
  for (long i = 0; i < X.rows(); ++i) {
    nlohmann::json row = nlohmann::json::array();
    for (long j = 0; j < X.cols(); ++j) row.push_back(X(i, j) + 0.0);
    rows.push_back(row);
  }
  return rows;
}

std::string format_json(const Prepared& p, const LinearModel& lin, const std::vector<Mode>& ms,
                        const TrimmedAt& trimmed) {
  const CompiledModel& cm = *p.compiled;
  nlohmann::json j;
  j["name"] = p.model->name;
  if (trimmed.result)
    j["trim"] = {{"steady", trimmed.steady},
                 {"iterations", trimmed.result->iterations},
                 {"residual", trimmed.result->residual},
                 {"drift", trimmed.result->drift},
                 {"inputs", nlohmann::json::object()}};
  for (const auto& [name, value] : trimmed.inputs) j["trim"]["inputs"][name] = value;
  j["t"] = 0.0;
  j["dt"] = lin.dt;
  j["coordinates"] = cm.coordinate_names;
  j["velocities"] = cm.velocity_names;
  j["q"] = p.q;
  j["v"] = p.v;
  j["equilibrium_residual"] = lin.equilibrium_residual;
  j["dependent"] = lin.dependent;
  j["states"] = lin.state_names;
  j["inputs"] = lin.input_names;
  j["outputs"] = lin.output_names;
  j["A"] = json_matrix(lin.A);
  j["B"] = json_matrix(lin.B);
  j["C"] = json_matrix(lin.C);
  j["D"] = json_matrix(lin.D);
  j["full_states"] = lin.full_state_names;
  j["basis"] = json_matrix(lin.basis);
  // The modes are A's before --discrete (its eigenvalues s, not z = exp(s dt)).
  j["modes_time"] = "continuous";
  j["modes"] = nlohmann::json::array();
  for (const Mode& m : ms) {
    nlohmann::json mode{
        {"re", m.eigenvalue.real()},
        {"im", m.eigenvalue.imag()},
        {"frequency_hz", m.frequency_hz},
        {"damping", m.damping},
        {"time_constant", std::isfinite(m.time_constant) ? nlohmann::json(m.time_constant)
                                                         : nlohmann::json(nullptr)}};
    mode["shape"] = nlohmann::json::array();
    for (const auto& c : m.shape)
      mode["shape"].push_back(
          {{"name", c.name}, {"magnitude", c.magnitude}, {"phase_deg", c.phase_deg}});
    j["modes"].push_back(mode);
  }
  return j.dump(2) + "\n";
}

std::string format_csv(const LinearModel& lin, const std::vector<Mode>& ms) {
  std::string out = csv_matrix("A", lin.A, lin.state_names, lin.state_names);
  out += csv_matrix("B", lin.B, lin.state_names, lin.input_names);
  out += csv_matrix("C", lin.C, lin.output_names, lin.state_names);
  out += csv_matrix("D", lin.D, lin.output_names, lin.input_names);
  out += "mode,re,im,frequency_hz,damping,time_constant\n";
  for (size_t k = 0; k < ms.size(); ++k)
    out += fmt::format("{},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g}\n", k + 1,
                       ms[k].eigenvalue.real(), ms[k].eigenvalue.imag(), ms[k].frequency_hz,
                       ms[k].damping, ms[k].time_constant);
  return out;
}

}  // namespace

int run_linearize(const Options& opt) {
  if (opt.discrete && !(*opt.discrete > 0 && std::isfinite(*opt.discrete)))
    throw UsageError(
        fmt::format("--discrete expects a positive sampling time, got {}", *opt.discrete));
  Prepared p = prepare(opt.model, opt.sets, opt.initial, "--at", "lagrangian");
  std::unique_ptr<DynamicsJacobian> jac;
  try {
    // Only the named model outputs are differentiated (a tether's per-segment outputs cost).
    std::vector<std::string> model_outputs;
    for (const auto& name : opt.outputs)
      if (std::count(p.compiled->output_names.begin(), p.compiled->output_names.end(), name) &&
          !std::count(model_outputs.begin(), model_outputs.end(), name))
        model_outputs.push_back(name);
    jac = std::make_unique<DynamicsJacobian>(p.equations, p.compiled, opt.inputs, model_outputs);
  } catch (const std::invalid_argument& e) {
    throw UsageError(fmt::format("--inputs: {}", e.what()));
  }
  TrimResult trimmed;
  TrimmedAt at;
  if (opt.at_trim) {
    const TrimOptions options = trim_options(*p.compiled, p.q, p.v, opt, jac->input_names());
    trimmed = trim_prepared(p, *jac, options);
    at = {&trimmed, !opt.steady.empty(), opt.tol, {}};
    for (size_t w = 0, k = 0; w < options.free_inputs.size(); ++w)
      if (options.free_inputs[w])
        at.inputs.emplace_back(jac->input_names()[w], trimmed.inputs[k++]);
  } else if (!opt.free.empty() || !opt.fix.empty() || !opt.steady.empty()) {
    throw UsageError("--free, --fix and --steady choose what trim varies: give --at-trim too");
  }
  LinearModel lin;
  try {
    lin = linearize(*jac, *p.dynamics, 0.0, p.q.data(), p.v.data(), opt.outputs);
  } catch (const std::invalid_argument& e) {
    throw UsageError(fmt::format("--outputs: {}", e.what()));
  }
  const std::vector<Mode> ms = modes(lin);
  if (opt.discrete) lin = discretize(lin, *opt.discrete);
  if (opt.format == "json")
    fmt::print("{}", format_json(p, lin, ms, at));
  else if (opt.format == "csv")
    fmt::print("{}", format_csv(lin, ms));
  else
    fmt::print("{}", format_text(p, lin, ms, at));
  return 0;
}

}  // namespace lagrange::cli

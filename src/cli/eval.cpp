// `lagrange eval MODEL --state q1=…,q1_dot=… [--tau q1=…]` (README.md, "Command line"): the mass
// matrix, the bias forces, the accelerations and, for manipulators, the joint forces of inverse
// dynamics at one state — how a model is checked against another tool.

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <nlohmann/json.hpp>

#include "cli/commands.hpp"
#include "cli/prepare.hpp"
#include "lagrange/tape.hpp"

namespace lagrange::cli {

namespace {

/// Everything eval prints, at one state.
struct StateEvaluation {
  Eigen::MatrixXd M;
  Eigen::VectorXd bias, forces, qddot, lambda, tau_inverse;
  bool given_tau = false, manipulator = false;
};

/// M (full), h and Q of `eq` at the dynamics tape inputs `in` (t, q, v, u, p).
void mass_and_forces(const Equations& eq, const std::vector<double>& in, StateEvaluation& e) {
  const size_t n = eq.nv;
  std::vector<GiNaC::ex> out;
  for (size_t i = 0; i < n; ++i)
    for (size_t j = 0; j < n; ++j) out.push_back(eq.M(i, j));
  for (size_t i = 0; i < n; ++i) out.push_back(eq.h[i]);
  for (size_t i = 0; i < n; ++i) out.push_back(eq.Q[i]);
  const Tape tape = Tape::compile(out, eq.tape_inputs());
  std::vector<double> values(tape.num_outputs()), work(tape.work_size());
  tape.eval(in.data(), values.data(), work.data());
  e.M = Eigen::Map<const Eigen::MatrixXd>(values.data(), static_cast<Eigen::Index>(n),
                                          static_cast<Eigen::Index>(n))
            .transpose();
  // −h + 0 prints 0 rather than −0 where h vanishes.
  e.bias = (-Eigen::Map<const Eigen::VectorXd>(values.data() + n * n, static_cast<Eigen::Index>(n)))
               .array() +
           0.0;
  e.forces =
      Eigen::Map<const Eigen::VectorXd>(values.data() + n * n + n, static_cast<Eigen::Index>(n));
}

/// `--tau NAME=VALUE`: the generalised force on each named coordinate, 0 on the others.
Eigen::VectorXd given_forces(const CompiledModel& cm, const std::vector<std::string>& args) {
  Eigen::VectorXd tau = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(cm.nv));
  for (const auto& [name, value] : parse_assignments(args, "--tau")) {
    const auto it = std::find(cm.coordinate_names.begin(),
                              cm.coordinate_names.begin() + static_cast<long>(cm.plain), name);
    if (it == cm.coordinate_names.begin() + static_cast<long>(cm.plain))
      throw UsageError(fmt::format("--tau: no coordinate '{}' in the model", name));
    tau[it - cm.coordinate_names.begin()] = value;
  }
  return tau;
}

StateEvaluation evaluate(Prepared& p, const Options& opt) {
  const CompiledModel& cm = *p.compiled;
  const size_t n = cm.nv;
  StateEvaluation e;
  std::vector<double> qdot(cm.nq), a(n), lambda(cm.m);
  p.dynamics->forward(0.0, p.q.data(), p.v.data(), qdot.data(), a.data(), lambda.data());
  mass_and_forces(p.equations, p.dynamics->last_inputs(), e);
  e.qddot = Eigen::Map<const Eigen::VectorXd>(a.data(), static_cast<Eigen::Index>(n));
  e.lambda = Eigen::Map<const Eigen::VectorXd>(lambda.data(), static_cast<Eigen::Index>(cm.m));
  e.manipulator = cm.m == 0 && cm.plain == cm.nq && cm.nq == cm.nv;
  if (!opt.tau.empty()) {
    if (!e.manipulator)
      throw UsageError(
          "--tau needs an unconstrained model of plain coordinates (a manipulator); this one "
          "has constraints or free bodies");
    e.forces = given_forces(cm, opt.tau);
    e.given_tau = true;
    e.qddot = e.M.llt().solve(e.forces - e.bias);
  }
  // Inverse dynamics τ = D(q) q̈ + C(q, q̇) q̇ + g(q) (docs/theory.md §4.8).
  if (e.manipulator) e.tau_inverse = e.M * e.qddot + e.bias;
  return e;
}

std::vector<double> to_std(const Eigen::VectorXd& x) {
  return {x.data(), x.data() + x.size()};
}

std::string format_json(const Prepared& p, const StateEvaluation& e) {
  const CompiledModel& cm = *p.compiled;
  nlohmann::json j;
  j["name"] = p.model->name;
  j["t"] = 0.0;
  j["coordinates"] = cm.coordinate_names;
  j["velocities"] = cm.velocity_names;
  j["q"] = p.q;
  j["v"] = p.v;
  for (Eigen::Index i = 0; i < e.M.rows(); ++i) {
    const Eigen::VectorXd row = e.M.row(i).transpose();
    j["M"].push_back(to_std(row));
  }
  j["bias"] = to_std(e.bias);
  j[e.given_tau ? "tau" : "Q"] = to_std(e.forces);
  j["qddot"] = to_std(e.qddot);
  if (cm.m > 0) j["lambda"] = to_std(e.lambda);
  if (e.manipulator) j["tau_inverse_dynamics"] = to_std(e.tau_inverse);
  return j.dump(2) + "\n";
}

std::string format_text(const Prepared& p, const StateEvaluation& e) {
  const CompiledModel& cm = *p.compiled;
  std::string out = fmt::format("{} at t = 0\n", p.model->name);
  auto column = [&](const std::string& title, const std::vector<std::string>& names,
                    const double* x, size_t count) {
    out += title + "\n";
    for (size_t i = 0; i < count; ++i) out += fmt::format("  {:<24} {:>22.15g}\n", names[i], x[i]);
  };
  column("State q", cm.coordinate_names, p.q.data(), cm.nq);
  column("Velocities v", cm.velocity_names, p.v.data(), cm.nv);
  // Rows of the equations: a manipulator's are its joints, others' are their velocities.
  const std::vector<std::string>& rows = e.manipulator ? cm.coordinate_names : cm.velocity_names;
  out += "Mass matrix M (rows and columns in the order of v)\n";
  for (Eigen::Index i = 0; i < e.M.rows(); ++i) {
    out += " ";
    for (Eigen::Index k = 0; k < e.M.cols(); ++k) out += fmt::format(" {:>22.15g}", e.M(i, k));
    out += "\n";
  }
  column(e.manipulator ? "Bias forces C(q, q_dot) q_dot + g(q) (= -h)"
                       : "Bias forces -h (M a = h + Q + constraint forces)",
         rows, e.bias.data(), cm.nv);
  column(e.given_tau ? "Joint forces tau (given by --tau)" : "Generalised forces Q (the model's)",
         rows, e.forces.data(), cm.nv);
  column("Accelerations", rows, e.qddot.data(), cm.nv);
  if (cm.m > 0) column("Multipliers lambda", cm.constraint_names, e.lambda.data(), cm.m);
  if (e.manipulator)
    column("Inverse dynamics tau = D(q) q_ddot + C(q, q_dot) q_dot + g(q)", rows,
           e.tau_inverse.data(), cm.nv);
  if (!p.initial.was_consistent) out += fmt::format("note: {}\n", p.initial.note());
  return out;
}

}  // namespace

int run_eval(const Options& opt) {
  Prepared p = prepare(opt.model, opt.sets, opt.initial, "--state");
  const StateEvaluation e = evaluate(p, opt);
  fmt::print("{}", opt.format == "json" ? format_json(p, e) : format_text(p, e));
  return 0;
}

}  // namespace lagrange::cli

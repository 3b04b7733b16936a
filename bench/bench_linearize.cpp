// Cost of the analysis (issue 21, docs/benchmarks.md "Linearise and trim"): per model, the
// symbolic differentiation (DynamicsJacobian), one exact Jacobian against one forward call and
// against central finite differences through the forward call (2(nq + nv) calls, the peers'
// way), `linearize` at the initial state and `trim` from it.
//   bench_linearize                the 50- and 200-segment tethered balloon (bench_tether's, and
//                                  in a uniform wind), the rigid AP2 on 50 segments, the Panda
//                                  (examples/robots/panda.urdf; and with its joint torques free
//                                  at a held pose): a table
//   bench_linearize TEXT           only the models whose label contains TEXT
//   bench_linearize pendulum N     the N-link pendulum (bench/n_link_pendulum.hpp, PerLink) at
//                                  its initial state: one JSON line with A and the times, read
//                                  by bench/linearize_vs_sympy.py

#include <fmt/format.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "support/test_paths.hpp"
#include "bench_support.hpp"
#include "lagrange/analysis.hpp"
#include "lagrange/reader.hpp"
#include "n_link_pendulum.hpp"
#include "tether_models.hpp"

namespace {

using namespace lagrange;

// Mean wall seconds of f over at least `min_seconds` (and at least 3 calls).
double seconds_per_call(const std::function<void()>& f, double min_seconds = 0.3) {
  const bench::Stopwatch clock;
  f();  // warm
  const double t0 = clock.now().wall;
  int calls = 0;
  double elapsed = 0.0;
  while (calls < 3 || elapsed < min_seconds) {
    f();
    ++calls;
    elapsed = clock.now().wall - t0;
  }
  return elapsed / calls;
}

// Central differences of a(q, v) through the forward call: [∂a/∂q ∂a/∂v], step 1e-6·max(1, |x|).
Eigen::MatrixXd finite_difference_jacobian(Dynamics& dyn, const std::vector<double>& q0,
                                           const std::vector<double>& v0) {
  const CompiledModel& cm = dyn.model();
  const long n = static_cast<long>(cm.nv), nq = static_cast<long>(cm.nq);
  Eigen::MatrixXd J(n, nq + n);
  std::vector<double> q = q0, v = v0, qdot(cm.nq), lambda(cm.m);
  Eigen::VectorXd ap(n), am(n);
  for (long k = 0; k < nq + n; ++k) {
    double& x = k < nq ? q[static_cast<size_t>(k)] : v[static_cast<size_t>(k - nq)];
    const double x0 = x, h = 1e-6 * std::max(1.0, std::abs(x0));
    x = x0 + h;
    dyn.forward(0.0, q.data(), v.data(), qdot.data(), ap.data(), lambda.data());
    x = x0 - h;
    dyn.forward(0.0, q.data(), v.data(), qdot.data(), am.data(), lambda.data());
    x = x0;
    J.col(k) = (ap - am) / (2 * h);
  }
  return J;
}

// The balloon of bench_tether in a uniform wind U (the tether's drag and the balloon's): the
// logarithmic profile's zero wind below z₀ is where trim's Newton iteration gets lost.
std::string uniform_wind_balloon(int segments) {
  const std::string log_wind = "U*log(z/z0)/log(href/z0)";
  std::string text = bench::replaced(
      bench::balloon_yaml(segments),
      "wind: {profile: logarithmic, speed: U, reference_height: href, roughness: z0}",
      "wind: {speed: U}");
  for (int k = 0; k < 2; ++k) text = bench::replaced(text, log_wind, "U");
  return text;
}

// The Panda with a torque parameter t1 … t7 on each joint, at a pose away from upright.
std::string panda_with_torques(const std::string& urdf) {
  std::string text = "name: panda held\nurdf: {file: " + urdf +
                     ", initial: {panda_joint2: 0.5, panda_joint4: -1.2, panda_joint6: 1.0}}\n"
                     "gravity: [0, 0, -9.81]\nparameters: {";
  std::string forces = "generalized_forces: {";
  for (int j = 1; j <= 7; ++j) {
    text += fmt::format("{}t{}: 0", j > 1 ? ", " : "", j);
    forces += fmt::format("{}panda_joint{}: t{}", j > 1 ? ", " : "", j, j);
  }
  return text + "}\n" + forces + "}\n";
}

struct Measured {
  double build = 0, differentiate = 0, forward = 0, jacobian = 0, implicit = 0, fd = 0,
         linearize = 0;
  double fd_difference = 0;  // max |exact − FD| / max |exact|
  size_t nonzeros = 0;
  std::string trim;  // "0.52 s, 6 iterations" or why it failed
  LinearModel lin;
};

// `torques`: also trim the model with every coordinate held and the parameters of that name
// free (the Panda's gravity compensation, docs/theory.md §5.5 "Free inputs").
Measured measure(bench::BuiltModel& b, bool with_trim,
                 const std::vector<std::string>& torques = {}) {
  Measured r;
  const bench::Stopwatch clock;
  r.build = b.times.build();
  const CompiledModel& cm = *b.compiled;
  Dynamics& dyn = *b.dynamics;
  std::vector<double> q = cm.q0, v = cm.v0, qdot(cm.nq), a(cm.nv), lambda(cm.m);
  if (cm.m > 0) dyn.project(0.0, q.data(), v.data(), cm.fixed);
  const auto t0 = clock.now().wall;
  const DynamicsJacobian jac(b.equations, b.compiled);
  r.differentiate = clock.now().wall - t0;
  r.nonzeros = jac.nonzeros();
  r.forward = seconds_per_call(
      [&] { dyn.forward(0.0, q.data(), v.data(), qdot.data(), a.data(), lambda.data()); });
  StateJacobian J;
  r.jacobian = seconds_per_call([&] { J = jac.evaluate(dyn, 0.0, q.data(), v.data()); });
  r.implicit = seconds_per_call([&] { (void)jac.implicit(dyn, 0.0, q.data(), v.data()); });
  Eigen::MatrixXd fd;
  r.fd = seconds_per_call([&] { fd = finite_difference_jacobian(dyn, q, v); });
  Eigen::MatrixXd exact(J.a_q.rows(), J.a_q.cols() + J.a_v.cols());
  exact << J.a_q, J.a_v;
  r.fd_difference =
      (exact - fd).cwiseAbs().maxCoeff() / std::max(1e-300, exact.cwiseAbs().maxCoeff());
  try {
    r.linearize = seconds_per_call([&] { r.lin = linearize(jac, dyn, 0.0, q.data(), v.data()); });
  } catch (const std::exception& e) {
    r.linearize = NAN;
    r.trim = fmt::format("linearize refused: {:.90}; ", e.what());
  }
  if (!with_trim) return r;
  try {
    TrimOptions options;
    options.tol = 1e-9;                      // the CLI's default (`trim --tol`)
    std::unique_ptr<DynamicsJacobian> held;  // differentiated by the torques too, not timed
    if (!torques.empty()) {
      held = std::make_unique<DynamicsJacobian>(b.equations, b.compiled, torques);
      options.free.assign(cm.nv, false);
      options.free_inputs.assign(torques.size(), true);
    }
    const auto s0 = clock.now().wall;
    const TrimResult t = trim(held ? *held : jac, dyn, 0.0, q, options);
    r.trim += fmt::format("trim {:.3g} s, {} {}, max |a| = {:.1e} (tolerance {:.1e}){}",
                          clock.now().wall - s0, t.iterations,
                          t.pseudo_transient ? "Ψtc steps" : "LM iterations", t.residual,
                          t.tolerance, t.not_isolated.empty() ? "" : ", not isolated");
  } catch (const std::exception& e) {
    // Newton's reason, then the continuation's (in parentheses) when it ran.
    const std::string what = e.what();
    const size_t ptc = what.find("pseudo-transient");
    r.trim += fmt::format("trim failed: {:.90}", what);
    if (ptc != std::string::npos)
      r.trim += fmt::format("; Ψtc: {}", what.substr(ptc, what.find(')', ptc) + 1 - ptc));
  }
  return r;
}

int pendulum(size_t n) {
  bench::BuiltModel b = bench::build_model(
      bench::n_link_pendulum_yaml(n, bench::PendulumParameters::PerLink), "<pendulum>");
  const bench::Stopwatch clock;
  const double t0 = clock.now().wall;
  const DynamicsJacobian jac(b.equations, b.compiled);
  const CompiledModel& cm = *b.compiled;
  const LinearModel once = linearize(jac, *b.dynamics, 0.0, cm.q0.data(), cm.v0.data());
  // From the model text to A once, as a user runs it (SymPy's figure is the same span).
  const double first = b.times.build() + (clock.now().wall - t0);
  const Measured m = measure(b, false);
  std::string A;
  for (long i = 0; i < once.A.rows(); ++i)
    for (long j = 0; j < once.A.cols(); ++j)
      A += fmt::format("{}{:.17g}", A.empty() ? "" : ", ", once.A(i, j));
  fmt::print(
      "{{\"peer\": \"lagrange\", \"n\": {}, \"build_s\": {:.6g}, \"differentiate_s\": {:.6g}, "
      "\"first_A_s\": {:.6g}, \"forward_us\": {:.6g}, \"jacobian_us\": {:.6g}, \"fd_us\": {:.6g}, "
      "\"linearize_us\": {:.6g}, \"fd_difference\": {:.3g}, \"A\": [{}]}}\n",
      n, m.build, m.differentiate, first, 1e6 * m.forward, 1e6 * m.jacobian, 1e6 * m.fd,
      1e6 * m.linearize, m.fd_difference, A);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc == 3 && std::strcmp(argv[1], "pendulum") == 0)
    return pendulum(static_cast<size_t>(std::atoi(argv[2])));
  struct Case {
    std::string label;
    std::function<bench::BuiltModel()> build;
    std::vector<std::string> torques;
  };
  const std::string panda = std::string(LAGRANGE_SOURCE_DIR) + "/examples/robots/panda.urdf";
  const std::vector<Case> cases{
      {"balloon, 50 segments",
       [] { return bench::build_model(bench::balloon_yaml(50), "<balloon 50>"); }},
      {"balloon, 50, uniform wind",
       [] { return bench::build_model(uniform_wind_balloon(50), "<balloon 50 uniform>"); }},
      {"balloon, 200 segments",
       [] { return bench::build_model(bench::balloon_yaml(200), "<balloon 200>"); }},
      {"balloon, 200, uniform wind",
       [] { return bench::build_model(uniform_wind_balloon(200), "<balloon 200 uniform>"); }},
      {"rigid AP2, 50 segments",
       [] { return bench::build_model(bench::kite_yaml(50), "<ap2 50>"); }},
      {"Panda (URDF)",
       [&] {
         return bench::build_with([&] { return read_model_file(panda); }, Formulation::Lagrangian);
       }},
      {"Panda, torques free",
       [&] { return bench::build_model(panda_with_torques(panda), "<panda torques>"); },
       {"t1", "t2", "t3", "t4", "t5", "t6", "t7"}}};
  fmt::print(
      "{:<24} {:>5} {:>8} {:>9} {:>10} {:>10} {:>8} {:>10} {:>8} {:>11} {:>8} {:>11} {:>9}  {}\n",
      "model", "nv", "build s", "diff. s", "forward us", "jacobian", "jac/fwd", "implicit",
      "imp/fwd", "FD (2n fwd)", "FD/jac", "linearize s", "|J-FD|", "trim");
  for (const Case& c : cases) {
    if (argc == 2 && c.label.find(argv[1]) == std::string::npos) continue;  // one model only
    bench::BuiltModel b = c.build();
    const Measured m = measure(b, true, c.torques);
    fmt::print(
        "{:<24} {:>5} {:>8.3g} {:>9.3g} {:>10.3g} {:>8.3g}us {:>8.3g} {:>8.3g}us {:>8.3g} "
        "{:>9.3g}us {:>8.3g} {:>11.3g} {:>9.1e}  {}\n",
        c.label, b.compiled->nv, m.build, m.differentiate, 1e6 * m.forward, 1e6 * m.jacobian,
        m.jacobian / m.forward, 1e6 * m.implicit, m.implicit / m.forward, 1e6 * m.fd,
        m.fd / m.jacobian, m.linearize, m.fd_difference, m.trim);
    std::fflush(stdout);
  }
  return 0;
}

// CasADi's C++ API as the same-run peer of `lagrange optimize` on the Panda's point-to-point motion
// (examples/optimal/panda_point_to_point.yaml; docs/benchmarks.md, "Optimal control: the Panda
// against CasADi"). The arm's equations are lagrange's own, as `lagrange derive --format json`
// prints them for a large model (the dynamics tape's common subexpressions x1 …, then M(q)'s lower
// triangle and h + Q), read into CasADi's SX: both tools then differentiate and evaluate the same
// expressions, and only the NLP functions, their derivatives and the set-up differ. The
// transcription is lagrange's (docs/theory.md §10; as bench/optimal_control_casadi.cpp for the
// cart-pole): Radau IIA of degree d on N intervals, the states at each interval's start and its
// collocation points, one torque vector per interval, the residual (q' − v, M(q) v' − (h + Q))
// at every collocation point, 0.01 ∫|τ|² by the Radau weights, the URDF's angle, rate and torque
// limits at every point, both ends fixed by equal bounds, the example's quintic guess (zero
// torques), and lagrange's Ipopt options (MUMPS, tol 1e-8, max_iter 1000).
//   optimal_control_casadi_panda EQUATIONS.json [N=50] [d=3] [exact|limited-memory] [sx|mx]
// sx writes the whole NLP as one SX graph (the per-point function inlined at every point), mx
// calls the per-point SX function from an MX graph (CasADi's advice for large models: each
// derivative is then a call of the function's own derivative). Prints the same two lines as the
// cart-pole peer.
#include <casadi/casadi.hpp>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "casadi_expression_reader.hpp"
#include "casadi_peer.hpp"

namespace {

using casadi::DM;
using casadi::MX;
using casadi::SX;
using casadi_peer::seconds_since;

// examples/optimal/panda_point_to_point.yaml
constexpr int kJoints = 7;
constexpr double kHorizon = 1.0;
const double kStart[kJoints] = {0, -0.785, 0, -2.356, 0, 1.571, 0.785};
const double kEnd[kJoints] = {M_PI / 3, -0.35, 0, -1.95, 0, 1.8, -0.262};
const bool kQuintic[kJoints] = {true, true, false, true, false, true, true};
const double kAngleLower[kJoints] = {-2.8973, -1.7628, -2.8973, -3.0718, -2.8973, -0.0175, -2.8973};
const double kAngleUpper[kJoints] = {2.8973, 1.7628, 2.8973, -0.0698, 2.8973, 3.7525, 2.8973};
const double kRate[kJoints] = {2.175, 2.175, 2.175, 2.175, 2.61, 2.61, 2.61};
const double kTorque[kJoints] = {87, 87, 87, 87, 12, 12, 12};
constexpr double kEffortWeight = 0.01;

/// docs/theory.md §10: the residual M(q) a − (h(q, v) + Q(q, v, τ)) as an SX function of
/// (q, v, a, τ), from lagrange's printed equations.
casadi::Function dynamics_residual(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path);
  const nlohmann::json j = nlohmann::json::parse(in);
  if (j.value("form", "") != "common_subexpressions")
    throw std::runtime_error(path + ": expected `lagrange derive --format json` of a large model");
  const std::vector<std::string> qn = j.at("coordinates"), vn = j.at("velocities");
  if (qn.size() != kJoints || vn.size() != kJoints)
    throw std::runtime_error(path + ": expected the Panda's 7 joints");
  const SX q = SX::sym("q", kJoints), v = SX::sym("v", kJoints), a = SX::sym("a", kJoints),
           tau = SX::sym("tau", kJoints);
  std::map<std::string, SX> names{{"t", SX(0)}};
  for (int i = 0; i < kJoints; ++i) {
    names[qn[static_cast<size_t>(i)]] = q(i);
    names[vn[static_cast<size_t>(i)]] = v(i);
    names["tau" + std::to_string(i + 1)] = tau(i);
  }
  casadi_peer::ExpressionReader reader(names);
  for (const auto& definition : j.at("subexpressions"))
    names[definition.at(0).get<std::string>()] = reader.read(definition.at(1).get<std::string>());
  const auto& eqs = j.at("equations");
  SX M = SX::zeros(kJoints, kJoints), rhs = SX::zeros(kJoints);
  for (int r = 0; r < kJoints; ++r) {
    for (int c = 0; c <= r; ++c) {
      const std::string key = "M_{" + std::to_string(r + 1) + "," + std::to_string(c + 1) + "}";
      if (eqs.contains(key)) M(r, c) = M(c, r) = reader.read(eqs.at(key).get<std::string>());
    }
    rhs(r) = reader.read(eqs.at("(h+Q)_{" + qn[static_cast<size_t>(r)] + "}").get<std::string>());
  }
  return casadi::Function("panda_residual", {q, v, a, tau}, {SX::mtimes(M, a) - rhs});
}

/// The NLP on lagrange's transcription in CasADi's symbolic type T (SX or MX).
template <class T>
casadi::Function transcribe(const casadi::Function& residual, int N, int d,
                            const casadi::Dict& opts, std::vector<double>& lbx,
                            std::vector<double>& ubx, std::vector<double>& x0) {
  const std::vector<double> tau = casadi::collocation_points(d, "radau");
  DM C, D, B;
  casadi::collocation_coeff(tau, C, D, B);
  const double h = kHorizon / N;
  std::vector<T> w, g;
  auto add_state = [&](double t, const double* fixed) {
    const T X = T::sym("X", 2 * kJoints);
    w.push_back(X);
    // lagrange's guess: the quintic path (its rate) on joints 1, 2, 4, 6 and 7, the straight
    // line (here constant) on 3 and 5; clipped to the bounds.
    const double s = t / kHorizon, blend = s * s * s * (10 - 15 * s + 6 * s * s),
                 rate = 30 * s * s * (1 - 2 * s + s * s) / kHorizon;
    for (int i = 0; i < 2 * kJoints; ++i) {
      const int joint = i % kJoints;
      const bool angle = i < kJoints;
      const double lo = angle ? kAngleLower[joint] : -kRate[joint],
                   up = angle ? kAngleUpper[joint] : kRate[joint];
      const double end = angle ? kEnd[joint] : 0.0, start = angle ? kStart[joint] : 0.0;
      lbx.push_back(fixed ? fixed[i] : lo);
      ubx.push_back(fixed ? fixed[i] : up);
      const double guess = kQuintic[joint] ? (angle ? start + (end - start) * blend
                                                    : (kEnd[joint] - kStart[joint]) * rate)
                                           : (1 - s) * start + s * end;
      x0.push_back(std::min(std::max(guess, lbx.back()), ubx.back()));
    }
    return X;
  };
  double start[2 * kJoints] = {}, end[2 * kJoints] = {};
  std::copy(kStart, kStart + kJoints, start);
  std::copy(kEnd, kEnd + kJoints, end);
  std::vector<std::vector<T>> X(static_cast<size_t>(N) + 1);
  std::vector<T> U(static_cast<size_t>(N));
  for (int k = 0; k < N; ++k) {
    for (int j = 0; j < d; ++j)
      X[k].push_back(
          add_state(h * (k + (j == 0 ? 0.0 : tau[j - 1])), k == 0 && j == 0 ? start : nullptr));
    U[k] = T::sym("U", kJoints);
    w.push_back(U[k]);
    for (int i = 0; i < kJoints; ++i) {
      lbx.push_back(-kTorque[i]);
      ubx.push_back(kTorque[i]);
      x0.push_back(0.0);
    }
  }
  X[N].push_back(add_state(kHorizon, end));
  T J = 0;
  for (int k = 0; k < N; ++k) {
    X[k].push_back(X[k + 1][0]);  // X_{k,d} ≡ X_{k+1,0}
    for (int j = 1; j <= d; ++j) {
      T xp = 0;
      for (int l = 0; l <= d; ++l) xp += static_cast<double>(C(l, j - 1)) / h * X[k][l];
      const T q = X[k][j](casadi::Slice(0, kJoints)),
              v = X[k][j](casadi::Slice(kJoints, 2 * kJoints));
      g.push_back(xp(casadi::Slice(0, kJoints)) - v);
      g.push_back(residual(std::vector<T>{q, v, xp(casadi::Slice(kJoints, 2 * kJoints)), U[k]})[0]);
      J += kEffortWeight * h * static_cast<double>(B(j - 1)) * T::dot(U[k], U[k]);
    }
  }
  return casadi::nlpsol("panda", "ipopt", {{"x", T::vertcat(w)}, {"f", J}, {"g", T::vertcat(g)}},
                        opts);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s EQUATIONS.json [N] [d] [exact|limited-memory] [sx|mx]\n",
                 argv[0]);
    return 2;
  }
  const int N = argc > 2 ? std::atoi(argv[2]) : 50, d = argc > 3 ? std::atoi(argv[3]) : 3;
  const std::string hessian = argc > 4 ? argv[4] : "exact", graph = argc > 5 ? argv[5] : "mx";
  if (N < 1 || d < 1 || (hessian != "exact" && hessian != "limited-memory") ||
      (graph != "sx" && graph != "mx")) {
    std::fprintf(stderr,
                 "usage: %s EQUATIONS.json [N >= 1] [d >= 1] [exact|limited-memory] [sx|mx]\n",
                 argv[0]);
    return 2;
  }
  const auto setup_start = std::chrono::steady_clock::now();
  const casadi::Function residual = dynamics_residual(argv[1]);
  const double read = seconds_since(setup_start);
  const casadi::Dict opts = casadi_peer::ipopt_options(hessian);
  std::vector<double> lbx, ubx, x0;
  const casadi::Function solver = graph == "sx"
                                      ? transcribe<SX>(residual, N, d, opts, lbx, ubx, x0)
                                      : transcribe<MX>(residual, N, d, opts, lbx, ubx, x0);
  char extra[128];
  std::snprintf(extra, sizeof extra, ", reading the equations %.4f s, %s Hessian, %s", read,
                hessian.c_str(), graph.c_str());
  return casadi_peer::solve_and_report(solver, x0, lbx, ubx, seconds_since(setup_start),
                                       2 * kJoints * N * d, extra);
}

// CasADi's C++ API as the same-run peer of `lagrange optimize` (docs/benchmarks.md, "Optimal
// control against CasADi"): the cart-pole swing-up of examples/optimal/cart_pole_swing_up.yaml on
// lagrange's own transcription (docs/theory.md §10): Radau IIA of degree d, N intervals, states at
// each interval's start and its collocation points (the last point is the next interval's start),
// one constant control per interval, the implicit residual (q' − v, M(q) v' − h(q, v, u)) at
// every collocation point, ∫u² by the Radau quadrature, the same bounds, fixed ends, initial guess
// and Ipopt options (src/optimize/ipopt_adapter.cpp). Built by bench/casadi.sh.
//   optimal_control_casadi [N] [d]
// Prints a line with the objective, status, Ipopt iterations, set-up (graph and nlpsol
// construction), solve, and the solve's time in CasADi's NLP functions (its solver stats
// t_wall_nlp_*), then a line with each function's calls and time.
#include <algorithm>
#include <casadi/casadi.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "casadi_peer.hpp"

namespace {

using casadi::DM;
using casadi::SX;
using casadi_peer::seconds_since;

// examples/optimal/cart_pole_swing_up.yaml
constexpr double kCart = 1.0, kBob = 0.3, kRod = 0.5, kGravity = 9.81, kDistance = 1.0;
constexpr double kHorizon = 2.0, kForce = 20.0, kRail = 2.0;

/// docs/theory.md §4.1 and §10: the cart-pole's Euler–Lagrange residual M(q) a − h(q, v, u) for
/// q = (x, θ), cart at (x, 0), bob at (x + l sin θ, −l cos θ), gravity −g along y, u on the cart.
SX dynamics_residual(const SX& q, const SX& v, const SX& a, const SX& u) {
  const SX s = sin(q(1)), c = cos(q(1));
  const SX M00 = kCart + kBob, M01 = kBob * kRod * c, M11 = kBob * kRod * kRod;
  const SX h0 = u + kBob * kRod * s * v(1) * v(1), h1 = -kBob * kGravity * kRod * s;
  return SX::vertcat({M00 * a(0) + M01 * a(1) - h0, M01 * a(0) + M11 * a(1) - h1});
}

}  // namespace

int main(int argc, char** argv) {
  const int N = argc > 1 ? std::atoi(argv[1]) : 100, d = argc > 2 ? std::atoi(argv[2]) : 3;
  if (N < 1 || d < 1) {
    std::fprintf(stderr, "usage: %s [N >= 1] [d >= 1]\n", argv[0]);
    return 2;
  }
  const auto setup_start = std::chrono::steady_clock::now();
  // Radau IIA: τ_1..τ_d (τ_d = 1); C gives x'(τ_j) = (1/h) Σ_l C_lj X_l over (τ_0 = 0, τ_1..τ_d),
  // B the quadrature weights b_j (CasADi's collocation_coeff, integration_tools.hpp).
  const std::vector<double> tau = casadi::collocation_points(d, "radau");
  DM C, D, B;
  casadi::collocation_coeff(tau, C, D, B);
  const double h = kHorizon / N;
  const double start[4] = {0, 0, 0, 0}, end[4] = {kDistance, M_PI, 0, 0};

  // Variables in lagrange's layout: per interval X_{k,0..d−1} (x, θ, ẋ, θ̇) then U_k; X_N last.
  std::vector<SX> w, g;
  std::vector<double> lbx, ubx, x0;
  auto add_state = [&](double t, const double* fixed) {
    const SX X = SX::sym("X", 4);
    w.push_back(X);
    const double s = t / kHorizon;
    for (int i = 0; i < 4; ++i) {
      const double lo = i == 0 ? -kRail : -casadi::inf, up = i == 0 ? kRail : casadi::inf;
      lbx.push_back(fixed ? fixed[i] : lo);
      ubx.push_back(fixed ? fixed[i] : up);
      // lagrange's guess: the straight line from the initial to the final state, clipped.
      x0.push_back(std::min(std::max((1 - s) * start[i] + s * end[i], lbx.back()), ubx.back()));
    }
    return X;
  };
  std::vector<std::vector<SX>> X(static_cast<size_t>(N) + 1);
  std::vector<SX> U(static_cast<size_t>(N));
  for (int k = 0; k < N; ++k) {
    for (int j = 0; j < d; ++j)
      X[k].push_back(
          add_state(h * (k + (j == 0 ? 0.0 : tau[j - 1])), k == 0 && j == 0 ? start : nullptr));
    U[k] = SX::sym("U");
    w.push_back(U[k]);
    lbx.push_back(-kForce);
    ubx.push_back(kForce);
    x0.push_back(0.0);
  }
  X[N].push_back(add_state(kHorizon, end));
  SX J = 0;
  for (int k = 0; k < N; ++k) {
    X[k].push_back(X[k + 1][0]);  // X_{k,d} ≡ X_{k+1,0}
    for (int j = 1; j <= d; ++j) {
      // docs/theory.md §10: x'(t_kj) = (1/h) Σ_l D_jl X_{k,l}; r = (q' − v, M v' − h(q, v, u)).
      SX xp = 0;
      for (int l = 0; l <= d; ++l) xp += static_cast<double>(C(l, j - 1)) / h * X[k][l];
      const SX q = X[k][j](casadi::Slice(0, 2)), v = X[k][j](casadi::Slice(2, 4));
      g.push_back(xp(casadi::Slice(0, 2)) - v);
      g.push_back(dynamics_residual(q, v, xp(casadi::Slice(2, 4)), U[k]));
      J += h * static_cast<double>(B(j - 1)) * U[k] * U[k];
    }
  }
  const casadi::Function solver =
      casadi::nlpsol("cart_pole", "ipopt", {{"x", SX::vertcat(w)}, {"f", J}, {"g", SX::vertcat(g)}},
                     casadi_peer::ipopt_options());
  return casadi_peer::solve_and_report(solver, x0, lbx, ubx, seconds_since(setup_start), 4 * N * d);
}

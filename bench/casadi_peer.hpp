#pragma once
// What the CasADi peers of `lagrange optimize` share (bench/optimal_control_casadi.cpp, the
// cart-pole; bench/optimal_control_casadi_panda.cpp, the Panda;
// bench/optimal_control_casadi_kite.cpp, the point-mass power cycle): lagrange's Ipopt options, the
// timed solve, and the two lines bench/optimal_control.sh reads.
#include <casadi/casadi.hpp>
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

namespace casadi_peer {

inline double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// src/optimize/ipopt_adapter.cpp's options; CasADi's own printing off, its timers on, and no
/// parameter multipliers after the solve (lagrange computes none).
inline casadi::Dict ipopt_options(const std::string& hessian = "exact") {
  return {{"ipopt.sb", "yes"},
          {"ipopt.print_level", 0},
          {"ipopt.hessian_approximation", hessian},
          {"ipopt.linear_solver", "mumps"},
          {"ipopt.tol", 1e-8},
          {"ipopt.max_iter", 1000},
          {"print_time", false},
          {"record_time", true},
          {"calc_lam_p", false}};
}

/// Solves from x0 within the bounds (every constraint an equation unless lbg and ubg say
/// otherwise), prints "casadi: J = …, status …, N iterations, set-up …, solve …, functions …,
/// rest (Ipopt) …, n = …, m = …" with `extra` appended, then each NLP function's calls and wall
/// time; returns the exit status. J is `sign` times the NLP's objective (−1: a maximisation).
inline int solve_and_report(const casadi::Function& solver, const std::vector<double>& x0,
                            const std::vector<double>& lbx, const std::vector<double>& ubx,
                            double setup, int constraints, const std::string& extra = "",
                            const std::vector<double>& lbg = {},
                            const std::vector<double>& ubg = {}, double sign = 1.0) {
  const auto solve_start = std::chrono::steady_clock::now();
  const casadi::DM lg = lbg.empty() ? casadi::DM(0) : casadi::DM(lbg),
                   ug = ubg.empty() ? casadi::DM(0) : casadi::DM(ubg);
  const casadi::DMDict result =
      solver(casadi::DMDict{{"x0", x0}, {"lbx", lbx}, {"ubx", ubx}, {"lbg", lg}, {"ubg", ug}});
  const double solve = seconds_since(solve_start);
  const casadi::Dict stats = solver.stats();
  double functions = 0.0;
  for (const auto& [key, value] : stats)
    if (key.rfind("t_wall_nlp_", 0) == 0) functions += value.to_double();
  std::printf(
      "casadi: J = %.9f, status %s, %d iterations, set-up %.4f s, solve %.4f s, functions %.4f "
      "s, rest (Ipopt) %.4f s, n = %d, m = %d%s\n",
      sign * static_cast<double>(result.at("f")), stats.at("return_status").to_string().c_str(),
      static_cast<int>(stats.at("iter_count").to_int()), setup, solve, functions, solve - functions,
      static_cast<int>(lbx.size()), constraints, extra.c_str());
  std::printf("casadi functions (calls, wall s):");
  for (const auto& [key, value] : stats)
    if (key.rfind("t_wall_nlp_", 0) == 0)
      std::printf(" %s %d %.4f", key.substr(7).c_str(),
                  static_cast<int>(stats.at("n_call_" + key.substr(7)).to_int()),
                  value.to_double());
  std::printf("\n");
  return stats.at("success").to_bool() ? 0 : 1;
}

}  // namespace casadi_peer

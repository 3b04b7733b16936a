// CasADi's C++ API as the same-run peer of `lagrange optimize` on the point-mass kite's power
// cycle (examples/optimal/power_cycle_pointmass.yaml, issue 35; docs/benchmarks.md, "Optimal
// control: the kite's power cycle against CasADi"). The kite's equations are lagrange's own, as
// `lagrange derive --format json` prints them (M, h, Q and the tether's C, Ċ, G, c), read into
// SX; the starting point is lagrange's, as `lagrange optimize --ipopt max_iter=0 -o START.csv`
// writes it (the simulated figure eight projected onto the invariants, its controls and
// multipliers), so that both solves start from the same point. The transcription is lagrange's
// (docs/theory.md §10): Radau IIA of degree d on N intervals, the states at each interval's start
// and collocation points, the multiplier at each collocation point, (ψ, C_L, τ) constant on each
// interval; at each collocation point q' − v, M a + Gᵀλ − (h + Q), G a + c + 2αĊ + α²C and the
// height row z ≥ 50; C = 0 and Ċ = 0 at t = 0; y(0) = 0 and ẏ(0) ≥ 0; the periodic rows lagrange
// chooses (Gram–Schmidt after the invariants at the start); the reeled length and its rate bounded
// at every node; the mean winch power (1/N) Σ_k Σ_j b_j (−τ_k l̇_kj / R) maximised.
//   optimal_control_casadi_kite EQUATIONS.json START.csv [N=40] [d=3] [exact|limited-memory]
//                               [sx|mx] [alpha=0]
// alpha is the model's Baumgarte rate (0 for this model: dop853 projects). Prints the same two
// lines as the other peers, J being the mean power.
#include <casadi/casadi.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
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

// examples/optimal/power_cycle_pointmass.yaml
constexpr int kQ = 4, kX = 2 * kQ, kControls = 3;  // (x, y, z, l), their rates; (ψ, C_L, τ)
constexpr double kHorizon = 10.0, kWind = 10.0, kDrumRadius = 0.2;
const char* const kControlNames[kControls] = {"psi", "CLc", "tau"};
const double kControlLower[kControls] = {-0.7, 0.1, -360},
             kControlUpper[kControls] = {0.7, 1.0, -10};
constexpr int kY = 1, kYRate = kQ + 1, kLength = 3, kLengthRate = kQ + 3, kZ = 2;
constexpr double kLengthLower = 100, kLengthUpper = 400, kRateLower = -15, kRateUpper = 20;
constexpr double kHeightLower = 50;

/// The DAE residual at a collocation point, (M a + Gᵀλ − (h + Q), G a + c + 2αĊ + α²C) as an SX
/// function of (q, v, a, u, λ), and the invariants (C, Ċ) of (q, v), from lagrange's equations.
struct KiteEquations {
  casadi::Function residual, invariants, invariant_jacobian;
  std::vector<std::string> state_names, multiplier_names;
};

KiteEquations read_equations(const std::string& path, double alpha) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path);
  const nlohmann::json j = nlohmann::json::parse(in);
  const std::vector<std::string> qn = j.at("coordinates"), vn = j.at("velocities");
  if (qn.size() != kQ || vn.size() != kQ)
    throw std::runtime_error(path + ": expected the point-mass kite's 4 coordinates");
  const SX q = SX::sym("q", kQ), v = SX::sym("v", kQ), a = SX::sym("a", kQ),
           u = SX::sym("u", kControls);
  std::map<std::string, SX> names{{"W", SX(kWind)}, {"R", SX(kDrumRadius)}, {"Pi", SX(M_PI)}};
  const auto text = [](const nlohmann::json& e) { return e.get<std::string>(); };
  KiteEquations eq;
  for (int i = 0; i < kQ; ++i) {
    names[qn[static_cast<size_t>(i)]] = q(i);
    names[vn[static_cast<size_t>(i)]] = v(i);
  }
  eq.state_names = qn;
  eq.state_names.insert(eq.state_names.end(), vn.begin(), vn.end());
  for (int c = 0; c < kControls; ++c) names[kControlNames[c]] = u(c);
  casadi_peer::ExpressionReader reader(names);
  SX M = SX::zeros(kQ, kQ), rhs = SX::zeros(kQ);
  for (int r = 0; r < kQ; ++r) {
    for (int c = 0; c < kQ; ++c)
      M(r, c) = reader.read(text(j.at("M").at(static_cast<size_t>(r)).at(static_cast<size_t>(c))));
    rhs(r) = reader.read(text(j.at("h").at(static_cast<size_t>(r)))) +
             reader.read(text(j.at("Q").at(static_cast<size_t>(r))));
  }
  const auto& constraints = j.at("constraints");
  const int m = static_cast<int>(constraints.size());
  const SX lambda = SX::sym("lambda", m);
  SX G = SX::zeros(m, kQ), dae = SX::zeros(m), C = SX::zeros(m), Cdot = SX::zeros(m);
  for (int k = 0; k < m; ++k) {
    const auto& row = constraints.at(static_cast<size_t>(k));
    for (int c = 0; c < kQ; ++c)
      G(k, c) = reader.read(text(row.at("G").at(static_cast<size_t>(c))));
    C(k) = reader.read(text(row.at("C")));
    Cdot(k) = reader.read(text(row.at("Cdot")));
    dae(k) = SX::mtimes(G(k, casadi::Slice()), a) + reader.read(text(row.at("c"))) +
             2 * alpha * Cdot(k) + alpha * alpha * C(k);
    eq.multiplier_names.push_back("lambda_" + row.at("name").get<std::string>());
  }
  eq.residual =
      casadi::Function("kite_residual", {q, v, a, u, lambda},
                       {SX::vertcat({SX::mtimes(M, a) + SX::mtimes(G.T(), lambda) - rhs, dae})});
  const SX x = SX::vertcat({q, v}), invariants = SX::vertcat({C, Cdot});
  eq.invariants = casadi::Function("kite_invariants", {x}, {invariants});
  eq.invariant_jacobian =
      casadi::Function("kite_invariant_jacobian", {x}, {SX::jacobian(invariants, x)});
  return eq;
}

/// START.csv as columns by name.
std::map<std::string, std::vector<double>> read_csv(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path);
  std::string line, cell;
  std::getline(in, line);
  std::vector<std::string> header;
  for (std::stringstream s(line); std::getline(s, cell, ',');) header.push_back(cell);
  std::map<std::string, std::vector<double>> columns;
  while (std::getline(in, line)) {
    std::stringstream s(line);
    for (const std::string& name : header) {
      if (!std::getline(s, cell, ',')) throw std::runtime_error(path + ": a short row");
      columns[name].push_back(std::strtod(cell.c_str(), nullptr));
    }
  }
  return columns;
}

/// lagrange's rule for the boundary rows (src/optimize/transcription.cpp, choose_boundary_rows):
/// a row is kept when it is independent of those kept before, Gram–Schmidt at relative tolerance
/// 1e-8.
class Independence {
 public:
  bool add(std::vector<double> r) {
    double size = 0.0;
    for (double v : r) size = std::max(size, std::fabs(v));
    if (!(size > 0.0)) return false;
    for (int pass = 0; pass < 2; ++pass)
      for (const std::vector<double>& b : basis_) {
        double dot = 0.0;
        for (size_t i = 0; i < r.size(); ++i) dot += r[i] * b[i];
        for (size_t i = 0; i < r.size(); ++i) r[i] -= dot * b[i];
      }
    double norm = 0.0;
    for (double v : r) norm += v * v;
    norm = std::sqrt(norm);
    if (!(norm > 1e-8 * size)) return false;
    for (double& v : r) v /= norm;
    basis_.push_back(std::move(r));
    return true;
  }
  void clear() { basis_.clear(); }

 private:
  std::vector<std::vector<double>> basis_;
};

std::vector<double> unit(int i) {
  std::vector<double> r(kX, 0.0);
  r[static_cast<size_t>(i)] = 1.0;
  return r;
}

/// The NLP in CasADi's symbolic type T (SX or MX), with its bounds and lagrange's start.
template <class T>
casadi::Function transcribe(const KiteEquations& eq,
                            const std::map<std::string, std::vector<double>>& start, int N, int d,
                            const casadi::Dict& opts, std::vector<double>& lbx,
                            std::vector<double>& ubx, std::vector<double>& x0,
                            std::vector<double>& lbg, std::vector<double>& ubg) {
  const std::vector<double> tau = casadi::collocation_points(d, "radau");
  DM Cc, D, B;
  casadi::collocation_coeff(tau, Cc, D, B);
  const double h = kHorizon / N, inf = casadi::inf;
  const int m = static_cast<int>(eq.multiplier_names.size());
  const auto column = [&](const std::string& name) -> const std::vector<double>& {
    const auto found = start.find(name);
    if (found == start.end()) throw std::runtime_error("START.csv has no column " + name);
    if (found->second.size() != static_cast<size_t>(N * d + 1))
      throw std::runtime_error("START.csv: expected the N d + 1 collocation rows");
    return found->second;
  };
  // Row 0 is t = 0; row 1 + k d + (j − 1) is interval k's collocation point j, the last of which
  // is interval k + 1's start.
  const auto node_row = [&](int k, int j) { return j == 0 ? k * d : 1 + k * d + (j - 1); };
  std::vector<T> w, g;
  auto add_state = [&](int row, bool first) {
    const T X = T::sym("X", kX);
    w.push_back(X);
    for (int i = 0; i < kX; ++i) {
      double lo = -inf, up = inf;
      if (i == kLength) lo = kLengthLower, up = kLengthUpper;
      if (i == kLengthRate) lo = kRateLower, up = kRateUpper;
      if (first && i == kY) lo = up = 0.0;
      if (first && i == kYRate) lo = 0.0, up = inf;
      lbx.push_back(lo);
      ubx.push_back(up);
      x0.push_back(column(eq.state_names[static_cast<size_t>(i)])[static_cast<size_t>(row)]);
    }
    return X;
  };
  std::vector<std::vector<T>> X(static_cast<size_t>(N) + 1), L(static_cast<size_t>(N));
  std::vector<T> U(static_cast<size_t>(N));
  for (int k = 0; k < N; ++k) {
    for (int j = 0; j < d; ++j) X[k].push_back(add_state(node_row(k, j), k == 0 && j == 0));
    for (int j = 1; j <= d; ++j) {
      L[k].push_back(T::sym("L", m));
      w.push_back(L[k].back());
      for (int i = 0; i < m; ++i) {
        lbx.push_back(-inf);
        ubx.push_back(inf);
        x0.push_back(column(
            eq.multiplier_names[static_cast<size_t>(i)])[static_cast<size_t>(node_row(k, j))]);
      }
    }
    U[k] = T::sym("U", kControls);
    w.push_back(U[k]);
    for (int c = 0; c < kControls; ++c) {
      lbx.push_back(kControlLower[c]);
      ubx.push_back(kControlUpper[c]);
      x0.push_back(column(kControlNames[c])[static_cast<size_t>(node_row(k, 1))]);
    }
  }
  X[N].push_back(add_state(N * d, false));
  T f = 0;
  auto add_rows = [&](const T& rows, double lo, double up) {
    g.push_back(rows);
    for (casadi_int i = 0; i < rows.size1(); ++i) {
      lbg.push_back(lo);
      ubg.push_back(up);
    }
  };
  for (int k = 0; k < N; ++k) {
    X[k].push_back(X[k + 1][0]);  // X_{k,d} ≡ X_{k+1,0}
    for (int j = 1; j <= d; ++j) {
      T xp = 0;
      for (int l = 0; l <= d; ++l) xp += static_cast<double>(Cc(l, j - 1)) / h * X[k][l];
      const T q = X[k][j](casadi::Slice(0, kQ)), v = X[k][j](casadi::Slice(kQ, kX));
      add_rows(xp(casadi::Slice(0, kQ)) - v, 0, 0);
      add_rows(eq.residual(std::vector<T>{q, v, xp(casadi::Slice(kQ, kX)), U[k], L[k][j - 1]})[0],
               0, 0);
      add_rows(q(kZ), kHeightLower, inf);
      // −(mean power): (1/N) b_j τ l̇ / R
      f += static_cast<double>(B(j - 1)) / N * U[k](2) * v(kLength) / kDrumRadius;
    }
  }
  // The boundary rows at lagrange's start state: the fixed initial value y first, then the
  // invariants it leaves free; for the periodic rows the invariants first, then each component.
  std::vector<double> start_state(kX);
  for (int i = 0; i < kX; ++i) start_state[static_cast<size_t>(i)] = x0[static_cast<size_t>(i)];
  const DM J0 = DM::densify(eq.invariant_jacobian(std::vector<DM>{DM(start_state)})[0]);
  const auto invariant_row = [&](casadi_int r) {
    std::vector<double> row(kX);
    for (int c = 0; c < kX; ++c) row[static_cast<size_t>(c)] = static_cast<double>(J0(r, c));
    return row;
  };
  Independence basis;
  basis.add(unit(kY));
  std::vector<casadi_int> start_rows;
  for (casadi_int r = 0; r < J0.size1(); ++r)
    if (basis.add(invariant_row(r))) start_rows.push_back(r);
  basis.clear();
  for (casadi_int r = 0; r < J0.size1(); ++r) basis.add(invariant_row(r));
  std::vector<int> periodic;
  for (int i = 0; i < kX; ++i)
    if (basis.add(unit(i))) periodic.push_back(i);
  const T invariants0 = eq.invariants(std::vector<T>{X[0][0]})[0];
  for (casadi_int r : start_rows) add_rows(invariants0(r), 0, 0);
  for (int i : periodic) add_rows(X[N][0](i) - X[0][0](i), 0, 0);
  std::printf("casadi: %zu invariants at t = 0, periodic in", start_rows.size());
  for (int i : periodic) std::printf(" %s", eq.state_names[static_cast<size_t>(i)].c_str());
  std::printf("\n");
  return casadi::nlpsol("kite", "ipopt", {{"x", T::vertcat(w)}, {"f", f}, {"g", T::vertcat(g)}},
                        opts);
}

}  // namespace

int main(int argc, char** argv) {
  const char* usage =
      "usage: %s EQUATIONS.json START.csv [N >= 1] [d >= 1] [exact|limited-memory] [sx|mx] "
      "[alpha]\n";
  if (argc < 3) {
    std::fprintf(stderr, usage, argv[0]);
    return 2;
  }
  const int N = argc > 3 ? std::atoi(argv[3]) : 40, d = argc > 4 ? std::atoi(argv[4]) : 3;
  const std::string hessian = argc > 5 ? argv[5] : "exact", graph = argc > 6 ? argv[6] : "sx";
  const double alpha = argc > 7 ? std::atof(argv[7]) : 0.0;
  if (N < 1 || d < 1 || (hessian != "exact" && hessian != "limited-memory") ||
      (graph != "sx" && graph != "mx")) {
    std::fprintf(stderr, usage, argv[0]);
    return 2;
  }
  const auto setup_start = std::chrono::steady_clock::now();
  const KiteEquations eq = read_equations(argv[1], alpha);
  const auto start = read_csv(argv[2]);
  const double read = seconds_since(setup_start);
  const casadi::Dict opts = casadi_peer::ipopt_options(hessian);
  std::vector<double> lbx, ubx, x0, lbg, ubg;
  const casadi::Function solver =
      graph == "sx" ? transcribe<SX>(eq, start, N, d, opts, lbx, ubx, x0, lbg, ubg)
                    : transcribe<MX>(eq, start, N, d, opts, lbx, ubx, x0, lbg, ubg);
  char extra[128];
  std::snprintf(extra, sizeof extra, ", reading the equations and start %.4f s, %s Hessian, %s",
                read, hessian.c_str(), graph.c_str());
  return casadi_peer::solve_and_report(solver, x0, lbx, ubx, seconds_since(setup_start),
                                       static_cast<int>(lbg.size()), extra, lbg, ubg, -1.0);
}

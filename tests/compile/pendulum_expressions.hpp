#pragma once
// An N-link planar pendulum written the way a derivation produces it (expanded sums of
// m_k·l_i·l_j·trig products), used as the realistic workload of the tape tests.

#include <ginac/ginac.h>

#include <string>
#include <vector>

namespace lagrange::test {

/// Symbols and outputs of the N-link pendulum: inputs are [θ₁…θ_N, θ̇₁…θ̇_N, m₁…m_N, l₁…l_N, g].
struct Pendulum {
  std::vector<GiNaC::symbol> inputs;
  std::vector<GiNaC::ex> outputs;  ///< M (row-major, N²) then the generalised force f (N)
  size_t first_parameter = 0;      ///< index of m₁ in inputs
};

/// M_ij = Σ_{k≥max(i,j)} (m_k l_i l_j cos θ_i cos θ_j + m_k l_i l_j sin θ_i sin θ_j) and
/// f_i = −Σ_{k≥i} Σ_{j≤k} m_k l_i l_j θ̇_j² sin(θ_i − θ_j) − Σ_{k≥i} g m_k l_i sin θ_i.
inline Pendulum make_pendulum(int n) {
  using GiNaC::ex;
  using GiNaC::symbol;
  Pendulum p;
  std::vector<symbol> th, v, m, l;
  for (int i = 0; i < n; ++i) th.emplace_back("th" + std::to_string(i));
  for (int i = 0; i < n; ++i) v.emplace_back("v" + std::to_string(i));
  for (int i = 0; i < n; ++i) m.emplace_back("m" + std::to_string(i));
  for (int i = 0; i < n; ++i) l.emplace_back("l" + std::to_string(i));
  symbol g("g");
  for (auto* group : {&th, &v, &m, &l})
    p.inputs.insert(p.inputs.end(), group->begin(), group->end());
  p.inputs.push_back(g);
  p.first_parameter = 2 * static_cast<size_t>(n);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      GiNaC::exvector terms;
      for (int k = std::max(i, j); k < n; ++k) {
        terms.push_back(m[k] * l[i] * l[j] * cos(th[i]) * cos(th[j]));
        terms.push_back(m[k] * l[i] * l[j] * sin(th[i]) * sin(th[j]));
      }
      p.outputs.push_back(GiNaC::add(terms));
    }
  }
  for (int i = 0; i < n; ++i) {
    GiNaC::exvector terms;
    for (int k = i; k < n; ++k) {
      for (int j = 0; j <= k; ++j) {
        terms.push_back(-m[k] * l[i] * l[j] * pow(v[j], 2) * sin(th[i] - th[j]));
      }
      terms.push_back(-g * m[k] * l[i] * sin(th[i]));
    }
    p.outputs.push_back(GiNaC::add(terms));
  }
  return p;
}

/// Deterministic input values: angles and rates in [−1.5, 1.5], masses and lengths in [0.5, 2].
inline std::vector<double> pendulum_point(int n, unsigned seed) {
  std::vector<double> x;
  unsigned s = seed * 2654435761u + 12345u;
  auto next = [&s]() {
    s = s * 1664525u + 1013904223u;
    return (s >> 8) / double(1u << 24);
  };
  for (int i = 0; i < 2 * n; ++i) x.push_back(3.0 * next() - 1.5);
  for (int i = 0; i < 2 * n; ++i) x.push_back(0.5 + 1.5 * next());
  x.push_back(9.81);
  return x;
}

}  // namespace lagrange::test

#pragma once
// Explicit embedded Runge–Kutta pairs that ARKODE does not ship, from published coefficients;
// handed to ARKODE with ARKodeButcherTable_Create (arkode_erk.cpp).

#include <vector>

namespace lagrange::integration {

/// An explicit Butcher table with an embedding: nodes c, rows of A below the diagonal, weights b
/// (the propagated solution, order `order`) and d (the error estimate's, order `embedding`).
struct ButcherCoefficients {
  std::vector<double> c;
  std::vector<std::vector<double>> a;  ///< row i holds a_i0 … a_i,i−1
  std::vector<double> b;
  std::vector<double> d;
  int order;
  int embedding;
};

/// Verner's "efficient" 13-stage 8(7) pair (Verner 2010).
const ButcherCoefficients& verner_8_7();

}  // namespace lagrange::integration

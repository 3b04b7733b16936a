#pragma once
// Radau IIA collocation on [0, 1] (docs/theory.md §10, "Collocation"): points, the derivative
// of the interpolating polynomial at them, and the quadrature weights.

#include <cstddef>
#include <vector>

namespace lagrange::collocation {

/// The d collocation points τ₁ < … < τ_d = 1 (zeros of P_d(2τ−1) − P_{d−1}(2τ−1)) with τ₀ = 0
/// in front (d + 1 nodes), D(j, l) = ℓ_l'(τ_j) for j = 1..d, l = 0..d (row-major, d × (d + 1)),
/// so that x'(τ_j) = Σ_l D(j, l) x_l, and the weights b_j = ∫₀¹ ℓ̃_j (Lagrange basis of τ₁…τ_d),
/// exact for polynomials of degree 2d − 2.
struct Radau {
  int degree = 0;
  std::vector<double> tau;  ///< d + 1 nodes, tau[0] = 0
  std::vector<double> D;    ///< d × (d + 1)
  std::vector<double> b;    ///< d weights
  double derivative(int j, int l) const {
    return D[static_cast<std::size_t>((j - 1) * (degree + 1) + l)];
  }
};

/// The scheme of degree 1 to 5 (std::invalid_argument otherwise).
Radau radau(int degree);

/// ℓ̃_j(τ), j = 1..d: the Lagrange basis of the collocation points τ₁…τ_d at τ, so that the degree
/// d − 1 polynomial through values U_j there is Σ_j ℓ̃_j(τ) U_j (docs/theory.md §10, "Polynomial
/// controls").
std::vector<double> point_basis(const Radau& r, double tau);

}  // namespace lagrange::collocation

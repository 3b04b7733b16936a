#include "optimize/radau.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace lagrange::collocation {

namespace {

/// P_n(x) and P_n'(x) by the three-term recurrence.
void legendre(int n, double x, double& p, double& dp) {
  double p0 = 1.0, p1 = x, d0 = 0.0, d1 = 1.0;
  if (n == 0) {
    p = 1.0;
    dp = 0.0;
    return;
  }
  for (int k = 2; k <= n; ++k) {
    const double p2 = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
    const double d2 = d0 + (2 * k - 1) * p1;
    p0 = p1;
    p1 = p2;
    d0 = d1;
    d1 = d2;
  }
  p = p1;
  dp = d1;
}

}  // namespace

Radau radau(int d) {
  if (d < 1 || d > 5)
    throw std::invalid_argument("expected a collocation degree from 1 to 5, got " +
                                std::to_string(d));
  // Starting values (Hairer & Wanner, Table IV.5.5), refined by Newton on P_d − P_{d−1} in x = 2τ
  // − 1.
  static const double start[5][5] = {
      {1.0},
      {1.0 / 3.0, 1.0},
      {0.155051025721682, 0.644948974278318, 1.0},
      {0.088587959512704, 0.409466864440735, 0.787659461760847, 1.0},
      {0.057104196114518, 0.276843013638124, 0.583590432368917, 0.860240135656219, 1.0}};
  Radau r;
  r.degree = d;
  r.tau.assign(1, 0.0);
  for (int j = 0; j < d; ++j) {
    double x = 2.0 * start[d - 1][j] - 1.0;
    for (int it = 0; it < 20 && j < d - 1; ++it) {
      double pa, da, pb, db;
      legendre(d, x, pa, da);
      legendre(d - 1, x, pb, db);
      x -= (pa - pb) / (da - db);
    }
    r.tau.push_back(j == d - 1 ? 1.0 : 0.5 * (x + 1.0));
  }
  // ℓ_l'(τ_j) on the nodes τ₀…τ_d (barycentric weights w_l = 1/Π_{m≠l}(τ_l − τ_m)).
  const int n = d + 1;
  std::vector<double> w(n, 1.0);
  for (int l = 0; l < n; ++l)
    for (int m = 0; m < n; ++m)
      if (m != l) w[l] /= r.tau[l] - r.tau[m];
  r.D.assign(static_cast<size_t>(d * n), 0.0);
  for (int j = 1; j <= d; ++j) {
    double diagonal = 0.0;
    for (int l = 0; l < n; ++l) {
      if (l == j) continue;
      const double v = (w[l] / w[j]) / (r.tau[j] - r.tau[l]);
      r.D[static_cast<size_t>((j - 1) * n + l)] = v;
      diagonal -= v;
    }
    r.D[static_cast<size_t>((j - 1) * n + j)] = diagonal;
  }
  // b from Σ_j b_j τ_j^k = 1/(k + 1), k < d (Gaussian elimination on the small Vandermonde).
  std::vector<std::vector<double>> A(d, std::vector<double>(d + 1));
  for (int k = 0; k < d; ++k) {
    for (int j = 0; j < d; ++j) A[k][j] = std::pow(r.tau[j + 1], k);
    A[k][d] = 1.0 / (k + 1);
  }
  for (int c = 0; c < d; ++c) {
    int p = c;
    for (int k = c + 1; k < d; ++k)
      if (std::fabs(A[k][c]) > std::fabs(A[p][c])) p = k;
    std::swap(A[c], A[p]);
    for (int k = 0; k < d; ++k) {
      if (k == c) continue;
      const double f = A[k][c] / A[c][c];
      for (int j = c; j <= d; ++j) A[k][j] -= f * A[c][j];
    }
  }
  for (int j = 0; j < d; ++j) r.b.push_back(A[j][d] / A[j][j]);
  return r;
}

// docs/theory.md §10, "Polynomial controls": ℓ̃_j(τ) = Π_{l≠j} (τ − τ_l)/(τ_j − τ_l) over l = 1..d.
std::vector<double> point_basis(const Radau& r, double tau) {
  const size_t d = static_cast<size_t>(r.degree);
  std::vector<double> w(d, 1.0);
  for (size_t j = 1; j <= d; ++j)
    for (size_t l = 1; l <= d; ++l)
      if (l != j) w[j - 1] *= (tau - r.tau[l]) / (r.tau[j] - r.tau[l]);
  return w;
}

}  // namespace lagrange::collocation

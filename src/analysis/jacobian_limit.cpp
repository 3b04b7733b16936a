// docs/theory.md §5.1, "Limits": a derivative the tape gives as 0/0 (d(|v| v)/dv = |v| + v²/|v|
// at v = 0) is the limit of the derivatives nearby when that limit exists.

#include "analysis/jacobian_limit.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>

namespace lagrange::analysis_detail {

namespace {

bool finite(const std::vector<Eigen::MatrixXd*>& blocks) {
  for (const Eigen::MatrixXd* B : blocks)
    if (!B->allFinite()) return false;
  return true;
}

// Step of the moved states, relative to |y| + 1: the O(s²) error of the extrapolation is then
// at the rounding of J itself, and |v| ~ s is far from underflow in v·v.
constexpr double kStep = 1e-8;
// Limits along different directions agreeing to this fraction of the derivatives nearby: those
// of a removable 0/0 agree to 4e-16, the figure-eight's roll law at |azimuth| = 0, whose sides
// differ by sech²(a0/0.02) ≈ 6e-11, to 1e-11.
constexpr double kAgree = 1e-12;
// A limit below this fraction of the derivatives nearby is the rounding of an exact 0.
constexpr double kRounding = 1e-10;

[[noreturn]] void not_differentiable(double t) {
  throw NotDifferentiable(fmt::format(
      "the derivatives of the dynamics are not finite at t = {}, and their limits there depend "
      "on the direction of approach: the dynamics are not differentiable there (|x| at x = 0, a "
      "norm at the zero vector, max or min at a tie)",
      t));
}

}  // namespace

std::vector<Eigen::MatrixXd*> derivative_blocks(StateJacobian& J) {
  return {&J.qdot_q, &J.qdot_v, &J.a_q, &J.a_v, &J.a_w, &J.G,
          &J.C_q,    &J.Cdot_q, &J.y_q, &J.y_v, &J.y_w};
}

void fill_limits(const std::vector<Eigen::MatrixXd*>& out, const DerivativesAt& at, const double* y,
                 size_t n, double t) {
  if (finite(out)) return;
  // J(s) = J₀ + J₁ s + O(s²) along a ray from the point (for |v| v exactly, J₁ s = 2|s d|):
  // 2 J(s) − J(2s) = J₀ + O(s²).
  std::mt19937 random(36);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::vector<double> d(n), d2(n);
  for (double& x : d) x = unit(random);
  for (double& x : d2) x = unit(random);
  const std::array<std::pair<const std::vector<double>*, double>, 3> rays{
      {{&d, 1.0}, {&d, -1.0}, {&d2, 1.0}}};
  std::vector<std::array<std::vector<Eigen::MatrixXd>, 2>> nearby;
  for (const auto& [dir, sign] : rays) {
    std::array<std::vector<Eigen::MatrixXd>, 2> pair;
    for (int k = 0; k < 2; ++k) {
      std::vector<double> moved(y, y + n);
      for (size_t i = 0; i < n; ++i)
        moved[i] += sign * (k + 1) * kStep * (std::abs(moved[i]) + 1.0) * (*dir)[i];
      pair[static_cast<size_t>(k)] = at(moved.data());
    }
    nearby.push_back(std::move(pair));
  }
  for (size_t b = 0; b < out.size(); ++b) {
    Eigen::MatrixXd& B = *out[b];
    for (long j = 0; j < B.cols(); ++j)
      for (long i = 0; i < B.rows(); ++i) {
        if (std::isfinite(B(i, j))) continue;
        double first = 0.0, spread = 0.0, size = 0.0;
        for (size_t r = 0; r < nearby.size(); ++r) {
          const double s1 = nearby[r][0][b](i, j), s2 = nearby[r][1][b](i, j);
          const double limit = 2.0 * s1 - s2;
          if (!std::isfinite(limit)) not_differentiable(t);
          if (r == 0) first = limit;
          spread = std::max(spread, std::abs(limit - first));
          size += std::abs(s1) + std::abs(s2);
        }
        if (spread > kAgree * size) not_differentiable(t);
        B(i, j) = std::abs(first) <= kRounding * size ? 0.0 : first;
      }
  }
}

}  // namespace lagrange::analysis_detail

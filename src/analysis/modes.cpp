// Eigenvalues, natural frequencies, damping ratios and mode shapes of a linear model, and its
// zero-order-hold discretisation (docs/theory.md §5.4).

#include <Eigen/QR>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <unsupported/Eigen/MatrixFunctions>

#include "lagrange/analysis.hpp"

namespace lagrange {

namespace {

/// max Re λ(A), 0 for an empty A, NaN when the eigenvalue solver fails.
double fastest_growth(const Eigen::MatrixXd& A) {
  if (A.rows() == 0) return 0.0;
  Eigen::EigenSolver<Eigen::MatrixXd> es(A, false);
  if (es.info() != Eigen::Success) return std::numeric_limits<double>::quiet_NaN();
  return es.eigenvalues().real().maxCoeff();
}

}  // namespace

LinearModel discretize(const LinearModel& continuous, double dt) {
  if (!(dt > 0 && std::isfinite(dt)))
    throw std::invalid_argument(
        fmt::format("the sampling time must be positive and finite, got {}", dt));
  if (continuous.dt > 0) throw std::invalid_argument("the model is already discrete");
  const long n = continuous.A.rows(), k = continuous.B.cols();
  // exp([A B; 0 0] dt) = [A_d B_d; 0 1]: the state transition and the held input's effect.
  Eigen::MatrixXd aug = Eigen::MatrixXd::Zero(n + k, n + k);
  aug.topLeftCorner(n, n) = continuous.A * dt;
  aug.topRightCorner(n, k) = continuous.B * dt;
  // Eigen's exp() scales and squares (Higham 2005); what overflows a double is refused, never
  // printed as NaN (issue 37 item 5).
  const Eigen::MatrixXd E = aug.exp();
  if (!E.allFinite())
    throw AnalysisError(fmt::format(
        "the zero-order hold over the sampling time dt = {} overflows a double (|A dt| = {:.3g}, "
        "fastest growth Re λ = {:.3g}/s): give a shorter step",
        dt, aug.topLeftCorner(n, n).cwiseAbs().maxCoeff(), fastest_growth(continuous.A)));
  LinearModel d = continuous;
  d.A = E.topLeftCorner(n, n);
  d.B = E.topRightCorner(n, k);
  d.dt = dt;
  return d;
}

namespace {

/// The algebraic multiplicity of the eigenvalue 0 of A: n − rank(Aᵏ) once the rank stops
/// falling (docs/theory.md §5.4). A defective 0 (a free coordinate's [0 1; 0 0]) comes out of
/// the eigenvalue solver as ±√ε·‖A‖, far above the round-off of a simple one.
long zero_eigenvalues(const Eigen::MatrixXd& A) {
  Eigen::MatrixXd P = A;
  long rank = A.rows();
  for (long k = 0; k < A.rows(); ++k) {
    Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(P);
    qr.setThreshold(1e-10);
    if (qr.rank() == rank) break;
    rank = qr.rank();
    const double size = P.cwiseAbs().maxCoeff();
    if (size == 0.0) break;
    P = (P / size) * A;  // scaled, so that high powers neither overflow nor underflow
  }
  return A.rows() - rank;
}

}  // namespace

std::vector<Mode> modes(const LinearModel& lin, size_t components) {
  std::vector<Mode> out;
  if (lin.A.rows() == 0) return out;
  Eigen::EigenSolver<Eigen::MatrixXd> es(lin.A);
  if (es.info() != Eigen::Success) throw AnalysisError("the eigenvalue solver did not converge");
  const double scale = std::max(1.0, lin.A.cwiseAbs().maxCoeff());
  const long n_full = lin.basis.rows() / 2;
  // The zero_eigenvalues() smallest in magnitude are exactly 0: each a real mode of its own.
  Eigen::VectorXcd eigenvalues = es.eigenvalues();
  std::vector<long> by_size(static_cast<size_t>(eigenvalues.size()));
  std::iota(by_size.begin(), by_size.end(), 0);
  std::stable_sort(by_size.begin(), by_size.end(), [&](long a, long b) {
    return std::abs(eigenvalues[a]) < std::abs(eigenvalues[b]);
  });
  const long zeros = zero_eigenvalues(lin.A);
  for (long k = 0; k < zeros; ++k) eigenvalues[by_size[static_cast<size_t>(k)]] = 0.0;
  for (long k = 0; k < lin.A.rows(); ++k) {
    const std::complex<double> lambda = eigenvalues[k];
    if (lambda.imag() < -1e-12 * scale) continue;  // the conjugate of a listed pair
    Mode mode;
    // Parts below round-off of A's scale are zero: a conservative system's pairs are printed
    // as purely imaginary, with damping 0 and an infinite time constant.
    const auto clean = [&](double x) { return std::abs(x) <= 1e-12 * scale ? 0.0 : x; };
    mode.eigenvalue = {clean(lambda.real()), clean(lambda.imag())};
    const double mag = std::abs(mode.eigenvalue);
    mode.frequency_hz = mag / (2 * M_PI);
    mode.damping = mag > 0 ? -mode.eigenvalue.real() / mag + 0.0 : 0.0;
    mode.time_constant = mode.eigenvalue.real() != 0.0 ? -1.0 / mode.eigenvalue.real()
                                                       : std::numeric_limits<double>::infinity();
    // The shape in the full tangent state; positions tell it (rates are λ times them) unless
    // the mode lives in the velocities alone.
    const Eigen::VectorXcd z = lin.basis.cast<std::complex<double>>() * es.eigenvectors().col(k);
    long first = 0, count = n_full;
    if (z.head(n_full).cwiseAbs().maxCoeff() < 1e-9 * z.cwiseAbs().maxCoeff()) count = 2 * n_full;
    if (count == 2 * n_full) first = 0;
    Eigen::Index top = 0;
    z.segment(first, count).cwiseAbs().maxCoeff(&top);
    const std::complex<double> ref = z[first + top];
    std::vector<long> order(static_cast<size_t>(count));
    std::iota(order.begin(), order.end(), first);
    std::stable_sort(order.begin(), order.end(),
                     [&](long a, long b) { return std::abs(z[a]) > std::abs(z[b]); });
    for (long i : order) {
      if (mode.shape.size() >= components) break;
      const std::complex<double> c = z[i] / ref;
      if (std::abs(c) < 1e-3) break;
      mode.shape.push_back(
          {lin.full_state_names[static_cast<size_t>(i)], std::abs(c), std::arg(c) * 180.0 / M_PI});
    }
    out.push_back(std::move(mode));
  }
  std::sort(out.begin(), out.end(), [](const Mode& a, const Mode& b) {
    const double ma = std::abs(a.eigenvalue), mb = std::abs(b.eigenvalue);
    if (std::abs(ma - mb) > 1e-12 * std::max(ma, mb)) return ma < mb;
    return a.eigenvalue.real() < b.eigenvalue.real();
  });
  return out;
}

}  // namespace lagrange

// docs/theory.md §5.1, "Implicit form": the sparse Jacobian of the residual
// Φ = (M a + Gᵀλ − f, G a + c + 2αĊ + α²C) at a and λ held, against central differences of Φ
// computed from the tape's values, and −K⁻¹ ∂Φ/∂x against DynamicsJacobian::evaluate (whose
// range-space solve, on the long line below, is a second formulation of the same system).

#include <gtest/gtest.h>

#include "analysis/analysed.hpp"

namespace lagrange {
namespace {

using testing::Analysed;

// Φ at tape inputs `in` with a, λ and α fixed, from the Jacobian tape's leading values.
Eigen::VectorXd residual(const DynamicsJacobian& jac, const std::vector<double>& in,
                         const Eigen::VectorXd& a, const Eigen::VectorXd& lambda, double alpha) {
  const CompiledModel& c = jac.model();
  const long n = static_cast<long>(c.nv), m = static_cast<long>(c.m);
  std::vector<double> out(jac.tape().num_outputs()), work(jac.tape().work_size() + 1);
  jac.tape().eval(in.data(), out.data(), work.data());
  Eigen::VectorXd phi = Eigen::VectorXd::Zero(n + m);
  for (size_t e = 0; e < c.M_pattern.size(); ++e) {
    const auto [i, j] = c.M_pattern[e];
    phi[static_cast<long>(i)] += out[e] * a[static_cast<long>(j)];
    if (i != j) phi[static_cast<long>(j)] += out[e] * a[static_cast<long>(i)];
  }
  for (long i = 0; i < n; ++i) phi[i] -= out[c.rhs_out() + static_cast<size_t>(i)];
  for (size_t e = 0; e < c.G_pattern.size(); ++e) {
    const auto [r, j] = c.G_pattern[e];
    phi[static_cast<long>(j)] += out[c.G_out() + e] * lambda[static_cast<long>(r)];
    phi[n + static_cast<long>(r)] += out[c.G_out() + e] * a[static_cast<long>(j)];
  }
  for (long r = 0; r < m; ++r) {
    const size_t k = static_cast<size_t>(r);
    phi[n + r] +=
        out[c.c_out() + k] + 2 * alpha * out[c.Cdot_out() + k] + alpha * alpha * out[c.C_out() + k];
  }
  return phi;
}

void check(Analysed& s) {
  const CompiledModel& c = *s.cm;
  const long n = static_cast<long>(c.nv), nq = static_cast<long>(c.nq);
  const ImplicitJacobian I = s.jac->implicit(*s.dyn, 0.0, s.q.data(), s.v.data());
  const std::vector<double> in = s.dyn->last_inputs();
  const double alpha = s.dyn->baumgarte();
  // Φ = 0 at the forward dynamics' a and λ: the implicit form is the same system.
  const Eigen::VectorXd phi0 = residual(*s.jac, in, I.a, I.lambda, alpha);
  EXPECT_LE(phi0.cwiseAbs().maxCoeff(), 1e-9 * std::max(1.0, I.a.cwiseAbs().maxCoeff()));
  const Eigen::MatrixXd P = I.Phi_x;
  const double scale = std::max(1.0, P.cwiseAbs().maxCoeff());
  for (long k = 0; k < nq + n; ++k) {
    const size_t at = c.q_offset() + static_cast<size_t>(k);  // v follows q in the inputs
    const auto phi = [&](double h) {
      std::vector<double> moved = in;
      moved[at] += h;
      return residual(*s.jac, moved, I.a, I.lambda, alpha);
    };
    const double h = 1e-5 * std::max(1.0, std::abs(in[at]));
    const Eigen::VectorXd d1 = (phi(h) - phi(-h)) / (2 * h);
    const Eigen::VectorXd d2 = (phi(h / 2) - phi(-h / 2)) / h;
    const Eigen::VectorXd fd = (4 * d2 - d1) / 3;
    EXPECT_LE((P.col(k) - fd).cwiseAbs().maxCoeff(), 1e-6 * scale)
        << "column " << k << "\nexact " << P.col(k).transpose() << "\nfd    " << fd.transpose();
  }
  // ∂(a, λ)/∂x = −K⁻¹ ∂Φ/∂x by a dense LU here, against evaluate's solve.
  StateJacobian J;
  try {
    J = s.jac->evaluate(*s.dyn, 0.0, s.q.data(), s.v.data());
  } catch (const NotDifferentiable&) {
    // A kink at the start (an elastic line at exactly its unstretched length, docs/theory.md
    // §5.6): the tape's ∂Φ/∂x has its 0/0 there, and evaluate refuses rather than answer NaN.
    EXPECT_FALSE(P.allFinite()) << "evaluate refused where the implicit form is finite";
    return;
  }
  const Eigen::MatrixXd X = Eigen::MatrixXd(I.K).partialPivLu().solve(-P).topRows(n);
  Eigen::MatrixXd exact(n, X.cols());
  exact << J.a_q, J.a_v, J.a_w;
  EXPECT_LE((X - exact).cwiseAbs().maxCoeff(), 1e-9 * std::max(1.0, exact.cwiseAbs().maxCoeff()));
  // q̇'s Jacobian is evaluate's too.
  EXPECT_EQ(Eigen::MatrixXd(I.qdot_x.leftCols(nq)), J.qdot_q);
  EXPECT_EQ(Eigen::MatrixXd(I.qdot_x.rightCols(n)), J.qdot_v);
}

class ExampleImplicitJacobian : public ::testing::TestWithParam<std::string> {};

TEST_P(ExampleImplicitJacobian, MatchesCentralDifferencesOfTheResidual) {
  Analysed s = testing::analyse_example(GetParam());
  for (size_t i = 0; i < s.cm->nv; ++i) s.v[i] += 0.1 * std::sin(1.0 + static_cast<double>(i));
  if (s.cm->m > 0) s.dyn->project(0.0, s.q.data(), s.v.data(), s.cm->fixed);
  check(s);
}

// Constraints (fixed and moving with an input), free bodies, tethers in wind, a winch.
INSTANTIATE_TEST_SUITE_P(Examples, ExampleImplicitJacobian,
                         ::testing::Values("cartesian_pendulum.yaml", "crane.yaml",
                                           "tumbling_brick.yaml", "tether_in_wind.yaml",
                                           "bridled_kite.yaml", "winch.yaml"),
                         [](const auto& info) { return testing::model_label(info.param); });

// More KKT rows than kSparseKkt with a diagonal M: evaluate solves in range-space form.
TEST(ImplicitJacobian, LongLineRangeSpaceSolveAgreesWithTheDenseKkt) {
  Analysed s = testing::analyse_string(R"(
name: long line in wind
parameters: {L: 12, mu: 0.05, d: 0.01, U: 6}
gravity: [0, 0, -9.81]
wind: {speed: U}
tethers:
  line: {between: [[0, 0, 0], [10, 0, 0]], segments: 40, length: L, mass_per_length: mu,
         diameter: d, cd: 1.2, drag: fine}
)",
                                       {"U"});
  ASSERT_GT(s.cm->nv + s.cm->m, 120u);
  for (size_t i = 0; i < s.cm->nv; ++i) s.v[i] = 0.3 * std::sin(1.0 + static_cast<double>(i));
  s.dyn->project(0.0, s.q.data(), s.v.data(), s.cm->fixed);
  check(s);
}

}  // namespace
}  // namespace lagrange

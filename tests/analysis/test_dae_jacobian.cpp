// docs/theory.md §5.6, "The DAE's Newton matrix": the exact sparse ∂F/∂y + c_j ∂F/∂y' of the
// index-1 DAE in (q, v, λ) against central differences of Dynamics::dae_residual, and
// ida:jacobian (IDA's Newton matrices from it) against DOP853 at tight tolerances on a tether,
// a chain and a kite.

#include <gtest/gtest.h>

#include <cmath>

#include "analysis/analysed.hpp"

namespace lagrange {
namespace {

using testing::Analysed;

// F(y, y') of the DAE that ida integrates, y = (q, v, λ).
Eigen::VectorXd dae_residual_at(Analysed& s, const std::vector<double>& y,
                                const std::vector<double>& yp) {
  const CompiledModel& cm = *s.cm;
  const size_t nq = cm.nq, n = cm.nq + cm.nv;
  Eigen::VectorXd r(static_cast<long>(n + cm.m));
  s.dyn->dae_residual(0.0, y.data(), y.data() + nq, yp.data(), yp.data() + nq, y.data() + n,
                      r.data());
  return r;
}

// Every entry of the Newton matrix at c_j = 37, zeros outside its pattern included, against
// Richardson-extrapolated central differences of F in y and y': max error ≤ 1e-6 · max(1, |J|).
// The state is the model's start with y' = (q̇, a) of the forward dynamics moved off by a
// smooth pattern, and λ likewise: the matrix is exact at any (y, y'), not only on the solution.
void check_newton_matrix_against_differences(Analysed s, const std::string& example) {
  const CompiledModel& cm = *s.cm;
  const size_t nq = cm.nq, nv = cm.nv, n = nq + nv, size = n + cm.m;
  std::vector<double> y(size), yp(size, 0.0);
  std::copy(s.q.begin(), s.q.end(), y.begin());
  std::copy(s.v.begin(), s.v.end(), y.begin() + static_cast<long>(nq));
  s.dyn->forward(0.0, s.q.data(), s.v.data(), yp.data(), yp.data() + nq, y.data() + n);
  for (size_t i = nq; i < size; ++i) {
    const double off = 0.3 * std::sin(1.7 * static_cast<double>(i));
    (i < n ? yp[i] : y[i]) += off * (1.0 + std::abs(i < n ? yp[i] : y[i]));
  }
  const double cj = 37.0;
  const DaeJacobian jac = dae_jacobian(*s.jac, *s.dyn, 0.0, y);
  ASSERT_EQ(jac.column_starts.size(), size + 1);
  std::vector<double> values(jac.nonzeros());
  jac.values(0.0, cj, y.data(), yp.data(), values.data());
  const long N = static_cast<long>(size);
  Eigen::MatrixXd exact = Eigen::MatrixXd::Zero(N, N);
  for (size_t j = 0; j < size; ++j)
    for (long e = jac.column_starts[j]; e < jac.column_starts[j + 1]; ++e)
      exact(jac.rows[static_cast<size_t>(e)], static_cast<long>(j)) =
          values[static_cast<size_t>(e)];
  ASSERT_TRUE(exact.allFinite()) << example;
  const double scale = std::max(1.0, exact.cwiseAbs().maxCoeff());
  for (size_t j = 0; j < size; ++j) {
    const auto derivative = [&](std::vector<double>& x) {  // ∂F/∂x_j, x = y or y'
      const double x0 = x[j], h = 1e-4 * std::max(1.0, std::abs(x0));
      const auto F = [&](double d) {
        x[j] = x0 + d;
        const Eigen::VectorXd r = dae_residual_at(s, y, yp);
        x[j] = x0;
        return r;
      };
      const Eigen::VectorXd d1 = (F(h) - F(-h)) / (2 * h), d2 = (F(h / 2) - F(-h / 2)) / h;
      return Eigen::VectorXd((4 * d2 - d1) / 3);
    };
    const Eigen::VectorXd fd = derivative(y) + cj * derivative(yp);
    ASSERT_TRUE(fd.allFinite()) << example << ": column " << j;
    EXPECT_LE((exact.col(static_cast<long>(j)) - fd).cwiseAbs().maxCoeff(), 1e-6 * scale)
        << example << ": column " << j;
  }
}

TEST(DaeJacobian, TetherInWindAgainstDifferences) {
  check_newton_matrix_against_differences(testing::analyse_example("tether_in_wind.yaml"),
                                          "tether_in_wind");
}
// A free body: R's nine entries with Ṙ = R(Ω + Ξ), as ida integrates them.
TEST(DaeJacobian, RigidKiteAgainstDifferences) {
  check_newton_matrix_against_differences(testing::analyse_example("rigid_kite_ap2.yaml"),
                                          "rigid AP2");
}

// ida:jacobian at rtol 1e-10 against DOP853 at rtol 1e-12 over 1 s of the example: every
// coordinate at every sample within `tol`.
void check_against_dop853(Analysed s, const std::string& example, double tol) {
  SimulationOptions so;
  so.t_end = 1.0;
  so.output_step = 0.05;
  const Trajectory ref = testing::dop853_reference(s, so);
  ASSERT_EQ(ref.status, Trajectory::Status::Complete) << ref.message;

  so.integrator.method = "ida:jacobian";
  so.integrator.rtol = 1e-10;
  so.integrator.atol = 1e-12;
  s.dyn->set_baumgarte(baumgarte_rate(s.model->stabilization, "ida:jacobian"));
  long evaluations = 0;
  so.jacobian_source.dae = [&](Dynamics& dyn, double t0, const std::vector<double>& y0) {
    DaeJacobian jac = dae_jacobian(*s.jac, dyn, t0, y0);
    jac.values = [&evaluations, values = jac.values](double t, double cj, const double* y,
                                                     const double* yp, double* out) {
      ++evaluations;
      values(t, cj, y, yp, out);
    };
    return jac;
  };
  const Trajectory tr = simulate(*s.dyn, so, s.q, s.v);
  ASSERT_EQ(tr.status, Trajectory::Status::Complete) << tr.message;
  ASSERT_EQ(tr.rows(), ref.rows());
  EXPECT_EQ(tr.stats.method, "ida:jacobian");
  EXPECT_GT(evaluations, 0);  // IDA's Newton matrices came from it
  EXPECT_LT(testing::worst_coordinate_difference(s, tr, ref), tol) << example;
}

TEST(IdaJacobian, HangingChainAgreesWithDop853) {
  check_against_dop853(testing::analyse_example("hanging_chain.yaml"), "hanging_chain", 1e-6);
}
TEST(IdaJacobian, TetherInWindAgreesWithDop853) {
  check_against_dop853(testing::analyse_example("tether_in_wind.yaml"), "tether_in_wind", 1e-6);
}
TEST(IdaJacobian, RigidKiteAgreesWithDop853) {
  check_against_dop853(testing::analyse_example("rigid_kite_ap2.yaml"), "rigid AP2", 1e-6);
}

// docs/theory.md §5.8: BDF held at order k converges at order k — the error against DOP853 falls
// as steps^(−k) — on the double pendulum (an ODE in IDA's residual form) and on the Cartesian
// pendulum (q, v and the multiplier λ), sampled once at the end so that no projection restarts it.
TEST(IdaJacobian, FixedOrderConvergesAtItsOrder) {
  for (const auto& [example, output_step] :
       {std::pair{"double_pendulum.yaml", 0.05}, std::pair{"cartesian_pendulum.yaml", 2.0}})
    for (const char* method : {"ida:jacobian", "ida"})  // plain ida: difference quotients
      testing::expect_fixed_order_convergence(example, method, output_step);
}

// At the default (variable order up to 5) the error follows the tolerance: 100 times tighter,
// 10 to 1000 times smaller.
TEST(IdaJacobian, ErrorFollowsTheTolerance) {
  testing::expect_error_follows_tolerance("ida:jacobian");
}

}  // namespace
}  // namespace lagrange

// docs/theory.md §5.1–5.2: the exact Jacobians ∂a/∂x (tangent coordinates, so free bodies'
// rotations too), ∂a/∂v and ∂a/∂p against central differences of the forward dynamics, for every
// example at its initial state and at a state nearby; examples whose dynamics are not
// differentiable at their initial state must be refused, not answered.

#include <gtest/gtest.h>

#include "analysis/analysed.hpp"

namespace lagrange {
namespace {

using testing::Analysed;

Eigen::VectorXd accelerations(Dynamics& dyn, const std::vector<double>& q,
                              const std::vector<double>& v) {
  const CompiledModel& cm = dyn.model();
  std::vector<double> qdot(cm.nq), lambda(cm.m);
  Eigen::VectorXd a(static_cast<long>(cm.nv));
  dyn.forward(0.0, q.data(), v.data(), qdot.data(), a.data(), lambda.data());
  return a;
}

// max |exact − central difference| ≤ 1e-6 · max(1, max |exact|), column by column named.
void expect_close(const Eigen::MatrixXd& exact, const Eigen::MatrixXd& fd,
                  const std::vector<std::string>& columns, const std::string& what) {
  const double scale = std::max(1.0, exact.cwiseAbs().maxCoeff());
  for (long k = 0; k < exact.cols(); ++k) {
    const double err = (exact.col(k) - fd.col(k)).cwiseAbs().maxCoeff();
    EXPECT_LE(err, 1e-6 * scale) << what << " column " << columns[static_cast<size_t>(k)]
                                 << ": exact\n"
                                 << exact.col(k).transpose() << "\nfd\n"
                                 << fd.col(k).transpose();
  }
}

void check_against_differences(Analysed& s) {
  const CompiledModel& cm = *s.cm;
  const long n = static_cast<long>(cm.nv);
  const StateJacobian J = s.jac->evaluate(*s.dyn, 0.0, s.q.data(), s.v.data());
  const TangentChart chart = tangent_chart(cm, s.q.data(), s.v.data());
  const Eigen::MatrixXd a_x = J.a_q * chart.T;

  // Central differences with one Richardson step, (4 D(h/2) − D(h))/3: O(h⁴) truncation.
  const auto richardson = [](const auto& f, double h) {
    const Eigen::VectorXd d1 = (f(h) - f(-h)) / (2 * h);
    const Eigen::VectorXd d2 = (f(h / 2) - f(-h / 2)) / h;
    return Eigen::VectorXd((4 * d2 - d1) / 3);
  };
  Eigen::MatrixXd fd_x(n, n), fd_v(n, n), fd_p(n, static_cast<long>(cm.np));
  for (long k = 0; k < n; ++k) {
    fd_x.col(k) = richardson(
        [&](double h) {
          Eigen::VectorXd dx = Eigen::VectorXd::Zero(n);
          dx[k] = h;
          std::vector<double> q = s.q;
          retract(cm, dx.data(), q.data());
          return accelerations(*s.dyn, q, s.v);
        },
        1e-4);
    fd_v.col(k) = richardson(
        [&](double h) {
          std::vector<double> v = s.v;
          v[static_cast<size_t>(k)] += h;
          return accelerations(*s.dyn, s.q, v);
        },
        1e-4 * std::max(1.0, std::abs(s.v[static_cast<size_t>(k)])));
  }
  std::vector<double> p = cm.parameter_defaults;
  for (size_t k = 0; k < cm.np; ++k)
    fd_p.col(static_cast<long>(k)) = richardson(
        [&](double h) {
          std::vector<double> pk = p;
          pk[k] += h;
          s.dyn->set_parameters(pk);
          return accelerations(*s.dyn, s.q, s.v);
        },
        p[k] != 0.0 ? 1e-3 * std::abs(p[k]) : 1e-4);  // relative: some parameters are small
  s.dyn->set_parameters(p);
  expect_close(a_x, fd_x, chart.names, "da/dx");
  expect_close(J.a_v, fd_v, cm.velocity_names, "da/dv");
  expect_close(J.a_w, fd_p.leftCols(J.a_w.cols()), cm.parameter_names, "da/dp");
}

class ExampleJacobian : public ::testing::TestWithParam<std::string> {};

TEST_P(ExampleJacobian, MatchesCentralDifferences) {
  const std::string name = GetParam();
  std::unique_ptr<Model> model =
      std::make_unique<Model>(read_model_file(testing::example_path(name)));
  std::vector<std::string> parameters;  // every parameter as an input: B's columns too
  for (const auto& p : model->parameters) parameters.push_back(p.name);
  Analysed s = testing::analyse(std::move(model), parameters);
  bool refused = false;  // never a NaN: a removable 0/0 is its limit, a kink an error
  try {
    const StateJacobian J = s.jac->evaluate(*s.dyn, 0.0, s.q.data(), s.v.data());
    EXPECT_TRUE(J.a_q.allFinite() && J.a_v.allFinite());
  } catch (const NotDifferentiable&) {
    refused = true;
  }
  if (refused) {
    // Not differentiable at the initial state (a control law with |azimuth| at 0): refused.
    try {
      (void)s.linear();
      FAIL() << "linearize answered at a point where the Jacobian is not finite";
    } catch (const AnalysisError& e) {
      EXPECT_NE(std::string(e.what()).find("not differentiable"), std::string::npos) << e.what();
    }
  } else {
    check_against_differences(s);
  }
  // A state nearby (positions and velocities moved, put back on the constraints).
  for (size_t i = 0; i < s.cm->nv; ++i) s.v[i] += 0.1 * std::sin(1.0 + static_cast<double>(i));
  Eigen::VectorXd dx(static_cast<long>(s.cm->nv));
  for (long i = 0; i < dx.size(); ++i) dx[i] = 0.05 * std::cos(2.0 + static_cast<double>(i));
  retract(*s.cm, dx.data(), s.q.data());
  if (s.cm->m > 0) s.dyn->project(0.0, s.q.data(), s.v.data(), s.cm->fixed);
  const StateJacobian J2 = s.jac->evaluate(*s.dyn, 0.0, s.q.data(), s.v.data());
  ASSERT_TRUE(J2.a_q.allFinite() && J2.a_v.allFinite()) << "not differentiable nearby either";
  check_against_differences(s);
}

INSTANTIATE_TEST_SUITE_P(Examples, ExampleJacobian, ::testing::ValuesIn(testing::example_files()),
                         [](const auto& info) { return testing::model_label(info.param); });

// More KKT rows than kSparseKkt (117 velocities, 40 constraints): the differentiated system is
// factorised sparse (dynamics_jacobian.cpp); a line between two anchors in a wind, with drag,
// moving, against central differences like every example.
TEST(SparseKktJacobian, LongLineInWindMatchesCentralDifferences) {
  Analysed s = testing::analyse_string(R"(
name: long line in wind
parameters: {L: 12, mu: 0.05, d: 0.01, U: 6}
gravity: [0, 0, -9.81]
wind: {speed: U}
tethers:
  line: {between: [[0, 0, 0], [10, 0, 0]], segments: 40, length: L, mass_per_length: mu,
         diameter: d, cd: 1.2, drag: fine}
)",
                                       {"L", "mu", "d", "U"});
  ASSERT_GT(s.cm->nv + s.cm->m, 120u);
  for (size_t i = 0; i < s.cm->nv; ++i) s.v[i] = 0.3 * std::sin(1.0 + static_cast<double>(i));
  s.dyn->project(0.0, s.q.data(), s.v.data(), s.cm->fixed);
  check_against_differences(s);
}

}  // namespace
}  // namespace lagrange

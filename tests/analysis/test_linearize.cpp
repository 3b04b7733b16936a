// docs/theory.md §5.3–5.4: eigenvalues of linearised models against closed forms; constrained
// models linearised on the manifold have exactly the physical eigenvalues.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>

#include "analysis/analysed.hpp"

namespace lagrange {
namespace {

using testing::analyse_example;
using testing::analyse_string;

std::vector<std::complex<double>> eigenvalues(const Eigen::MatrixXd& A) {
  Eigen::EigenSolver<Eigen::MatrixXd> es(A, false);
  std::vector<std::complex<double>> ev(es.eigenvalues().data(),
                                       es.eigenvalues().data() + es.eigenvalues().size());
  std::sort(ev.begin(), ev.end(), [](auto a, auto b) {
    return std::abs(a) != std::abs(b) ? std::abs(a) < std::abs(b) : a.imag() < b.imag();
  });
  return ev;
}

TEST(Linearize, PendulumAtTheBottomOscillatesAtSqrtGOverL) {
  auto s = analyse_example("pendulum.yaml");
  s.set("theta", 0.0);
  s.dyn->set_parameters({1.0, 2.0, 9.81});  // m, l = 2, g
  const LinearModel lin = s.linear();
  ASSERT_EQ(lin.state_names, (std::vector<std::string>{"theta", "theta_dot"}));
  const double w = std::sqrt(9.81 / 2.0);
  const auto ev = eigenvalues(lin.A);
  ASSERT_EQ(ev.size(), 2u);
  EXPECT_NEAR(ev[0].real(), 0.0, 1e-12);
  EXPECT_NEAR(ev[0].imag(), -w, 1e-12);
  EXPECT_NEAR(ev[1].imag(), w, 1e-12);
  EXPECT_LT(lin.equilibrium_residual, 1e-12);
  const auto ms = modes(lin);
  ASSERT_EQ(ms.size(), 1u);
  EXPECT_NEAR(ms[0].frequency_hz, w / (2 * M_PI), 1e-12);
  EXPECT_NEAR(ms[0].damping, 0.0, 1e-12);
  EXPECT_EQ(ms[0].shape.at(0).name, "theta");
}

// Small oscillations of the double pendulum: det(K − ω² M) = 0 with M, K at θ = 0.
TEST(Linearize, DoublePendulumFrequenciesFromMassAndStiffness) {
  auto s = analyse_example("double_pendulum.yaml");
  s.set("theta1", 0.0);
  s.set("theta2", 0.0);
  const double m1 = 1, m2 = 1, l1 = 1, l2 = 1, g = 9.81;  // examples/double_pendulum.yaml
  Eigen::Matrix2d M, K;
  M << (m1 + m2) * l1 * l1, m2 * l1 * l2, m2 * l1 * l2, m2 * l2 * l2;
  K << (m1 + m2) * g * l1, 0, 0, m2 * g * l2;
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix2d> ges(K, M);
  const Eigen::Vector2d w = ges.eigenvalues().cwiseSqrt();
  const auto ev = eigenvalues(s.linear().A);
  ASSERT_EQ(ev.size(), 4u);
  for (const auto& z : ev) EXPECT_NEAR(z.real(), 0.0, 1e-10);
  EXPECT_NEAR(ev[1].imag(), w[0], 1e-10);
  EXPECT_NEAR(ev[3].imag(), w[1], 1e-10);
  // The Cartesian double pendulum (two rods as constraints) has the same two frequencies and
  // nothing else: four eigenvalues on the manifold.
  auto c = analyse_example("double_pendulum_cartesian.yaml");
  const std::vector<std::string>& names = c.cm->coordinate_names;
  ASSERT_EQ(names.size(), 4u);
  for (size_t i = 0; i < 4; ++i) c.q[i] = (i % 2 == 0) ? 0.0 : -static_cast<double>(i / 2 + 1);
  c.v.assign(4, 0.0);
  c.dyn->project(0.0, c.q.data(), c.v.data(), c.cm->fixed);
  const auto evc = eigenvalues(c.linear().A);
  ASSERT_EQ(evc.size(), 4u);
  for (size_t i = 0; i < 4; ++i) {
    EXPECT_NEAR(evc[i].real(), 0.0, 1e-9);
    EXPECT_NEAR(evc[i].imag(), ev[i].imag(), 1e-9);
  }
}

// The polar, the Cartesian and the constrained-polar pendulum: the same two eigenvalues, and no
// others (none at −α from Baumgarte, none from the constraint).
TEST(Linearize, ConstrainedPendulumsHaveOnlyThePhysicalEigenvalues) {
  const double w = std::sqrt(9.81);
  auto polar = analyse_example("pendulum.yaml");
  polar.set("theta", 0.0);
  auto cart = analyse_example("cartesian_pendulum.yaml");
  cart.q = {0.0, -1.0};
  cart.v = {0.0, 0.0};
  auto constrained = analyse_example("constrained_pendulum.yaml");
  constrained.set("theta", 0.0);
  for (auto* s : {&polar, &cart, &constrained}) {
    const LinearModel lin = s->linear();
    const auto ev = eigenvalues(lin.A);
    ASSERT_EQ(ev.size(), 2u) << s->model->name;
    EXPECT_NEAR(ev[0].real(), 0.0, 1e-10) << s->model->name;
    EXPECT_NEAR(ev[1].real(), 0.0, 1e-10) << s->model->name;
    EXPECT_NEAR(ev[1].imag(), w, 1e-10) << s->model->name;
  }
  const LinearModel lin = cart.linear({"x", "y"});
  EXPECT_EQ(lin.state_names, (std::vector<std::string>{"x", "x_dot"}));
  EXPECT_EQ(lin.dependent, (std::vector<std::string>{"y"}));
  // y = −√(l² − x²): δy = 0 to first order at the bottom.
  EXPECT_NEAR(lin.C(1, 0), 0.0, 1e-12);
  EXPECT_NEAR(lin.C(0, 0), 1.0, 1e-12);
}

// A free box spinning about its intermediate axis: a real pair ±σ with
// σ = ω √((I₂ − I₁)(I₃ − I₂)/(I₁ I₃)); about the major axis no eigenvalue with Re ≠ 0.
TEST(Linearize, TorqueFreeSpinAboutTheIntermediateAxisIsUnstable) {
  const std::string yaml = R"(
name: spinning box
parameters: {m: 1.0, a: 0.3, b: 0.2, c: 0.1, w: 5.0}
bodies:
  box:
    mass: m
    shape: {box: [a, b, c]}
    frame: free
    initial: {omega: [0, w, 0]}
)";
  auto s = analyse_string(yaml);
  const double a = 0.3, b = 0.2, c = 0.1, m = 1.0, w = 5.0;
  const double I1 = m * (b * b + c * c) / 12, I2 = m * (a * a + c * c) / 12,
               I3 = m * (a * a + b * b) / 12;
  const double sigma = w * std::sqrt((I2 - I1) * (I3 - I2) / (I1 * I3));
  const LinearModel lin = s.linear();
  ASSERT_EQ(lin.A.rows(), 12);
  double largest = 0;
  for (const auto& z : eigenvalues(lin.A)) largest = std::max(largest, z.real());
  EXPECT_NEAR(largest, sigma, 1e-9 * sigma);
  // About the major axis z: stable (no growth).
  auto major = analyse_string(yaml);
  major.v[3 + 1] = 0.0;
  major.v[3 + 2] = w;
  for (const auto& z : eigenvalues(major.linear().A)) EXPECT_LE(z.real(), 1e-9);
}

// B for a model input equals B for a parameter that enters the same way; C and D of a model
// output; the zero-order hold of the pendulum against cos/sin of ω dt.
// docs/theory.md §5.1, "Limits": quadratic drag −c‖v‖v (a point's) and −c|θ̇|θ̇ (a coordinate's)
// has the derivative 0 at rest, 0/0 on the tape as written. The pendulum with either drag,
// linearised at rest at θ = 0.3, has the undamped pendulum's A: [0 1; −(g/l) cos θ 0].
TEST(Linearize, QuadraticDragAtRestHasTheUndampedA) {
  const std::string pendulum = R"(
name: pendulum with drag
parameters: {m: 1.0, l: 1.0, g: 9.81, c: 0.7}
coordinates:
  theta: {initial: 0.3, rate: 0}
points:
  bob: [l*sin(theta), -l*cos(theta), 0]
particles:
  - {point: bob, mass: m}
gravity: [0, -g, 0]
)";
  const Eigen::Matrix2d undamped{{0.0, 1.0}, {-9.81 * std::cos(0.3), 0.0}};
  for (const std::string drag : {"forces:\n  - {point: bob, force: -c*norm(vel(bob))*vel(bob)}\n",
                                 "generalized_forces: {theta: -c*der(theta)*abs(der(theta))}\n"}) {
    auto s = analyse_string(pendulum + drag);
    const Eigen::MatrixXd A = s.linear().A;
    ASSERT_EQ(A.rows(), 2) << drag;
    EXPECT_LE((A - undamped).cwiseAbs().maxCoeff(), 1e-12) << drag << A;
    EXPECT_EQ(A(1, 1), 0.0) << drag;  // the limit's rounding is not printed as damping
  }
}

// |θ̇| alone has no derivative at θ̇ = 0 (±1 by the side): an error, not a NaN or a one-sided value.
TEST(Linearize, AbsoluteRateAtRestIsNotDifferentiable) {
  auto s = analyse_string(R"(
name: dry friction
parameters: {m: 1.0, c: 0.7}
coordinates:
  x: {initial: 0.0, rate: 0}
kinetic: m/2*der(x)^2
generalized_forces: {x: -c*abs(der(x))}
)");
  EXPECT_THROW(s.linear(), NotDifferentiable);
  EXPECT_THROW(s.jac->evaluate(*s.dyn, 0.0, s.q.data(), s.v.data()), NotDifferentiable);
}

TEST(Linearize, InputsOutputsAndZeroOrderHold) {
  const std::string yaml = R"(
name: pushed pendulum
parameters: {m: 2.0, l: 1.5, g: 9.81, F0: 0.0}
inputs:
  F: 0*t
coordinates:
  theta: {initial: 0, rate: 0}
points:
  bob: [l*sin(theta), -l*cos(theta), 0]
particles:
  - {point: bob, mass: m}
gravity: [0, -g, 0]
generalized_forces: {theta: (F + F0)*l*cos(theta)}
outputs:
  bob_x: bob.x + 0.5*F
)";
  auto s = analyse_string(yaml, {"F", "F0"}, {"bob_x"});
  const LinearModel lin = s.linear({"bob_x"});
  ASSERT_EQ(lin.B.cols(), 2);
  EXPECT_NEAR(lin.B(1, 0), 1.5 / (2.0 * 1.5 * 1.5), 1e-12);  // F l / (m l²)
  EXPECT_NEAR(lin.B(1, 1), lin.B(1, 0), 1e-12);
  EXPECT_NEAR(lin.C(0, 0), 1.5, 1e-12);  // ∂(l sin θ)/∂θ
  EXPECT_NEAR(lin.D(0, 0), 0.5, 1e-12);
  const double w = std::sqrt(9.81 / 1.5), dt = 0.05;
  const LinearModel d = discretize(s.linear(), dt);
  EXPECT_NEAR(d.A(0, 0), std::cos(w * dt), 1e-12);
  EXPECT_NEAR(d.A(0, 1), std::sin(w * dt) / w, 1e-12);
  EXPECT_NEAR(d.A(1, 0), -w * std::sin(w * dt), 1e-12);
  // B_d = ∫₀^dt e^{Aτ} dτ B: the velocity row is sin(ω dt)/ω · b.
  EXPECT_NEAR(d.B(1, 0), std::sin(w * dt) / w * lin.B(1, 0), 1e-12);
}

TEST(Linearize, UnknownOutputsAndInputsAreNamed) {
  auto s = analyse_example("pendulum.yaml");
  try {
    (void)s.linear({"nope"});
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("no output 'nope'"), std::string::npos);
  }
  auto model = std::make_unique<Model>(read_model_file(testing::example_path("pendulum.yaml")));
  const Equations eq = derive(*model);
  EXPECT_THROW(DynamicsJacobian(eq, compile(eq), {"u9"}), std::invalid_argument);
}

}  // namespace
}  // namespace lagrange

// The stepping interface (include/lagrange/stepper.hpp): step for step the run of one simulate()
// call (bit for bit with DOP853), caller-set inputs against closed forms and against the same law
// written in the model file, and a failed step that leaves the state as it was.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include "../support/harness.hpp"
#include "lagrange/error.hpp"
#include "lagrange/stepper.hpp"

namespace lagrange {
namespace {

using testing::Loaded;

// A mass on a linear spring pushed by an external force F: m ẍ = −k x + F.
const char* kForcedOscillator = R"(
name: forced oscillator
parameters: {m: 2.0, k: 8.0}
coordinates:
  x: {initial: 0.3, rate: 0.0}
points: {p: [x, 0, 0]}
particles: [{point: p, mass: m}]
potential: k*x^2/2
inputs:
  F: {value: 0, external: true}
generalized_forces: {x: F}
simulate: {t_end: 4, output_step: 0.05, rtol: 1e-11, atol: 1e-13}
)";

// The same oscillator under the PD law F = −Kp (x − 1) − Kd ẋ written in the file.
const char* kOscillatorPd = R"(
name: oscillator under PD
parameters: {m: 2.0, k: 8.0, Kp: 5.0, Kd: 1.5}
coordinates:
  x: {initial: 0.3, rate: 0.0}
points: {p: [x, 0, 0]}
particles: [{point: p, mass: m}]
potential: k*x^2/2
generalized_forces: {x: -Kp*(x - 1) - Kd*der(x)}
simulate: {t_end: 4, output_step: 0.05, rtol: 1e-11, atol: 1e-13}
)";

Stepper make_stepper(const Loaded& sys, const SimulationOptions& so) {
  Dynamics dyn(sys.compiled, sys.compiled->parameter_defaults);
  dyn.set_baumgarte(sys.dynamics->baumgarte());
  return Stepper(std::move(dyn), so, sys.compiled->q0, sys.compiled->v0);
}

// Every row of the stepper's record equals simulate()'s, bit for bit.
void expect_same_rows(const Trajectory& a, const Trajectory& b) {
  ASSERT_EQ(a.columns, b.columns);
  ASSERT_EQ(a.data.size(), b.data.size());
  for (size_t i = 0; i < a.data.size(); ++i)
    ASSERT_EQ(std::memcmp(&a.data[i], &b.data[i], sizeof(double)), 0)
        << "row " << i / a.columns.size() << ", column " << a.columns[i % a.columns.size()] << ": "
        << a.data[i] << " vs " << b.data[i];
}

class StepperMatchesSimulate : public ::testing::TestWithParam<const char*> {};

TEST_P(StepperMatchesSimulate, BitIdenticalWithDop853) {
  Loaded sys = testing::load_example(GetParam());
  SimulationOptions so = sys.options();
  so.integrator.method = "dop853";
  so.t_end = 2.0;
  so.output_step = 0.05;
  const Trajectory one = sys.run(so);
  ASSERT_EQ(one.status, Trajectory::Status::Complete) << one.message;
  Stepper s = make_stepper(sys, so);
  for (size_t k = 1; k < one.rows(); ++k) s.step(so.output_step);
  EXPECT_EQ(s.time(), so.t_end);
  expect_same_rows(s.record(), one);
  EXPECT_EQ(s.record().stats.steps, one.stats.steps);
  EXPECT_EQ(s.record().stats.rhs_evals, one.stats.rhs_evals);
  // state() is the last row's q and v
  const size_t last = one.rows() - 1;
  for (size_t i = 0; i < sys.compiled->nq; ++i)
    EXPECT_EQ(s.state()[i], one.at(last, sys.compiled->coordinate_names[i]));
}

// Unconstrained, constrained (projection after steps), a free body (re-orthonormalisation) and a
// tethered kite on a winch.
INSTANTIATE_TEST_SUITE_P(Examples, StepperMatchesSimulate,
                         ::testing::Values("double_pendulum.yaml", "constrained_pendulum.yaml",
                                           "tumbling_brick.yaml", "figure_eight.yaml"));

TEST(Stepper, RestartingMethodAgreesWithOneRun) {
  Loaded sys = testing::load_example("double_pendulum.yaml");
  SimulationOptions so = testing::tight(sys, 1.0, 0.1);
  so.integrator.method = "cvode";
  so.integrator.rtol = 1e-10;
  const Trajectory one = sys.run(so);
  Stepper s = make_stepper(sys, so);
  for (int k = 0; k < 10; ++k) s.step(0.1);
  ASSERT_EQ(s.record().rows(), one.rows());
  for (const char* c : {"theta1", "theta2", "theta1_dot", "theta2_dot"})
    EXPECT_NEAR(s.record().at(10, c), one.at(10, c), 1e-7) << c;
}

// m ẍ = −k x + F with F held: from (x0, v0), x(t) = F/k + (x0 − F/k) cos ωt + (v0/ω) sin ωt.
TEST(Stepper, HeldInputsFollowTheClosedForm) {
  Loaded sys = testing::load_string(kForcedOscillator);
  const SimulationOptions so = sys.options();
  Stepper s = make_stepper(sys, so);
  ASSERT_EQ(s.external_inputs(), std::vector<std::string>{"F"});
  const double m = 2.0, k = 8.0, w = std::sqrt(k / m);
  double x0 = 0.3, v0 = 0.0, t0 = 0.0;
  const double forces[] = {2.0, -1.0, 0.5, 0.5};
  for (int piece = 0; piece < 4; ++piece) {
    const double F = forces[piece];
    s.set_input("F", F);
    for (int j = 0; j < 10; ++j) s.step(0.05);
    const double t = s.time() - t0, xs = F / k;
    const double x = xs + (x0 - xs) * std::cos(w * t) + v0 / w * std::sin(w * t);
    const double v = -(x0 - xs) * w * std::sin(w * t) + v0 * std::cos(w * t);
    EXPECT_NEAR(s.state()[0], x, 1e-9) << "piece " << piece;
    EXPECT_NEAR(s.state()[1], v, 1e-9) << "piece " << piece;
    x0 = s.state()[0];
    v0 = s.state()[1];
    t0 = s.time();
  }
  EXPECT_NEAR(s.time(), 2.0, 1e-12);
  // Without a caller the input keeps its declared value 0: free oscillation about 0.
  const Trajectory free = sys.run(so);
  EXPECT_NEAR(free.at(free.rows() - 1, "x"), 0.3 * std::cos(w * 4.0), 1e-9);
}

TEST(Stepper, InputLawEqualsTheLawInTheFile) {
  Loaded file = testing::load_string(kOscillatorPd);
  const Trajectory one = file.run(file.options());
  Loaded sys = testing::load_string(kForcedOscillator);
  Stepper s = make_stepper(sys, sys.options());
  s.set_input_law([](double, const double* q, const double* v, double* u) {
    u[0] = -5.0 * (q[0] - 1.0) - 1.5 * v[0];
  });
  for (size_t k = 1; k < one.rows(); ++k) s.step(0.05);
  for (size_t r = 0; r < one.rows(); r += 10) {
    EXPECT_NEAR(s.record().at(r, "x"), one.at(r, "x"), 1e-9) << "row " << r;
    EXPECT_NEAR(s.record().at(r, "x_dot"), one.at(r, "x_dot"), 1e-9) << "row " << r;
  }
}

TEST(Stepper, FailedStepKeepsTheState) {
  Loaded sys = testing::load_string(kForcedOscillator);
  Stepper s = make_stepper(sys, sys.options());
  s.step(0.1);
  const std::vector<double> before = s.state();
  const double t = s.time();
  const size_t rows = s.record().rows();
  s.set_input_law([](double time, const double*, const double*, double* u) {
    if (time > 0.15) throw SimulationError(time, "the actuator failed");
    u[0] = 1.0;
  });
  try {
    s.step(0.1);
    FAIL() << "expected a SimulationError";
  } catch (const SimulationError& e) {
    EXPECT_GT(e.time(), 0.15);
    EXPECT_LE(e.time(), 0.2 + 1e-12);
  }
  EXPECT_EQ(s.time(), t);
  EXPECT_EQ(s.state(), before);
  EXPECT_EQ(s.record().rows(), rows);
  // The next call starts afresh from there.
  s.set_input_law(nullptr);
  s.set_input("F", 0.0);
  s.step(0.1);
  const double w = 2.0;
  EXPECT_NEAR(s.state()[0], 0.3 * std::cos(w * 0.2), 1e-9);
}

// The radial fall onto −1/r (tests/hardening, CompleteButWrong): DOP853 at a fixed step steps
// across r = 0 near t = π/(2√2) and the energy of this conservative model jumps. The Stepper checks
// its samples as simulate() does (docs/theory.md §8.2), so it fails at the same sample for the same
// reason, keeping the rows before it.
TEST(Stepper, CollapseFailsAsSimulateDoes) {
  Loaded sys = testing::load_string(
      "name: collapse\ncoordinates:\n  r: {initial: 1}\nkinetic: der(r)^2/2\npotential: -1/r\n"
      "simulate: {t_end: 3, output_step: 0.01}\n");
  SimulationOptions so = sys.options();
  so.integrator.step = 0.002;
  const Trajectory one = sys.run(so);
  ASSERT_EQ(one.status, Trajectory::Status::Failed);
  const double collapse = 3.14159265358979 / (2 * std::sqrt(2.0));
  EXPECT_NEAR(one.failure_time, collapse, 0.01);
  ASSERT_NE(one.message.find("the energy T + U of this conservative model"), std::string::npos)
      << one.message;
  Stepper s = make_stepper(sys, so);
  try {
    while (s.time() < so.t_end) s.step(so.output_step);
    FAIL() << "expected a SimulationError";
  } catch (const SimulationError& e) {
    EXPECT_EQ(e.time(), one.failure_time);
    EXPECT_EQ(std::string(e.what()), one.message);
  }
  expect_same_rows(s.record(), one);  // the rows before the failing sample, bit for bit
}

TEST(Stepper, RejectsInputsThatAreNotExternal) {
  Loaded sys = testing::load_example("planar_arm_pd.yaml");
  Stepper s = make_stepper(sys, sys.options());
  EXPECT_TRUE(s.external_inputs().empty());
  try {
    s.set_input("q1_ref", 0.0);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'q1_ref' is not an external input"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW(s.step(0.0), std::invalid_argument);
}

// A model's warnings (a kite falling below the ground of its light wind) come from the Stepper
// as from one simulate() run: once, at the same sample, with the explicit default and with a
// method that restarts at each call.
TEST(Stepper, WarnsOnceAsSimulateDoes) {
  Loaded sys = testing::load_example("pointmass_kite.yaml");
  std::vector<double> values = sys.compiled->parameter_defaults;
  const auto& names = sys.compiled->parameter_names;
  values[static_cast<size_t>(std::find(names.begin(), names.end(), "W") - names.begin())] = 3;
  for (const char* method : {"dop853", "rk4"}) {
    SimulationOptions so = sys.options();
    so.integrator.method = method;
    so.t_end = 12.0;
    so.output_step = 0.1;
    sys.dynamics->set_parameters(values);
    const Trajectory one = sys.run(so);
    ASSERT_EQ(one.status, Trajectory::Status::Complete) << one.message;
    ASSERT_EQ(one.warnings.size(), 1u) << method;
    Dynamics dyn(sys.compiled, values);
    dyn.set_baumgarte(sys.dynamics->baumgarte());
    Stepper s(std::move(dyn), so, sys.compiled->q0, sys.compiled->v0);
    for (size_t k = 1; k < one.rows(); ++k) s.step(so.output_step);
    EXPECT_EQ(s.record().warnings, one.warnings) << method;
  }
}

}  // namespace
}  // namespace lagrange

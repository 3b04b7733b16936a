// One exact Jacobian for every entry point (src/cli/jacobian_source.cpp, docs/theory.md §5.6):
// derived once per model, built for each run's own workspace, so that the Stepper and a sweep's
// cases integrate cvode:jacobian and auto as one simulate() call does.

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "support/test_paths.hpp"
#include "cli/commands.hpp"
#include "cli/prepare.hpp"
#include "hardening/cli_runner.hpp"
#include "lagrange/stepper.hpp"
#include "lagrange/sweep.hpp"

namespace lagrange::cli {
namespace {

namespace fs = std::filesystem;

const std::string kElasticTether =
    std::string(LAGRANGE_SOURCE_DIR) + "/examples/elastic_tether.yaml";

// The example's own settings over its first second, with `method`, and the Jacobian it needs.
SimulationOptions options(const Prepared& p, const std::string& method, double rtol) {
  SimulationOptions so =
      simulation_options(*p.model, RunSettings{1.0, 0.05, rtol, rtol * 1e-2, {}, method, {}});
  so.jacobian_source = jacobian_source(p, method);
  return so;
}

double largest_difference(const Trajectory& a, const Trajectory& b, const CompiledModel& cm) {
  double worst = 0.0;
  for (size_t r = 0; r < std::min(a.rows(), b.rows()); ++r) {
    EXPECT_EQ(a.at(r, "t"), b.at(r, "t"));
    for (const std::string& name : cm.coordinate_names)
      worst = std::max(worst, std::abs(a.at(r, name) - b.at(r, name)));
  }
  return worst;
}

TEST(JacobianSource, DerivedOnceForEveryRunOfTheModel) {
  Prepared p = prepare(kElasticTether, {});
  EXPECT_FALSE(jacobian_source(p, "dop853"));
  EXPECT_FALSE(p.jacobian);  // nothing derived for a method that does not use it
  const JacobianSource first = jacobian_source(p, "cvode:jacobian");
  const DynamicsJacobian* derived = p.jacobian.get();
  ASSERT_NE(derived, nullptr);
  jacobian_source(p, "auto");
  EXPECT_EQ(p.jacobian.get(), derived);
  // bound to a second workspace, it gives the same values as on the prepared one
  Dynamics other(p.compiled, p.dynamics->parameters());
  other.set_baumgarte(p.dynamics->baumgarte());
  std::vector<double> y = p.q;
  y.insert(y.end(), p.v.begin(), p.v.end());
  y[0] += 0.3;  // off the unstretched start, where every segment pulls
  y[2] -= 0.5;
  const OdeJacobian a = first.ode(*p.dynamics, 0.0, y), b = first.ode(other, 0.0, y);
  ASSERT_EQ(a.rows, b.rows);
  std::vector<double> va(a.nonzeros()), vb(b.nonzeros());
  a.values(0.0, y.data(), va.data());
  b.values(0.0, y.data(), vb.data());
  EXPECT_EQ(va, vb);
}

TEST(JacobianSource, RecursiveFormHasNoneToGive) {
  Prepared p = prepare(std::string(LAGRANGE_SOURCE_DIR) + "/examples/planar_arm_pd.yaml", {}, {},
                       "--initial", "recursive");
  ASSERT_TRUE(p.equations.recursive);
  EXPECT_FALSE(jacobian_source(p, "auto"));  // auto runs DOP853
  for (const char* method : {"cvode:jacobian", "ida:jacobian"}) {
    try {
      jacobian_source(p, method);
      FAIL() << "expected a UsageError for " << method;
    } catch (const UsageError& e) {
      EXPECT_NE(std::string(e.what()).find(method), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("add --dynamics lagrangian"), std::string::npos)
          << e.what();
    }
  }
}

// The Stepper restarts cvode:jacobian at each call, on the Jacobian built once for its own
// workspace: 20 calls of 0.05 s agree with one run, and both with DOP853 at rtol 1e-11, to the
// tolerance (rtol 1e-8 on a 100 m line: 8e-8 m apart at most, measured).
TEST(JacobianSource, StepperWithCvodeJacobianFollowsOneRun) {
  Prepared p = prepare(kElasticTether, {});
  const SimulationOptions so = options(p, "cvode:jacobian", 1e-8);
  p.dynamics->set_baumgarte(baumgarte_rate(p.model->stabilization, "cvode:jacobian"));
  const Trajectory one = simulate(*p.dynamics, so, p.q, p.v);
  ASSERT_EQ(one.status, Trajectory::Status::Complete) << one.message;
  EXPECT_EQ(one.stats.method, "cvode:jacobian");
  Dynamics dyn(p.compiled, p.dynamics->parameters());
  dyn.set_baumgarte(p.dynamics->baumgarte());
  Stepper stepper(std::move(dyn), so, p.q, p.v);
  for (size_t k = 1; k < one.rows(); ++k) stepper.step(so.output_step);
  const Trajectory& stepped = stepper.record();
  ASSERT_EQ(stepped.rows(), one.rows());
  EXPECT_EQ(stepped.stats.method, "cvode:jacobian");
  const double apart = largest_difference(stepped, one, *p.compiled);
  EXPECT_LT(apart, 1e-6);

  SimulationOptions reference = options(p, "dop853", 1e-11);
  p.dynamics->set_baumgarte(baumgarte_rate(p.model->stabilization, "dop853"));
  const Trajectory exact = simulate(*p.dynamics, reference, p.q, p.v);
  ASSERT_EQ(exact.status, Trajectory::Status::Complete) << exact.message;
  EXPECT_LT(largest_difference(one, exact, *p.compiled), 1e-6);
  EXPECT_LT(largest_difference(stepped, exact, *p.compiled), 1e-6);
}

// A sweep case with auto, on a worker's workspace of its own, switches where simulate() does and
// gives its trajectory bit for bit.
TEST(JacobianSource, SweepCaseSwitchesAsSimulateDoes) {
  Prepared p = prepare(kElasticTether, {});
  const SimulationOptions so = options(p, "auto", 1e-6);
  p.dynamics->set_baumgarte(baumgarte_rate(p.model->stabilization, "auto"));
  const Trajectory alone = simulate(*p.dynamics, so, p.q, p.v);
  ASSERT_EQ(alone.status, Trajectory::Status::Complete) << alone.message;
  EXPECT_EQ(alone.stats.method.rfind("dop853, stiff at t = ", 0), 0u) << alone.stats.method;

  const sweep::CaseInput input = sweep::case_input(*p.model, *p.compiled, so);
  Dynamics worker(p.compiled, p.compiled->parameter_defaults);
  Trajectory kept;
  const sweep::CaseResult result = sweep::run_case(worker, input, {}, &kept);
  ASSERT_EQ(result.status, Trajectory::Status::Complete) << result.reason;
  EXPECT_EQ(kept.stats.method, alone.stats.method);
  EXPECT_EQ(kept.data, alone.data);
}

// `lagrange sweep --integrator auto` on two workers: each case's trajectory is, byte for byte,
// the one `simulate --set … --integrator auto` writes alone (the Jacobian derived once for the
// study, bound to each worker's workspace).
TEST(JacobianSource, SweepCommandCasesAreTheLoneRuns) {
  using hardening::run_lagrange;
  using hardening::slurp;
  hardening::ScratchDir dir("sweep-auto");
  const fs::path study = dir.path() / "study";
  const hardening::RunResult r = run_lagrange(
      dir.path(), {"sweep", kElasticTether, "-o", study.string(), "--vary", "D=1000,3000",
                   "--integrator", "auto", "--t-end", "1", "-j", "2", "--keep-trajectories", "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* c : {"0", "1"}) {
    const fs::path alone = dir.path() / (std::string("alone_") + c + ".csv");
    const hardening::RunResult s = run_lagrange(
        dir.path(), {"simulate", kElasticTether, "--set", c[0] == '0' ? "D=1000" : "D=3000",
                     "--integrator", "auto", "--t-end", "1", "-o", alone.string()});
    ASSERT_EQ(s.exit_code, 0) << s.err;
    if (c[0] == '1') {  // the example's damping: auto turns implicit (D = 1000 stays explicit)
      EXPECT_NE(s.out.find("dop853, stiff at t = "), std::string::npos) << s.out;
    }
    EXPECT_EQ(slurp(study / (std::string("case_") + c + ".csv")), slurp(alone)) << "case " << c;
  }
}

// A mass on a spring (ω = 10 rad/s) whose damper engages only in a window around t = 1.5 s:
// c(t) = 1e5 exp(−((t − 1.5)/0.4)⁸), an overdamped rate c/m of 1e5 s⁻¹ there. `auto` goes
// implicit as the damper engages and explicit again once it has let go (docs/theory.md §5.6,
// "Returning to DOP853"), and follows DOP853 at rtol 1e-12 through all three phases.
TEST(JacobianSource, DamperEngagedInAWindowSwitchesBothWays) {
  const std::string yaml = R"(
name: damper engaged in a window
parameters: {m: 1.0, k: 100.0, c: 1.0e5}
coordinates:
  y: {initial: 1.0, rate: 0.0}
points:
  anchor: [0, 0, 0]
  mass: [0, y, 0]
particles:
  - {point: mass, mass: m}
springs:
  - {between: [anchor, mass], k: k, l0: 0}
dampers:
  - {between: [anchor, mass], c: c*exp(-((t - 1.5)/0.4)^8)}
simulate: {t_end: 4, output_step: 0.02}
)";
  Prepared p = prepare_source(ModelSource{"<window>", yaml}, {}, "lagrangian");
  SimulationOptions so = simulation_options(*p.model, RunSettings{{}, {}, {}, {}, {}, "auto", {}});
  so.jacobian_source = jacobian_source(p, "auto");
  p.dynamics->set_baumgarte(baumgarte_rate(p.model->stabilization, "auto"));
  const Trajectory automatic = simulate(*p.dynamics, so, p.q, p.v);
  ASSERT_EQ(automatic.status, Trajectory::Status::Complete) << automatic.message;
  const std::string& method = automatic.stats.method;
  const size_t in = method.find("stiff at t = "), out = method.find(", not stiff at t = ");
  ASSERT_NE(in, std::string::npos) << method;
  ASSERT_NE(out, std::string::npos) << method;
  EXPECT_GT(std::stod(method.substr(in + 13)), 0.9) << method;  // c/m = 1e3 s⁻¹ at t = 0.98
  EXPECT_LT(std::stod(method.substr(out + 19)), 3.5) << method;

  SimulationOptions reference = so;
  reference.integrator.method = "dop853";
  reference.integrator.rtol = 1e-12;
  reference.integrator.atol = 1e-14;
  const Trajectory exact = simulate(*p.dynamics, reference, p.q, p.v);
  ASSERT_EQ(exact.status, Trajectory::Status::Complete) << exact.message;
  ASSERT_EQ(exact.rows(), automatic.rows());
  EXPECT_LT(largest_difference(automatic, exact, *p.compiled), 1e-6);
}

}  // namespace
}  // namespace lagrange::cli

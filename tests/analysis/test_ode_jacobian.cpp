// docs/theory.md §5.6: the exact Jacobian of the first-order form y' = f(y) against central
// differences of the forward dynamics, and cvode:jacobian (CVODE's Newton matrices from it)
// against DOP853 at tight tolerances on the tether, chain and kite examples.

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "analysis/analysed.hpp"

namespace lagrange {
namespace {

using testing::Analysed;

std::vector<double> state(const Analysed& s) {
  std::vector<double> y = s.q;
  y.insert(y.end(), s.v.begin(), s.v.end());
  return y;
}

// The state after `t_end` of the model's own flight (DOP853, rtol 1e-10).
std::vector<double> state_after(Analysed& s, double t_end) {
  SimulationOptions so;
  so.t_end = t_end;
  so.output_step = t_end;
  so.integrator.rtol = 1e-10;
  so.integrator.atol = 1e-12;
  const Trajectory tr = simulate(*s.dyn, so, s.q, s.v);
  EXPECT_EQ(tr.status, Trajectory::Status::Complete) << tr.message;
  std::vector<double> y;
  for (const auto* names : {&s.cm->coordinate_names, &s.cm->velocity_names})
    for (const std::string& name : *names) y.push_back(tr.at(tr.rows() - 1, name));
  return y;
}

// f(y) = (q̇, a) at t = 0.
Eigen::VectorXd rhs(Analysed& s, const std::vector<double>& y) {
  const CompiledModel& cm = *s.cm;
  Eigen::VectorXd f(static_cast<long>(cm.nq + cm.nv));
  std::vector<double> lambda(cm.m);
  s.dyn->forward(0.0, y.data(), y.data() + cm.nq, f.data(), f.data() + cm.nq, lambda.data());
  return f;
}

// The rigid AP2 of rigid_kite_ap2.yaml on a 6-segment elastic Dyneema tether in a logarithmic
// wind: the KPS4-like case of bench/bench_elastic_kite.cpp (EA = 314 kN, D = 1000 N·s).
std::string elastic_kite_yaml() {
  std::ifstream in(testing::example_path("rigid_kite_ap2.yaml"));
  std::stringstream ss;
  ss << in.rdbuf();
  std::string text = ss.str();
  const auto replace = [&](const std::string& from, const std::string& to) {
    const size_t at = text.find(from);
    if (at == std::string::npos) throw std::runtime_error("rigid_kite_ap2.yaml lacks " + from);
    text.replace(at, from.size(), to);
  };
  replace("segments: 5", "segments: 6");
  replace("drag: simple}", "drag: simple, elasticity: {EA: 314159, damping: 1000}}");
  replace("wind: {speed: W}",
          "wind: {profile: logarithmic, speed: W, reference_height: 10, roughness: 0.1}");
  return text;
}

// Every entry of the exact Jacobian, zeros outside its pattern included, against Richardson-
// extrapolated central differences of f: max error ≤ 1e-6 · max(1, max |J|).
void check_against_differences(Analysed s, const std::string& example, double flown = 0.0) {
  const std::vector<double> y0 = flown > 0.0 ? state_after(s, flown) : state(s);
  const OdeJacobian jac = ode_jacobian(*s.jac, *s.dyn, 0.0, y0);
  const long n = static_cast<long>(y0.size());
  ASSERT_EQ(jac.column_starts.size(), static_cast<size_t>(n) + 1);
  std::vector<double> values(jac.nonzeros());
  jac.values(0.0, y0.data(), values.data());
  Eigen::MatrixXd exact = Eigen::MatrixXd::Zero(n, n);
  for (long j = 0; j < n; ++j)
    for (long e = jac.column_starts[static_cast<size_t>(j)];
         e < jac.column_starts[static_cast<size_t>(j) + 1]; ++e)
      exact(jac.rows[static_cast<size_t>(e)], j) = values[static_cast<size_t>(e)];
  ASSERT_TRUE(exact.allFinite()) << example;
  const double scale = std::max(1.0, exact.cwiseAbs().maxCoeff());
  for (long j = 0; j < n; ++j) {
    const auto f = [&](double h) {
      std::vector<double> y = y0;
      y[static_cast<size_t>(j)] += h;
      return rhs(s, y);
    };
    const double h = 1e-4 * std::max(1.0, std::abs(y0[static_cast<size_t>(j)]));
    const Eigen::VectorXd d1 = (f(h) - f(-h)) / (2 * h), d2 = (f(h / 2) - f(-h / 2)) / h;
    const Eigen::VectorXd fd = (4 * d2 - d1) / 3;
    ASSERT_TRUE(fd.allFinite()) << example << ": column " << j;
    EXPECT_LE((exact.col(j) - fd).cwiseAbs().maxCoeff(), 1e-6 * scale)
        << example << ": column " << j << "\nexact " << exact.col(j).transpose() << "\nfd    "
        << fd.transpose();
  }
}

TEST(OdeJacobian, HangingChainAgainstDifferences) {
  check_against_differences(testing::analyse_example("hanging_chain.yaml"), "hanging_chain.yaml");
}
TEST(OdeJacobian, TetherInWindAgainstDifferences) {
  check_against_differences(testing::analyse_example("tether_in_wind.yaml"), "tether_in_wind.yaml");
}
TEST(OdeJacobian, PointMassKiteAgainstDifferences) {
  check_against_differences(testing::analyse_example("pointmass_kite.yaml"), "pointmass_kite.yaml");
}
TEST(OdeJacobian, SpringMassDamperAgainstDifferences) {
  check_against_differences(testing::analyse_example("spring_mass_damper.yaml"),
                            "spring_mass_damper.yaml");
}

// Free bodies: R's nine entries as CVODE integrates them, Ṙ = R(Ω + Ξ) with the drift
// correction Ξ differentiated too (exact off SO(3) as well: the differences move R off it).
TEST(OdeJacobian, TumblingBrickAgainstDifferences) {
  check_against_differences(testing::analyse_example("tumbling_brick.yaml"), "tumbling brick");
}
TEST(OdeJacobian, RigidKiteAgainstDifferences) {
  check_against_differences(testing::analyse_example("rigid_kite_ap2.yaml"), "rigid AP2");
}
// In flight (t = 0.5 s, every segment taut): at the start the line lies at its unstretched
// length, on the kink of max(ε, 0), where central differences average the two sides.
TEST(OdeJacobian, ElasticTetherKiteAgainstDifferences) {
  check_against_differences(testing::analyse_string(elastic_kite_yaml()), "elastic AP2", 0.5);
}

// cvode:jacobian at rtol 1e-10 against DOP853 at rtol 1e-12 over `t_end` of the example's own
// run: every coordinate at every sample within `tol` (metres/radians), and the constraint rows
// consistent.
void check_against_dop853(Analysed s, const std::string& example, double t_end, double tol) {
  SimulationOptions so;
  so.t_end = t_end;
  so.output_step = t_end / 20;
  const Trajectory ref = testing::dop853_reference(s, so);
  ASSERT_EQ(ref.status, Trajectory::Status::Complete) << ref.message;

  so.integrator.method = "cvode:jacobian";
  so.integrator.rtol = 1e-10;
  so.integrator.atol = 1e-12;
  s.dyn->set_baumgarte(baumgarte_rate(s.model->stabilization, "cvode:jacobian"));
  so.jacobian = ode_jacobian(*s.jac, *s.dyn, 0.0, state(s));
  const Trajectory tr = simulate(*s.dyn, so, s.q, s.v);
  ASSERT_EQ(tr.status, Trajectory::Status::Complete) << tr.message;
  ASSERT_EQ(tr.rows(), ref.rows());
  EXPECT_EQ(tr.stats.method, "cvode:jacobian");
  EXPECT_LT(testing::worst_coordinate_difference(s, tr, ref), tol) << example;
}

TEST(CvodeJacobian, HangingChainAgreesWithDop853) {
  check_against_dop853(testing::analyse_example("hanging_chain.yaml"), "hanging_chain.yaml", 2.0,
                       1e-6);
}
TEST(CvodeJacobian, TetherInWindAgreesWithDop853) {
  check_against_dop853(testing::analyse_example("tether_in_wind.yaml"), "tether_in_wind.yaml", 2.0,
                       1e-6);
}
TEST(CvodeJacobian, PointMassKiteAgreesWithDop853) {
  check_against_dop853(testing::analyse_example("pointmass_kite.yaml"), "pointmass_kite.yaml", 2.0,
                       1e-6);
}

TEST(CvodeJacobian, TumblingBrickAgreesWithDop853) {
  check_against_dop853(testing::analyse_example("tumbling_brick.yaml"), "tumbling brick", 2.0,
                       1e-6);
}
TEST(CvodeJacobian, RigidKiteAgreesWithDop853) {
  check_against_dop853(testing::analyse_example("rigid_kite_ap2.yaml"), "rigid AP2", 2.0, 1e-6);
}
TEST(CvodeJacobian, ElasticTetherKiteAgreesWithDop853) {
  check_against_dop853(testing::analyse_string(elastic_kite_yaml()), "elastic AP2", 2.0, 1e-6);
}

// docs/theory.md §5.6, "Choosing the method": an overdamped spring–mass–damper with rates 1 and
// 1e4 s⁻¹ (k = 1e4, c = 10001, m = 1: y'' + 10001 y' + 1e4 y = 0; ρ·Δt = 1e4 · 0.02 = 200) goes
// to cvode:jacobian, whose run then matches the closed form y = A e^(−t) + B e^(−1e4 t),
// A + B = y0, A + 1e4 B = 0.
constexpr const char* kStiffDamper = R"(
name: stiff damper
parameters: {m: 1.0, k: 1.0e4, c: 10001.0}
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
  - {between: [anchor, mass], c: c}
simulate: {t_end: 1, output_step: 0.02}
)";

TEST(AutoMethod, StiffDamperGoesImplicit) {
  Analysed s = testing::analyse_string(kStiffDamper);
  const std::vector<double> y0 = state(s);
  const OdeJacobian jac = ode_jacobian(*s.jac, *s.dyn, 0.0, y0);
  EXPECT_NEAR(spectral_radius_estimate(jac, 0.0, y0), 1e4, 1e2);
  EXPECT_EQ(choose_ode_method(jac, 0.0, y0, 0.02), "cvode:jacobian");
  SimulationOptions so;
  so.t_end = 1.0;
  so.output_step = 0.02;
  so.integrator.method = "auto";
  so.integrator.rtol = 1e-10;
  so.integrator.atol = 1e-12;
  so.jacobian = jac;
  const Trajectory tr = simulate(*s.dyn, so, s.q, s.v);
  ASSERT_EQ(tr.status, Trajectory::Status::Complete) << tr.message;
  EXPECT_EQ(tr.stats.method, "cvode:jacobian");
  const double A = 1.0 / (1.0 - 1e-4), B = 1.0 - A;
  for (size_t r = 0; r < tr.rows(); ++r) {
    const double t = tr.at(r, "t");
    EXPECT_NEAR(tr.at(r, "y"), A * std::exp(-t) + B * std::exp(-1e4 * t), 1e-8) << "t = " << t;
  }
}

// `auto` with the example's own tolerances over `t_end`: the method it ran, and the trajectory
// against DOP853 at rtol 1e-10 (largest coordinate difference over the samples up to
// `compared`, which fall on the same times).
struct AutoRun {
  std::string method;
  double worst = 0.0;
};
AutoRun run_auto(Analysed& s, double t_end, double compared) {
  SimulationOptions so;
  so.t_end = t_end;
  so.output_step = s.model->simulate.output_step;
  so.integrator.rtol = 1e-10;
  so.integrator.atol = 1e-12;
  const Trajectory ref = simulate(*s.dyn, so, s.q, s.v);
  EXPECT_EQ(ref.status, Trajectory::Status::Complete) << ref.message;
  so.integrator.method = "auto";
  so.integrator.rtol = s.model->simulate.rtol;
  so.integrator.atol = s.model->simulate.atol;
  so.jacobian = ode_jacobian(*s.jac, *s.dyn, 0.0, state(s));
  const Trajectory tr = simulate(*s.dyn, so, s.q, s.v);
  EXPECT_EQ(tr.status, Trajectory::Status::Complete) << tr.message;
  EXPECT_EQ(tr.rows(), ref.rows());
  AutoRun out{tr.stats.method, 0.0};
  for (size_t r = 0; r < std::min(tr.rows(), ref.rows()); ++r) {
    EXPECT_EQ(tr.at(r, "t"), ref.at(r, "t"));
    if (tr.at(r, "t") > compared) continue;
    for (const std::string& name : s.cm->coordinate_names)
      out.worst = std::max(out.worst, std::abs(tr.at(r, name) - ref.at(r, name)));
  }
  return out;
}

TEST(AutoMethod, DoublePendulumStaysExplicit) {
  Analysed s = testing::analyse_example("double_pendulum.yaml");
  const std::vector<double> y0 = state(s);
  const OdeJacobian jac = ode_jacobian(*s.jac, *s.dyn, 0.0, y0);
  EXPECT_LT(spectral_radius_estimate(jac, 0.0, y0), 50.0);
  EXPECT_EQ(choose_ode_method(jac, 0.0, y0, s.model->simulate.output_step), "dop853");
  // and through the whole run: DOP853's stiffness test never concludes (the motion is chaotic:
  // compared over the first 2 s).
  const AutoRun run = run_auto(s, s.model->simulate.t_end, 2.0);
  EXPECT_EQ(run.method, "dop853");
  EXPECT_LT(run.worst, 1e-5);
}

// docs/theory.md §5.6, "Noticing stiffness during the run": the elastic tether starts at its
// unstretched length (ρ·Δt_out small at t = 0: auto starts explicit); once the line is taut its
// axial modes hold DOP853 at its stability boundary, its stiffness test concludes within the
// first tenth of a second, and the run continues on cvode:jacobian from the next sample (1 s of
// the example's 5: the reference is DOP853 at its stability boundary all along).
TEST(AutoMethod, ElasticTetherTurnsImplicitDuringTheRun) {
  Analysed s = testing::analyse_example("elastic_tether.yaml");
  const std::vector<double> y0 = state(s);
  const OdeJacobian jac = ode_jacobian(*s.jac, *s.dyn, 0.0, y0);
  EXPECT_EQ(choose_ode_method(jac, 0.0, y0, s.model->simulate.output_step), "dop853");
  const AutoRun run = run_auto(s, 1.0, 1.0);
  EXPECT_EQ(run.method.rfind("dop853, stiff at t = ", 0), 0u) << run.method;
  const size_t from = run.method.find(": cvode:jacobian from t = ");
  ASSERT_NE(from, std::string::npos) << run.method;
  EXPECT_LT(std::stod(run.method.substr(from + 26)), 0.2) << run.method;
  EXPECT_LT(run.worst, 1e-4);
}

// docs/theory.md §5.8: BDF held at order k converges at order k — the error against DOP853 falls
// as steps^(−k) — on the double pendulum.
TEST(CvodeJacobian, FixedOrderConvergesAtItsOrder) {
  for (const char* method : {"cvode:jacobian", "cvode"})  // plain cvode: difference quotients
    testing::expect_fixed_order_convergence("double_pendulum.yaml", method, 0.05);
}

// At the default (variable order up to 5) the error follows the tolerance: 100 times tighter,
// 10 to 1000 times smaller.
TEST(CvodeJacobian, ErrorFollowsTheTolerance) {
  testing::expect_error_follows_tolerance("cvode:jacobian");
}

}  // namespace
}  // namespace lagrange

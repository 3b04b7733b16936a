// `lagrange linearize` and `lagrange trim` as a user runs them: output, formats, exit codes.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "analysis/euler_top.hpp"
#include "cli/shell_run.hpp"
#include "support/scratch_dir.hpp"
#include "support/test_paths.hpp"

namespace {

namespace fs = std::filesystem;
using Result = lagrange::testing::ShellResult;

Result run(const std::string& args) {
  return lagrange::testing::run_shell(args);
}

using lagrange::test::example_path;

fs::path write_model(const std::string& name, const std::string& text) {
  static const lagrange::test::ScratchDir folder("cli-analysis");
  const fs::path& dir = folder.path();
  std::ofstream(dir / name) << text;
  return dir / name;
}

TEST(CliLinearize, PendulumTextShowsStatesMatricesAndModes) {
  const Result r = run("linearize " + example_path("pendulum.yaml") + " --at theta=0");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("states (2): theta, theta_dot"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("-9.81"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("0 ± 3.13209i"), std::string::npos) << r.output;  // √9.81
  EXPECT_NE(r.output.find("0.498488"), std::string::npos) << r.output;      // √9.81 / 2π Hz
  EXPECT_EQ(r.output.find("not an equilibrium"), std::string::npos) << r.output;
}

TEST(CliLinearize, CartesianPendulumJsonOnTheManifold) {
  const Result r =
      run("linearize " + example_path("cartesian_pendulum.yaml") + " --at x=0,y=-1 --format json");
  ASSERT_EQ(r.code, 0) << r.output;
  const auto j = nlohmann::json::parse(r.output);
  EXPECT_EQ(j["states"], (std::vector<std::string>{"x", "x_dot"}));
  EXPECT_EQ(j["dependent"], (std::vector<std::string>{"y"}));
  ASSERT_EQ(j["modes"].size(), 1u);
  EXPECT_NEAR(j["modes"][0]["im"].get<double>(), std::sqrt(9.81), 1e-9);
  EXPECT_NEAR(j["A"][1][0].get<double>(), -9.81, 1e-9);
}

TEST(CliLinearize, InputsOutputsDiscreteAndCsv) {
  const Result r = run("linearize " + example_path("pendulum.yaml") +
                       " --at theta=0 --inputs g --outputs x,theta --discrete 0.01 --format csv");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("B,g\n"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("C,theta,theta_dot\nx,1,0\ntheta,1,0\n"), std::string::npos) << r.output;
  // A_d(0,0) = cos(ω dt) at ω = √9.81, dt = 0.01.
  const std::string row = "\ntheta,";
  const size_t at = r.output.find(row, r.output.find("A,theta,theta_dot"));
  ASSERT_NE(at, std::string::npos) << r.output;
  EXPECT_NEAR(std::stod(r.output.substr(at + row.size())), std::cos(std::sqrt(9.81) * 0.01), 1e-14);
}

TEST(CliLinearize, BadNamesAreUsageErrors) {
  Result r = run("linearize " + example_path("pendulum.yaml") + " --inputs torque");
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("--inputs: no input or parameter 'torque'"), std::string::npos)
      << r.output;
  r = run("linearize " + example_path("pendulum.yaml") + " --outputs speed");
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("no output 'speed'"), std::string::npos) << r.output;
  r = run("linearize " + example_path("pendulum.yaml") + " --at phi=1");
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("'phi'"), std::string::npos) << r.output;
  r = run("linearize " + example_path("pendulum.yaml") + " --discrete -1");
  EXPECT_EQ(r.code, 2) << r.output;
}

// A control law with |azimuth| at azimuth 0 is not differentiable there: refused (exit 3).
TEST(CliLinearize, NonDifferentiablePointIsRefused) {
  const Result r = run("linearize " + example_path("figure_eight.yaml"));
  EXPECT_EQ(r.code, 3) << r.output;
  EXPECT_NE(r.output.find("not differentiable"), std::string::npos) << r.output;
}

// docs/theory.md §5.4: the cart's free coordinate gives a defective eigenvalue 0 ([0 1; 0 0]),
// printed as exactly 0, twice; each real eigenvalue is one mode and each complex pair one:
// hanging 0, 0, ±iω (3 modes), upright 0, 0, ±σ (4), ω² = σ² = (M + m) g / (M l).
TEST(CliLinearize, CartPoleModesHaveExactZerosAndOneModePerPairOrRealEigenvalue) {
  const auto model = write_model("cart_pole.yaml", R"(
name: cart-pole
parameters: {M: 1.0, m: 0.2, l: 0.6, g: 9.81}
coordinates: {x: {initial: 0}, theta: {initial: 0}}
points: {cart: [x, 0, 0], bob: [x + l*sin(theta), -l*cos(theta), 0]}
particles: {cart: M, bob: m}
gravity: [0, -g, 0]
)");
  const double rate = std::sqrt(1.2 * 9.81 / 0.6);
  for (const bool upright : {false, true}) {
    const Result r =
        run("linearize " + model.string() + (upright ? " --at theta=3.14159265358979" : "") +
            " --format json --discrete 0.01");
    ASSERT_EQ(r.code, 0) << r.output;
    const auto j = nlohmann::json::parse(r.output);
    EXPECT_EQ(j["modes_time"], "continuous");
    const auto& modes = j["modes"];
    ASSERT_EQ(modes.size(), upright ? 4u : 3u) << r.output;
    for (size_t k = 0; k < 2; ++k) {  // sorted by |λ|: the zeros first
      EXPECT_EQ(modes[k]["re"].get<double>(), 0.0) << r.output;
      EXPECT_EQ(modes[k]["im"].get<double>(), 0.0) << r.output;
    }
    for (size_t k = 2; k < modes.size(); ++k)
      EXPECT_NEAR(std::hypot(modes[k]["re"].get<double>(), modes[k]["im"].get<double>()), rate,
                  1e-9 * rate)
          << r.output;
  }
  const Result text = run("linearize " + model.string());
  ASSERT_EQ(text.code, 0) << text.output;
  EXPECT_EQ(text.output.find("e-0"), std::string::npos) << text.output;  // no 1.36e-08i
}

// The operating point trim found includes the free inputs' values: F = m g tan θ holds the
// pendulum at θ = 0.3 (examples' pendulum with a side force F).
TEST(CliLinearize, AtTrimPrintsTheTrimmedInputs) {
  const auto model = write_model("side_force.yaml", R"(
name: pendulum in a side force
parameters: {m: 1.0, l: 1.0, g: 9.81, F: 0.0}
coordinates: {theta: {initial: 0.3}}
points: {bob: [l*sin(theta), -l*cos(theta), 0]}
particles: {bob: m}
gravity: [0, -g, 0]
forces: [{point: bob, force: [F, 0, 0]}]
)");
  Result r = run("linearize " + model.string() + " --at-trim --free F --inputs F");
  ASSERT_EQ(r.code, 0) << r.output;
  const std::string key = "operating point: theta = 0.3, F = ";
  const size_t at = r.output.find(key);
  ASSERT_NE(at, std::string::npos) << r.output;
  EXPECT_NEAR(std::stod(r.output.substr(at + key.size())), 9.81 * std::tan(0.3), 1e-8) << r.output;
  r = run("linearize " + model.string() + " --at-trim --free F --inputs F --format json");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NEAR(nlohmann::json::parse(r.output)["trim"]["inputs"]["F"].get<double>(),
              9.81 * std::tan(0.3), 1e-8);
}

// docs/theory.md §5.1, "Limits": quadratic drag at rest is differentiable (A undamped, exit 0).
TEST(CliLinearize, QuadraticDragAtRestIsLinearised) {
  const auto model = write_model("drag.yaml", R"(
name: pendulum with drag
parameters: {m: 1.0, l: 1.0, g: 9.81, c: 0.7}
coordinates: {theta: {initial: 0, rate: 0}}
points: {bob: [l*sin(theta), -l*cos(theta), 0]}
particles: {bob: m}
gravity: [0, -g, 0]
forces: [{point: bob, force: -c*norm(vel(bob))*vel(bob)}]
)");
  const Result r = run("linearize " + model.string() + " --format csv");
  ASSERT_EQ(r.code, 0) << r.output;
  const std::string rows = "A,theta,theta_dot\ntheta,0,1\ntheta_dot,";
  const size_t at = r.output.find(rows);
  ASSERT_NE(at, std::string::npos) << r.output;
  size_t used = 0;
  EXPECT_NEAR(std::stod(r.output.substr(at + rows.size()), &used), -9.81, 1e-12) << r.output;
  EXPECT_EQ(r.output.substr(at + rows.size() + used, 3), ",0\n") << r.output;  // no damping
}

TEST(CliTrim, PendulumFromTwentyDegreesPrintsTheInitialBlock) {
  const Result r = run("trim " + example_path("pendulum.yaml") + " --at theta=0.349");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("equilibrium found by Levenberg–Marquardt"), std::string::npos)
      << r.output;
  const std::string key = "theta: {initial: ";
  const size_t at = r.output.find(key);
  ASSERT_NE(at, std::string::npos) << r.output;
  EXPECT_NEAR(std::stod(r.output.substr(at + key.size())), 0.0, 1e-12) << r.output;
  EXPECT_NE(r.output.find("rate: 0}"), std::string::npos) << r.output;
}

TEST(CliTrim, CartesianPendulumReportsTheConstraintResidual) {
  const Result r = run("trim " + example_path("cartesian_pendulum.yaml"));
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("max |C| ="), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("y: {initial: -1"), std::string::npos) << r.output;
}

TEST(CliTrim, NoEquilibriumExitsThreeWithTheReason) {
  const auto model = write_model("pushed.yaml", R"(
name: pushed mass
parameters: {m: 2.0, F: 3.0}
coordinates:
  x: {initial: 0.5, rate: 0}
kinetic: m/2*der(x)^2
generalized_forces: {x: F}
)");
  const Result r = run("trim " + model.string());
  EXPECT_EQ(r.code, 3) << r.output;
  EXPECT_NE(r.output.find("singular"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("stopped at x = 0.5"), std::string::npos) << r.output;
}

// a = −(x² + 1): never zero, but the Jacobian −2x is regular away from 0, so Newton walks to the
// minimum of |a| at x = 0 and must stop there, saying so (exit 3), not print a state.
TEST(CliTrim, NoRootWithARegularJacobianExitsThree) {
  const auto model = write_model("no_root.yaml", R"(
name: no equilibrium
parameters: {m: 1.0}
coordinates:
  x: {initial: 1.0, rate: 0}
kinetic: m/2*der(x)^2
potential: m*(x^3/3 + x)
)");
  const Result r = run("trim " + model.string());
  EXPECT_EQ(r.code, 3) << r.output;
  EXPECT_EQ(r.output.find("coordinates:"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("trim: "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("stopped at x = "), std::string::npos) << r.output;
}

TEST(CliTrim, UnknownOrNoFreeCoordinatesAreUsageErrors) {
  Result r = run("trim " + example_path("pendulum.yaml") + " --free phi");
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("--free: no coordinate 'phi'"), std::string::npos) << r.output;
  r = run("trim " + example_path("pendulum.yaml") + " --fix theta");
  EXPECT_EQ(r.code, 2) << r.output;
}

// The top of test_steady_state.cpp in Euler angles: steady precession at φ̇ = 4.55, ψ̇ = 20 has
// cos θ = (I₃ s Ω − m g l) / ((I₁ − I₃) Ω²) (derived there).
const char* const kTop = lagrange::testing::kEulerTop;

double number_after(const std::string& text, const std::string& key) {
  const size_t at = text.find(key);
  if (at == std::string::npos) return NAN;
  return std::stod(text.substr(at + key.size()));
}

TEST(CliTrim, SteadyPrecessionOfATopInEulerAngles) {
  const auto model = write_model("top_euler.yaml", kTop);
  Result r = run("trim " + model.string() + " --steady phi_dot,psi_dot");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("steady state found by Levenberg–Marquardt"), std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("steady along the motion: max |da/dt| = 0"), std::string::npos)
      << r.output;
  const double cos_theta = (0.01 * 20 * 4.55 - 9.81 * 0.1) / ((0.006 - 0.01) * 4.55 * 4.55);
  EXPECT_NEAR(number_after(r.output, "theta: {initial: "), std::acos(cos_theta), 1e-9) << r.output;
  EXPECT_NEAR(number_after(r.output, "phi: {initial: 0, rate: "), 4.55, 1e-15) << r.output;
  // One rate given the angle: φ̇ at θ = 0.5 (the slow root of the quadratic in Ω).
  r = run("trim " + model.string() + " --steady phi_dot,psi_dot --free phi_dot --at theta=0.5");
  ASSERT_EQ(r.code, 0) << r.output;
  const double a = (0.006 - 0.01) * std::cos(0.5), b = -0.01 * 20, c = 9.81 * 0.1;
  EXPECT_NEAR(number_after(r.output, "phi: {initial: 0, rate: "),
              (-b - std::sqrt(b * b - 4 * a * c)) / (2 * a), 1e-9)
      << r.output;
}

TEST(CliLinearize, AtTrimSaysWhereTheOperatingPointCameFrom) {
  const auto model = write_model("top_euler.yaml", kTop);
  Result r = run("linearize " + model.string() + " --at-trim --steady phi_dot,psi_dot");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("operating point from trim: steady state found"), std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("a steady motion (held rates)"), std::string::npos) << r.output;
  r = run("linearize " + example_path("pendulum.yaml") +
          " --at-trim --at theta=0.349 --format json");
  ASSERT_EQ(r.code, 0) << r.output;
  const auto j = nlohmann::json::parse(r.output);
  EXPECT_FALSE(j["trim"]["steady"].get<bool>());
  EXPECT_LE(j["trim"]["residual"].get<double>(), 1e-9);
  EXPECT_NEAR(j["q"][0].get<double>(), 0.0, 1e-12);  // linearised at the bottom, not at 20°
  EXPECT_NEAR(j["modes"][0]["im"].get<double>(), std::sqrt(9.81), 1e-9);
  EXPECT_LE(j["equilibrium_residual"].get<double>(), 1e-9);
}

TEST(CliTrim, SteadyNamesAreChecked) {
  const auto model = write_model("top_euler.yaml", kTop);
  Result r = run("trim " + model.string() + " --steady theta");
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("--steady: no rate 'theta'"), std::string::npos) << r.output;
  r = run("trim " + model.string() + " --steady psi_dot --free phi_dot");
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("'phi_dot' is not held by --steady"), std::string::npos) << r.output;
  r = run("linearize " + model.string() + " --steady phi_dot");
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("--at-trim"), std::string::npos) << r.output;
  r = run("trim " + example_path("heavy_top.yaml") + " --steady top.omega_z");
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("free body"), std::string::npos) << r.output;
}

}  // namespace

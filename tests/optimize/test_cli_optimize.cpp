// `lagrange optimize`: the summary, the CSV, --verify (also along polynomial controls), and exit
// code 3 naming the most violated constraint of an infeasible problem.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "cli/shell_run.hpp"
#include "support/test_paths.hpp"

namespace lagrange {
namespace {

const std::string kDir = std::string(LAGRANGE_SOURCE_DIR) + "/examples/optimal/";

TEST(OptimizeCommand, SolvesWritesAndVerifies) {
  const std::string csv =
      (std::filesystem::temp_directory_path() / "lagrange_optimize_di.csv").string();
  const auto r = testing::run_shell("optimize " + kDir +
                                    "double_integrator_min_energy.yaml --intervals 10 -o " + csv +
                                    " --verify");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("optimal solution found"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("objective          12.12121212"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("final-state gap"), std::string::npos) << r.output;
  std::ifstream in(csv);
  std::string header;
  std::getline(in, header);
  EXPECT_EQ(header, "t,x,x_dot,kinetic,potential,energy,u");  // simulate's columns, the control
  size_t rows = 0;
  for (std::string line; std::getline(in, line);) ++rows;
  EXPECT_EQ(rows, 1u + 10u * 3u);  // t = 0 and every collocation point
  std::filesystem::remove(csv);
  std::filesystem::remove(csv + ".json");
}

// A homotopy stage gets its own summary line, before the problem's (docs/model-language.md,
// "Homotopy stages"): its status, iterations and objective, here the closed form 12·(10/11)/0.99.
TEST(OptimizeCommand, SummarisesEachHomotopyStage) {
  const auto r = testing::run_shell("optimize " + std::string(LAGRANGE_SOURCE_DIR) +
                                    "/tests/optimize/data/double_integrator_fictitious.yaml");
  ASSERT_EQ(r.code, 0) << r.output;
  const size_t stage = r.output.find("  stage fictitious   optimal solution found (");
  const size_t problem = r.output.find("double integrator with a fictitious force: optimal");
  ASSERT_NE(stage, std::string::npos) << r.output;
  EXPECT_LT(stage, problem) << r.output;
  EXPECT_NE(r.output.find("iterations), objective 11.0193"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("objective          12.12121212"), std::string::npos) << r.output;
}

// |u| ≤ 1 cannot carry the mass over distance 1 in T = 1 (that takes 2 s): exit 3, naming a
// constraint and where.
TEST(OptimizeCommand, InfeasibleProblemExitsThreeNamingTheMostViolatedConstraint) {
  const std::string yaml = (std::filesystem::temp_directory_path() / "infeasible.yaml").string();
  {
    std::ifstream src(kDir + "double_integrator_min_time.yaml");
    std::ofstream dst(yaml);
    for (std::string line; std::getline(src, line);) {
      if (line.rfind("  horizon:", 0) == 0) line = "  horizon: 1";
      if (line.rfind("  minimize:", 0) == 0) line = "  minimize: integral(u^2)";
      dst << line << "\n";
    }
  }
  const auto bad = testing::run_shell("optimize " + yaml + " --intervals 6");
  EXPECT_EQ(bad.code, 3) << bad.output;
  EXPECT_NE(bad.output.find("most violated:"), std::string::npos) << bad.output;
  EXPECT_NE(bad.output.find("at t = "), std::string::npos) << bad.output;
  std::filesystem::remove(yaml);
}

// --report writes simulate's HTML report of the collocated motion; a bad report name is refused
// before the solve, with nothing written.
TEST(OptimizeCommand, WritesTheReportOfTheOptimalMotion) {
  const std::string html =
      (std::filesystem::temp_directory_path() / "lagrange_optimize_report.html").string();
  std::filesystem::remove(html);
  const auto r = testing::run_shell(
      "optimize " + kDir + "pendulum_swing_up_cartesian.yaml --intervals 10 --report " + html);
  ASSERT_EQ(r.code, 0) << r.output;
  std::ifstream in(html);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("Radau IIA collocation (optimize)"), std::string::npos);
  EXPECT_NE(text.find("lambda_rod"), std::string::npos);
  std::filesystem::remove(html);
  const auto bad =
      testing::run_shell("optimize " + kDir + "pendulum_swing_up_cartesian.yaml --report out.txt");
  EXPECT_EQ(bad.code, 2) << bad.output;
  EXPECT_NE(bad.output.find("expected a file name ending in .html"), std::string::npos)
      << bad.output;
  EXPECT_EQ(bad.output.find("optimal solution"), std::string::npos) << bad.output;
}

// A control that nothing uses is solved around, with a located warning naming it.
TEST(OptimizeCommand, AnUnusedControlIsALocatedWarning) {
  const std::string yaml = (std::filesystem::temp_directory_path() / "unused.yaml").string();
  {
    std::ifstream src(kDir + "double_integrator_min_energy.yaml");
    std::ofstream dst(yaml);
    for (std::string line; std::getline(src, line);) {
      if (line == "  u: 0") line = "  u: 0\n  w: 0";
      if (line == "    u: {}") line = "    u: {}\n    w: {lower: -1, upper: 1}";
      dst << line << "\n";
    }
  }
  const auto r = testing::run_shell("optimize " + yaml + " --intervals 4");
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("unused.yaml:17:5: warning: control 'w' is used by no equation of "
                          "motion, objective term or path constraint"),
            std::string::npos)
      << r.output;
  EXPECT_EQ(r.output.find("control 'u' is used by no"), std::string::npos) << r.output;
  std::filesystem::remove(yaml);
}

// --hessian chooses what Ipopt gets: the exact Hessian and L-BFGS reach the same optimum, the
// summary says which was used, and an unknown choice is a usage error.
TEST(OptimizeCommand, HessianChoiceReachesTheSameOptimum) {
  const std::string model = kDir + "cart_pole_swing_up.yaml --intervals 20";
  const auto exact = testing::run_shell("optimize " + model + " --hessian exact");
  const auto lbfgs = testing::run_shell("optimize " + model + " --hessian limited-memory");
  ASSERT_EQ(exact.code, 0) << exact.output;
  ASSERT_EQ(lbfgs.code, 0) << lbfgs.output;
  EXPECT_NE(exact.output.find("(Radau IIA), exact Hessian"), std::string::npos) << exact.output;
  EXPECT_NE(lbfgs.output.find("(Radau IIA), limited-memory Hessian"), std::string::npos)
      << lbfgs.output;
  const auto objective = [](const std::string& out) {
    const size_t at = out.find("objective");
    return std::stod(out.substr(out.find_first_not_of(' ', at + 9)));
  };
  EXPECT_NEAR(objective(exact.output), objective(lbfgs.output), 1e-6 * objective(exact.output));
  EXPECT_EQ(testing::run_shell("optimize " + model + " --hessian newton").code, 2);
}

// `--compile` as `simulate` has it (docs/theory.md §8): the Hessian's second derivatives and the
// DAE residual with its first derivatives on machine code or the interpreter, the same iterates
// to the last digit, the summary saying which.
TEST(OptimizeCommand, CompileChoiceSaysWhichRanAndChangesNoIterate) {
  const std::string model = kDir + "cart_pole_swing_up.yaml --intervals 20";
  ::setenv("LAGRANGE_CACHE_DIR", LAGRANGE_TEST_CACHE, 1);
  const auto on = testing::run_shell("optimize " + model + " --compile on");
  const auto off = testing::run_shell("optimize " + model + " --compile off");
  const auto bad = testing::run_shell("optimize " + model + " --compile sometimes");
  ::unsetenv("LAGRANGE_CACHE_DIR");
  ASSERT_EQ(on.code, 0) << on.output;
  ASSERT_EQ(off.code, 0) << off.output;
  EXPECT_NE(on.output.find("  hessian            machine code ("), std::string::npos) << on.output;
  EXPECT_NE(off.output.find("  hessian            interpreter\n"), std::string::npos) << off.output;
  EXPECT_NE(on.output.find("  residual           machine code ("), std::string::npos) << on.output;
  EXPECT_NE(off.output.find("  residual           interpreter\n"), std::string::npos) << off.output;
  // Everything up to the timings is the same text: status, iterations, objective, violation.
  const auto solved = [](const std::string& out) { return out.substr(0, out.find("  time  ")); };
  EXPECT_EQ(solved(on.output), solved(off.output));
  EXPECT_EQ(bad.code, 2) << bad.output;
  EXPECT_NE(bad.output.find("compile: expected auto, on or off, got 'sometimes'"),
            std::string::npos)
      << bad.output;
}

// A polynomial control (docs/theory.md §10, "Polynomial controls"): the summary names it, the
// minimum-energy optimum J = 12 is exact at N = 2, and --verify, simulating the input along the
// polynomials, finds the collocated states to the integrator's tolerance.
TEST(OptimizeCommand, PolynomialControlIsSummarisedAndVerified) {
  const auto r =
      testing::run_shell("optimize " + std::string(LAGRANGE_SOURCE_DIR) +
                         "/tests/optimize/data/double_integrator_polynomial.yaml --verify");
  ASSERT_EQ(r.code, 0) << r.output;
  const size_t objective = r.output.find("objective ");
  ASSERT_NE(objective, std::string::npos) << r.output;
  EXPECT_NEAR(std::stod(r.output.substr(objective + 10)), 12.0, 1e-7) << r.output;
  EXPECT_NE(r.output.find("polynomial         u (degree 2 on each interval)"), std::string::npos)
      << r.output;
  const size_t at = r.output.find("final-state gap ");
  ASSERT_NE(at, std::string::npos) << r.output;
  EXPECT_LT(std::stod(r.output.substr(at + 16)), 1e-8) << r.output;
}

TEST(OptimizeCommand, ModelWithoutAProblemIsAUsageError) {
  const auto r = testing::run_shell("optimize " + std::string(LAGRANGE_SOURCE_DIR) +
                                    "/examples/pendulum.yaml");
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("has no optimal_control section"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace lagrange

// `simulate --dynamics auto|lagrangian|recursive` (and `export --dynamics`) as a user meets it
// (docs/theory.md §4.9): both formulations give the same trajectory; auto takes the recursive one
// wherever it applies; asking for it where it does not apply is a usage error that says why.

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <sstream>
#include <string>

#include "support/test_paths.hpp"
#include "hardening/cli_runner.hpp"
#include "support/csv_table.hpp"

namespace lagrange::hardening {
namespace {

using lagrange::test::read_csv_table;

using lagrange::test::example_path;

/// A planar chain of n links written as `links:`.
std::string chain(size_t n) {
  std::string y = "name: chain\nparameters: {g: 9.81}\ngravity: [0, -g, 0]\nlinks:\n";
  for (size_t k = 1; k <= n; ++k) {
    y += "  l" + std::to_string(k) + ":\n";
    if (k > 1) y += "    parent: l" + std::to_string(k - 1) + "\n";
    y += "    joint: {name: q" + std::to_string(k) + ", type: revolute, initial: 0.1" +
         (k > 1 ? ", origin: {xyz: [0, -0.5, 0]}" : "") + "}\n";
    y += "    mass: 1\n    com: [0, -0.5, 0]\n    inertia: [0.01, 0.01, 0.01]\n";
  }
  return y;
}

TEST(DynamicsOption, BothFormulationsGiveTheSameTrajectory) {
  const ScratchDir dir("dynamics-same");
  const std::string model = example_path("planar_arm_pd.yaml");
  const auto run = [&](const std::string& form) {
    return run_lagrange(dir.path(),
                        {"simulate", model, "--t-end", "2", "--rtol", "1e-11", "--atol", "1e-12",
                         "--dynamics", form, "-o", (dir.path() / (form + ".csv")).string()});
  };
  const RunResult lagrangian = run("lagrangian"), recursive = run("recursive"),
                  automatic = run("auto");
  ASSERT_EQ(lagrangian.exit_code, 0) << lagrangian.err;
  ASSERT_EQ(recursive.exit_code, 0) << recursive.err;
  ASSERT_EQ(automatic.exit_code, 0) << automatic.err;
  EXPECT_NE(recursive.out.find("recursive (articulated-body algorithm)"), std::string::npos)
      << recursive.out;
  EXPECT_EQ(lagrangian.out.find("recursive"), std::string::npos) << lagrangian.out;
  EXPECT_NE(automatic.out.find("recursive (articulated-body algorithm)"), std::string::npos)
      << automatic.out;
  const auto a = read_csv_table(dir.path() / "lagrangian.csv").rows.back();
  const auto b = read_csv_table(dir.path() / "recursive.csv").rows.back();
  ASSERT_EQ(a.size(), b.size());
  ASSERT_GT(a.size(), 4u);
  for (size_t i = 0; i < a.size(); ++i) EXPECT_NEAR(a[i], b[i], 1e-8 * (1 + std::abs(a[i]))) << i;
}

TEST(DynamicsOption, AutoTakesTheRecursiveFormAndTheReportSaysSo) {
  const ScratchDir dir("dynamics-auto");
  const auto at = [&](const std::string& name) { return (dir.path() / name).string(); };
  // 13 joints: beyond the trees whose report shows the Lagrangian form instead.
  spit(dir.path() / "chain.yaml", chain(13));
  const RunResult r =
      run_lagrange(dir.path(), {"simulate", at("chain.yaml"), "--t-end", "0.5", "-o",
                                at("chain.csv"), "--report", at("chain.html")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("recursive (articulated-body algorithm)"), std::string::npos) << r.out;
  EXPECT_NE(slurp(dir.path() / "chain.html").find("articulated-body algorithm over 13 joints"),
            std::string::npos);
  // A small arm's report shows its mass matrix; a model without a tree stays Lagrangian.
  const RunResult arm =
      run_lagrange(dir.path(), {"simulate", example_path("elbow_manipulator.yaml"), "--t-end",
                                "0.2", "-o", at("arm.csv"), "--report", at("arm.html")});
  ASSERT_EQ(arm.exit_code, 0) << arm.err;
  EXPECT_NE(arm.out.find("recursive"), std::string::npos) << arm.out;
  EXPECT_NE(slurp(dir.path() / "arm.html").find("Mass matrix"), std::string::npos);
  const RunResult p = run_lagrange(
      dir.path(), {"simulate", example_path("pendulum.yaml"), "--t-end", "0.1", "-o", at("p.csv")});
  ASSERT_EQ(p.exit_code, 0) << p.err;
  EXPECT_EQ(p.out.find("recursive"), std::string::npos) << p.out;
}

TEST(DynamicsOption, RecursiveWhereItDoesNotApplyIsAUsageErrorSayingWhy) {
  const ScratchDir dir("dynamics-refused");
  const RunResult r =
      run_lagrange(dir.path(), {"simulate", example_path("pendulum.yaml"), "--dynamics",
                                "recursive", "-o", (dir.path() / "p.csv").string()});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--dynamics recursive: the articulated-body algorithm does not apply"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("it has no joint tree"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir.path() / "p.csv"));
  const RunResult bad = run_lagrange(
      dir.path(), {"simulate", example_path("pendulum.yaml"), "--dynamics", "fast", "-o", "p.csv"});
  EXPECT_EQ(bad.exit_code, 2);
}

TEST(DynamicsOption, DeriveFormRecursivePrintsTheAlgorithm) {
  const ScratchDir dir("derive-recursive");
  const RunResult r = run_lagrange(
      dir.path(), {"derive", example_path("elbow_manipulator.yaml"), "--form", "recursive"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("Articulated-body algorithm"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("L2.invD = L2.IA33^(-1)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("q2_ddot = "), std::string::npos) << r.out;
  const RunResult json = run_lagrange(dir.path(), {"derive", example_path("elbow_manipulator.yaml"),
                                                   "--form", "recursive", "--format", "json"});
  ASSERT_EQ(json.exit_code, 0) << json.err;
  EXPECT_NE(json.out.find("\"definitions\""), std::string::npos);
  const RunResult refused =
      run_lagrange(dir.path(), {"derive", example_path("pendulum.yaml"), "--form", "recursive"});
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_NE(refused.err.find("it has no joint tree"), std::string::npos) << refused.err;
}

// `export --dynamics`: auto exports a tree's recursive form (M = 1, no factorisation in the C),
// lagrangian the energies' form; recursive where it does not apply, or with the manipulator form
// (D, C, g are Lagrangian), is a usage error with nothing written.
TEST(DynamicsOption, ExportTakesTheFormulationToo) {
  const ScratchDir dir("export-recursive");
  const auto c_source = [&](const std::string& sub) {
    std::ifstream in(dir.path() / sub / "lagrange_model.c");
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  };
  const RunResult r = run_lagrange(dir.path(), {"export", example_path("robots/ur5.urdf"), "--c",
                                                (dir.path() / "auto").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("recursive"), std::string::npos) << r.out;
  EXPECT_NE(c_source("auto").find("#define LAGRANGE_DIAGONAL_M 1"), std::string::npos);
  EXPECT_EQ(c_source("auto").find("static int lg_chol("), std::string::npos)
      << "M = 1 needs no Cholesky";
  const RunResult l =
      run_lagrange(dir.path(), {"export", example_path("robots/ur5.urdf"), "--c",
                                (dir.path() / "lagrangian").string(), "--dynamics", "lagrangian"});
  ASSERT_EQ(l.exit_code, 0) << l.err;
  EXPECT_NE(l.out.find("lagrangian"), std::string::npos) << l.out;
  EXPECT_NE(c_source("lagrangian").find("static int lg_chol("), std::string::npos);
  const RunResult refused =
      run_lagrange(dir.path(), {"export", example_path("pendulum.yaml"), "--c",
                                (dir.path() / "refused").string(), "--dynamics", "recursive"});
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_NE(refused.err.find("it has no joint tree"), std::string::npos) << refused.err;
  EXPECT_FALSE(fs::exists(dir.path() / "refused"));
  const RunResult manipulator = run_lagrange(
      dir.path(), {"export", example_path("robots/ur5.urdf"), "--c", (dir.path() / "m").string(),
                   "--form", "manipulator", "--dynamics", "recursive"});
  EXPECT_EQ(manipulator.exit_code, 2);
  EXPECT_NE(manipulator.err.find("drop --dynamics recursive"), std::string::npos)
      << manipulator.err;
}

}  // namespace
}  // namespace lagrange::hardening

// The exported C99 dynamics, compiled with the system compiler, reproduce Dynamics::forward.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>

#include "hardening/cli_runner.hpp"
#include "lagrange/equations.hpp"
#include "lagrange/io.hpp"
#include "lagrange/reader.hpp"
#include "support/harness.hpp"

namespace lagrange {
namespace {

namespace fs = std::filesystem;

// Build a driver around the exported model that prints q̈ and λ for a given state.
std::vector<double> run_exported(const CompiledModel& cm, const std::string& tag,
                                 const std::vector<double>& q, const std::vector<double>& v,
                                 double t, double alpha) {
  // A folder of this process's own: two tests export the same example, and ctest runs them at once.
  const hardening::ScratchDir scratch("export-" + testing::model_label(tag));
  const fs::path& dir = scratch.path();
  export_c(cm, dir.string());
  std::ostringstream main;
  main << "#include <stdio.h>\n#include \"lagrange_model.h\"\nint main(void) {\n";
  auto arr = [&](const char* name, const std::vector<double>& x) {
    main << "  double " << name << "[" << std::max<size_t>(x.size(), 1) << "] = {";
    for (size_t i = 0; i < x.size(); ++i) main << (i ? ", " : "") << std::setprecision(17) << x[i];
    if (x.empty()) main << "0";
    main << "};\n";
  };
  arr("q", q);
  arr("v", v);
  arr("p", cm.parameter_defaults);
  main << "  double u[3 * LAGRANGE_K + 1], qd[LAGRANGE_NQ], a[LAGRANGE_N], lam[LAGRANGE_M + 1];\n"
       << "  int i, rc;\n  lagrange_inputs(" << std::setprecision(17) << t << ", p, u);\n"
       << "  rc = lagrange_dynamics(" << t << ", q, v, u, p, " << alpha << ", qd, a, lam);\n"
       << "  if (rc) return 10 + rc;\n"
       << "  for (i = 0; i < LAGRANGE_N; ++i) printf(\"%.17g\\n\", a[i]);\n"
       << "  for (i = 0; i < LAGRANGE_M; ++i) printf(\"%.17g\\n\", lam[i]);\n  return 0;\n}\n";
  std::ofstream(dir / "main.c") << main.str();
  const std::string exe = (dir / "run").string();
  const std::string cmd = "cc -std=c99 -O1 -ffp-contract=off -Wall -Werror -pedantic -o " + exe +
                          " " + (dir / "main.c").string() + " " +
                          (dir / "lagrange_model.c").string() + " -lm 2>&1";
  EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
  FILE* pipe = popen(exe.c_str(), "r");
  std::vector<double> out;
  double x;
  while (std::fscanf(pipe, "%lf", &x) == 1) out.push_back(x);
  EXPECT_EQ(pclose(pipe), 0);
  return out;
}

/// The exported C of `example` (in the formulation `form`) against the engine's Lagrangian
/// forward dynamics at (t, q, v).
void expect_export_matches(const std::string& example, const std::vector<double>& q,
                           const std::vector<double>& v, double t,
                           Formulation form = Formulation::Lagrangian) {
  auto sys = testing::load_example(example);
  const CompiledModel& cm = *sys.compiled;
  const double alpha = 7.0;
  sys.dynamics->set_baumgarte(alpha);
  std::vector<double> qd(cm.nq), a(cm.nv), lambda(cm.m);
  sys.dynamics->forward(t, q.data(), v.data(), qd.data(), a.data(), lambda.data());
  const bool recursive = form == Formulation::Recursive;
  const std::shared_ptr<const CompiledModel> exported =
      recursive ? compile(derive(*sys.model, form)) : sys.compiled;
  const std::vector<double> c =
      run_exported(*exported, example + (recursive ? "_recursive" : ""), q, v, t, alpha);
  ASSERT_EQ(c.size(), cm.nv + cm.m);
  // Norm-wise relative agreement: the two solve the same linear system with different code (Eigen
  // here, the exported Cholesky there), which agree to κ·ε in norm, not digit by digit.
  auto expect_close = [](const double* got, const std::vector<double>& want, const char* what) {
    double scale = 1.0, worst = 0.0;
    for (size_t i = 0; i < want.size(); ++i) {
      scale = std::max(scale, std::abs(want[i]));
      worst = std::max(worst, std::abs(got[i] - want[i]));
    }
    EXPECT_LE(worst, 1e-12 * scale)
        << what << ": max difference " << worst << ", max |value| " << scale;
  };
  expect_close(c.data(), a, "accelerations");
  expect_close(c.data() + cm.nv, lambda, "multipliers");
}

TEST(ExportC, DoublePendulumMatchesEngine) {
  expect_export_matches("double_pendulum.yaml", {0.3, -1.2}, {0.7, 2.1}, 0.0);
}

TEST(ExportC, ConstrainedCraneWithInputsMatchesEngine) {
  expect_export_matches("crane.yaml", {0.3, -1.9}, {0.2, -0.1}, 1.3);
}

TEST(ExportC, FiveBarMatchesEngine) {
  expect_export_matches("five_bar.yaml", {1.8, 0.3, 1.2, 2.6}, {0.5, 0.1, -0.3, 0.2}, 0.0);
}

// Every example and URDF arm, at its initial state with perturbed rates: the exported C and the
// engine agree to 1e-12 (one more evaluation path of the forward-speed issue).
class ExportEveryModel : public ::testing::TestWithParam<std::string> {};

TEST_P(ExportEveryModel, MatchesEngine) {
  auto sys = testing::load_example(GetParam());
  std::vector<double> v = sys.compiled->v0;
  for (size_t i = 0; i < v.size(); ++i) v[i] += 0.1 * std::sin(1.0 + static_cast<double>(i));
  expect_export_matches(GetParam(), sys.compiled->q0, v, 0.4);
}

INSTANTIATE_TEST_SUITE_P(Examples, ExportEveryModel, ::testing::ValuesIn(testing::model_files()),
                         [](const auto& info) { return testing::model_label(info.param); });

/// The model files with a joint tree the recursive formulation takes (docs/theory.md §4.9).
std::vector<std::string> tree_model_files() {
  std::vector<std::string> trees;
  for (const std::string& file : testing::model_files())
    if (recursive_unsuitable(read_model_file(testing::example_path(file))).empty())
      trees.push_back(file);
  return trees;
}

// `export --dynamics recursive`: the articulated-body algorithm as C (M = 1, divided rather than
// factored) gives the Lagrangian engine's accelerations to 1e-12, for every example with a tree
// and both URDF arms.
class ExportRecursive : public ::testing::TestWithParam<std::string> {};

TEST_P(ExportRecursive, MatchesTheLagrangianEngine) {
  auto sys = testing::load_example(GetParam());
  std::vector<double> v = sys.compiled->v0;
  for (size_t i = 0; i < v.size(); ++i) v[i] += 0.1 * std::sin(1.0 + static_cast<double>(i));
  expect_export_matches(GetParam(), sys.compiled->q0, v, 0.4, Formulation::Recursive);
}

INSTANTIATE_TEST_SUITE_P(Trees, ExportRecursive, ::testing::ValuesIn(tree_model_files()),
                         [](const auto& info) { return testing::model_label(info.param); });

TEST(ExportRecursive, TreesAreFound) {
  const std::vector<std::string> trees = tree_model_files();
  EXPECT_GE(trees.size(), 4u);
  EXPECT_NE(std::find(trees.begin(), trees.end(), "robots/ur5.urdf"), trees.end());
}

}  // namespace
}  // namespace lagrange

// The exported C99 dynamics, compiled with the system compiler, reproduce Dynamics::forward.

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>

#include "lagrange/io.hpp"
#include "support/harness.hpp"

namespace lagrange {
namespace {

namespace fs = std::filesystem;

// Build a driver around the exported model that prints q̈ and λ for a given state.
std::vector<double> run_exported(const CompiledModel& cm, const std::string& tag,
                                 const std::vector<double>& q, const std::vector<double>& v,
                                 double t, double alpha) {
  const fs::path dir = fs::temp_directory_path() / ("lagrange_export_" + tag);
  fs::remove_all(dir);
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

void expect_export_matches(const std::string& example, const std::vector<double>& q,
                           const std::vector<double>& v, double t) {
  auto sys = testing::load_example(example);
  const CompiledModel& cm = *sys.compiled;
  const double alpha = 7.0;
  sys.dynamics->set_baumgarte(alpha);
  std::vector<double> qd(cm.nq), a(cm.nv), lambda(cm.m);
  sys.dynamics->forward(t, q.data(), v.data(), qd.data(), a.data(), lambda.data());
  const std::vector<double> c = run_exported(cm, example, q, v, t, alpha);
  ASSERT_EQ(c.size(), cm.nv + cm.m);
  for (size_t i = 0; i < cm.nv; ++i) EXPECT_NEAR(c[i], a[i], 1e-12 * (1 + std::abs(a[i]))) << i;
  for (size_t r = 0; r < cm.m; ++r)
    EXPECT_NEAR(c[cm.nv + r], lambda[r], 1e-12 * (1 + std::abs(lambda[r]))) << r;
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

}  // namespace
}  // namespace lagrange

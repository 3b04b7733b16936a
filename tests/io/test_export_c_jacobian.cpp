// `export --c --jacobian` (docs/theory.md §5.7): the exported ∂a/∂q, ∂a/∂v, ∂a/∂u, compiled with
// the system C compiler, against the library's DynamicsJacobian (itself checked against finite
// differences in tests/analysis/test_jacobian_fd.cpp), and their CSC patterns holding every
// non-zero.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <random>
#include <sstream>

#include "analysis/analysed.hpp"
#include "hardening/cli_runner.hpp"
#include "lagrange/io.hpp"

namespace lagrange {
namespace {

namespace fs = std::filesystem;

struct ExportedJacobian {
  // (block 0 = a_q, 1 = a_v, 2 = a_u; row; column; value) per pattern entry.
  struct Value {
    int block, row, col;
    double value;
  };
  std::vector<Value> values;
};

ExportedJacobian run_exported(const DynamicsJacobian& jac, const std::string& tag,
                              const std::vector<double>& q, const std::vector<double>& v, double t,
                              double alpha) {
  const CompiledModel& cm = jac.model();
  const hardening::ScratchDir scratch("export-jacobian-" + tag);  // this process's own folder
  const fs::path& dir = scratch.path();
  export_c_jacobian(jac, dir.string());
  std::ostringstream main;
  main << std::setprecision(17) << "#include <stdio.h>\n#include \"lagrange_jacobian.h\"\n"
       << "static void show(int block, int cols, const int* colptr, const int* rowind, const "
          "double* x) {\n  int k, e;\n  for (k = 0; k < cols; ++k)\n"
       << "    for (e = colptr[k]; e < colptr[k + 1]; ++e)\n"
       << "      printf(\"%d %d %d %.17g\\n\", block, rowind[e], k, x[e]);\n}\n"
       << "int main(void) {\n";
  const auto arr = [&](const char* name, const std::vector<double>& x) {
    main << "  double " << name << "[" << std::max<size_t>(x.size(), 1) << "] = {";
    for (size_t i = 0; i < x.size(); ++i) main << (i ? ", " : "") << x[i];
    main << (x.empty() ? "0};\n" : "};\n");
  };
  arr("q", q);
  arr("v", v);
  arr("p", cm.parameter_defaults);
  main << "  double u[3 * LAGRANGE_K + 1], aq[LAGRANGE_A_Q_NNZ + 1], av[LAGRANGE_A_V_NNZ + 1],\n"
       << "      au[LAGRANGE_A_U_NNZ + 1];\n  int rc;\n"
       << "  lagrange_inputs(" << t << ", p, u);\n"
       << "  rc = lagrange_jacobian(" << t << ", q, v, u, p, " << alpha << ", aq, av, au);\n"
       << "  if (rc) return 10 + rc;\n"
       << "  show(0, LAGRANGE_NQ, lagrange_a_q_colptr, lagrange_a_q_rowind, aq);\n"
       << "  show(1, LAGRANGE_N, lagrange_a_v_colptr, lagrange_a_v_rowind, av);\n"
       << "  show(2, LAGRANGE_K, lagrange_a_u_colptr, lagrange_a_u_rowind, au);\n"
       << "  return 0;\n}\n";
  std::ofstream(dir / "main.c") << main.str();
  const std::string exe = (dir / "run").string();
  const std::string cmd = "cc -std=c99 -O1 -ffp-contract=off -Wall -Werror -pedantic -o " + exe +
                          " " + (dir / "main.c").string() + " " +
                          (dir / "lagrange_model.c").string() + " " +
                          (dir / "lagrange_jacobian.c").string() + " -lm 2>&1";
  EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
  FILE* pipe = popen(exe.c_str(), "r");
  ExportedJacobian out;
  ExportedJacobian::Value x{};
  while (std::fscanf(pipe, "%d %d %d %lf", &x.block, &x.row, &x.col, &x.value) == 4)
    out.values.push_back(x);
  EXPECT_EQ(pclose(pipe), 0);
  return out;
}

// The exported derivatives of `yaml`'s model at its initial state moved by a random amount and
// given random rates, against DynamicsJacobian::evaluate there.
ExportedJacobian expect_exported_jacobian_matches(const std::string& tag, testing::Analysed s) {
  const CompiledModel& cm = *s.cm;
  const DynamicsJacobian jac(s.eq, s.cm, cm.input_names);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> jitter(-0.3, 0.3);
  std::vector<double> q = s.q, v = s.v;
  for (size_t i = 0; i < cm.plain; ++i) q[i] += jitter(rng);
  for (double& x : v) x += jitter(rng);
  const double t = 0.7, alpha = 5.0;
  s.dyn->set_baumgarte(alpha);
  const StateJacobian J = jac.evaluate(*s.dyn, t, q.data(), v.data());
  const ExportedJacobian c = run_exported(jac, tag, q, v, t, alpha);
  const Eigen::MatrixXd* blocks[3] = {&J.a_q, &J.a_v, &J.a_w};
  std::vector<Eigen::MatrixXd> seen;
  for (const Eigen::MatrixXd* b : blocks)
    seen.push_back(Eigen::MatrixXd::Zero(b->rows(), b->cols()));
  for (const auto& x : c.values) {
    const Eigen::MatrixXd& lib = *blocks[x.block];
    const double scale = std::max(1.0, lib.cwiseAbs().maxCoeff());
    EXPECT_NEAR(x.value, lib(x.row, x.col), 1e-10 * scale)
        << tag << " block " << x.block << " (" << x.row << ", " << x.col << ")";
    seen[static_cast<size_t>(x.block)](x.row, x.col) = 1.0;
  }
  for (size_t b = 0; b < 3; ++b)  // every non-zero of the library's derivatives is in a pattern
    for (long i = 0; i < blocks[b]->rows(); ++i)
      for (long k = 0; k < blocks[b]->cols(); ++k)
        if (seen[b](i, k) == 0.0) {
          EXPECT_EQ((*blocks[b])(i, k), 0.0) << tag << " block " << b;
        }
  EXPECT_GT(c.values.size(), 0u);
  return c;
}

TEST(ExportCJacobian, DoublePendulumMatchesTheLibrary) {
  expect_exported_jacobian_matches("double_pendulum",
                                   testing::analyse_example("double_pendulum.yaml"));
}

// Inputs: da/du for the horizontal force, a column of B.
TEST(ExportCJacobian, InputColumnsOfAForcedPendulum) {
  expect_exported_jacobian_matches("forced_pendulum",
                                   testing::analyse_example("pendulum_horizontal_force.yaml"));
}

// A constraint that moves with the inputs (the crane's trolley and rope length), with Baumgarte
// terms: the range-space solve of the differentiated KKT system.
TEST(ExportCJacobian, ConstrainedCraneWithMovingInputs) {
  expect_exported_jacobian_matches("crane", testing::analyse_example("crane.yaml"));
}

// A chain of 6 rigid links between two anchors: the patterns of a constrained model with many
// constraints, one KKT component.
TEST(ExportCJacobian, HangingLineWithDrag) {
  expect_exported_jacobian_matches("hanging_line", testing::analyse_string(R"(
name: hanging line
parameters: {L: 10, mu: 0.05, d: 0.01}
gravity: [0, 0, -9.81]
tethers:
  line: {between: [[0, 0, 0], [8, 0, 0]], segments: 6, length: L, mass_per_length: mu,
         diameter: d, cd: 1.2, drag: simple}
)"));
}

// Two subsystems that do not touch (x; y and z): the patterns keep them apart. ∂a/∂q has x's
// column in row x only and y's and z's in rows y, z (5 entries, not 9); ∂a/∂v only the damping of
// x (1 entry).
TEST(ExportCJacobian, IndependentSubsystemsGiveASparsePattern) {
  const ExportedJacobian c =
      expect_exported_jacobian_matches("two_oscillators", testing::analyse_string(R"(
name: two oscillators
parameters: {m1: 1.0, m2: 2.0, k1: 3.0, k2: 5.0, c: 0.4}
coordinates:
  x: {initial: 0.3, rate: 0.1}
  y: {initial: -0.2, rate: 0.5}
  z: {initial: 0.1, rate: 0}
kinetic: m1/2*der(x)^2 + m2/2*(der(y)^2 + der(z)^2)
potential: k1/2*x^2 + k2/2*(y - z)^2 + k2*z^4
generalized_forces: {x: -c*der(x)}
)"));
  size_t in_q = 0, in_v = 0;
  for (const auto& x : c.values) {
    in_q += x.block == 0;
    in_v += x.block == 1;
    if (x.block == 0) {
      EXPECT_EQ(x.row == 0, x.col == 0) << x.row << ", " << x.col;
    }
  }
  EXPECT_EQ(in_q, 5u);
  EXPECT_EQ(in_v, 1u);
}

}  // namespace
}  // namespace lagrange

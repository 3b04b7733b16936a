// The robot-facing commands as a user meets them (issue 11): `simulate --initial`, `eval` at a
// state (inverse dynamics of forward dynamics returns τ), the URDF friction warning, and
// `export --form manipulator` compiled with the system cc and compared with `eval`.

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "hardening/cli_runner.hpp"
#include "support/csv_table.hpp"
#include "support/test_paths.hpp"

namespace lagrange::hardening {
namespace {

using lagrange::test::CsvTable;
using lagrange::test::read_csv_table;

const std::string kUr5 = std::string(LAGRANGE_SOURCE_DIR) + "/examples/robots/ur5.urdf";
const std::string kElbow = std::string(LAGRANGE_SOURCE_DIR) + "/examples/elbow_manipulator.yaml";

TEST(SimulateInitial, UrdfRobotStartsAtTheGivenJointValuesAndRates) {
  ScratchDir dir("robots-initial");
  const fs::path csv = dir.path() / "ur5.csv";
  const RunResult r =
      run_lagrange(dir.path(), {"simulate", kUr5, "--t-end", "0.1", "-o", csv.string(), "--initial",
                                "shoulder_lift_joint=-1.2,elbow_joint_dot=0.5", "--initial",
                                "wrist_1_joint=0.3"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const CsvTable table = read_csv_table(csv);
  EXPECT_DOUBLE_EQ(table.at(0, "shoulder_lift_joint"), -1.2);
  EXPECT_DOUBLE_EQ(table.at(0, "elbow_joint_dot"), 0.5);
  EXPECT_DOUBLE_EQ(table.at(0, "wrist_1_joint"), 0.3);
  EXPECT_DOUBLE_EQ(table.at(0, "shoulder_pan_joint"), 0.0);
}

TEST(SimulateInitial, YamlModelTakesItToo) {
  ScratchDir dir("robots-initial-yaml");
  const fs::path csv = dir.path() / "elbow.csv";
  const RunResult r = run_lagrange(dir.path(), {"simulate", kElbow, "--t-end", "0.1", "-o",
                                                csv.string(), "--initial", "q2=1.5,q1_dot=-2"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const CsvTable table = read_csv_table(csv);
  EXPECT_DOUBLE_EQ(table.at(0, "q1"), 0.3);  // the file's
  EXPECT_DOUBLE_EQ(table.at(0, "q2"), 1.5);
  EXPECT_DOUBLE_EQ(table.at(0, "q1_dot"), -2.0);
}

TEST(SimulateInitial, UnknownNameExitsTwoNamingItAndWritesNothing) {
  ScratchDir dir("robots-initial-bad");
  const fs::path csv = dir.path() / "out.csv";
  for (const std::string arg : {"elbow=1", "q1_ddot=2", "q1"}) {
    const RunResult r =
        run_lagrange(dir.path(), {"simulate", kElbow, "-o", csv.string(), "--initial", arg});
    EXPECT_EQ(r.exit_code, 2) << arg << "\n" << r.err;
    const std::string name = arg.substr(0, arg.find('='));
    EXPECT_NE(r.err.find("--initial"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("'" + name + "'"), std::string::npos) << r.err;
    EXPECT_EQ(dir.files(), std::vector<std::string>{}) << arg;
  }
}

nlohmann::json eval_json(const ScratchDir& dir, std::vector<std::string> args) {
  args.insert(args.begin(), "eval");
  args.insert(args.end(), {"--format", "json"});
  const RunResult r = run_lagrange(dir.path(), args);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return nlohmann::json::parse(r.out);
}

// Forward dynamics with the given τ, then inverse dynamics of the q̈ found: τ comes back.
TEST(Eval, InverseDynamicsOfForwardDynamicsReturnsTau) {
  ScratchDir dir("robots-eval");
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-2, 2);
  const std::vector<std::string> joints{"shoulder_pan_joint", "shoulder_lift_joint",
                                        "elbow_joint",        "wrist_1_joint",
                                        "wrist_2_joint",      "wrist_3_joint"};
  for (int s = 0; s < 3; ++s) {
    std::string state, tau;
    std::vector<double> given;
    for (const auto& j : joints) {
      state += fmt::format("{}{}={:.17g},{}_dot={:.17g}", state.empty() ? "" : ",", j, u(rng), j,
                           u(rng));
      given.push_back(u(rng) * 10);
      tau += fmt::format("{}{}={:.17g}", tau.empty() ? "" : ",", j, given.back());
    }
    const nlohmann::json out = eval_json(dir, {kUr5, "--state", state, "--tau", tau});
    ASSERT_EQ(out["tau_inverse_dynamics"].size(), 6u);
    for (size_t i = 0; i < 6; ++i) {
      EXPECT_NEAR(out["tau_inverse_dynamics"][i].get<double>(), given[i], 1e-10) << joints[i];
      EXPECT_DOUBLE_EQ(out["tau"][i].get<double>(), given[i]);
    }
    // M is symmetric and the accelerations are not all zero.
    for (size_t i = 0; i < 6; ++i)
      for (size_t k = 0; k < 6; ++k)
        EXPECT_DOUBLE_EQ(out["M"][i][k].get<double>(), out["M"][k][i].get<double>());
  }
}

// The elbow manipulator (seed 001): at rest, the bias forces are g(q) = ∂P/∂q.
TEST(Eval, ElbowAtRestHasGravityAsBias) {
  ScratchDir dir("robots-eval-elbow");
  const nlohmann::json out = eval_json(dir, {kElbow, "--state", "q1=0.4,q2=-0.7"});
  const double m1 = 1.0, m2 = 0.8, L1 = 1.0, Lc1 = 0.5, Lc2 = 0.4, g = 9.81, q1 = 0.4, q2 = -0.7;
  EXPECT_NEAR(out["bias"][0].get<double>(),
              (m1 * Lc1 + m2 * L1) * g * std::cos(q1) + m2 * Lc2 * g * std::cos(q1 + q2), 1e-12);
  EXPECT_NEAR(out["bias"][1].get<double>(), m2 * Lc2 * g * std::cos(q1 + q2), 1e-12);
  EXPECT_EQ(out["coordinates"], nlohmann::json({"q1", "q2"}));
}

TEST(Eval, TextNamesTheBlocks) {
  ScratchDir dir("robots-eval-text");
  const RunResult r = run_lagrange(dir.path(), {"eval", kElbow, "--state", "q1_dot=1"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* block : {"Mass matrix M", "Bias forces C(q, q_dot) q_dot + g(q)",
                            "Accelerations", "Inverse dynamics tau"})
    EXPECT_NE(r.out.find(block), std::string::npos) << block << "\n" << r.out;
}

TEST(Eval, MistakesAreUsageErrors) {
  ScratchDir dir("robots-eval-bad");
  const RunResult bad_state = run_lagrange(dir.path(), {"eval", kElbow, "--state", "q3=1"});
  EXPECT_EQ(bad_state.exit_code, 2);
  EXPECT_NE(bad_state.err.find("--state: no coordinate or velocity 'q3'"), std::string::npos)
      << bad_state.err;
  const RunResult bad_tau = run_lagrange(dir.path(), {"eval", kElbow, "--tau", "q1_dot=1"});
  EXPECT_EQ(bad_tau.exit_code, 2);
  EXPECT_NE(bad_tau.err.find("--tau: no coordinate 'q1_dot'"), std::string::npos) << bad_tau.err;
  const RunResult bad_value = run_lagrange(dir.path(), {"eval", kElbow, "--state", "q1=abc"});
  EXPECT_EQ(bad_value.exit_code, 2);
  EXPECT_NE(bad_value.err.find("--state: expected a finite number after 'q1='"), std::string::npos)
      << bad_value.err;
}

TEST(UrdfFriction, NonZeroFrictionIsIgnoredWithAWarningAtItsLine) {
  ScratchDir dir("robots-friction");
  spit(dir.path() / "arm.urdf",
       "<robot name=\"r\">\n"
       "  <link name=\"base\"/>\n"
       "  <joint name=\"j1\" type=\"revolute\"><parent link=\"base\"/><child link=\"a\"/>\n"
       "    <axis xyz=\"0 1 0\"/><dynamics damping=\"0.1\" friction=\"0.5\"/></joint>\n"
       "  <link name=\"a\"><inertial><origin xyz=\"0.3 0 0\"/><mass value=\"1\"/><inertia "
       "ixx=\"0.01\" ixy=\"0\" ixz=\"0\" iyy=\"0.01\" iyz=\"0\" izz=\"0.01\"/></inertial></link>\n"
       "</robot>\n");
  const RunResult r =
      run_lagrange(dir.path(), {"simulate", (dir.path() / "arm.urdf").string(), "--t-end", "0.1"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("arm.urdf:4: warning: joint 'j1' has friction=\"0.5\": Coulomb joint "
                       "friction is ignored"),
            std::string::npos)
      << r.err;
}

/// Runs `command` through the shell and returns its exit status.
int shell(const std::string& command) {
  return std::system(command.c_str());
}

/// One sample state of an n-joint arm: positions, rates and joint forces.
struct ArmState {
  std::vector<double> q, v, tau;
};

/// Output of a C driver around the exported manipulator (linked with its object `manipulator`),
/// for each state in turn: D (n²), C q̇ (n), g (n), q̈ for `tau` (n), then τ of inverse dynamics
/// of that q̈ (n), with the default parameters. One driver for every state: one compile.
std::vector<double> run_exported(const fs::path& dir, const fs::path& manipulator,
                                 const std::vector<ArmState>& states) {
  auto arr = [](const std::string& name, const std::vector<double>& x) {
    std::string s = fmt::format("  static const double {}[] = {{", name);
    for (size_t i = 0; i < x.size(); ++i) s += fmt::format("{}{:.17g}", i ? ", " : "", x[i]);
    return s + "};\n";
  };
  const size_t n = states.at(0).q.size();
  std::string main = fmt::format(
      "#include <stdio.h>\n#include \"lagrange_manipulator.h\"\n"
      "static int print_state(const double* q, const double* v, const double* tau) {{\n"
      "  double D[{0}], c[{1}], g[{1}], a[{1}], back[{1}];\n  int i;\n"
      "  const double* p = lagrange_parameter_defaults;\n"
      "  lagrange_D(q, p, D);\n  lagrange_C_qdot(q, v, p, c);\n"
      "  lagrange_g(q, p, g);\n"
      "  if (lagrange_forward_dynamics(q, v, tau, p, a)) return 3;\n"
      "  lagrange_inverse_dynamics(q, v, a, p, back);\n"
      "  for (i = 0; i < {0}; ++i) printf(\"%.17g\\n\", D[i]);\n"
      "  for (i = 0; i < {1}; ++i) printf(\"%.17g\\n\", c[i]);\n"
      "  for (i = 0; i < {1}; ++i) printf(\"%.17g\\n\", g[i]);\n"
      "  for (i = 0; i < {1}; ++i) printf(\"%.17g\\n\", a[i]);\n"
      "  for (i = 0; i < {1}; ++i) printf(\"%.17g\\n\", back[i]);\n"
      "  return 0;\n}}\nint main(void) {{\n  int status = 0;\n",
      n * n, n);
  for (size_t s = 0; s < states.size(); ++s) {
    main += arr(fmt::format("q{}", s), states[s].q) + arr(fmt::format("v{}", s), states[s].v) +
            arr(fmt::format("tau{}", s), states[s].tau);
    main += fmt::format("  status |= print_state(q{0}, v{0}, tau{0});\n", s);
  }
  spit(dir / "driver.c", main + "  return status;\n}\n");
  // warnings are errors, as for the object the driver is linked with
  const fs::path exe = dir / "driver", out = dir / "driver.out";
  const std::string build = "cc -std=c99 -O1 -Wall -Werror -pedantic -o " + exe.string() + " " +
                            (dir / "driver.c").string() + " " + manipulator.string() + " -lm";
  EXPECT_EQ(shell(build), 0) << build;
  EXPECT_EQ(shell(exe.string() + " > " + out.string()), 0);
  std::istringstream text(slurp(out));
  std::vector<double> values;
  for (double x; text >> x;) values.push_back(x);
  return values;
}

/// Exports `model` as a manipulator, builds and runs the example main.c, and compares D, C q̇,
/// g, forward and inverse dynamics with `eval` at random states. The exported source is compiled
/// once (warnings are errors, -pedantic) and linked with the example and the driver.
void expect_export_matches_eval(const std::string& model, const std::vector<std::string>& joints,
                                const std::string& label) {
  ScratchDir dir("robots-export-" + label);
  const fs::path out = dir.path() / "c";
  const RunResult r =
      run_lagrange(dir.path(), {"export", model, "--c", out.string(), "--form", "manipulator"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const fs::path manipulator = out / "lagrange_manipulator.o";
  ASSERT_EQ(shell("cc -std=c99 -O2 -Wall -Werror -pedantic -c -o " + manipulator.string() + " " +
                  (out / "lagrange_manipulator.c").string()),
            0);
  const std::string example = (out / "example").string();
  ASSERT_EQ(shell("cc -std=c99 -O2 -Wall -Werror -o " + example + " " + (out / "main.c").string() +
                  " " + manipulator.string() + " -lm"),
            0);
  ASSERT_EQ(shell(example + " > " + (out / "example.txt").string()), 0);
  EXPECT_NE(slurp(out / "example.txt").find("gravity compensation"), std::string::npos);
  const size_t n = joints.size();
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> u(-2, 2);
  std::vector<ArmState> states(
      3, ArmState{std::vector<double>(n), std::vector<double>(n), std::vector<double>(n)});
  std::vector<nlohmann::json> moving, at_rest;
  for (ArmState& st : states) {
    std::string state, rest, given;
    for (size_t i = 0; i < n; ++i) {
      st.q[i] = u(rng);
      st.v[i] = u(rng);
      st.tau[i] = 5 * u(rng);
      const std::string comma = i ? "," : "";
      state +=
          fmt::format("{}{}={:.17g},{}_dot={:.17g}", comma, joints[i], st.q[i], joints[i], st.v[i]);
      rest += fmt::format("{}{}={:.17g}", comma, joints[i], st.q[i]);
      given += fmt::format("{}{}={:.17g}", comma, joints[i], st.tau[i]);
    }
    moving.push_back(eval_json(dir, {model, "--state", state, "--tau", given}));
    at_rest.push_back(eval_json(dir, {model, "--state", rest}));
  }
  const std::vector<double> all = run_exported(out, manipulator, states);
  const size_t block = n * n + 4 * n;
  ASSERT_EQ(all.size(), states.size() * block);
  for (size_t s = 0; s < states.size(); ++s) {
    const double* c = all.data() + s * block;
    const double tol = 1e-12;
    for (size_t i = 0; i < n; ++i) {
      const double g = at_rest[s]["bias"][i].get<double>();
      const double bias = moving[s]["bias"][i].get<double>();
      for (size_t k = 0; k < n; ++k)
        EXPECT_NEAR(c[i * n + k], moving[s]["M"][i][k].get<double>(), tol)
            << label << " D" << i << k;
      EXPECT_NEAR(c[n * n + i], bias - g, tol * (1 + std::abs(bias))) << label << " C q_dot " << i;
      EXPECT_NEAR(c[n * n + n + i], g, tol * (1 + std::abs(g))) << label << " g " << i;
      const double a = moving[s]["qddot"][i].get<double>();
      EXPECT_NEAR(c[n * n + 2 * n + i], a, 1e-10 * (1 + std::abs(a))) << label << " qddot " << i;
      EXPECT_NEAR(c[n * n + 3 * n + i], states[s].tau[i], 1e-10) << label << " tau " << i;
    }
  }
}

TEST(ExportManipulator, ElbowMatchesEval) {
  expect_export_matches_eval(kElbow, {"q1", "q2"}, "elbow");
}

TEST(ExportManipulator, Ur5MatchesEval) {
  expect_export_matches_eval(kUr5,
                             {"shoulder_pan_joint", "shoulder_lift_joint", "elbow_joint",
                              "wrist_1_joint", "wrist_2_joint", "wrist_3_joint"},
                             "ur5");
}

TEST(ExportManipulator, ConstrainedModelIsRefused) {
  ScratchDir dir("robots-export-five-bar");
  const RunResult r = run_lagrange(
      dir.path(), {"export", std::string(LAGRANGE_SOURCE_DIR) + "/examples/five_bar.yaml", "--c",
                   (dir.path() / "c").string(), "--form", "manipulator"});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("needs an unconstrained model"), std::string::npos) << r.err;
  EXPECT_EQ(dir.files(), std::vector<std::string>{});
}

}  // namespace
}  // namespace lagrange::hardening

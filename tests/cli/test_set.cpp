// `--set NAME=VALUE` as a user meets it (issue 8, items 6 and 8): the value replaces the file's
// before anything is evaluated, so initial values, rates, free-body initial states and simulate
// settings written as expressions of parameters follow it; a value the model rejects is a
// command-line mistake (exit 2) that names the --set, and nothing is written.

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "hardening/cli_runner.hpp"
#include "support/csv_table.hpp"

namespace lagrange::hardening {
namespace {

using lagrange::test::CsvTable;
using lagrange::test::read_csv_table;

const std::string kPendulum = R"(parameters: {m: 1, g: 9.81, l: 1, th0: 0.3}
coordinates:
  theta: {initial: th0, rate: th0/10}
points:
  bob: [l*sin(theta), -l*cos(theta), 0]
particles: {bob: m}
gravity: [0, -g, 0]
simulate: {t_end: th0/2, output_step: 0.01}
)";

TEST(SetOption, InitialValuesRatesAndSettingsFollowTheParameter) {
  ScratchDir dir("set-initial");
  const fs::path model = dir.path() / "pendulum.yaml", csv = dir.path() / "out.csv";
  spit(model, kPendulum);
  const RunResult r = run_lagrange(
      dir.path(), {"simulate", model.string(), "--set", "th0=1.0", "-q", "-o", csv.string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const CsvTable out = read_csv_table(csv);
  EXPECT_EQ(out.at(0, "theta"), 1.0);
  EXPECT_DOUBLE_EQ(out.at(0, "theta_dot"), 0.1);
  EXPECT_DOUBLE_EQ(out.last("t"), 0.5);  // t_end: th0/2
}

TEST(SetOption, FreeBodyInitialStateFollowsTheParameter) {
  ScratchDir dir("set-body");
  const fs::path model = dir.path() / "brick.yaml", csv = dir.path() / "out.csv";
  spit(model, R"(parameters: {m: 1, spin: 5, h: 0}
bodies:
  brick:
    mass: m
    shape: {box: [0.3, 0.2, 0.1]}
    frame: free
    initial:
      position: [0, 0, h]
      orientation: {axis_angle: {axis: [0, 0, 1], angle: h}}
      omega: [0, spin, 0]
simulate: {t_end: 0.1}
)");
  const RunResult r = run_lagrange(dir.path(), {"simulate", model.string(), "--set", "spin=2",
                                                "--set", "h=0.5", "-q", "-o", csv.string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const CsvTable out = read_csv_table(csv);
  EXPECT_EQ(out.at(0, "brick.wy"), 2.0);
  EXPECT_EQ(out.at(0, "brick.z"), 0.5);
  EXPECT_NEAR(out.at(0, "brick.R11"), std::cos(0.5), 1e-15);
}

TEST(SetOption, AValueTheModelRejectsIsACommandLineError) {
  ScratchDir dir("set-negative");
  const fs::path model = dir.path() / "pendulum.yaml";
  spit(model, kPendulum);
  for (const char* command : {"check", "simulate"}) {
    std::vector<std::string> args{command, model.string(), "--set", "m=-1"};
    if (std::string(command) == "simulate")
      args.insert(args.end(), {"-o", (dir.path() / "out.csv").string()});
    const RunResult r = run_lagrange(dir.path(), args);
    EXPECT_EQ(r.exit_code, 2) << command << "\n" << r.err;
    EXPECT_EQ(r.err.rfind("lagrange: --set m=-1: the model does not accept this value: expected "
                          "a positive mass for the particle at 'bob', got m = -1 (found at ",
                          0),
              0u)
        << r.err;
    EXPECT_EQ(dir.files(), std::vector<std::string>{"pendulum.yaml"});
  }
  // The same mistake written in the file is the file's: exit 1 at its place.
  std::string bad = kPendulum;
  bad.replace(bad.find("m: 1"), 4, "m: -1");
  spit(model, bad);
  const RunResult r = run_lagrange(dir.path(), {"check", model.string(), "--set", "l=2"});
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_EQ(r.err.rfind(model.string() + ":6:", 0), 0u) << r.err;
}

TEST(SetOption, UnknownNamesAndBadNumbersAreCommandLineErrors) {
  ScratchDir dir("set-unknown");
  const fs::path model = dir.path() / "pendulum.yaml";
  spit(model, kPendulum);
  const RunResult unknown = run_lagrange(dir.path(), {"check", model.string(), "--set", "mass=2"});
  EXPECT_EQ(unknown.exit_code, 2);
  EXPECT_NE(unknown.err.find("--set: unknown parameter 'mass' (parameters: m, g, l, th0)"),
            std::string::npos)
      << unknown.err;
  const RunResult text = run_lagrange(dir.path(), {"check", model.string(), "--set", "m=heavy"});
  EXPECT_EQ(text.exit_code, 2);
  EXPECT_NE(text.err.find("expected a finite number after 'm=', got 'heavy'"), std::string::npos)
      << text.err;
}

}  // namespace
}  // namespace lagrange::hardening

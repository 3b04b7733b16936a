// Values on the command line read as the model file reads them (issue 36 item 5): `--initial`,
// `--at`, `--set` and `--vary` take `pi`, `pi/10`, `2*pi/3`, and the start values the model's
// parameters; a value that does not read is a located command-line mistake (exit 2).

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "hardening/cli_runner.hpp"
#include "lagrange/reader.hpp"
#include "support/csv_table.hpp"

namespace lagrange::hardening {
namespace {

using lagrange::test::CsvTable;
using lagrange::test::read_csv_table;

constexpr double kPi = 3.14159265358979323846;

// t_end is d, so the last row's time shows a --set value exactly.
const std::string kPendulumEndingAtD = R"(parameters: {m: 1, g: 9.81, l: 1, d: 0.1}
coordinates:
  theta: {initial: 0.3}
points:
  bob: [l*sin(theta), -l*cos(theta), 0]
particles: {bob: m}
gravity: [0, -g, 0]
simulate: {t_end: d, output_step: 0.05}
)";

TEST(ValueExpressions, EvaluatedAsTheFileEvaluatesThem) {
  EXPECT_EQ(evaluate_value_text("pi"), kPi);
  EXPECT_DOUBLE_EQ(evaluate_value_text("2*pi/3"), 2 * kPi / 3);
  EXPECT_DOUBLE_EQ(evaluate_value_text("sqrt(2)/2"), std::sqrt(2.0) / 2);
  EXPECT_EQ(evaluate_value_text("l/2", {{"l", 3.0}}), 1.5);
  EXPECT_THROW(evaluate_value_text("sqrt(-1)"), ValueTextError);
  EXPECT_THROW(evaluate_value_text("[1, 2, 3]"), ValueTextError);
  try {
    evaluate_value_text("pi/");
    ADD_FAILURE() << "no error";
  } catch (const ValueTextError& e) {
    EXPECT_NE(std::string(e.what()).find("at character 4 of 'pi/'"), std::string::npos) << e.what();
  }
}

TEST(ValueExpressions, InitialEqualsTheSameValueWrittenInTheFile) {
  ScratchDir dir("values-initial");
  const GivenAndWritten runs =
      run_given_and_written(dir, kPendulumEndingAtD, "initial: 0.3", "initial: pi/3", "theta=pi/3");
  const fs::path model = dir.path() / "model.yaml";
  const CsvTable ca = read_csv_table(runs.given), cb = read_csv_table(runs.written);
  EXPECT_DOUBLE_EQ(ca.at(0, "theta"), kPi / 3);
  // A function of two arguments survives the option's split at commas.
  const fs::path c = dir.path() / "c.csv";
  const RunResult two = run_lagrange(
      dir.path(), {"simulate", model.string(), "--initial",
                   "theta=atan2(sqrt(3),1),theta_dot=4*atan2(1,1)", "-q", "-o", c.string()});
  ASSERT_EQ(two.exit_code, 0) << two.err;
  EXPECT_DOUBLE_EQ(read_csv_table(c).at(0, "theta"), kPi / 3);
  EXPECT_DOUBLE_EQ(read_csv_table(c).at(0, "theta_dot"), kPi);
  ASSERT_EQ(ca.rows.size(), cb.rows.size());
  for (size_t i = 0; i < ca.rows.size(); ++i) EXPECT_EQ(ca.rows[i], cb.rows[i]) << "row " << i;
}

TEST(ValueExpressions, SetAndInitialUseParametersAfterSet) {
  ScratchDir dir("values-set");
  const fs::path model = dir.path() / "pendulum.yaml", csv = dir.path() / "out.csv";
  spit(model, kPendulumEndingAtD);
  // --set d=pi/10 sets t_end; --initial theta=l/4 sees l = 2 from --set.
  const RunResult r =
      run_lagrange(dir.path(), {"simulate", model.string(), "--set", "d=pi/10", "--set", "l=2",
                                "--initial", "theta=l/4", "-q", "-o", csv.string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const CsvTable out = read_csv_table(csv);
  EXPECT_EQ(out.at(0, "theta"), 0.5);
  EXPECT_DOUBLE_EQ(out.at(out.rows.size() - 1, "t"), kPi / 10);
}

TEST(ValueExpressions, LinearizeAtPiIsTheUprightPendulum) {
  ScratchDir dir("values-at");
  const fs::path model = dir.path() / "pendulum.yaml";
  spit(model, kPendulumEndingAtD);
  const RunResult r = run_lagrange(
      dir.path(), {"linearize", model.string(), "--at", "theta=pi", "--format", "json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  // Upright: theta'' = (g/l) (theta - pi) to first order.
  EXPECT_NEAR(j["A"][1][0].get<double>(), 9.81, 1e-12);
  EXPECT_NEAR(j["A"][0][1].get<double>(), 1.0, 1e-15);
}

TEST(ValueExpressions, VaryTakesExpressions) {
  ScratchDir dir("values-vary");
  const fs::path model = dir.path() / "pendulum.yaml", study = dir.path() / "study";
  spit(model, kPendulumEndingAtD);
  const RunResult grid = run_lagrange(
      dir.path(), {"sweep", model.string(), "--vary", "d=pi/4:pi/2:3", "-q", "-o", study.string()});
  ASSERT_EQ(grid.exit_code, 0) << grid.err;
  const CsvTable summary = read_csv_table(study / "summary.csv");
  ASSERT_EQ(summary.rows.size(), 3u);
  EXPECT_DOUBLE_EQ(summary.at(0, "d"), kPi / 4);
  EXPECT_DOUBLE_EQ(summary.at(1, "d"), 3 * kPi / 8);
  EXPECT_DOUBLE_EQ(summary.at(2, "d"), kPi / 2);
}

TEST(ValueExpressions, MistakesAreLocatedUsageErrors) {
  ScratchDir dir("values-bad");
  const fs::path model = dir.path() / "pendulum.yaml", csv = dir.path() / "out.csv";
  spit(model, kPendulumEndingAtD);
  const RunResult cut = run_lagrange(
      dir.path(), {"simulate", model.string(), "--initial", "theta=pi/", "-o", csv.string()});
  EXPECT_EQ(cut.exit_code, 2);
  EXPECT_NE(cut.err.find("--initial: expected a finite number after 'theta=', got 'pi/': "),
            std::string::npos)
      << cut.err;
  EXPECT_NE(cut.err.find("at character 4"), std::string::npos) << cut.err;
  const RunResult unknown = run_lagrange(
      dir.path(), {"simulate", model.string(), "--initial", "theta=len", "-o", csv.string()});
  EXPECT_EQ(unknown.exit_code, 2);
  EXPECT_NE(
      unknown.err.find("unknown name 'len' at character 1 of 'len' (names here: pi, d, g, l, m)"),
      std::string::npos)
      << unknown.err;
  const RunResult set_name = run_lagrange(dir.path(), {"check", model.string(), "--set", "d=l"});
  EXPECT_EQ(set_name.exit_code, 2);
  EXPECT_NE(set_name.err.find("no names"), std::string::npos) << set_name.err;
  EXPECT_FALSE(fs::exists(csv));
}

}  // namespace
}  // namespace lagrange::hardening

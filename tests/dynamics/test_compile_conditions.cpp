// A model's stop_when, fail_when and warn_when are compiled once, with the model (src/dynamics/
// compile_conditions.cpp): a bad name fails compile() itself, and a run's StopConditions only
// evaluates the tapes (no symbolic code per run, so runs on several threads share nothing
// mutable).
#include <gtest/gtest.h>

#include <cmath>

#include "lagrange/error.hpp"
#include "lagrange/stop_conditions.hpp"
#include "support/harness.hpp"

namespace lagrange {
namespace {

const char* kPendulum =
    "name: pendulum\nparameters: {m: 1.0, l: 2.0, g: 9.81}\n"
    "coordinates: {theta: {initial: 0.5}}\n"
    "points: {bob: [l*sin(theta), -l*cos(theta), 0]}\nparticles: {bob: m}\n"
    "gravity: [0, -g, 0]\n";

// g_i = rhs − lhs for `<`, lhs − rhs for `>`, over the row's columns and the parameters.
TEST(CompileConditions, EachKindIsATapeOverTheRowAndTheParameters) {
  testing::Loaded sys = testing::load_string(
      std::string(kPendulum) + "stop_when: {bottom: theta < 0, high: 2*theta_dot > l}\n");
  const CompiledModel& cm = *sys.compiled;
  ASSERT_EQ(cm.stop_tape.num_outputs(), 2u);
  EXPECT_EQ(cm.fail_tape.num_outputs(), 0u);
  EXPECT_EQ(cm.stop_tape.num_inputs(), trajectory_columns(cm).size() + cm.np);

  const std::vector<std::string> columns = trajectory_columns(cm);
  std::vector<double> row(columns.size(), 0.0);
  const auto column = [&](const char* name) {
    return static_cast<size_t>(std::find(columns.begin(), columns.end(), name) - columns.begin());
  };
  row[column("theta")] = 0.3;
  row[column("theta_dot")] = 1.5;
  const std::vector<double> parameters{1.0, 2.0, 9.81};  // m, l, g as declared
  ASSERT_EQ(cm.parameter_names, (std::vector<std::string>{"m", "l", "g"}));
  const StopConditions stop(cm);
  ASSERT_EQ(stop.size(), 2u);
  EXPECT_EQ(stop.spec(1).name, "high");
  double g[2];
  stop.evaluate(row.data(), parameters.data(), g);
  EXPECT_DOUBLE_EQ(g[0], -0.3);           // 0 − θ
  EXPECT_DOUBLE_EQ(g[1], 2 * 1.5 - 2.0);  // 2 θ̇ − l
  EXPECT_TRUE(StopConditions(cm, StopConditions::Kind::Fail).empty());
}

// An unknown name is the model's error at the condition's line, raised when the model is
// compiled: before any run, and never again by one.
TEST(CompileConditions, AnUnknownNameFailsTheCompilation) {
  auto model = std::make_unique<Model>(
      read_model_string(std::string(kPendulum) + "stop_when: {bad: thet < 0}\n", "<test>"));
  const Equations eq = derive(*model);
  try {
    compile(eq);
    ADD_FAILURE() << "expected a ModelError";
  } catch (const ModelError& e) {
    EXPECT_EQ(e.loc().line, 7);  // stop_when:
    EXPECT_NE(std::string(e.what()).find("thet"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace lagrange

// The optimal_control section's mistakes, each a located error before anything runs.

#include <gtest/gtest.h>

#include <string>

#include "lagrange/reader.hpp"

namespace lagrange {
namespace {

const std::string kModel = R"(name: di
coordinates:
  x: {initial: 0}
inputs:
  u: 0
kinetic: der(x)^2/2
generalized_forces: {x: u}
optimal_control:
)";

/// The error message of reading kModel followed by `section` (the optimal_control body).
std::string error_of(const std::string& section) {
  try {
    read_model_string(kModel + section, "di.yaml");
  } catch (const ModelError& e) {
    return e.what();
  }
  return "no error";
}

TEST(OptimalControlErrors, AreLocatedAndSayWhatWasExpected) {
  const std::string ok = "  horizon: 1\n  minimize: integral(u^2)\n";
  // An unknown control: line 10, column 3.
  EXPECT_NE(error_of("  controls: {v: {}}\n" + ok)
                .find("di.yaml:9:14: error: expected an input of the model as a control, got 'v'"),
            std::string::npos)
      << error_of("  controls: {v: {}}\n" + ok);
  // A lower bound above the upper one.
  const std::string bad_bounds = error_of("  controls: {u: {lower: 2, upper: 1}}\n" + ok);
  EXPECT_NE(bad_bounds.find("di.yaml:9:"), std::string::npos) << bad_bounds;
  EXPECT_NE(bad_bounds.find("lower bound of control 'u' at most its upper bound 1, got 2"),
            std::string::npos)
      << bad_bounds;
  // A horizon ≤ 0.
  const std::string horizon =
      error_of("  controls: {u: {}}\n  horizon: -1\n  minimize: integral(u^2)\n");
  EXPECT_NE(horizon.find("di.yaml:10:12: error: expected a horizon > 0, got -1"), std::string::npos)
      << horizon;
  // A boundary value for a coordinate that does not exist.
  const std::string final = error_of("  controls: {u: {}}\n" + ok + "  final: {z: 1}\n");
  EXPECT_NE(final.find("di.yaml:12:11: error: expected a coordinate or its rate NAME_dot for a "
                       "final value, got 'z'"),
            std::string::npos)
      << final;
  // An unknown name inside integral(…), located at its column.
  const std::string unknown =
      error_of("  controls: {u: {}}\n  horizon: 1\n  minimize: integral(w^2)\n");
  EXPECT_NE(unknown.find("di.yaml:11:22:"), std::string::npos) << unknown;
  EXPECT_NE(unknown.find("'w'"), std::string::npos) << unknown;
  // An integral used nonlinearly.
  const std::string nonlinear =
      error_of("  controls: {u: {}}\n  horizon: 1\n  minimize: integral(u^2)^2\n");
  EXPECT_NE(nonlinear.find("constant factors"), std::string::npos) << nonlinear;
  // Both minimize and maximize; a free horizon with lower ≤ 0.
  EXPECT_NE(error_of("  controls: {u: {}}\n" + ok + "  maximize: t\n").find("got both"),
            std::string::npos);
  EXPECT_NE(error_of("  controls: {u: {}}\n  horizon: {lower: 0, upper: 2}\n  minimize: t\n")
                .find("0 < lower <= upper < inf"),
            std::string::npos);
  // A misspelt key lists the valid ones.
  EXPECT_NE(error_of("  controls: {u: {}}\n" + ok + "  intervalls: 3\n").find("intervals"),
            std::string::npos);
}

// stages: a list of changes to the problem, each read and located like the problem's own keys.
TEST(OptimalControlErrors, HomotopyStagesAreCheckedWhereWritten) {
  const std::string ok =
      "  controls: {u: {lower: -5, upper: 5}}\n  horizon: 1\n  minimize: "
      "integral(u^2)\n  stages:\n";
  const Model m = read_model_string(
      kModel + ok +
          "    - {name: loose, controls: {u: 0.5}, maximize: x, track: 2, ipopt: {tol: 1e-4}}\n",
      "di.yaml");
  ASSERT_EQ(m.optimal_control->stages.size(), 1u);
  const StageSpec& s = m.optimal_control->stages[0];
  EXPECT_TRUE(s.replaces_objective && s.maximize);
  EXPECT_TRUE((s.terminal - m.coordinates[0].q).is_zero());
  ASSERT_EQ(s.control_bounds.size(), 1u);
  EXPECT_EQ(s.control_bounds[0].second.lower, 0.5);  // a number fixes the control
  EXPECT_EQ(s.control_bounds[0].second.upper, 0.5);
  EXPECT_EQ(s.track, 2.0);
  ASSERT_EQ(s.ipopt.size(), 1u);
  EXPECT_EQ(s.ipopt[0].second, "1e-4");
  const std::string unknown = error_of(ok + "    - {name: a, controls: {v: 1}}\n");
  EXPECT_NE(unknown.find("di.yaml:13:28: error: expected a control of the problem in stage 'a', "
                         "got 'v' (controls: u)"),
            std::string::npos)
      << unknown;
  const std::string negative = error_of(ok + "    - {name: a, track: -1}\n");
  EXPECT_NE(negative.find("di.yaml:13:24: error: expected track >= 0 in stage 'a'"),
            std::string::npos)
      << negative;
  const std::string twice = error_of(ok + "    - {name: a, track: 1}\n    - {name: a, track: 2}\n");
  EXPECT_NE(twice.find("di.yaml:14:14: error: expected stage names used once, got 'a' twice (the "
                       "first at di.yaml:13:7)"),
            std::string::npos)
      << twice;
  const std::string idle = error_of(ok + "    - {name: a}\n");
  EXPECT_NE(idle.find("di.yaml:13:7: error: expected stage 'a' to change the problem"),
            std::string::npos)
      << idle;
  const std::string key = error_of(ok + "    - {name: a, trak: 1}\n");
  EXPECT_NE(key.find("track"), std::string::npos) << key;
  const std::string held = error_of(ok + "    - {name: a, horizon: 2}\n");
  EXPECT_NE(held.find("di.yaml:13:26: error: expected the horizon of stage 'a' only with a free "
                      "horizon in the problem (horizon: {lower, upper}), got a fixed T = 1"),
            std::string::npos)
      << held;
  const std::string nameless = error_of(ok + "    - {track: 1}\n");
  EXPECT_NE(nameless.find("expected 'name' in a stage"), std::string::npos) << nameless;
}

// mean(M) is (1/T) ∫ M: its own term, whatever the horizon (docs/theory.md §10).
TEST(OptimalControlErrors, MeanTermsAreTheirOwnIntegrand) {
  const Model m = read_model_string(
      kModel + "  controls: {u: {}}\n  horizon: 2\n  minimize: integral(x) + 4*mean(u^2) - x\n",
      "di.yaml");
  const GiNaC::symbol& x = m.coordinates[0].q;
  const GiNaC::symbol& u = m.inputs[0].u;
  EXPECT_TRUE((m.optimal_control->integrand - x).expand().is_zero());
  EXPECT_TRUE((m.optimal_control->mean_integrand - 4 * u * u).expand().is_zero());
  EXPECT_TRUE((m.optimal_control->terminal + x).expand().is_zero());
  EXPECT_NE(error_of("  controls: {u: {}}\n  horizon: 1\n  minimize: mean(u^2)^2\n")
                .find("constant factors"),
            std::string::npos);
}

TEST(OptimalControlErrors, ObjectiveSplitsIntoIntegrandAndTerminalTerms) {
  const Model m = read_model_string(
      kModel +
          "  controls: {u: {}}\n  horizon: 1\n  minimize: 3*integral(u^2) - integral(x) + x^2\n",
      "di.yaml");
  ASSERT_TRUE(m.optimal_control.has_value());
  const GiNaC::symbol& x = m.coordinates[0].q;
  const GiNaC::symbol& u = m.inputs[0].u;
  EXPECT_TRUE((m.optimal_control->integrand - (3 * u * u - x)).expand().is_zero());
  EXPECT_TRUE((m.optimal_control->terminal - x * x).expand().is_zero());
}

// Each integral(…) is renamed to a placeholder no longer than the text it replaces, for any count
// (a longer one underflowed the padding from the 101st term on).
TEST(OptimalControlErrors, TwoHundredIntegralTermsSum) {
  std::string objective = "integral(x)";
  for (int k = 1; k < 200; ++k) objective += "+integral(x)";
  const Model m = read_model_string(
      kModel + "  controls: {u: {}}\n  horizon: 1\n  minimize: " + objective + "\n", "di.yaml");
  ASSERT_TRUE(m.optimal_control.has_value());
  const GiNaC::symbol& x = m.coordinates[0].q;
  EXPECT_TRUE((m.optimal_control->integrand - 200 * x).expand().is_zero());
}

// guess: a map of paths in t; a rate there is refused, saying it follows its coordinate.
TEST(OptimalControlErrors, AGuessedPathIsACoordinateInT) {
  const std::string ok = "  controls: {u: {}}\n  horizon: 1\n  minimize: integral(u^2)\n";
  const Model m = read_model_string(kModel + ok + "  guess: {x: sin(t)}\n", "di.yaml");
  ASSERT_EQ(m.optimal_control->guess_paths.size(), 1u);
  EXPECT_EQ(m.optimal_control->guess_paths[0].first.coordinate, 0u);
  const std::string rate = error_of(ok + "  guess: {x_dot: 1}\n");
  EXPECT_NE(rate.find("di.yaml:12:11: error: expected a coordinate in guess, got the rate 'x_dot'"),
            std::string::npos)
      << rate;
  const std::string periodic = error_of(ok + "  periodic: [z]\n");
  EXPECT_NE(periodic.find("di.yaml:12:14: error: expected a coordinate or its rate NAME_dot for a "
                          "periodic component, got 'z'"),
            std::string::npos)
      << periodic;
  const Model p = read_model_string(kModel + ok + "  periodic: true\n", "di.yaml");
  EXPECT_EQ(p.optimal_control->periodic.size(), 2u);    // x and x_dot
  ASSERT_TRUE(p.optimal_control->initial.has_value());  // free: the orbit starts where it ends
  EXPECT_TRUE(p.optimal_control->initial->empty());
  const std::string missing = error_of(ok + "  guess: nowhere.csv\n");
  EXPECT_NE(missing.find("di.yaml:12:10: error: expected a trajectory CSV for guess, cannot open"),
            std::string::npos)
      << missing;
  const std::string word = error_of(ok + "  guess: straight\n");
  EXPECT_NE(word.find("expected guess linear, simulation, a FILE.csv or a map"), std::string::npos)
      << word;
}

// Periodicity on a coordinate that moves one way only (a reel that only reels out) cannot hold:
// said at the periodic entry, not left to Ipopt's "infeasible".
TEST(OptimalControlErrors, APeriodicCoordinateThatCannotReturnIsRefused) {
  const std::string ok = "  controls: {u: {}}\n  horizon: 1\n  minimize: integral(u^2)\n";
  const std::string one_way =
      error_of(ok + "  bounds: {x_dot: {lower: 0.5}}\n  periodic: [x, x_dot]\n");
  EXPECT_NE(one_way.find("di.yaml:13:14: error: expected periodic coordinates that can return to "
                         "their start, got 'x', whose rate is bounded to [0.5, inf] (it only "
                         "grows)"),
            std::string::npos)
      << one_way;
  // A rate that may change sign, or periodicity of the rate alone, is fine.
  EXPECT_EQ(error_of(ok + "  bounds: {x_dot: {lower: -1, upper: 2}}\n  periodic: [x]\n"),
            "no error");
  EXPECT_EQ(error_of(ok + "  bounds: {x_dot: {lower: 0.5}}\n  periodic: [x_dot]\n"), "no error");
}

// `constant: true` with `polynomial: true` is refused, located at the polynomial key.
TEST(PolynomialControls, ConstantAndPolynomialTogetherIsALocatedError) {
  const std::string message = error_of(
      "  controls:\n    u: {constant: true, polynomial: true}\n  horizon: 1\n"
      "  minimize: integral(u^2)\n");
  EXPECT_NE(message.find("di.yaml:10:37: error: expected either constant: true or polynomial: "
                         "true for control 'u', not both"),
            std::string::npos)
      << message;
}

}  // namespace
}  // namespace lagrange

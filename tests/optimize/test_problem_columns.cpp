// The trajectory's columns beyond the state in the problem (docs/model-language.md, "Optimal
// control"): a constraint's multiplier by its name, an element's reaction (a tether's tension)
// and outputs, in the objective and the path constraints.

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <iterator>
#include <string>

#include "lagrange/reader.hpp"
#include "optimize/optimal_problem.hpp"

namespace lagrange {
namespace {

/// The largest value of column `name` of a result's trajectory.
double largest(const OptimizeResult& r, const std::string& name) {
  const Trajectory& t = r.trajectory;
  const auto it = std::find(t.columns.begin(), t.columns.end(), name);
  EXPECT_NE(it, t.columns.end()) << name;
  const size_t c = static_cast<size_t>(it - t.columns.begin()), n = t.columns.size();
  double most = -1e300;
  for (size_t row = 1; row < t.rows(); ++row) most = std::max(most, t.data[row * n + c]);
  return most;  // row 0 (t = 0) has no collocated multiplier: the forward dynamics' is written
}

// The swing-up with the rod's pull held below 38 N (it peaks at 41.9 N without the bound), three
// ways: the multiplier by the constraint's name (λ l), the tension written from the state (the
// radial balance m|v|²/l − m g y/l + F x/l), and a rigid tether's tension column. The same
// optimum (to the collocation's error for the state's version), above the unbounded one, with the
// bound active and held at every collocation point.
TEST(ProblemColumns, ATensionBoundIsTheSameThroughTheMultiplierTheStateAndATether) {
  testing::OptimalProblem free_pull("pendulum_swing_up_cartesian.yaml");
  const OptimizeResult unbounded = free_pull.solve();
  ASSERT_TRUE(unbounded.optimal) << unbounded.status;
  EXPECT_NEAR(largest(unbounded, "lambda_rod"), 41.88, 0.01);

  testing::OptimalProblem rod("data/pendulum_pull_multiplier.yaml");
  testing::OptimalProblem state("data/pendulum_pull_state.yaml");
  testing::OptimalProblem tether("data/tether_swing_up.yaml");
  const OptimizeResult a = rod.solve(), b = state.solve(), c = tether.solve();
  ASSERT_TRUE(a.optimal && b.optimal && c.optimal) << a.status << b.status << c.status;
  EXPECT_GT(a.objective, unbounded.objective + 1.0);
  // The tether is the rod (its mass 1e-12 kg): the same NLP.
  EXPECT_NEAR(c.objective, a.objective, 1e-6 * a.objective);
  EXPECT_NEAR(largest(a, "lambda_rod"), 38.0, 1e-5);  // l = 1: λ is the pull
  EXPECT_NEAR(largest(c, "lambda_line.segment1"), 38.0, 1e-5);
  // The radial balance holds for the exact motion; on the collocated one it differs from the
  // collocated λ by the discretisation error (measured 2.5e-5 of the cost, 0.013 N of the pull).
  EXPECT_NEAR(b.objective, a.objective, 1e-4 * a.objective);
  EXPECT_NEAR(largest(b, "lambda_rod"), 38.0, 0.05);
}

// A load column needs the accelerations, which a point of the problem does not have: refused,
// located, naming what stands in for it.
TEST(ProblemColumns, ALoadIsRefusedWithWhatStandsInForIt) {
  std::string text;
  {
    std::ifstream in(testing::path("data/tether_swing_up.yaml"));
    text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  const std::string from = "expression: line.tension_1";
  text.replace(text.find(from), from.size(), "expression: line.load_ground");
  try {
    read_model_string(text, "tether.yaml");
    FAIL() << "a load was taken in a path constraint";
  } catch (const ModelError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("tether.yaml:26:"), std::string::npos) << what;
    EXPECT_NE(what.find("the load 'line.load_ground' (it needs the accelerations"),
              std::string::npos)
        << what;
  }
}

}  // namespace
}  // namespace lagrange

// Tape::specialize: constant folding on the tape equals evaluating with the fixed inputs.

#include <gtest/gtest.h>

#include <cmath>

#include "compile/pendulum_expressions.hpp"
#include "compile/run_tape.hpp"
#include "lagrange/tape.hpp"

namespace lagrange {
namespace {

/// Evaluates every output of t at x.

TEST(TapeSpecialize, PendulumParametersFoldAway) {
  const int n = 8;
  const test::Pendulum p = test::make_pendulum(n);
  const Tape full = Tape::compile(p.outputs, p.inputs);
  const std::vector<double> point = test::pendulum_point(n, 7);
  const std::vector<double> params(point.begin() + p.first_parameter, point.end());
  const Tape fixed = full.specialize(p.first_parameter, params);
  EXPECT_EQ(fixed.num_inputs(), full.num_inputs());
  // Parameter Inputs and the Σmₖ sums fold away; fused SumProds remain but lose factors.
  EXPECT_LT(fixed.num_instructions() + 2 * n, full.num_instructions())
      << fixed.num_instructions() << " vs " << full.num_instructions();
  EXPECT_LT(fixed.work_size(), full.work_size());
  for (unsigned seed = 0; seed < 10; ++seed) {
    std::vector<double> x = test::pendulum_point(n, seed);
    std::copy(params.begin(), params.end(), x.begin() + p.first_parameter);
    const std::vector<double> want = run(full, x);
    // Fixed inputs are ignored: scramble them.
    std::vector<double> y = x;
    for (size_t i = p.first_parameter; i < y.size(); ++i) y[i] = -123.0;
    const std::vector<double> got = run(fixed, y);
    for (size_t i = 0; i < want.size(); ++i) {
      EXPECT_NEAR(got[i], want[i], 1e-15 * 64 * std::max(1.0, std::fabs(want[i]))) << i;
    }
  }
}

TEST(TapeSpecialize, AllInputsFixedGivesConstants) {
  GiNaC::symbol x("x"), y("y");
  const Tape t = Tape::compile({sin(x) * y + pow(x, 3), atan2(y, x), x / y}, {x, y});
  const Tape c = t.specialize(0, {0.4, -1.3});
  EXPECT_EQ(c.num_instructions(), 3u);  // three Const
  EXPECT_EQ(run(c, {9.0, 9.0}), run(t, {0.4, -1.3}));
}

TEST(TapeSpecialize, FoldsUnaryChainsAndKeepsOthers) {
  GiNaC::symbol a("a"), b("b");
  const GiNaC::ex e = exp(cos(a) * 2) * b + sqrt(a) * b * b;
  const Tape t = Tape::compile({e}, {a, b});
  const Tape s = t.specialize(0, {0.81});
  EXPECT_LT(s.num_instructions(), t.num_instructions());
  const std::vector<double> want = run(t, {0.81, 1.7});
  const std::vector<double> got = run(s, {0.0, 1.7});
  EXPECT_NEAR(got[0], want[0], 1e-15 * std::fabs(want[0]));
}

TEST(TapeSpecialize, RangeIsChecked) {
  GiNaC::symbol a("a");
  const Tape t = Tape::compile({a}, {a});
  EXPECT_THROW(t.specialize(1, {1.0}), std::invalid_argument);
  EXPECT_NO_THROW(t.specialize(1, {}));
}

}  // namespace
}  // namespace lagrange

// collect_common_factors: Σ mₖ·X → X·Σ mₖ (docs/theory.md §8), value unchanged.

#include "compile/collect_factors.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "compile/pendulum_expressions.hpp"

namespace lagrange {
namespace {

using GiNaC::ex;
using GiNaC::symbol;

/// e at the given substitution, as a double.
double at(const ex& e, const GiNaC::exmap& m) {
  return GiNaC::ex_to<GiNaC::numeric>(e.subs(m).evalf()).to_double();
}

TEST(CollectCommonFactors, PullsSharedFactorOutOfSum) {
  symbol m1("m1"), m2("m2"), m3("m3"), l("l"), th("th");
  const ex x = l * l * cos(th);
  const ex e = m1 * x + 2 * m2 * x - m3 * x;
  const ex got = lagrange::collect_common_factors(e);
  EXPECT_TRUE(got.is_equal(x * (m1 + 2 * m2 - m3))) << got;
  const GiNaC::exmap at_point = {{m1, 1.5}, {m2, 0.25}, {m3, 2.0}, {l, 0.7}, {th, 0.3}};
  EXPECT_NEAR(at(got, at_point), at(e, at_point), 1e-15);
}

TEST(CollectCommonFactors, KeepsOtherTermsAndConstant) {
  symbol m1("m1"), m2("m2"), a("a"), th("th");
  const ex e = m1 * sin(th) + m2 * sin(th) + a * cos(th) + 3;
  const ex got = lagrange::collect_common_factors(e);
  EXPECT_TRUE(got.is_equal(sin(th) * (m1 + m2) + a * cos(th) + 3)) << got;
}

TEST(CollectCommonFactors, LeavesSumWithoutCommonFactorAlone) {
  symbol a("a"), b("b"), c("c");
  const ex e = a * sin(b) + b * cos(c) + c;
  EXPECT_TRUE(lagrange::collect_common_factors(e).is_equal(e));
}

TEST(CollectCommonFactors, RewritesNestedSums) {
  symbol m1("m1"), m2("m2"), x("x");
  const ex inner = m1 * exp(x) + m2 * exp(x);
  const ex e = sin(inner) * x;
  EXPECT_TRUE(lagrange::collect_common_factors(e).is_equal(sin(exp(x) * (m1 + m2)) * x));
}

TEST(CollectCommonFactors, PendulumMassMatrixHasOneTermPerTrigProduct) {
  const test::Pendulum p = test::make_pendulum(4);
  tape_detail::CanonicalOrder order(p.inputs);
  const std::vector<ex> got = lagrange::collect_common_factors(p.outputs, order);
  // M₀₀ = Σₖ mₖ l₀² (cos²θ₀ + sin²θ₀) → two terms l₀²cos²θ₀·Σmₖ + l₀²sin²θ₀·Σmₖ.
  ASSERT_TRUE(GiNaC::is_a<GiNaC::add>(got[0])) << got[0];
  EXPECT_EQ(got[0].nops(), 2u) << got[0];
  GiNaC::exmap m;
  const std::vector<double> x = test::pendulum_point(4, 3);
  for (size_t i = 0; i < p.inputs.size(); ++i) m[p.inputs[i]] = x[i];
  for (size_t i = 0; i < got.size(); ++i) {
    const double want = at(p.outputs[i], m);
    EXPECT_NEAR(at(got[i], m), want, 1e-14 * std::max(1.0, std::fabs(want))) << i;
  }
}

}  // namespace
}  // namespace lagrange

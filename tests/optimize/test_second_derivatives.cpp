// Second derivatives compiled from GiNaC's symbolic ones (src/optimize/second_derivatives.cpp):
// GiNaC differentiates |x| through conjugate(x), and its second derivative holds the formal
// D[0](conjugate)(x), which for real values is 1. Compiled as conjugate itself it made
// d²|x|/dx² = 1/|x| instead of 0, and with it the exact Hessian of every model whose equations
// hold a max or min (the logarithmic and power-law winds) wrong.

#include <gtest/gtest.h>

#include <cmath>

#include "optimize/second_derivatives.hpp"

namespace lagrange {
namespace {

TEST(SecondDerivatives, OfAbsAndOfAWindsLogarithmicProfileMatchTheirClosedForms) {
  const GiNaC::symbol z("z"), w("w");
  const GiNaC::ex above = (z + 1 + GiNaC::abs(z - 1)) / 2;  // max(z, 1), as the wind writes it
  // w (|z − 3| + log max(z, 1)): ∂²/∂z² = w (0 − 1/z²) for z > 1, ∂²/∂z∂w = sign(z − 3) + 1/z.
  const GiNaC::ex s = w * (GiNaC::abs(z - 3) + GiNaC::log(above));
  const collocation::SecondDerivatives h(s, {z, w}, {0, 1});
  std::vector<double> out;
  for (const double at : {2.0, 5.0}) {
    h.eval({at, 0.7}, out);
    ASSERT_EQ(h.pattern().size(), out.size());
    for (size_t e = 0; e < out.size(); ++e) {
      const auto [a, b] = h.pattern()[e];
      const double expected = a == 0 && b == 0 ? -0.7 / (at * at)
                              : a == 1 && b == 0 ? (at > 3 ? 1.0 : -1.0) + 1 / at
                                                 : 0.0;
      EXPECT_NEAR(out[e], expected, 1e-14) << "(" << a << ", " << b << ") at z = " << at;
    }
  }
}

}  // namespace
}  // namespace lagrange

// Second derivatives compiled from GiNaC's symbolic ones (src/optimize/second_derivatives.cpp):
// GiNaC differentiates |x| through conjugate(x), and its second derivative holds the formal
// D[0](conjugate)(x), which for real values is 1. Compiled as conjugate itself it made
// d²|x|/dx² = 1/|x| instead of 0, and with it the exact Hessian of every model whose equations
// hold a max or min (the logarithmic and power-law winds) wrong.

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "optimize/second_derivatives.hpp"
#include "support/test_paths.hpp"

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
      const double expected = a == 0 && b == 0   ? -0.7 / (at * at)
                              : a == 1 && b == 0 ? (at > 3 ? 1.0 : -1.0) + 1 / at
                                                 : 0.0;
      EXPECT_NEAR(out[e], expected, 1e-14) << "(" << a << ", " << b << ") at z = " << at;
    }
  }
}

// The optimiser's costliest tape runs on machine code (docs/theory.md §8): the library computes
// the interpreter's bits, so switching to it in the middle of a solve changes no iterate; without
// a compiler the interpreter runs and the note says why.
TEST(SecondDerivatives, OnMachineCodeGiveTheInterpretersBitsAndSayWhichRan) {
  const GiNaC::symbol x("x"), y("y"), w("w");
  // Enough work for a compiled library to differ if it rounded differently (no contraction).
  const GiNaC::ex s =
      w * (GiNaC::sin(x * y) * GiNaC::exp(x - y) + GiNaC::pow(x, 3) * y / (1 + y * y) +
           GiNaC::sqrt(1 + x * x) * GiNaC::atan2(y, x));
  const collocation::SecondDerivatives interpreted(s, {x, y, w}, {0, 1});
  collocation::SecondDerivatives compiled(s, {x, y, w}, {0, 1});
  MachineCodeOptions options;
  options.cache_dir = LAGRANGE_TEST_CACHE;
  compiled.use_machine_code(Evaluation::MachineCode, options);
  EXPECT_EQ(compiled.evaluation_note().rfind("machine code", 0), 0u) << compiled.evaluation_note();
  EXPECT_EQ(interpreted.evaluation_note(), "interpreter");
  std::vector<double> a, b;
  for (const double at : {0.3, -1.7, 2.9}) {
    interpreted.eval({at, 0.5 - at, 1.3}, a);
    compiled.eval({at, 0.5 - at, 1.3}, b);
    ASSERT_EQ(a.size(), 3u);  // xx, yx, yy
    ASSERT_EQ(a.size(), b.size());
    EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(double)), 0) << "at x = " << at;
  }

  collocation::SecondDerivatives without(s, {x, y, w}, {0, 1});
  options.compiler = "/nonexistent/cc";
  without.use_machine_code(Evaluation::MachineCode, options);
  EXPECT_NE(without.evaluation_note().find("interpreter (machine code: "), std::string::npos)
      << without.evaluation_note();
  without.eval({0.3, 0.2, 1.3}, b);
  interpreted.eval({0.3, 0.2, 1.3}, a);
  EXPECT_EQ(a, b);
}

}  // namespace
}  // namespace lagrange

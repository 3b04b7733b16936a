// The printers' tidying (src/io/equation_text.cpp) does only bounded algebra: a short sum of
// fractions whose common denominator has millions of terms is printed as derived, at once,
// while small expressions still get their shortest form.
#include <gtest/gtest.h>

#include <string>

#include "io/equation_text.hpp"
#include "lagrange/io.hpp"
#include "lagrange/reader.hpp"
#include "support/harness.hpp"
#include "symbolic/expansion_bound.hpp"

namespace lagrange::io {
namespace {

// Σ 1/(xᵢ + yᵢ), i < n: n terms, a normal form of n · 2ⁿ⁻¹.
GiNaC::ex fractions(int n) {
  GiNaC::ex sum = 0;
  for (int i = 0; i < n; ++i)
    sum += 1 / (GiNaC::symbol("x" + std::to_string(i)) + GiNaC::symbol("y" + std::to_string(i)));
  return sum;
}

// The bound: e's terms times every denominator's terms (Σ of n fractions: n · 2ⁿ, twice the
// n · 2ⁿ⁻¹ terms of the true numerator, an upper bound as it must be).
TEST(NormalizesWithin, BoundsTheCommonDenominator) {
  EXPECT_TRUE(symbolic::normalizes_within(fractions(2), 8));
  EXPECT_FALSE(symbolic::normalizes_within(fractions(2), 7));
  EXPECT_TRUE(symbolic::normalizes_within(fractions(5), 5 * 32));
  EXPECT_FALSE(symbolic::normalizes_within(fractions(20), 400));
  EXPECT_TRUE(symbolic::normalizes_within(GiNaC::symbol("b") / 2, 1));  // numbers are not sums
  const GiNaC::symbol a("a");
  EXPECT_FALSE(symbolic::normalizes_within(GiNaC::sin(fractions(20)) + a, 400));  // inside too
}

// Without the bound, simplify() puts the 20 fractions over one denominator: 10 million terms,
// which does not finish. The text is the sum as derived.
TEST(EquationText, AShortSumOfManyFractionsIsPrintedAsDerived) {
  const std::string text = str(fractions(20), Style::Text);
  size_t denominators = 0;
  for (size_t at = text.find("^(-1)"); at != std::string::npos; at = text.find("^(-1)", at + 1))
    ++denominators;
  EXPECT_EQ(denominators, 20u) << text;
}

// sin² + cos² = 1 still shortens what is small enough.
TEST(EquationText, SmallExpressionsStillGetTheirShortestForm) {
  const GiNaC::symbol th("theta"), l("l");
  EXPECT_EQ(str(l * GiNaC::pow(GiNaC::sin(th), 2) + l * GiNaC::pow(GiNaC::cos(th), 2), Style::Text),
            "l");
}

// An element's equation names in LaTeX as the model's symbols are (issue 36 item 12): the
// winch's T_drum and Q_drum.reeled_out with the whole subscript braced, not `T_drum`, which
// renders as T_d rum.
TEST(EquationText, ElementEquationNamesAreLatex) {
  const Model model = read_model_file(testing::example_path("winch.yaml"));
  const std::string tex = format_equations(derive(model), "latex");
  EXPECT_NE(tex.find("T_{\\mathrm{drum}} &="), std::string::npos) << tex;
  EXPECT_EQ(tex.find("T_drum"), std::string::npos) << tex;
  // The winch's generated coordinate drum.reeled_out is one upright name, its _ no subscript.
  EXPECT_NE(tex.find("\\mathrm{drum.reeled\\_out}"), std::string::npos) << tex;
  EXPECT_EQ(tex.find("\\mathrm{drum.reeled}_"), std::string::npos) << tex;
  EXPECT_NE(format_equations(derive(model), "text").find("T_drum = "), std::string::npos);
}

}  // namespace
}  // namespace lagrange::io

// Kinks in the optimiser (docs/theory.md §10, "Kinks"): where the NLP's point sits exactly on the
// kink of |x|, the tape's derivative of |x| is 0/0; the optimiser takes the one-sided derivatives
// there, in the dynamics' Jacobian, the point functions' gradients and the Hessian.

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "lagrange/reader.hpp"
#include "optimize/optimal_problem.hpp"
#include "support/file_text.hpp"

namespace lagrange {
namespace {

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  for (size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size()))
    text.replace(at, from.size(), to);
  return text;
}

// The periodic end state x(T) = x(0) = 0 lies on the kink of the force u − k|x| (and, in the
// second problem, of the integrand |x|): Ipopt stopped there at its first iteration on the NaN.
// The one-sided derivatives reach the optimum of the same problem with |x| written as
// √(x² + 10⁻²⁰), differentiable everywhere.
TEST(Kinks, AnEndStateOnTheKinkOfAbsSolvesAsItsSmoothedTwin) {
  const std::string file = test::slurp(testing::path("data/periodic_through_a_kink.yaml"));
  for (const std::string objective : {"integral(u^2)", "integral(u^2 + abs(x))"}) {
    const std::string kinked = replaced(file, "integral(u^2)", objective);
    testing::OptimalProblem kink(read_model_string(kinked, "kink.yaml"));
    const OptimizeResult r = kink.solve();
    ASSERT_TRUE(r.optimal) << objective << ": " << r.status;
    const std::vector<double> x = testing::column(r.trajectory, "x");
    EXPECT_EQ(x.front(), 0.0);
    EXPECT_LT(std::fabs(x.back()), 1e-8) << "the end state is on the kink";
    testing::OptimalProblem smooth(
        read_model_string(replaced(kinked, "abs(x)", "sqrt(x^2 + 1e-20)"), "smooth.yaml"));
    const OptimizeResult s = smooth.solve();
    ASSERT_TRUE(s.optimal) << s.status;
    EXPECT_NEAR(r.objective, s.objective, 1e-9 * s.objective) << objective;
  }
}

}  // namespace
}  // namespace lagrange

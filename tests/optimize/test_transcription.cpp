// The transcription's pieces: Radau IIA coefficients, and the NLP's exact derivatives against
// central differences on every example problem (docs/theory.md §10).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "optimize/nlp_derivative_check.hpp"
#include "optimize/optimal_problem.hpp"
#include "optimize/radau.hpp"
#include "optimize/transcription.hpp"

namespace lagrange {
namespace {

// x'(τ_j) exact for polynomials of degree ≤ d, quadrature exact to degree 2d − 2 (order 2d − 1).
TEST(Radau, DifferentiatesAndIntegratesPolynomialsExactly) {
  for (int d = 1; d <= 5; ++d) {
    const collocation::Radau r = collocation::radau(d);
    EXPECT_DOUBLE_EQ(r.tau.back(), 1.0);
    for (int p = 0; p <= 2 * d - 2; ++p) {
      double s = 0.0;
      for (int j = 1; j <= d; ++j)
        s += r.b[static_cast<size_t>(j - 1)] * std::pow(r.tau[static_cast<size_t>(j)], p);
      EXPECT_NEAR(s, 1.0 / (p + 1), 1e-13) << "d = " << d << ", τ^" << p;
    }
    for (int p = 0; p <= d; ++p)
      for (int j = 1; j <= d; ++j) {
        double s = 0.0;
        for (int l = 0; l <= d; ++l)
          s += r.derivative(j, l) * std::pow(r.tau[static_cast<size_t>(l)], p);
        const double exact = p == 0 ? 0.0 : p * std::pow(r.tau[static_cast<size_t>(j)], p - 1);
        EXPECT_NEAR(s, exact, 1e-11) << "d = " << d << ", τ^" << p << " at point " << j;
      }
  }
  // Radau IIA of degree 2: points 1/3 and 1, weights 3/4 and 1/4 (Hairer & Wanner IV.5).
  const collocation::Radau r2 = collocation::radau(2);
  EXPECT_NEAR(r2.tau[1], 1.0 / 3.0, 1e-15);
  EXPECT_NEAR(r2.b[0], 0.75, 1e-15);
  EXPECT_NEAR(r2.b[1], 0.25, 1e-15);
}

class NlpDerivatives : public ::testing::TestWithParam<std::string> {};

// Constraint Jacobian and objective gradient against central differences at a random point near
// the starting one (every entry, not only the pattern's: an entry missing from the pattern shows).
TEST_P(NlpDerivatives, MatchCentralDifferences) {
  testing::OptimalProblem p(GetParam());
  collocation::Transcription nlp(p.eq, p.cm, *p.dyn, p.spec(), 3, 2, p.cm->q0, p.cm->v0);
  testing::expect_first_derivatives_match(
      nlp, testing::perturbed_guess(nlp, p.spec().free_horizon.has_value(), 7));
}

// The Hessian of the Lagrangian against central differences of its gradient, with random
// multipliers, every entry; with a free horizon its row and column too (T enters
// x' = (1/h) Σ D X nonlinearly).
TEST_P(NlpDerivatives, HessianMatchesDifferencesOfTheLagrangiansGradient) {
  testing::OptimalProblem p(GetParam());
  collocation::Transcription nlp(p.eq, p.cm, *p.dyn, p.spec(), 3, 2, p.cm->q0, p.cm->v0);
  testing::expect_hessian_matches(
      nlp, testing::perturbed_guess(nlp, p.spec().free_horizon.has_value(), 11), 11);
}

INSTANTIATE_TEST_SUITE_P(
    Examples, NlpDerivatives,
    ::testing::Values("double_integrator_min_energy.yaml", "double_integrator_min_time.yaml",
                      "cart_pole_swing_up.yaml", "pendulum_swing_up_polar.yaml",
                      "pendulum_swing_up_cartesian.yaml", "van_der_pol_limit_cycle.yaml",
                      "data/everything.yaml", "data/everything_fixed_horizon.yaml",
                      "data/spring_damper_to_speed.yaml", "attitude_slew.yaml",
                      "data/spin_orbit.yaml", "power_cycle_pointmass.yaml", "power_cycle_ap2.yaml"),
    [](const auto& info) {
      std::string s = info.param.substr(0, info.param.size() - 5);
      for (char& c : s)
        if (c == '.' || c == '/') c = '_';
      return s;
    });

}  // namespace
}  // namespace lagrange

namespace lagrange {
namespace {

// docs/theory.md §10, "Scaling": a variable's nominal magnitude is its largest value in the
// starting point or bounds (the kite's reeled-out length: its 400 m bound), every scaled
// constraint gradient is at most 100 at the starting point, and the scaled problem has the same
// optimum as Ipopt's own scaling.
TEST(NlpScaling, NominalMagnitudesScaleVariablesAndRowsWithoutMovingTheOptimum) {
  testing::OptimalProblem kite("power_cycle_pointmass.yaml");
  collocation::Transcription nlp(kite.eq, kite.cm, *kite.dyn, kite.spec(), 8, 3, kite.cm->q0,
                                 kite.cm->v0, HessianChoice::LimitedMemory);
  std::vector<double> xs(nlp.variables()), gs(nlp.constraints());
  double fs = 0.0;
  nlp.scaling(xs.data(), gs.data(), fs);
  const auto& names = kite.cm->coordinate_names;
  const size_t l =
      static_cast<size_t>(std::find(names.begin(), names.end(), "drum.reeled_out") - names.begin());
  const double* first = nlp.state(xs.data(), 0, 0);
  EXPECT_DOUBLE_EQ(first[l], 1.0 / 400);
  EXPECT_DOUBLE_EQ(nlp.state(xs.data(), 5, 2)[l], 1.0 / 400);
  std::vector<double> values(nlp.jacobian_pattern().size());
  std::vector<double> x = nlp.guess();
  nlp.jacobian(x.data(), values.data());
  for (size_t e = 0; e < values.size(); ++e) {
    const auto [r, c] = nlp.jacobian_pattern()[e];
    EXPECT_LE(std::fabs(values[e]) * gs[r] / xs[c], 100 * (1 + 1e-12));
  }
  EXPECT_GT(fs, 0.0);
  EXPECT_LE(fs, 1.0);

  testing::OptimalProblem cart("cart_pole_swing_up.yaml");
  const OptimizeResult own = cart.solve();
  OptimizeOptions o;
  o.ipopt = {{"nlp_scaling_method", "user-scaling"}};
  const OptimizeResult nominal =
      optimize(cart.eq, cart.cm, *cart.dyn, cart.spec(), cart.cm->q0, cart.cm->v0, o);
  ASSERT_TRUE(own.optimal && nominal.optimal) << nominal.status;
  EXPECT_NEAR(nominal.objective, own.objective, 1e-7 * own.objective);
}

}  // namespace
}  // namespace lagrange

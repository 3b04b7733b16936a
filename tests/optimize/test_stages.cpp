// Homotopy stages (docs/theory.md §10, "Homotopy"): each stage's optimum against its closed form,
// the problem's optimum unchanged by the path to it, and the tracking term's exact derivatives.

#include <gtest/gtest.h>

#include <cmath>

#include "lagrange/reader.hpp"
#include "optimize/nlp_derivative_check.hpp"
#include "optimize/optimal_problem.hpp"
#include "support/file_text.hpp"

namespace lagrange {
namespace {

// A fictitious force F, free at a price w in the stage and fixed at 0 in the problem: the stage
// costs w/(1 + w) of the minimum-energy optimum 12/(1 − h²), the problem that optimum itself,
// with F back at 0 (the data file's header derives both).
TEST(HomotopyStages, FictitiousForceStageAndProblemMeetTheirClosedForms) {
  testing::OptimalProblem p("data/double_integrator_fictitious.yaml");
  const OptimizeResult r = p.solve();
  ASSERT_TRUE(r.optimal) << r.status;
  ASSERT_EQ(r.stages.size(), 1U);
  const StageResult& stage = r.stages[0];
  EXPECT_EQ(stage.name, "fictitious");
  EXPECT_TRUE(stage.optimal) << stage.status;
  EXPECT_GT(stage.iterations, 0);
  const double h = 1.0 / 10, w = 10, closed = 12.0 / (1 - h * h);
  EXPECT_NEAR(stage.objective, w / (1 + w) * closed, 1e-7);
  EXPECT_EQ(stage.tracking, 0.0);
  EXPECT_NEAR(r.objective, closed, 1e-7);
  for (size_t k = 0; k < 10; ++k) {
    EXPECT_NEAR(r.controls[2 * k], (6 - 12 * (k + 0.5) * h) / (1 - h * h), 1e-5) << k;
    EXPECT_NEAR(r.controls[2 * k + 1], 0.0, 1e-12) << k;  // F, fixed at 0 by its bounds
  }
}

// A stage can hold or bound a free horizon: minimum energy with T held at 3 costs
// 12 d²/T³/(1 − 1/N²) (the closed form of the double integrator scaled to T); minimum time with
// T ≥ 2.5 ends on that bound; the problem then reaches its own T = 2√d = 2 from there.
TEST(HomotopyStages, AStageHoldsOrBoundsAFreeHorizon) {
  std::string model = test::slurp(testing::path("double_integrator_min_time.yaml"));
  const std::string last = "  degree: 3\n";  // the problem's last key
  ASSERT_NE(model.find(last), std::string::npos);
  model.insert(model.find(last) + last.size(),
               "  stages:\n    - {name: held, horizon: 3, minimize: integral(u^2)}\n"
               "    - {name: bounded, horizon: {lower: 2.5, upper: 4}}\n");
  testing::OptimalProblem p(read_model_string(model, "min_time.yaml"));
  const OptimizeResult r = p.solve();
  ASSERT_TRUE(r.optimal) << r.status;
  ASSERT_EQ(r.stages.size(), 2U);
  for (const StageResult& s : r.stages) EXPECT_TRUE(s.optimal) << s.name << ": " << s.status;
  EXPECT_NEAR(r.stages[0].objective, 12.0 / 27 / (1 - 1.0 / 400), 1e-7);
  EXPECT_NEAR(r.stages[1].objective, 2.5, 1e-7);
  EXPECT_NEAR(r.horizon, 2.0, 1e-6);
}

// A stage that only tracks its start (no objective): the motion nearest the straight-line guess
// that the dynamics allow (the line moves x at zero rate, which no motion does). The problem is
// convex, so from there it reaches the same optimum, 12/(1 − h²), as from the guess itself.
TEST(HomotopyStages, TrackingStageLeadsToTheSameOptimum) {
  testing::OptimalProblem p("double_integrator_min_energy.yaml");
  StageSpec track;
  track.name = "feasible";
  track.replaces_objective = true;  // objective 0: only the tracking term
  track.track = 1.0;
  p.model->optimal_control->stages = {track};
  const OptimizeResult staged = p.solve(10, 3);
  ASSERT_TRUE(staged.optimal) << staged.status;
  ASSERT_EQ(staged.stages.size(), 1U);
  EXPECT_TRUE(staged.stages[0].optimal) << staged.stages[0].status;
  EXPECT_EQ(staged.stages[0].objective, 0.0);
  EXPECT_GT(staged.stages[0].tracking, 1e-3);
  EXPECT_NEAR(staged.objective, 12.0 / (1 - 0.01), 1e-7);
}

// A stage asked to warm-start (warm_start_init_point) starts from the last stage's multipliers
// as well as its point: the same problem again, from its own solution with an active control
// bound, is solved in a step or two, where the same start with Ipopt's cold multipliers takes
// many more. Both reach the first solve's optimum.
TEST(HomotopyStages, AWarmStartedStageStartsFromTheLastStagesMultipliers) {
  const auto solve_twice = [](bool warm) {
    std::string model = test::slurp(testing::path("double_integrator_min_energy.yaml"));
    const std::string control = "    u: {}\n", last = "  degree: 3\n";
    EXPECT_NE(model.find(control), std::string::npos);
    model.replace(model.find(control), control.size(), "    u: {lower: -5, upper: 5}\n");
    const std::string options = std::string(warm ? "warm_start_init_point: yes, " : "") +
                                "mu_init: 1e-9, warm_start_bound_push: 1e-9, "
                                "warm_start_mult_bound_push: 1e-9";
    model.insert(
        model.find(last) + last.size(),
        "  stages:\n    - {name: first, ipopt: {tol: 1e-10}}\n    - {name: again, ipopt: {" +
            options + "}}\n");
    testing::OptimalProblem p(read_model_string(model, "warm.yaml"));
    return p.solve();
  };
  const OptimizeResult warm = solve_twice(true), cold = solve_twice(false);
  for (const OptimizeResult* r : {&warm, &cold}) {
    ASSERT_TRUE(r->optimal) << r->status;
    ASSERT_EQ(r->stages.size(), 2U);
    for (const StageResult& s : r->stages) EXPECT_TRUE(s.optimal) << s.name << ": " << s.status;
    EXPECT_NEAR(r->stages[1].objective, r->stages[0].objective, 1e-7);
    EXPECT_GT(r->stages[0].objective, 12.0);  // the bound |u| <= 5 is active: above 12/(1 - h²)
  }
  EXPECT_LE(warm.stages[1].iterations, 3);
  EXPECT_GT(cold.stages[1].iterations, 2 * warm.stages[1].iterations)
      << cold.stages[1].iterations << " vs " << warm.stages[1].iterations;
}

// The tracking term's gradient and Hessian (a diagonal on every state node) against central
// differences, from a starting point other than the problem's own guess.
TEST(HomotopyStages, TrackingTermDerivativesMatchCentralDifferences) {
  testing::OptimalProblem p("cart_pole_swing_up.yaml");
  const collocation::Transcription plain(p.eq, p.cm, *p.dyn, p.spec(), 3, 2, p.cm->q0, p.cm->v0);
  const std::vector<double> from = testing::perturbed_guess(plain, false, 5);
  const collocation::StageStart start{&from, 2.5, plain.dae_hessian(), plain.residual()};
  collocation::Transcription nlp(p.eq, p.cm, *p.dyn, p.spec(), 3, 2, p.cm->q0, p.cm->v0,
                                 HessianChoice::Exact, &start);
  EXPECT_EQ(nlp.guess(), from);
  EXPECT_EQ(nlp.dae_hessian(), plain.dae_hessian());  // shared, not compiled again
  EXPECT_EQ(nlp.residual(), plain.residual());
  const std::vector<double> x = testing::perturbed_guess(nlp, false, 13);
  EXPECT_GT(nlp.tracking(x.data()), 0.0);
  testing::expect_first_derivatives_match(nlp, x);
  testing::expect_hessian_matches(nlp, x, 17);
}

}  // namespace
}  // namespace lagrange

// The Panda's point-to-point motion (examples/optimal/panda_point_to_point.yaml, issue 34): the
// minimum-effort torques keep the URDF's limits, reach the target pose at rest, land there when
// flown open loop, and cost less than a known feasible motion of the same duration, the
// quintic (minimum-jerk) path with the torques its inverse dynamics needs.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

#include "optimize/optimal_problem.hpp"

namespace lagrange {
namespace {

// The rest-to-rest quintic s(x) = 10x³ − 15x⁴ + 6x⁵ on x = t/T and its first two derivatives.
std::array<double, 3> quintic(double x) {
  return {x * x * x * (10 - 15 * x + 6 * x * x), 30 * x * x * (1 - 2 * x + x * x),
          60 * x * (1 - 3 * x + 2 * x * x)};
}

// The torques τ = M(q) q̈ − h(q, q̇) that move the arm along (q, q̇, q̈): the residual r_v of the
// implicit equations of motion with every torque input held at zero (docs/theory.md §4.3).
std::vector<double> inverse_dynamics(Dynamics& dyn, double t, const std::vector<double>& q,
                                     const std::vector<double>& v, const std::vector<double>& a) {
  const size_t nq = q.size();
  std::vector<double> r(nq + v.size());
  dyn.dae_residual(t, q.data(), v.data(), v.data(), a.data(), nullptr, r.data());  // q̇ = v
  return {r.begin() + static_cast<long>(nq), r.end()};
}

TEST(PandaPointToPoint, MinimumEffortKeepsTheUrdfLimitsLandsOnTheTargetAndBeatsTheQuintic) {
  testing::OptimalProblem arm("panda_point_to_point.yaml");
  const OptimalControlSpec& spec = arm.spec();
  const OptimizeResult r = arm.solve();
  ASSERT_TRUE(r.optimal) << r.status;
  const size_t nq = arm.cm->nq, nu = r.control_names.size();
  ASSERT_EQ(nq, 7u);
  ASSERT_EQ(nu, 7u);

  // The bounds are the URDF's efforts: 87 N·m on joints 1–4, 12 N·m on 5–7; every control holds
  // them on every interval (Ipopt's bound relaxation is 1e-8 relative).
  for (size_t c = 0; c < nu; ++c) {
    const double effort = c < 4 ? 87.0 : 12.0;
    EXPECT_EQ(spec.controls[c].bounds.upper, effort) << r.control_names[c];
    EXPECT_EQ(spec.controls[c].bounds.lower, -effort) << r.control_names[c];
    for (int k = 0; k < r.intervals; ++k)
      EXPECT_LE(std::fabs(r.controls[static_cast<size_t>(k) * nu + c]), effort * (1 + 1e-7));
  }

  // Joint angles and rates keep their URDF limits at every collocation point.
  const Trajectory& tr = r.trajectory;
  for (const StateBound& b : spec.bounds) {
    const std::string& name = arm.model->coordinates[b.state.coordinate].name;
    const std::string column = b.state.velocity ? name + "_dot" : name;
    for (size_t row = 0; row < tr.rows(); ++row) {
      EXPECT_GE(tr.at(row, column), b.bounds.lower - 1e-6) << column << " at row " << row;
      EXPECT_LE(tr.at(row, column), b.bounds.upper + 1e-6) << column << " at row " << row;
    }
  }

  // From rest at the ready pose to rest at the target: the first and last rows.
  const size_t last = tr.rows() - 1;
  for (size_t i = 0; i < nq; ++i) {
    const std::string& name = arm.cm->coordinate_names[i];
    EXPECT_NEAR(tr.at(0, name), arm.cm->q0[i], 1e-9) << name;
    EXPECT_NEAR(tr.at(0, name + "_dot"), 0.0, 1e-9) << name;
  }
  for (const BoundaryValue& f : spec.final) {
    const std::string& name = arm.model->coordinates[f.state.coordinate].name;
    EXPECT_NEAR(tr.at(last, f.state.velocity ? name + "_dot" : name), f.bounds.lower, 1e-7);
  }

  // The objective is 0.01 ∫|τ|² dt of the piecewise-constant torques: 0.01 h Σ_k |U_k|².
  const double h = r.horizon / r.intervals;
  double effort = 0.0;
  for (double u : r.controls) effort += h * u * u;
  EXPECT_NEAR(r.objective, 0.01 * effort, 1e-9 * effort);

  // The torques flown open loop from the start (tight tolerances) land on the target pose: the
  // gap measured is 2.6e-4 (rad and rad/s); the open-loop arm amplifies collocation errors.
  SimulationOptions tight;
  tight.integrator.rtol = 1e-10;
  tight.integrator.atol = 1e-12;
  const VerifyResult flown = verify(*arm.dyn, spec, r, tight);
  EXPECT_TRUE(flown.message.empty()) << flown.message;
  EXPECT_LT(flown.final_gap, 2e-3);

  // The quintic path between the same poses over the same T, its torques from the inverse
  // dynamics: within the torque and rate limits (a feasible motion), and costlier.
  arm.dyn->release_inputs();
  for (size_t c = 0; c < nu; ++c) arm.dyn->hold_input(spec.controls[c].input, 0.0);
  std::vector<double> q1(nq), delta(nq);
  for (const BoundaryValue& f : spec.final)
    if (!f.state.velocity) q1[f.state.coordinate] = f.bounds.lower;
  for (size_t i = 0; i < nq; ++i) delta[i] = q1[i] - arm.cm->q0[i];
  const double T = r.horizon;
  const int steps = 2000;  // composite Simpson over [0, T]
  double quintic_effort = 0.0, peak_ratio = 0.0;
  for (int s = 0; s <= steps; ++s) {
    const double t = T * s / steps;
    const std::array<double, 3> p = quintic(t / T);
    std::vector<double> q(nq), v(nq), a(nq);
    for (size_t i = 0; i < nq; ++i) {
      q[i] = arm.cm->q0[i] + delta[i] * p[0];
      v[i] = delta[i] * p[1] / T;
      a[i] = delta[i] * p[2] / (T * T);
    }
    const std::vector<double> tau = inverse_dynamics(*arm.dyn, t, q, v, a);
    double sq = 0.0;
    for (size_t c = 0; c < nu; ++c) {
      sq += tau[c] * tau[c];
      peak_ratio = std::max(peak_ratio, std::fabs(tau[c]) / spec.controls[c].bounds.upper);
    }
    for (const StateBound& b : spec.bounds) {
      if (b.state.velocity) {
        EXPECT_LE(std::fabs(v[b.state.coordinate]), b.bounds.upper);
      }
    }
    const double weight = (s == 0 || s == steps) ? 1 : (s % 2 ? 4 : 2);
    quintic_effort += weight * sq * T / (3.0 * steps);
  }
  EXPECT_LT(peak_ratio, 1.0);
  std::printf("effort %.6g, quintic %.6g, peak torque/limit %.3g, open-loop gap %.3g\n", effort,
              quintic_effort, peak_ratio, flown.final_gap);
  EXPECT_LT(effort, quintic_effort) << effort << " vs " << quintic_effort;
}

}  // namespace
}  // namespace lagrange

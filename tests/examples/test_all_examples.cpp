// Every bundled example runs to completion with its own settings; constrained ones keep
// |C| and |Ċ| below 1e-9 over the whole run (the documented stabilisation defaults), and
// systems without dissipation, time-dependent inputs or driven points conserve energy.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "support/harness.hpp"

namespace lagrange {
namespace {

class Example : public ::testing::TestWithParam<std::string> {};

TEST_P(Example, RunsAndKeepsItsInvariants) {
  auto sys = testing::load_example(GetParam());
  const Trajectory tr = sys.run(sys.options());
  ASSERT_EQ(tr.status, Trajectory::Status::Complete) << tr.message;
  ASSERT_GT(tr.rows(), 10u);
  EXPECT_NEAR(tr.at(tr.rows() - 1, "t"), sys.model->simulate.t_end, 1e-12);
  if (sys.compiled->m > 0) {
    for (size_t r = 0; r < tr.rows(); ++r) {
      ASSERT_LT(tr.at(r, "constraint_residual"), 1e-9) << "t = " << tr.at(r, "t");
      ASSERT_LT(tr.at(r, "constraint_rate_residual"), 1e-9) << "t = " << tr.at(r, "t");
    }
  }
  const Model& m = *sys.model;
  bool conservative = m.dampers.empty() && m.forces.empty() && m.torques.empty() &&
                      m.inputs.empty() && !m.kinetic.has(m.t) && !m.potential.has(m.t);
  for (const auto& q : m.generalized_forces) conservative = conservative && q.is_zero();
  for (const auto& c : m.constraints) conservative = conservative && !c.expr.has(m.t);
  // A point moved by t (a bead on a turning hoop) is driven: the drive works on the system.
  for (const auto& p : m.points)
    for (const auto& c : p.pos) conservative = conservative && !c.has(m.t);
  if (conservative) {
    const double e0 = tr.at(0, "energy");
    const double e1 = tr.at(tr.rows() - 1, "energy");
    EXPECT_NEAR(e1, e0, 1e-5 * std::max(1.0, std::abs(e0)));
  }
}

INSTANTIATE_TEST_SUITE_P(Examples, Example, ::testing::ValuesIn(testing::example_files()),
                         [](const auto& info) {
                           std::string s = info.param.substr(0, info.param.size() - 5);
                           for (char& c : s)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return s;
                         });

}  // namespace
}  // namespace lagrange

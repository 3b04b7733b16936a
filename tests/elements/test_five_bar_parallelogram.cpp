// The five-bar parallelogram (seed 001, Example 7; examples/five_bar_parallelogram.yaml): the
// seed's D(q) symbolically, D diagonal and C = 0 under the decoupling condition
// m3 L2 Lc3 = m4 L1 Lc4, and q1 moving the same whatever q2 does.

#include <gtest/gtest.h>

#include "lagrange/manipulator.hpp"
#include "support/harness.hpp"

namespace lagrange {
namespace {

using testing::sym;

const char* kFile = "five_bar_parallelogram.yaml";

TEST(FiveBarParallelogram, InertiaMatrixIsTheSeeds) {
  const Model m = read_model_file(testing::example_path(kFile));
  const Equations eq = derive(m);
  const ManipulatorForm f = manipulator_form(eq);
  auto s = [&](const char* n) { return GiNaC::ex(sym(m, n)); };
  const GiNaC::ex d11 = s("m1") * pow(s("Lc1"), 2) + s("m3") * pow(s("Lc3"), 2) +
                        s("m4") * pow(s("L1"), 2) + s("I1") + s("I3");
  const GiNaC::ex d22 = s("m2") * pow(s("Lc2"), 2) + s("m3") * pow(s("L2"), 2) +
                        s("m4") * pow(s("Lc4"), 2) + s("I2") + s("I4");
  const GiNaC::ex d12 =
      (s("m3") * s("L2") * s("Lc3") - s("m4") * s("L1") * s("Lc4")) * cos(s("q2") - s("q1"));
  EXPECT_TRUE(trig_simplify(f.D(0, 0) - d11).is_zero()) << f.D(0, 0);
  EXPECT_TRUE(trig_simplify(f.D(1, 1) - d22).is_zero()) << f.D(1, 1);
  EXPECT_TRUE(trig_simplify(f.D(0, 1) - d12).is_zero()) << f.D(0, 1);
  EXPECT_TRUE(trig_simplify(f.D(1, 0) - d12).is_zero()) << f.D(1, 0);
}

TEST(FiveBarParallelogram, DecouplingConditionMakesDDiagonalAndCZero) {
  const Model m = read_model_file(testing::example_path(kFile));
  const Equations eq = derive(m);
  const ManipulatorForm f = manipulator_form(eq);
  auto s = [&](const char* n) { return GiNaC::ex(sym(m, n)); };
  // m4 = m3 L2 Lc3 / (L1 Lc4)
  const GiNaC::exmap decoupled{{sym(m, "m4"), s("m3") * s("L2") * s("Lc3") / (s("L1") * s("Lc4"))}};
  EXPECT_TRUE(trig_simplify(f.D(0, 1).subs(decoupled)).is_zero());
  for (size_t k = 0; k < 2; ++k)
    for (size_t j = 0; j < 2; ++j)
      EXPECT_TRUE(trig_simplify(f.C(k, j).subs(decoupled)).is_zero()) << k << j;
  // Without it the arm is coupled.
  EXPECT_FALSE(trig_simplify(f.D(0, 1)).is_zero());
}

// The file's parameters satisfy the condition: q1's motion does not depend on q2's.
TEST(FiveBarParallelogram, JointsMoveIndependently) {
  auto sys = testing::load_example(kFile);
  const SimulationOptions so = testing::tight(sys, 2.0, 0.1);
  const Trajectory a = simulate(*sys.dynamics, so, {0.4, 2.0}, {0.0, 0.0});
  const Trajectory b = simulate(*sys.dynamics, so, {0.4, -1.0}, {0.0, 3.0});
  ASSERT_EQ(a.status, Trajectory::Status::Complete) << a.message;
  ASSERT_EQ(b.status, Trajectory::Status::Complete) << b.message;
  ASSERT_EQ(a.rows(), b.rows());
  double moved = 0;
  for (size_t r = 0; r < a.rows(); ++r) {
    EXPECT_NEAR(a.at(r, "q1"), b.at(r, "q1"), 1e-8) << "t = " << a.at(r, "t");
    moved = std::max(moved, std::abs(a.at(r, "q2") - b.at(r, "q2")));
  }
  EXPECT_GT(moved, 1.0);  // while q2 differs widely
}

}  // namespace
}  // namespace lagrange

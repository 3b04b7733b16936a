// Dynamics on machine code (docs/theory.md §8): on every example the library computes the same
// q̇, accelerations, multipliers and observables as the interpreter, bit for bit, so that a run
// may switch between them (Background mode) without changing a single output.

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <thread>

#include "support/test_paths.hpp"
#include "lagrange/error.hpp"
#include "n_link_pendulum.hpp"
#include "support/harness.hpp"

namespace lagrange {
namespace {

/// The test build's own cache (a fresh clone starts empty; later runs hit it).
MachineCodeOptions build_cache() {
  MachineCodeOptions o;
  o.cache_dir = LAGRANGE_TEST_CACHE;
  return o;
}

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0);
}

/// Everything forward() and observe() produce at (t, q, v), or the error message.
struct Evaluated {
  std::vector<double> qdot, a, lambda, obs;
  std::string error;
};

Evaluated evaluate(Dynamics& d, double t, const std::vector<double>& q,
                   const std::vector<double>& v) {
  const CompiledModel& cm = d.model();
  Evaluated e{std::vector<double>(cm.nq), std::vector<double>(cm.nv), std::vector<double>(cm.m),
              std::vector<double>(cm.observables.num_outputs()), ""};
  try {
    d.forward(t, q.data(), v.data(), e.qdot.data(), e.a.data(), e.lambda.data());
    d.observe(t, q.data(), v.data(), e.obs.data());
  } catch (const SimulationError& err) {
    e.error = err.what();
  }
  return e;
}

class MachineCodeExample : public ::testing::TestWithParam<std::string> {};

/// Machine code against the interpreter on the same tapes at four states, bit for bit.
void expect_same_bits(const std::shared_ptr<const CompiledModel>& model, double alpha,
                      const std::string& form) {
  Dynamics interpreted(model, model->parameter_defaults), native(model, model->parameter_defaults);
  interpreted.set_baumgarte(alpha);
  native.set_baumgarte(alpha);
  native.set_evaluation(Evaluation::MachineCode, build_cache());
  ASSERT_TRUE(native.uses_machine_code()) << native.evaluation_note();
  const CompiledModel& cm = *model;
  for (int k = 0; k < 4; ++k) {
    std::vector<double> q = cm.q0, v = cm.v0;
    for (size_t i = 0; i < cm.nv; ++i) v[i] += 0.1 * k * std::sin(1.0 + static_cast<double>(i));
    const double t = 0.37 * k;
    const Evaluated want = evaluate(interpreted, t, q, v), got = evaluate(native, t, q, v);
    EXPECT_EQ(got.error, want.error) << form;
    EXPECT_TRUE(same_bits(got.qdot, want.qdot)) << form << ": q̇ at state " << k;
    EXPECT_TRUE(same_bits(got.a, want.a)) << form << ": accelerations at state " << k;
    EXPECT_TRUE(same_bits(got.lambda, want.lambda)) << form << ": multipliers at state " << k;
    EXPECT_TRUE(same_bits(got.obs, want.obs)) << form << ": observables at state " << k;
  }
}

// Both formulations where the recursive one applies (docs/theory.md §4.9).
TEST_P(MachineCodeExample, SameBitsAsTheInterpreter) {
  auto sys = testing::load_example(GetParam());
  expect_same_bits(sys.compiled, sys.dynamics->baumgarte(), "Lagrangian");
  if (recursive_unsuitable(*sys.model).empty())
    expect_same_bits(compile(derive(*sys.model, Formulation::Recursive)), sys.dynamics->baumgarte(),
                     "recursive");
}

INSTANTIATE_TEST_SUITE_P(Examples, MachineCodeExample, ::testing::ValuesIn(testing::model_files()),
                         [](const auto& info) { return testing::model_label(info.param); });

/// Column-wise identical trajectories (same rows, same bits).
void expect_same_trajectory(const Trajectory& a, const Trajectory& b) {
  ASSERT_EQ(a.columns, b.columns);
  ASSERT_EQ(a.data.size(), b.data.size());
  EXPECT_EQ(std::memcmp(a.data.data(), b.data.data(), a.data.size() * sizeof(double)), 0);
  EXPECT_EQ(a.stats.steps, b.stats.steps);
}

TEST(MachineCodeBackground, SwitchingMidRunChangesNoOutput) {
  // A fresh cache: the run starts on the interpreter and switches when the compiler is done.
  const auto dir = std::filesystem::temp_directory_path() /
                   ("lagrange-background-" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  MachineCodeOptions o;
  o.cache_dir = dir.string();
  auto sys = testing::load_string(bench::n_link_pendulum_yaml(16));
  const CompiledModel& cm = *sys.compiled;
  ASSERT_GE(cm.dynamics.specialize(cm.p_offset(), cm.parameter_defaults).num_instructions(),
            Dynamics::kBackgroundMinInstructions);
  SimulationOptions so = sys.options();
  so.t_end = 2.0;
  const Trajectory reference = sys.run(so);
  Dynamics background(sys.compiled, sys.compiled->parameter_defaults);
  background.set_baumgarte(sys.dynamics->baumgarte());
  background.set_evaluation(Evaluation::Background, o);
  const Trajectory mixed = simulate(background, so, sys.compiled->q0, sys.compiled->v0);
  expect_same_trajectory(reference, mixed);
  for (int i = 0; i < 600 && !background.uses_machine_code(); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  EXPECT_TRUE(background.uses_machine_code()) << background.evaluation_note();
  EXPECT_NE(background.evaluation_note().find("machine code (compiled in"), std::string::npos)
      << background.evaluation_note();
  const Trajectory native = simulate(background, so, sys.compiled->q0, sys.compiled->v0);
  expect_same_trajectory(reference, native);
  std::filesystem::remove_all(dir);
}

TEST(MachineCodeBackground, SmallTapesStayInterpreted) {
  auto sys = testing::load_example("pendulum.yaml");
  MachineCodeOptions o;
  o.cache_dir = "/proc/self/never-created";  // would fail if anything were compiled
  sys.dynamics->set_evaluation(Evaluation::Background, o);
  EXPECT_FALSE(sys.dynamics->uses_machine_code());
  EXPECT_NE(sys.dynamics->evaluation_note().find("interprets faster than it compiles"),
            std::string::npos)
      << sys.dynamics->evaluation_note();
}

TEST(MachineCodeFallback, MissingCompilerKeepsTheInterpreterAndSaysWhy) {
  auto sys = testing::load_example("double_pendulum.yaml");
  MachineCodeOptions o = build_cache();
  o.compiler = "no-such-compiler-for-lagrange";
  sys.dynamics->set_evaluation(Evaluation::MachineCode, o);
  EXPECT_FALSE(sys.dynamics->uses_machine_code());
  EXPECT_NE(sys.dynamics->evaluation_note().find("interpreter (machine code: no C compiler"),
            std::string::npos)
      << sys.dynamics->evaluation_note();
  SimulationOptions so = sys.options();
  so.t_end = 0.5;
  EXPECT_EQ(sys.run(so).status, Trajectory::Status::Complete);
}

TEST(MachineCodeParameters, NewParameterValuesGetTheirOwnCode) {
  auto sys = testing::load_example("double_pendulum.yaml");
  Dynamics native(sys.compiled, sys.compiled->parameter_defaults);
  native.set_evaluation(Evaluation::MachineCode, build_cache());
  std::vector<double> p = sys.compiled->parameter_defaults;
  for (double& x : p) x *= 1.5;
  native.set_parameters(p);
  sys.dynamics->set_parameters(p);
  ASSERT_TRUE(native.uses_machine_code()) << native.evaluation_note();
  const Evaluated want = evaluate(*sys.dynamics, 0.0, sys.compiled->q0, sys.compiled->v0);
  const Evaluated got = evaluate(native, 0.0, sys.compiled->q0, sys.compiled->v0);
  EXPECT_TRUE(same_bits(got.a, want.a));
}

}  // namespace
}  // namespace lagrange

// Forward dynamics never allocates (docs/theory.md §2: the integrator's right-hand side is
// allocation-free). malloc is interposed in this test binary and counted around the calls.

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstddef>

#include "support/test_paths.hpp"
#include "n_link_pendulum.hpp"
#include "support/harness.hpp"

extern "C" void* __libc_malloc(size_t size);  // glibc's allocator behind malloc

namespace {
std::atomic<bool> g_counting{false};
std::atomic<long> g_mallocs{0};
}  // namespace

extern "C" void* malloc(size_t size) {
  if (g_counting.load(std::memory_order_relaxed)) g_mallocs.fetch_add(1);
  return __libc_malloc(size);
}

namespace lagrange {
namespace {

long allocations_in_forward(const std::string& yaml_or_example, bool is_file,
                            bool machine_code = false, Formulation form = Formulation::Lagrangian) {
  auto sys =
      is_file ? testing::load_example(yaml_or_example) : testing::load_string(yaml_or_example);
  if (form == Formulation::Recursive) {  // docs/theory.md §4.9
    sys.compiled = compile(derive(*sys.model, form));
    sys.dynamics = std::make_unique<Dynamics>(sys.compiled, sys.compiled->parameter_defaults);
  }
  if (machine_code) {
    MachineCodeOptions o;
    o.cache_dir = LAGRANGE_TEST_CACHE;
    sys.dynamics->set_evaluation(Evaluation::MachineCode, o);
    EXPECT_TRUE(sys.dynamics->uses_machine_code()) << sys.dynamics->evaluation_note();
  }
  const CompiledModel& cm = *sys.compiled;
  std::vector<double> q = cm.q0, v(cm.nv, 0.1), qd(cm.nq), a(cm.nv), lambda(cm.m);
  sys.dynamics->forward(0.0, q.data(), v.data(), qd.data(), a.data(), lambda.data());  // warm-up
  g_mallocs = 0;
  g_counting = true;
  for (int k = 0; k < 100; ++k)
    sys.dynamics->forward(0.01 * k, q.data(), v.data(), qd.data(), a.data(), lambda.data());
  g_counting = false;
  return g_mallocs.load();
}

TEST(NoAllocation, CountingWorks) {
  g_mallocs = 0;
  g_counting = true;
  std::vector<double>* p = new std::vector<double>(1000);
  g_counting = false;
  delete p;
  EXPECT_GE(g_mallocs.load(), 1);
}

TEST(NoAllocation, DenseUnconstrained) {
  EXPECT_EQ(allocations_in_forward("double_pendulum.yaml", true), 0);
}
TEST(NoAllocation, DenseConstrainedWithInputs) {
  EXPECT_EQ(allocations_in_forward("crane.yaml", true), 0);
}
TEST(NoAllocation, FiveBar) {
  EXPECT_EQ(allocations_in_forward("five_bar.yaml", true), 0);
}

TEST(NoAllocation, MachineCode) {
  EXPECT_EQ(allocations_in_forward("five_bar.yaml", true, true), 0);
  EXPECT_EQ(allocations_in_forward(bench::n_link_pendulum_yaml(20), false, true), 0);
}

TEST(NoAllocation, RecursiveChainAndArm) {
  for (const bool native : {false, true}) {
    EXPECT_EQ(
        allocations_in_forward(bench::links_chain_yaml(12), false, native, Formulation::Recursive),
        0);
    EXPECT_EQ(
        allocations_in_forward("elbow_manipulator.yaml", true, native, Formulation::Recursive), 0);
  }
}

TEST(NoAllocation, SparseChain) {
  EXPECT_EQ(allocations_in_forward(bench::cartesian_chain_yaml(15), false), 0);
}

// Projection onto the constraints (docs/theory.md §4.3): its sparse structure is set up by the
// first call; later ones only compute.
TEST(NoAllocation, ProjectionAfterTheFirst) {
  auto sys = testing::load_string(bench::cartesian_chain_yaml(15, 0.4));
  const CompiledModel& cm = *sys.compiled;
  const std::vector<bool> none(cm.nq, false);
  std::vector<double> q = cm.q0, v = cm.v0;
  sys.dynamics->project(0.0, q.data(), v.data(), none);
  g_mallocs = 0;
  for (int k = 1; k <= 10; ++k) {
    for (size_t i = 0; i < cm.nq; ++i) q[i] += 1e-6 * k * std::sin(double(i));
    for (size_t i = 0; i < cm.nv; ++i) v[i] += 1e-4 * k * std::cos(double(i));
    g_counting = true;
    const ProjectionResult res = sys.dynamics->project(0.0, q.data(), v.data(), none);
    g_counting = false;
    EXPECT_GT(res.position_change, 0.0);
  }
  EXPECT_EQ(g_mallocs.load(), 0);
}

}  // namespace
}  // namespace lagrange

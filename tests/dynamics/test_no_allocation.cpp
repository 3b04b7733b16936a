// Forward dynamics never allocates (DESIGN.md §2: the integrator's right-hand side is
// allocation-free). malloc is interposed in this test binary and counted around the calls.

#include <gtest/gtest.h>

#include <atomic>
#include <cstddef>

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

long allocations_in_forward(const std::string& yaml_or_example, bool is_file) {
  auto sys =
      is_file ? testing::load_example(yaml_or_example) : testing::load_string(yaml_or_example);
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

TEST(NoAllocation, SparseChain) {
  std::string coords, points, particles, constraints;
  const int N = 15;
  for (int i = 1; i <= N; ++i) {
    coords += "  x" + std::to_string(i) + ": {initial: 0}\n  y" + std::to_string(i) +
              ": {initial: " + std::to_string(-0.5 * i) + "}\n";
    points += "  p" + std::to_string(i) + ": [x" + std::to_string(i) + ", y" + std::to_string(i) +
              ", 0]\n";
    particles += (i > 1 ? ", p" : "p") + std::to_string(i) + ": m";
    const std::string px = i > 1 ? "x" + std::to_string(i - 1) : "0";
    const std::string py = i > 1 ? "y" + std::to_string(i - 1) : "0";
    constraints += "  rod" + std::to_string(i) + ": ((x" + std::to_string(i) + " - " + px +
                   ")^2 + (y" + std::to_string(i) + " - " + py + ")^2 - l^2)/2\n";
  }
  const std::string yaml = "parameters: {m: 1.0, l: 0.5, g: 9.81}\ncoordinates:\n" + coords +
                           "points:\n" + points + "particles: {" + particles +
                           "}\ngravity: [0, -g, 0]\nconstraints:\n" + constraints;
  EXPECT_EQ(allocations_in_forward(yaml, false), 0);
}

}  // namespace
}  // namespace lagrange

// A study's workers as forked processes and this one (sweep::run_pool_processes, docs/sweeps.md
// "Speed"): every case reported once, here, with the numbers the thread pool gives, bit for
// bit; a worker's exception stops the study and is thrown here with its message.

#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <map>
#include <stdexcept>
#include <string>
#include <thread>

#include "lagrange/compiled_model.hpp"
#include "lagrange/equations.hpp"
#include "lagrange/reader.hpp"
#include "lagrange/sweep.hpp"

namespace lagrange::sweep {
namespace {

const std::string kPoolModel = R"(
parameters: {l: 1, m: 1}
coordinates:
  th: {initial: 0.8}
points:
  p: [l*sin(th), -l*cos(th), 0]
particles:
  - {point: p, mass: m}
gravity: [0, -9.81, 0]
)";

struct Study {
  std::shared_ptr<const CompiledModel> compiled;
  std::vector<CaseInput> inputs;
  std::vector<size_t> pending;
  std::vector<Metric> metrics;
};

// Eight pendulums of lengths 0.5 … 1.55 for 1 s: the final angle and the least after 0.5 s.
Study pendulums() {
  const Model model = read_model_string(kPoolModel, "pendulum.yaml");
  Study s;
  s.compiled = compile(derive(model));
  s.metrics = study_metrics(model, *s.compiled, {"final(th)", "min(th, t > 0.5)"});
  for (size_t i = 0; i < 8; ++i) {
    const Model m = read_model_string(kPoolModel, "pendulum.yaml", {{"l", 0.5 + 0.15 * i}});
    SimulationOptions so;
    so.t_end = 1.0;
    s.inputs.push_back(case_input(m, *s.compiled, so));
    s.pending.push_back(i);
  }
  return s;
}

std::map<size_t, CaseResult> results(const Study& s, bool processes, PoolOptions pool = {}) {
  std::map<size_t, CaseResult> got;
  const pid_t here = getpid();
  pool.workers = 2;
  pool.done = [&](const CaseResult& r) {
    EXPECT_EQ(getpid(), here);  // rows are written by the study's own process
    EXPECT_TRUE(got.emplace(r.index, r).second) << "case " << r.index << " twice";
  };
  if (processes)
    run_pool_processes(s.compiled, s.inputs, s.pending, s.metrics, pool);
  else
    run_pool(s.compiled, s.inputs, s.pending, s.metrics, pool);
  return got;
}

TEST(ProcessPool, EveryCaseOnceWithTheThreadPoolsNumbers) {
  const Study s = pendulums();
  const auto threads = results(s, false), processes = results(s, true);
  ASSERT_EQ(processes.size(), s.pending.size());
  for (const auto& [index, r] : threads) {
    const CaseResult& p = processes.at(index);
    EXPECT_EQ(p.status, Trajectory::Status::Complete);
    ASSERT_EQ(p.metrics.size(), r.metrics.size());
    EXPECT_EQ(std::memcmp(p.metrics.data(), r.metrics.data(), r.metrics.size() * sizeof(double)), 0)
        << "case " << index;
  }
}

// With two workers, one is a forked process and the other this one (docs/sweeps.md, "Speed"):
// an exception in either stops the study and is thrown here with its message.
TEST(ProcessPool, AWorkersExceptionIsThrownHere) {
  const Study s = pendulums();
  const pid_t here = getpid();
  for (const bool in_the_fork : {true, false}) {
    PoolOptions pool;
    pool.read = [&](size_t index) -> CaseRead {
      if ((getpid() != here) == in_the_fork)
        throw std::runtime_error(in_the_fork ? "refused in a worker" : "refused here");
      // The side that does not throw is slow, so that the side that does gets a case on a loaded
      // machine too: the forked worker starts after this process, and may then run before it.
      std::this_thread::sleep_for(std::chrono::milliseconds(200));
      return {s.inputs[index], {}, -1.0};
    };
    try {
      results(s, true, pool);
      FAIL() << "no exception";
    } catch (const std::runtime_error& e) {
      EXPECT_STREQ(e.what(), in_the_fork ? "refused in a worker" : "refused here");
    }
  }
}

}  // namespace
}  // namespace lagrange::sweep

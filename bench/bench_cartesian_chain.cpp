// N-link planar chain in Cartesian coordinates (2N coordinates, N rod constraints): time per
// forward-dynamics call (KKT solve included) for N = 10, 50, 200, and the scaling ratio
// t(200)/t(50). Target: ≤ 5 (an O(N) solve would give 4; a dense O(N³) one about 64).

#include <benchmark/benchmark.h>

#include <cstdio>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "bench_support.hpp"
#include "n_link_pendulum.hpp"

namespace {

void BM_ChainForward(benchmark::State& state) {
  const size_t links = static_cast<size_t>(state.range(0));
  lagrange::bench::BuiltModel b =
      lagrange::bench::build_model(lagrange::bench::cartesian_chain_yaml(links),
                                   "<" + std::to_string(links) + "-link Cartesian chain>");
  const lagrange::CompiledModel& cm = *b.compiled;
  lagrange::Dynamics& dyn = *b.dynamics;
  const std::vector<double> q = cm.q0, v = cm.v0;
  std::vector<double> qdot(cm.nq), a(cm.nv), lambda(cm.m);
  for (auto _ : state) {
    dyn.forward(0.0, q.data(), v.data(), qdot.data(), a.data(), lambda.data());
    benchmark::DoNotOptimize(a.data());
    benchmark::ClobberMemory();
  }
  state.counters["links"] = static_cast<double>(links);
  state.counters["M_diagonal"] = cm.M_diagonal ? 1.0 : 0.0;
  state.counters["build_s"] = b.times.build();
  state.counters["build_cpu_s"] = b.cpu_times.build();
  state.counters["instr_spec"] = static_cast<double>(lagrange::bench::specialised_instructions(cm));
}

BENCHMARK(BM_ChainForward)->Arg(10)->Arg(50)->Arg(200)->Unit(benchmark::kMicrosecond);

/// Console output plus the scaling ratio once all runs are in.
class ChainReporter : public benchmark::ConsoleReporter {
 public:
  void ReportRuns(const std::vector<Run>& runs) override {
    for (const Run& r : runs)
      if (!r.error_occurred && r.run_type == Run::RT_Iteration && r.iterations > 0)
        per_call_[r.run_name.args] = {r.real_accumulated_time / static_cast<double>(r.iterations),
                                      r.cpu_accumulated_time / static_cast<double>(r.iterations)};
    ConsoleReporter::ReportRuns(runs);
  }
  void Finalize() override {
    ConsoleReporter::Finalize();
    const auto t50 = per_call_.find("50"), t200 = per_call_.find("200");
    if (t50 == per_call_.end() || t200 == per_call_.end()) return;
    std::printf("chain_ratio t(200)/t(50) = %.2f wall, %.2f cpu (target <= 5)\n",
                t200->second.first / t50->second.first, t200->second.second / t50->second.second);
    std::fflush(stdout);
  }

 private:
  std::map<std::string, std::pair<double, double>> per_call_;  ///< args → (wall, cpu) seconds
};

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  ChainReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  benchmark::Shutdown();
  return 0;
}

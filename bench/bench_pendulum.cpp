// N-link planar pendulum (absolute angles, point masses at the link ends): derivation +
// compilation time, tape sizes and forward-dynamics time per call (docs/theory.md §8).
//
// Extra mode for cross-checking against the SymPy peer (bench/run.sh):
//   bench_pendulum --accelerations N   prints "accelerations N a1 … aN" at the benchmark state.

#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "bench_support.hpp"
#include "n_link_pendulum.hpp"

namespace {

using lagrange::bench::BuiltModel;
using lagrange::bench::n_link_pendulum_yaml;
using lagrange::bench::PendulumParameters;

/// The state every forward call and the SymPy peer use: θₖ = initial_angle(k) (the model's
/// initial values), θ̇ₖ = 0.1·k.
std::vector<double> bench_rates(size_t n) {
  std::vector<double> v(n);
  for (size_t k = 0; k < n; ++k) v[k] = 0.1 * static_cast<double>(k + 1);
  return v;
}

BuiltModel build_pendulum(size_t n, PendulumParameters p) {
  return lagrange::bench::build_model(n_link_pendulum_yaml(n, p),
                                      "<" + std::to_string(n) + "-link pendulum>");
}

void set_tape_counters(benchmark::State& state, const lagrange::CompiledModel& cm) {
  state.counters["instr"] = static_cast<double>(cm.dynamics.num_instructions());
  state.counters["instr_spec"] = static_cast<double>(lagrange::bench::specialised_instructions(cm));
}

// Wall time of derive + compile + specialise (the manual time); the stages (wall) and the
// total process CPU time as counters.
void derive_compile(benchmark::State& state, PendulumParameters p) {
  const size_t n = static_cast<size_t>(state.range(0));
  const std::string yaml = n_link_pendulum_yaml(n, p);
  const std::string label = "<" + std::to_string(n) + "-link pendulum>";
  lagrange::bench::StageTimes sum, cpu;
  BuiltModel last;
  for (auto _ : state) {
    BuiltModel b = lagrange::bench::build_model(yaml, label);
    state.SetIterationTime(b.times.build());
    sum.read += b.times.read;
    sum.derive += b.times.derive;
    sum.compile += b.times.compile;
    sum.specialise += b.times.specialise;
    cpu.derive += b.cpu_times.derive;
    cpu.compile += b.cpu_times.compile;
    cpu.specialise += b.cpu_times.specialise;
    last = std::move(b);
  }
  using benchmark::Counter;
  state.counters["read_s"] = Counter(sum.read, Counter::kAvgIterations);
  state.counters["derive_s"] = Counter(sum.derive, Counter::kAvgIterations);
  state.counters["compile_s"] = Counter(sum.compile, Counter::kAvgIterations);
  state.counters["specialise_s"] = Counter(sum.specialise, Counter::kAvgIterations);
  state.counters["build_cpu_s"] = Counter(cpu.build(), Counter::kAvgIterations);
  state.counters["n"] = static_cast<double>(n);
  set_tape_counters(state, *last.compiled);
}

void BM_DeriveCompile(benchmark::State& state) {
  derive_compile(state, PendulumParameters::PerLink);
}
void BM_DeriveCompileShared(benchmark::State& state) {
  derive_compile(state, PendulumParameters::Shared);
}

void forward(benchmark::State& state, PendulumParameters p) {
  const size_t n = static_cast<size_t>(state.range(0));
  BuiltModel b = build_pendulum(n, p);
  lagrange::Dynamics& dyn = *b.dynamics;
  const std::vector<double> q = b.compiled->q0, v = bench_rates(n);
  std::vector<double> qdot(n), a(n);
  double lambda = 0.0;  // unconstrained: never written
  for (auto _ : state) {
    dyn.forward(0.0, q.data(), v.data(), qdot.data(), a.data(), &lambda);
    benchmark::DoNotOptimize(a.data());
    benchmark::ClobberMemory();
  }
  state.counters["n"] = static_cast<double>(n);
  set_tape_counters(state, *b.compiled);
}

void BM_Forward(benchmark::State& state) {
  forward(state, PendulumParameters::PerLink);
}
void BM_ForwardShared(benchmark::State& state) {
  forward(state, PendulumParameters::Shared);
}

// Small N repeat until the minimum time; large N are timed once (N = 50 takes seconds).
BENCHMARK(BM_DeriveCompile)
    ->Arg(2)
    ->Arg(5)
    ->Arg(8)
    ->Arg(10)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DeriveCompile)
    ->Arg(20)
    ->Arg(50)
    ->Iterations(1)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DeriveCompileShared)->Arg(8)->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DeriveCompileShared)
    ->Arg(50)
    ->Iterations(1)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Forward)->Arg(2)->Arg(5)->Arg(10)->Arg(20)->Arg(50)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ForwardShared)->Arg(10)->Arg(50)->Unit(benchmark::kMicrosecond);

int print_accelerations(const char* arg) {
  const long parsed = std::strtol(arg, nullptr, 10);
  if (parsed < 1) {
    std::fprintf(stderr, "--accelerations needs a positive N, got '%s'\n", arg);
    return 2;
  }
  const size_t n = static_cast<size_t>(parsed);
  BuiltModel b = build_pendulum(n, PendulumParameters::PerLink);
  const std::vector<double> q = b.compiled->q0, v = bench_rates(n);
  std::vector<double> qdot(n), a(n);
  double lambda = 0.0;
  b.dynamics->forward(0.0, q.data(), v.data(), qdot.data(), a.data(), &lambda);
  std::printf("accelerations %zu", n);
  for (double x : a) std::printf(" %.17g", x);
  std::printf("\n");
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc == 3 && std::strcmp(argv[1], "--accelerations") == 0)
    return print_accelerations(argv[2]);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

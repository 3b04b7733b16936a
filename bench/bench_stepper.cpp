// A controller in the loop at 20 Hz (issues 22 and 23): the figure-eight kite of
// examples/figure_eight.yaml stepped by include/lagrange/stepper.hpp against one simulate() run
// of the same flight in the same process (CPU time, best of `repeats`).
//
//   bench_stepper [--quick]      (--quick: 10 s of flight instead of 60)
//
// - one run: simulate(t_end, output_step 0.05) with the roll law written in the file;
// - stepped: the same model, 20 steps a second and no input set: the same integration step for
//   step (the rows are compared bit for bit), so the difference is the interface's cost;
// - in the loop: roll an external input, set every 0.05 s by the file's law evaluated in C++ from
//   the kite's azimuth, elevation and heading in the last row (zero-order hold). Its extra work
//   (steps landing on each control instant, one evaluation after each new value) is integration
//   that the held input makes necessary, counted in evaluations.

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "support/test_paths.hpp"
#include "bench_support.hpp"
#include "lagrange/simulation.hpp"
#include "lagrange/stepper.hpp"

using namespace lagrange;

namespace {

constexpr double kPeriod = 0.05;  // 20 Hz

std::string file_text() {
  std::ifstream in(std::string(LAGRANGE_SOURCE_DIR) + "/examples/figure_eight.yaml");
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The file with its roll law replaced by the external input roll_cmd.
std::string in_loop_text(const std::string& text) {
  const size_t law = text.find("    roll: >-"), end = text.find("simulate:");
  const size_t coordinates = text.find("coordinates:");
  if (law == std::string::npos || end == std::string::npos || coordinates == std::string::npos)
    throw std::runtime_error("figure_eight.yaml no longer has its roll law where expected");
  std::string out = text.substr(0, law) + "    roll: roll_cmd\n" + text.substr(end);
  out.insert(coordinates, "inputs:\n  roll_cmd: {value: 0, external: true}\n");
  return out;
}

double parameter(const Model& m, const std::string& name) {
  return m.parameters.at(static_cast<size_t>(m.parameter_index(name))).value;
}

struct Timing {
  double cpu = HUGE_VAL;
  long evals = 0;
  Trajectory rows;
};

// Best CPU time of `repeats` runs of `run` (which returns its trajectory).
Timing best_of(int repeats, const std::function<Trajectory()>& run) {
  const bench::Stopwatch clock;
  Timing t;
  for (int r = 0; r < repeats; ++r) {
    const auto c0 = clock.now();
    Trajectory tr = run();
    t.cpu = std::min(t.cpu, clock.now().cpu - c0.cpu);
    t.evals = tr.stats.rhs_evals;
    t.rows = std::move(tr);
  }
  return t;
}

}  // namespace

int main(int argc, char** argv) {
  const bool quick = argc > 1 && std::strcmp(argv[1], "--quick") == 0;
  const double t_end = quick ? 10.0 : 60.0;
  const int repeats = 11;
  const std::string text = file_text();
  bench::BuiltModel file = bench::build_model(text, "figure_eight.yaml");
  bench::BuiltModel loop = bench::build_model(in_loop_text(text), "figure_eight in the loop");
  SimulationOptions so;
  so.t_end = t_end;
  so.output_step = kPeriod;
  so.integrator.rtol = file.model->simulate.rtol;
  so.integrator.atol = file.model->simulate.atol;
  const size_t steps = static_cast<size_t>(std::lround(t_end / kPeriod));

  // One run and the stepped run alternate, each first in every other pair, so that both see the
  // same load and caches; the overhead is the median of the pairs' ratios.
  const auto run_one = [&] {
    Dynamics dyn(file.compiled, file.compiled->parameter_defaults);
    return simulate(dyn, so, file.compiled->q0, file.compiled->v0);
  };
  const auto run_stepped = [&] {
    Stepper s(Dynamics(file.compiled, file.compiled->parameter_defaults), so, file.compiled->q0,
              file.compiled->v0);
    for (size_t k = 0; k < steps; ++k) s.step(kPeriod);
    return s.record();
  };
  Timing one, stepped;
  std::vector<double> ratios;
  for (int r = 0; r < repeats; ++r) {
    Timing a, b;
    if (r % 2 == 0) {
      a = best_of(1, run_one);
      b = best_of(1, run_stepped);
    } else {
      b = best_of(1, run_stepped);
      a = best_of(1, run_one);
    }
    ratios.push_back(b.cpu / a.cpu);
    if (a.cpu < one.cpu) one = std::move(a);
    if (b.cpu < stepped.cpu) stepped = std::move(b);
  }
  std::sort(ratios.begin(), ratios.end());
  const double overhead = ratios[ratios.size() / 2] - 1.0;
  const bool identical = stepped.rows.data.size() == one.rows.data.size() &&
                         std::memcmp(stepped.rows.data.data(), one.rows.data.data(),
                                     one.rows.data.size() * sizeof(double)) == 0;

  const Model& m = *loop.model;
  const double a0 = parameter(m, "a0"), K_loop = parameter(m, "K_loop"), K_h = parameter(m, "K_h"),
               gamma0 = parameter(m, "gamma0"), k_e = parameter(m, "k_e"),
               el0 = parameter(m, "el0");
  const Timing in_loop = best_of(repeats, [&] {
    Stepper s(Dynamics(loop.compiled, loop.compiled->parameter_defaults), so, loop.compiled->q0,
              loop.compiled->v0);
    const Trajectory& r = s.record();
    const size_t width = r.columns.size(), az = r.column_index("wing.azimuth"),
                 el = r.column_index("wing.elevation"), hd = r.column_index("wing.heading");
    for (size_t k = 0; k < steps; ++k) {
      const double* row = r.data.data() + (r.rows() - 1) * width;
      const double azimuth = row[az], elevation = row[el], heading = row[hd];
      const double turn = (1 + std::tanh((std::abs(azimuth) - a0) / 0.02)) / 2;
      const double aim = std::tanh(heading / 0.05) * (M_PI / 2 + gamma0 + k_e * (elevation - el0));
      s.set_input("roll_cmd",
                  turn * K_loop * std::tanh(azimuth / 0.02) + (1 - turn) * K_h * (heading - aim));
      s.step(kPeriod);
    }
    return s.record();
  });

  const double az_one = one.rows.at(one.rows.rows() - 1, "wing.azimuth");
  const double az_loop = in_loop.rows.at(in_loop.rows.rows() - 1, "wing.azimuth");
  std::printf(
      "figure-eight kite, %g s flown at 20 Hz (%zu control steps), rtol %g, CPU s (best "
      "of %d)\n\n",
      t_end, steps, so.integrator.rtol, repeats);
  std::printf(
      "| run | CPU s | evaluations | real-time factor | overhead per control step |\n"
      "|---|---|---|---|---|\n");
  std::printf("| one simulate() call | %.4f | %ld | %.0f× | — |\n", one.cpu, one.evals,
              t_end / one.cpu);
  std::printf(
      "| stepped, no input set (rows %s) | %.4f | %ld | %.0f× | %.2f %% (%.2f µs; median "
      "of %d pairs) |\n",
      identical ? "bit-identical" : "DIFFER", stepped.cpu, stepped.evals, t_end / stepped.cpu,
      100.0 * overhead, 1e6 * overhead * one.cpu / static_cast<double>(steps), repeats);
  std::printf(
      "| in the loop, roll set every step | %.4f | %ld (%+.1f %%) | %.0f× | the hold's extra "
      "evaluations |\n",
      in_loop.cpu, in_loop.evals,
      100.0 * (static_cast<double>(in_loop.evals) / static_cast<double>(one.evals) - 1.0),
      t_end / in_loop.cpu);
  std::printf(
      "\nstepper_overhead_percent = %.2f\nfinal azimuth: file's law %.4f, in the loop %.4f\n",
      100.0 * overhead, az_one, az_loop);
  return identical ? 0 : 1;
}

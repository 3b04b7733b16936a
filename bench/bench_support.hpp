#pragma once
// Shared set-up of the benchmarks: a model read, derived, compiled and specialised, with the
// time each stage took.

#include <time.h>

#include <chrono>
#include <memory>
#include <string>
#include <vector>

#include "lagrange/compiled_model.hpp"
#include "lagrange/dynamics.hpp"
#include "lagrange/equations.hpp"
#include "lagrange/model.hpp"
#include "lagrange/reader.hpp"

namespace lagrange::bench {

/// Seconds spent in each stage of building a model from YAML text.
struct StageTimes {
  double read = 0.0, derive = 0.0, compile = 0.0, specialise = 0.0;
  /// derive + compile + specialise: what a user waits for after the file is read.
  double build() const { return derive + compile + specialise; }
};

/// Wall-clock and process CPU time together. CPU time is what the comparison with the
/// (single-threaded) SymPy peer should use when other jobs share the machine's cores.
class Stopwatch {
 public:
  struct Reading {
    double wall, cpu;
  };
  Reading now() const {
    timespec ts{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    const double cpu = static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
    const double wall =
        std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
    return {wall, cpu};
  }
};

/// A model carried through every stage. The Model is heap-allocated because Equations keeps a
/// pointer to it.
struct BuiltModel {
  std::unique_ptr<Model> model;
  Equations equations;
  std::shared_ptr<const CompiledModel> compiled;
  std::unique_ptr<Dynamics> dynamics;  ///< tapes specialised to the default parameters
  StageTimes times;                    ///< wall-clock seconds
  StageTimes cpu_times;                ///< process CPU seconds
};

/// A model read by `read()` (which returns a Model), derived in `form`, compiled and specialised,
/// each stage timed.
template <class Read>
BuiltModel build_with(Read&& read, Formulation form) {
  const Stopwatch clock;
  BuiltModel b;
  const auto t0 = clock.now();
  b.model = std::make_unique<Model>(read());
  const auto t1 = clock.now();
  b.equations = derive(*b.model, form);
  const auto t2 = clock.now();
  b.compiled = compile(b.equations);
  const auto t3 = clock.now();
  b.dynamics = std::make_unique<Dynamics>(b.compiled, b.compiled->parameter_defaults);
  const auto t4 = clock.now();
  b.times = {t1.wall - t0.wall, t2.wall - t1.wall, t3.wall - t2.wall, t4.wall - t3.wall};
  b.cpu_times = {t1.cpu - t0.cpu, t2.cpu - t1.cpu, t3.cpu - t2.cpu, t4.cpu - t3.cpu};
  return b;
}

/// build_with of YAML text (`label` names it in errors).
inline BuiltModel build_model(const std::string& yaml, const std::string& label,
                              Formulation form = Formulation::Lagrangian) {
  return build_with([&] { return read_model_string(yaml, label); }, form);
}

/// build_with of a model file (YAML or URDF).
inline BuiltModel build_model_file(const std::string& path,
                                   Formulation form = Formulation::Lagrangian) {
  return build_with([&] { return read_model_file(path); }, form);
}

/// What evaluates the tapes: machine code, as `lagrange simulate` runs once its cache holds the
/// model (compiled first when it does not), unless `interpreter`. Returns evaluation_note().
inline std::string choose_evaluation(BuiltModel& b, bool interpreter) {
  if (!interpreter) b.dynamics->set_evaluation(Evaluation::MachineCode);
  return b.dynamics->evaluation_note();
}

/// CPU seconds per Dynamics::forward call (KKT solve included) at the model's initial state,
/// after one warm-up call, averaged over at least 0.3 s of calls.
inline double forward_call_seconds(const BuiltModel& b) {
  const CompiledModel& cm = *b.compiled;
  std::vector<double> q = cm.q0, v = cm.v0, qdot(cm.nq), a(cm.nv), lambda(cm.m);
  b.dynamics->forward(0.0, q.data(), v.data(), qdot.data(), a.data(), lambda.data());
  const Stopwatch clock;
  long calls = 0;
  const auto c0 = clock.now();
  do {
    for (int i = 0; i < 100; ++i)
      b.dynamics->forward(0.0, q.data(), v.data(), qdot.data(), a.data(), lambda.data());
    calls += 100;
  } while (clock.now().cpu - c0.cpu < 0.3);
  return (clock.now().cpu - c0.cpu) / static_cast<double>(calls);
}

/// Instruction count of the dynamics tape after specialisation to the default parameters
/// (Dynamics keeps its specialised tape private; this repeats the same specialisation).
inline size_t specialised_instructions(const CompiledModel& cm) {
  return cm.dynamics.specialize(cm.p_offset(), cm.parameter_defaults).num_instructions();
}

}  // namespace lagrange::bench

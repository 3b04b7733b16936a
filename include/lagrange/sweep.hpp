#pragma once
// Parameter studies (docs/sweeps.md): the cases of a grid or of a seeded random sample, metrics
// over each case's trajectory, a pool of workers sharing one compiled model, and a summary file
// that a study interrupted part-way resumes without losing or repeating a case.

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <random>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "lagrange/compiled_model.hpp"
#include "lagrange/model.hpp"
#include "lagrange/reader.hpp"
#include "lagrange/simulation.hpp"
#include "lagrange/tape.hpp"

namespace lagrange::sweep {

/// A mistake in a study's description (a range, a distribution, a metric): the message says what
/// was given and what was expected.
struct StudyError : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

/// The most cases a study may have (docs/sweeps.md): its case list and summary are kept in memory,
/// a few hundred bytes a case; a larger grid or sample is refused before anything is allocated.
constexpr size_t kMaxStudyCases = 1000000;

/// One `--vary` axis: a parameter and the values it takes.
struct Axis {
  std::string name;
  std::vector<double> values;
};

/// `NAME=A:B:N` (N values evenly spaced from A to B, both included; N at most kMaxStudyCases) or
/// `NAME=V1,V2,…`; StudyError when a value is not a finite number.
Axis parse_axis(const std::string& spec);

/// A distribution a random parameter is drawn from (docs/theory.md §9.1).
struct Distribution {
  enum class Kind { Normal, Uniform, LogNormal } kind = Kind::Normal;
  double a = 0.0, b = 0.0;  ///< normal(μ, σ), uniform(low, high), lognormal(μ, σ) of log x
  std::string text;         ///< as written, e.g. "normal(1,0.1)"
};

/// One `--random` parameter.
struct RandomParameter {
  std::string name;
  Distribution distribution;
};

/// `NAME=normal(MU,SIGMA)`, `NAME=uniform(LOW,HIGH)` or `NAME=lognormal(MU,SIGMA)`.
RandomParameter parse_random(const std::string& spec);

/// One draw from `d` using `rng` (docs/theory.md §9.1): the same on every platform for a seed.
double sample(const Distribution& d, std::mt19937_64& rng);

/// One case of a study: its number (0-based, the row order of the summary) and parameter values.
struct Case {
  size_t index = 0;
  std::vector<std::pair<std::string, double>> values;  ///< grid axes first, then random ones
};

/// Every combination of the axes (the last axis varying fastest), each combined with `samples`
/// random draws when `random` is not empty (draws made in case order from one mt19937_64 seeded
/// with `seed`). StudyError when nothing varies, a name is given twice, the study would have more
/// than kMaxStudyCases cases, or a draw is not a finite number.
std::vector<Case> make_cases(const std::vector<Axis>& axes,
                             const std::vector<RandomParameter>& random, size_t samples,
                             std::uint64_t seed);

/// A number computed from one case's trajectory (docs/theory.md §9.2).
struct Metric {
  enum class Aggregate { Max, Min, Mean, Final, Initial, Drift } aggregate = Aggregate::Max;
  std::string name;        ///< the summary column
  std::string expression;  ///< aggregated: an expression of the columns and the parameters
  /// Samples with t > after (or ≥ when after_inclusive) and t < before (≤) count.
  std::optional<double> after, before;
  bool after_inclusive = false, before_inclusive = false;
  std::string text;  ///< as written
  /// `expression` compiled by bind_metrics over (columns, parameters); read-only, shared by
  /// the workers.
  std::shared_ptr<const Tape> tape;
  size_t columns = 0;  ///< of the trajectory it was bound to
};

/// `NAME=AGG(EXPR[, WINDOW])` or `AGG(EXPR[, WINDOW])` (then NAME is the text itself): AGG one
/// of max, min, mean, final, initial, drift (largest |x − first x|); EXPR an expression of the
/// trajectory's columns and the parameters (`abs(theta1)`, `sqrt(x^2 + y^2)`,
/// `main.tension_ground * wing.airspeed`); WINDOW a condition on t such as `t > 60` or
/// `t >= 5 and t < 10`. Errors start with `context` (default "--metric SPEC").
Metric parse_metric(const std::string& spec, const std::string& context = "");

/// Compiles each metric's expression over `columns` (a trajectory's) and `parameters`;
/// StudyError naming the metric and the unknown name or the syntax error.
void bind_metrics(std::vector<Metric>& metrics, const std::vector<std::string>& columns,
                  const std::vector<std::string>& parameters);

/// A study's metrics, bound to `cm`'s trajectory columns (or to `bound_to` when given: an
/// optimisation's trajectory, whose controls follow them) and parameters: the model file's
/// `metrics:` (errors located there, as ModelError) then those of `specs` (`--metric`; a name
/// given twice is a StudyError).
std::vector<Metric> study_metrics(const Model& model, const CompiledModel& cm,
                                  const std::vector<std::string>& specs,
                                  const std::vector<std::string>& bound_to = {});

/// The metric over `traj` with the case's `parameters` (NaN when no sample falls in its
/// window); the metric must be bound to `traj`'s columns.
double evaluate(const Metric& metric, const Trajectory& traj,
                const std::vector<double>& parameters = {});

/// A trajectory's row (its columns) at time t between samples, integrated from sample `row`.
using RowAt = std::function<std::vector<double>(size_t row, double t)>;

/// Rows between the samples of `traj`, a run of `dyn` with `options`: re-integrated from the
/// sample before with the run's integrator and tolerances, as stop conditions are located.
RowAt rows_between_samples(Dynamics& dyn, const SimulationOptions& options, const Trajectory& traj);

/// evaluate() with `max` and `min` located between samples (docs/theory.md §9.2): where the
/// samples peak inside the window, the extremum over the two intervals around that sample, by
/// golden-section search on rows from `row_at`, to 1e-10 (1 + |t|) in time.
double evaluate(const Metric& metric, const Trajectory& traj, const std::vector<double>& parameters,
                const RowAt& row_at);

/// What one case needs besides the shared compiled model.
struct CaseInput {
  std::vector<double> parameters, q0, v0;
  SimulationOptions options;
  double baumgarte = 0.0;
};

/// The parameter values, initial state and settings of `case_model` (the model file read with
/// the case's values) for `base`, the model compiled once for the study. StudyError when the
/// case's values change the model's structure (coordinates, constraints, parameters), which one
/// compiled model cannot follow.
CaseInput case_input(const Model& case_model, const CompiledModel& base,
                     const SimulationOptions& options);

/// Cases' inputs without reading the model file again (docs/theory.md §9.4): the parameters'
/// values put in, the checks the traced read made repeated and the initial values written as
/// expressions of them recomputed, each on a tape, as the reader computes them, bit for bit.
class ReplayedInputs {
 public:
  /// From `traced`, the model read with `trace` (which found nothing it cannot repeat: its
  /// `opaque` is empty), and `base`, that model's case_input.
  ReplayedInputs(const Model& traced, const ReadTrace& trace, CaseInput base);
  /// The inputs for the watched parameters at `values` (by name, each watched), or nothing when
  /// one of the read's checks comes out otherwise or a value is not a finite number: only a
  /// read of the file says then what the model makes of them. Safe to call from many threads.
  std::optional<CaseInput> operator()(
      const std::vector<std::pair<std::string, double>>& values) const;

 private:
  struct Check {
    std::shared_ptr<const Tape> tape;
    std::function<bool(double)> test;
    bool outcome = false;
  };
  struct Initial {
    std::shared_ptr<const Tape> tape;
    size_t coordinate = 0;
    bool rate = false;
  };
  CaseInput base_;
  std::vector<std::pair<std::string, size_t>> watched_;  ///< name, index in base_.parameters
  std::vector<Check> checks_;
  std::vector<Initial> initials_;
};

/// A case's inputs read from the model file with its values, or why it rejects them.
struct CaseRead {
  std::optional<CaseInput> input;
  std::string rejected;        ///< why the model file rejects the values (when input is empty)
  double read_seconds = -1.0;  ///< the model file's read time, or negative when not read
};

/// How one case ended.
struct CaseResult {
  size_t index = 0;
  Trajectory::Status status = Trajectory::Status::Complete;
  std::string reason;  ///< why it failed (empty when complete)
  double failure_time = 0.0;
  std::vector<double> metrics;
  double wall_seconds = 0.0;
  double read_seconds = -1.0;  ///< the CaseRead's, passed on by the pools
};

/// Runs one case on `dyn` (a workspace over the study's compiled model): sets its parameters
/// (no new derivation), makes its initial state consistent and simulates, as `simulate --set`
/// does, so the numbers are the same bit for bit. Never throws for a failing case. `kept`, when
/// given, receives the trajectory.
CaseResult run_case(Dynamics& dyn, const CaseInput& input, const std::vector<Metric>& metrics,
                    Trajectory* kept = nullptr);

/// run_case on `read.input`, or, when the model file rejected the case's values, a failed
/// result giving `read.rejected` as the reason (metrics NaN, nothing kept).
CaseResult run_case(Dynamics& dyn, const CaseRead& read, const std::vector<Metric>& metrics,
                    Trajectory* kept = nullptr);

/// Runs the cases numbered `pending` (indices into `inputs`) on `workers` threads, each with its
/// own Dynamics over `model`, handing each a new case when it finishes one (cases differ in
/// cost). `done` is called for each finished case, one call at a time, from any thread; cases
/// stopped by `interrupt` are not reported. `keep`, when set, receives each trajectory first.
struct PoolOptions {
  size_t workers = 1;
  const std::atomic<bool>* interrupt = nullptr;
  std::function<void(const CaseResult&)> done;
  std::function<void(size_t index, const Trajectory&)> keep;
  /// When set, each case is read by this on the worker that runs it (`inputs` is then not
  /// used), called by several workers at once: it serialises what is not thread-safe itself
  /// (the model reader's GiNaC); a rejected case is reported as failed with the reason.
  std::function<CaseRead(size_t index)> read;
  /// What evaluates each worker's tapes: SharedMachineCode compiles (or loads from the cache)
  /// one library that serves every case whose values fold alike (docs/theory.md §8).
  Evaluation evaluation = Evaluation::Interpreter;
  /// When set, a workspace over `model` with `evaluation` already chosen, which the calling
  /// thread's worker (and every worker process, each on its own copy) runs its cases on instead
  /// of making one: a worker's set-up (tapes specialised, machine code loaded) is then paid once.
  Dynamics* workspace = nullptr;
};
void run_pool(const std::shared_ptr<const CompiledModel>& model,
              const std::vector<CaseInput>& inputs, const std::vector<size_t>& pending,
              const std::vector<Metric>& metrics, const PoolOptions& options);

/// A worker process that died from a signal (SIGKILL from the out-of-memory killer, say): the case
/// it was running, if any, and the signal; run_pool_processes throws it after the other workers
/// have finished their cases.
struct WorkerDied : std::runtime_error {
  WorkerDied(const std::string& what, std::optional<size_t> running, int signal)
      : std::runtime_error(what), index(running), signal(signal) {}
  std::optional<size_t> index;  ///< the case it was running (none: it died between cases)
  int signal;
};

/// As run_pool, each worker a process forked from this one (docs/sweeps.md, "Speed"): a
/// single-threaded worker allocates without glibc's locks, as a lone run does. `read` and `keep`
/// run in the workers, `done` here; a worker's exception, its death (WorkerDied) or `done`'s
/// exception stops the others after their case and is thrown here (else std::runtime_error); this
/// process's
/// interrupt is passed on to them. run_pool (threads) for fewer than two workers, or when this
/// process has other threads (whose locks a fork would copy held).
void run_pool_processes(const std::shared_ptr<const CompiledModel>& model,
                        const std::vector<CaseInput>& inputs, const std::vector<size_t>& pending,
                        const std::vector<Metric>& metrics, const PoolOptions& options);

/// Makes this process keep the memory that cases free for the next ones (glibc: no unmapping,
/// no trimming; docs/sweeps.md, "Speed"), for a process that runs a study.
void keep_freed_memory();

/// The study's summary table, one CSV row per case, appended as each case finishes: a row is
/// one write() of a whole line, and a line without its end (the process died while writing) is
/// cut off on resume; finish() rewrites the table in case order through an atomic rename.
class SummaryFile {
 public:
  /// Opens `path` for the columns `header`. Without `resume` the file must not exist (a
  /// std::runtime_error says so); with it, the rows already there are kept (a different header
  /// is a std::runtime_error, as is a row without a case number or repeating one) and their case
  /// numbers are returned by done(). A new file is
  /// written by the first append() or finish() (with worker processes, while the first cases
  /// run), after `before_first_write` (the study's record, say), which an existing file runs at
  /// once. With `repeats_replace` a later row of a case replaces its earlier one (an optimisation
  /// study's improved cases) instead of being refused.
  SummaryFile(const std::string& path, std::vector<std::string> header, bool resume,
              std::function<void()> before_first_write = {}, bool repeats_replace = false);
  ~SummaryFile();
  SummaryFile(const SummaryFile&) = delete;
  SummaryFile& operator=(const SummaryFile&) = delete;

  const std::set<size_t>& done() const { return done_; }
  /// Appends the row of case `index` (fields already formatted, the first being the index).
  void append(size_t index, const std::vector<std::string>& fields);
  /// Rewrites the file with its rows sorted by case number.
  void finish();

 private:
  std::string path_;
  std::vector<std::string> header_;
  std::set<size_t> done_;
  std::function<void()> before_first_write_;
  int fd_ = -1;

  void open_for_appending();
};

/// A summary field: doubles as `{:.17g}` (they read back to the same bits), text quoted when it
/// holds a comma, a quote or a line break.
std::string csv_field(double value);
std::string csv_field(const std::string& text);

}  // namespace lagrange::sweep

// `lagrange sweep`: a parameter study (docs/sweeps.md). Everything the command line says is
// checked, and every case's model read, before the first case runs or anything is written; then a
// pool of workers shares the one compiled model, or, under mpirun, rank 0 hands the cases to the
// other ranks (cli/sweep_mpi.hpp).

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <optional>
#include <sstream>
#include <thread>

#include "cli/commands.hpp"
#include "cli/interrupt.hpp"
#include "cli/optimal_sweep.hpp"
#include "cli/optimize_options.hpp"
#include "cli/plot_check.hpp"
#include "cli/prepare.hpp"
#include "cli/study_lock.hpp"
#include "cli/study_record.hpp"
#include "cli/sweep_inputs.hpp"
#include "lagrange/dynamics.hpp"
#include "lagrange/error.hpp"
#include "lagrange/io.hpp"
#include "lagrange/reader.hpp"
#include "lagrange/report.hpp"
#include "lagrange/sweep.hpp"

#ifdef LAGRANGE_HAVE_MPI
#include "cli/sweep_mpi.hpp"
#include "support/seconds_since.hpp"
#endif

namespace lagrange::cli {

namespace {

using Clock = std::chrono::steady_clock;
namespace fs = std::filesystem;

// Started by mpirun (OpenMPI's or a PMI launcher's environment) with more than one rank.
bool started_by_mpirun() {
  for (const char* var : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE"})
    if (const char* v = std::getenv(var); v && std::atoi(v) > 1) return true;
  return false;
}

struct StudyPlan {
  std::vector<sweep::Case> cases;
  std::vector<sweep::Metric> metrics;
};

StudyPlan plan(const Options& opt) {
  StudyPlan plan;
  try {
    std::vector<sweep::Axis> axes;
    std::vector<sweep::RandomParameter> random;
    for (const auto& v : opt.vary) axes.push_back(sweep::parse_axis(v));
    for (const auto& r : opt.random) random.push_back(sweep::parse_random(r));
    if (opt.samples > 0 && random.empty())
      throw sweep::StudyError("--samples draws the --random parameters; give --random too");
    plan.cases = sweep::make_cases(axes, random, opt.samples, opt.seed);
    for (const auto& m : opt.metrics) sweep::parse_metric(m);  // checked before the model is read
  } catch (const sweep::StudyError& e) {
    throw UsageError(e.what());
  }
  return plan;
}

// The summary row of a finished case: number, values, status, reason, failure time, metrics, wall
// time.
std::vector<std::string> row_fields(const sweep::Case& c, const sweep::CaseResult& r) {
  std::vector<std::string> row{std::to_string(c.index)};
  for (const auto& [name, value] : c.values) row.push_back(sweep::csv_field(value));
  const bool ok = r.status == Trajectory::Status::Complete;
  row.emplace_back(ok ? "ok" : "failed");
  row.push_back(sweep::csv_field(r.reason));
  row.push_back(ok ? "" : sweep::csv_field(r.failure_time));
  for (const double x : r.metrics) row.push_back(sweep::csv_field(x));
  row.push_back(fmt::format("{:.6f}", r.wall_seconds));
  return row;
}

// Everything checked before a case runs: the plan, the model derived and compiled once, the
// settings every case shares and the summary's columns. The cases' inputs come from one traced
// read of the model file when it can give them (cli/sweep_inputs.hpp), else the workers read the
// file for each case.
struct Study {
  StudyPlan plan;
  Prepared prepared;
  RunSettings settings;
  CaseInputSource from;
  std::vector<std::string> header;
  Evaluation evaluation = Evaluation::Interpreter;  ///< the workers'
  StudyReplay replay;

  Study() = default;
  Study(const Study&) = delete;  // `from` refers to `prepared`
  Study& operator=(const Study&) = delete;
};

// --optimize: a model with an optimal_control section, none of simulate's settings (the
// transcription has its own time grid).
void check_optimization(const Options& opt, const Prepared& p) {
  if (!p.model->optimal_control)
    throw UsageError(
        fmt::format("--optimize: {} has no optimal_control section (docs/model-language.md, "
                    "\"Optimal control\")",
                    opt.model));
  for (const auto& [given, option] : {std::pair{opt.t_end.has_value(), "--t-end"},
                                      {opt.output_step.has_value(), "--output-step"},
                                      {opt.integrator.has_value(), "--integrator"},
                                      {opt.rtol.has_value(), "--rtol"},
                                      {opt.atol.has_value(), "--atol"},
                                      {opt.step.has_value(), "--step"},
                                      {opt.max_order.has_value(), "--max-order"}})
    if (given)
      throw UsageError(fmt::format(
          "{} is a simulation setting; with --optimize each case is solved by collocation "
          "(--intervals, --degree, --ipopt set it)",
          option));
}

// --plot FILE: one varied parameter to plot against, an image format gnuplot writes.
void check_plot(const Options& opt) {
  if (opt.plot.empty()) return;
  if (opt.vary.size() != 1 || !opt.random.empty())
    throw UsageError(
        "--plot draws the summary against one parameter: give one --vary and no --random");
  checked_plot_format(opt.plot, [](PlotFormat) { return "plot STUDY/summary.csv yourself"; });
}

void set_up(const Options& opt, Study& s) {
  if (!opt.optimize &&
      (opt.intervals > 0 || opt.degree > 0 || !opt.ipopt.empty() || opt.hessian != "auto"))
    throw UsageError("--intervals, --degree, --ipopt and --hessian apply to --optimize");
  s.plan = plan(opt);
  const ParameterOverrides sets = parse_sets(opt.sets);
  for (const auto& [name, value] : s.plan.cases.front().values)
    if (sets.count(name))
      throw UsageError(
          fmt::format("--set {}: the parameter is varied (--vary or --random), which "
                      "would override the value set; give one or the other",
                      name));
  // Collocation needs the Lagrangian form (as `lagrange optimize` derives it).
  s.prepared =
      prepare(opt.model, opt.sets, {}, "--initial", opt.optimize ? "lagrangian" : opt.dynamics);
  const Prepared& p = s.prepared;
  for (const auto& [name, value] : s.plan.cases.front().values)
    if (p.model->parameter_index(name) < 0) {
      std::string known;
      for (const auto& par : p.model->parameters) known += (known.empty() ? "" : ", ") + par.name;
      throw UsageError(fmt::format("no parameter '{}' in {} (parameters: {})", name, opt.model,
                                   known.empty() ? "none" : known));
    }
  if (opt.optimize) check_optimization(opt, p);
  try {
    s.plan.metrics = sweep::study_metrics(
        *p.model, *p.compiled, opt.metrics,
        opt.optimize ? optimal_trajectory_columns(p) : std::vector<std::string>{});
  } catch (const sweep::StudyError& e) {
    throw UsageError(e.what());
  }
  s.settings = {opt.t_end, opt.output_step, opt.rtol,     opt.atol,
                opt.step,  opt.integrator,  opt.max_order};
  simulation_options(*p.model, s.settings);  // a bad --t-end or tolerance: refused up front
  s.header = {"case"};
  for (const auto& [name, value] : s.plan.cases.front().values) s.header.push_back(name);
  if (opt.optimize) {  // docs/sweeps.md, "Optimal control"
    for (const auto& m : s.plan.metrics)
      if (std::count(kOptimalColumns.begin(), kOptimalColumns.end(), m.name) ||
          std::count(kOptimalTrailingColumns.begin(), kOptimalTrailingColumns.end(), m.name))
        throw UsageError(fmt::format(
            "metric '{}' is named like a column every optimisation study has; give it another "
            "name",
            m.name));
    s.header.insert(s.header.end(), kOptimalColumns.begin(), kOptimalColumns.end());
    for (const auto& m : s.plan.metrics) s.header.push_back(sweep::csv_field(m.name));
    s.header.insert(s.header.end(), kOptimalTrailingColumns.begin(), kOptimalTrailingColumns.end());
  } else {
    for (const char* c : {"status", "reason", "failure_time"}) s.header.emplace_back(c);
    for (const auto& m : s.plan.metrics) s.header.push_back(sweep::csv_field(m.name));
    s.header.emplace_back("wall_s");
  }
  check_plot(opt);
  // A case's inputs from its model read: its settings, the Jacobian derived once.
  s.from = {ModelSource{opt.model, std::nullopt}, parse_sets(opt.sets),
            [&p = s.prepared, &settings = s.settings](const Model& m) {
              SimulationOptions so = simulation_options(m, settings);
              so.jacobian_source = jacobian_source(p, so.integrator.method);
              return sweep::case_input(m, *p.compiled, so);
            }};
  std::vector<CaseValues> values;
  for (const sweep::Case& c : s.plan.cases) values.push_back(c.values);
  s.replay = replay_study(s.from, values);
  if (!s.replay.warning.empty()) fmt::print(stderr, "warning: {}\n", s.replay.warning);
}

// Case `index`'s inputs from the study's one read, or nothing when the file must say.
// Thread-safe.
std::optional<sweep::CaseRead> replayed_case(const Study& s, size_t index) {
  if (!s.replay.inputs) return std::nullopt;
  std::optional<sweep::CaseInput> input = (*s.replay.inputs)(s.plan.cases.at(index).values);
  if (!input) return std::nullopt;
  sweep::CaseRead r;
  r.input = std::move(input);
  return r;
}

// Case `index`'s inputs, read from the model file when the study's one read does not give them
// (not thread-safe then: GiNaC).
sweep::CaseRead case_inputs(const Study& s, size_t index) {
  if (std::optional<sweep::CaseRead> r = replayed_case(s, index)) return std::move(*r);
  return read_case_inputs(s.from, s.plan.cases.at(index).values);
}

// --compile auto or on: machine code with the tapes' constants in memory, built (or loaded)
// here with the study's default values so that the workers load it from the cache; the
// interpreter when it cannot be had. `build` false: the workers build it (MPI ranks 1 …, which
// wait for their first case until rank 0 has built it).
void choose_evaluation(const Options& opt, Study& s, bool build) {
  if (opt.compile == "off") return;
  s.evaluation = Evaluation::SharedMachineCode;
  if (!build) return;
  MachineCodeOptions options;  // Ctrl-C stops the compiler; the study then ends keeping its rows
  const auto interrupted = [&] { return opt.interrupt != nullptr && opt.interrupt->load(); };
  options.interrupted = interrupted;
  s.prepared.dynamics->set_evaluation(Evaluation::SharedMachineCode, options);
  if (s.prepared.dynamics->uses_machine_code()) return;
  s.evaluation = Evaluation::Interpreter;
  if (opt.compile == "on" && !interrupted())
    fmt::print(stderr, "warning: machine code: {}; the tape interpreter runs instead\n",
               s.prepared.dynamics->machine_code_error());
}

#ifdef LAGRANGE_HAVE_MPI
// A worker's cases under MPI (rank 0's own and the other ranks'): each read, run on the
// worker's Dynamics and turned into its summary row, its trajectory written when kept.
class CaseRunner {
 public:
  CaseRunner(const Options& opt, const Study& s)
      : opt_(opt), s_(s), dyn_(s.prepared.compiled, s.prepared.compiled->parameter_defaults) {}
  // False when the case was interrupted (no row then).
  bool operator()(size_t index, std::vector<std::string>& fields) {
    if (s_.evaluation != Evaluation::Interpreter && !evaluation_set_) {
      dyn_.set_evaluation(s_.evaluation);  // from the cache rank 0 filled before the first case
      evaluation_set_ = true;
    }
    sweep::CaseRead read = case_inputs(s_, index);
    if (read.input) read.input->options.interrupt = opt_.interrupt;
    const bool keep = opt_.keep_trajectories && read.input;
    sweep::CaseResult r = sweep::run_case(dyn_, read, s_.plan.metrics, keep ? &traj_ : nullptr);
    if (r.status == Trajectory::Status::Interrupted) return false;
    if (keep)
      write_trajectory_csv(traj_,
                           (fs::path(opt_.study) / fmt::format("case_{}.csv", index)).string());
    fields = row_fields(s_.plan.cases[index], r);
    return true;
  }

 private:
  const Options& opt_;
  const Study& s_;
  Dynamics dyn_;
  Trajectory traj_;
  bool evaluation_set_ = false;
};
#endif

// The study directory's summary, with `lock` taken on the directory; a UsageError when it cannot
// be made, another study runs there or holds it, or --resume is given for a study started with
// other options or whose study.txt is gone.
std::unique_ptr<sweep::SummaryFile> open_summary(const Options& opt, const Study& s,
                                                 std::unique_ptr<StudyLock>& lock) {
  const fs::path about = fs::path(opt.study) / "study.txt";
  const std::string text = study_record(opt, *s.prepared.compiled, s.plan.metrics);
  try {
    fs::create_directories(opt.study);
    lock = std::make_unique<StudyLock>(opt.study);
    if (opt.resume && !fs::exists(about) && fs::exists(fs::path(opt.study) / "summary.csv"))
      throw UsageError(
          fmt::format("--resume: {} has a summary.csv but no study.txt, which says "
                      "which study it holds; it cannot be finished",
                      opt.study));
    if (opt.resume && fs::exists(about)) {
      std::ifstream in(about, std::ios::binary);
      std::stringstream was;
      was << in.rdbuf();
      if (was.str() != text)
        throw UsageError(fmt::format(
            "--resume: {} was started with other options or another model; the same command "
            "with --resume finishes it, over the same model file. What differs:\n{}",
            opt.study, record_changes(was.str(), text)));
    }
    // study.txt, then the summary's header, are written when the first row is (while the first
    // cases run), or at once when resuming.
    auto summary = std::make_unique<sweep::SummaryFile>(
        (fs::path(opt.study) / "summary.csv").string(), s.header, opt.resume,
        [about, text] { write_file_atomically(about.string(), text); }, opt.optimize);
    for (const size_t index : summary->done())
      if (index >= s.plan.cases.size())
        throw UsageError(
            fmt::format("--resume: {}/summary.csv has a row of case {}, beyond this "
                        "study's {} cases (edited by hand?)",
                        opt.study, index, s.plan.cases.size()));
    return summary;
  } catch (const UsageError&) {
    throw;
  } catch (const std::exception& e) {
    throw UsageError(fmt::format("-o {}: {}", opt.study, e.what()));
  }
}

// Progress on a terminal and the counts, as rows reach the summary.
class Progress {
 public:
  Progress(const Options& opt, size_t total, size_t already)
      : show_(!opt.quiet && opt.terminal), total_(total), already_(already), done_(already) {}
  void add(bool ok) {
    ++done_;
    if (!ok) ++failed_;
    const auto now = Clock::now();
    if (!show_ || (std::chrono::duration<double>(now - last_).count() < 0.2 && done_ < total_))
      return;
    last_ = now;
    const double rate = static_cast<double>(done_ - already_) / seconds_since(start_);
    fmt::print(stderr, "\r  {} / {} cases, {} failed, {:.1f} cases/s, {:.0f} s left   ", done_,
               total_, failed_, rate, static_cast<double>(total_ - done_) / rate);
  }
  void clear() const {
    if (show_) fmt::print(stderr, "\r{:70}\r", "");
  }
  size_t done() const { return done_; }
  size_t failed() const { return failed_; }
  double seconds() const { return seconds_since(start_); }

 private:
  bool show_;
  size_t total_, already_, done_, failed_ = 0;
  Clock::time_point start_ = Clock::now(), last_ = start_;
};

// The cases still to run: those not in the summary.
std::vector<size_t> pending_cases(const Study& s, const sweep::SummaryFile& summary) {
  std::vector<size_t> pending;
  for (size_t i = 0; i < s.plan.cases.size(); ++i)
    if (!summary.done().count(i)) pending.push_back(i);
  return pending;
}

// How many cases' model files the workers read, and in what time.
struct Reading {
  size_t files = 0;
  double seconds = 0.0;
};

// Where the cases' inputs came from, for the summary line: ", …" or "".
std::string reading_note(const Study& s, const Reading& r) {
  if (s.replay.inputs)
    return r.files == 0 ? ", the cases' inputs from one read of the model file"
                        : fmt::format(
                              ", the cases' inputs from one read of the model file, {} "
                              "read again ({:.3f} s)",
                              r.files, r.seconds);
  return fmt::format(", {:.3f} s of it reading the cases' model files ({})", r.seconds,
                     s.replay.not_replayed);
}

// The end of a study on rank 0 or the one machine: 130 when interrupted, else the table sorted.
// `reading`: the workers' reads of the cases' model files, when counted.
int conclude(const Options& opt, const Study& s, sweep::SummaryFile& summary,
             const Progress& progress, size_t already, const std::string& workers,
             std::optional<Reading> reading) {
  const fs::path path = fs::path(opt.study) / "summary.csv";
  const size_t total = s.plan.cases.size();
  progress.clear();
  if (progress.done() < total) {
    fmt::print(stderr,
               "lagrange: interrupted: {} of {} cases are in {}; run the same command with "
               "--resume to finish the others\n",
               progress.done(), total, path.string());
    return 130;
  }
  summary.finish();
  if (!opt.quiet) {
    const size_t ran = total - already;
    fmt::print("{}: {} cases ({} run now, {} of them failed) on {}\n", s.prepared.model->name,
               total, ran, progress.failed(), workers);
    fmt::print("  tapes: {}\n", s.evaluation == Evaluation::Interpreter
                                    ? std::string("interpreter")
                                    : s.prepared.dynamics->evaluation_note());
    fmt::print("  derive {:.3f} s and compile {:.3f} s once, run {:.3f} s ({:.1f} cases/s{})\n",
               s.prepared.derive_seconds, s.prepared.compile_seconds, progress.seconds(),
               static_cast<double>(ran) / std::max(progress.seconds(), 1e-9),
               reading ? reading_note(s, *reading) : "");
    fmt::print("  wrote {}\n", path.string());
  }
  return 0;
}

constexpr int kWorkerDied = 4;  // the exit code of a study whose worker process died

// A worker process that died (issue 37 item 20): which case it was running, why, and what is
// kept; exit 4 (docs/errors.md).
int worker_died(const Options& opt, const Study& s, const Progress& progress,
                const sweep::WorkerDied& e) {
  progress.clear();
  std::string running;
  if (e.index)
    for (const auto& [name, value] : s.plan.cases.at(*e.index).values)
      running += fmt::format("{}{} = {:g}", running.empty() ? " (" : ", ", name, value);
  if (!running.empty()) running += ")";
  fmt::print(stderr,
             "lagrange: the study stopped: {}{}; {} of {} cases are in {}; run the same command "
             "with --resume to run the others{}\n",
             e.what(), running, progress.done(), s.plan.cases.size(),
             (fs::path(opt.study) / "summary.csv").string(),
             e.signal == SIGKILL
                 ? " (SIGKILL comes from outside the process: the kernel's out-of-memory killer, "
                   "say)"
                 : "");
  return kWorkerDied;
}

#ifdef LAGRANGE_HAVE_MPI
// Under mpirun: every rank sets the study up (the same checks, so a mistake stops them all
// alike; rank 0 alone reports it); rank 0 hands out the cases, runs cases itself between
// requests and writes the summary.
int run_sweep_mpi(const Options& opt) {
  MpiSession mpi;
  if (mpi.rank() != 0) {
    std::optional<Study> s;
    try {
      s.emplace();
      set_up(opt, *s);
      choose_evaluation(opt, *s, false);
    } catch (const std::exception&) {
      return 2;  // rank 0 meets the same mistake and reports it
    }
    CaseRunner run(opt, *s);
    mpi_work(std::ref(run));
    return 0;
  }
  Study s;
  set_up(opt, s);
  std::unique_ptr<StudyLock> lock;
  std::unique_ptr<sweep::SummaryFile> summary;
  try {
    summary = open_summary(opt, s, lock);
    choose_evaluation(opt, s, true);
  } catch (const UsageError&) {
    mpi_hand_out(mpi, {}, opt.interrupt, {}, {});  // the workers stop at once
    throw;
  }
  const size_t already = summary->done().size();
  Progress progress(opt, s.plan.cases.size(), already);
  CaseRunner run(opt, s);
  mpi_hand_out(mpi, pending_cases(s, *summary), opt.interrupt, std::ref(run),
               [&](size_t index, const std::vector<std::string>& fields) {
                 summary->append(index, fields);
                 progress.add(fields.at(s.header.size() - 1 - s.plan.metrics.size() - 3) == "ok");
               });
  return conclude(opt, s, *summary, progress, already,
                  fmt::format("{} MPI ranks (rank 0 handing out and running cases)", mpi.size()),
                  std::nullopt);
}
#endif

// The study is written (its summary published, or its rows kept when interrupted): the process
// ends with `code` at once, its output flushed, without taking apart the derived model, GiNaC's
// tables and the loaded machine code. That teardown writes to hundreds of pages, each a page
// fault (10-25 µs on a virtual machine), after fork made them copy-on-write: ~10 ms of a short
// study (docs/sweeps.md, "Speed"). Under AddressSanitizer the process ends normally, so that
// LeakSanitizer still checks it.
int end_process(int code) {
#if defined(__SANITIZE_ADDRESS__)
  return code;
#else
  std::fflush(nullptr);
  std::_Exit(code);
#endif
}

// A summary line's fields (RFC 4180: a quoted field may hold commas and doubled quotes).
std::vector<std::string> csv_fields(const std::string& line) {
  std::vector<std::string> out(1);
  bool quoted = false;
  for (size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted && c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
      out.back() += '"';
      ++i;
    } else if (c == '"') {
      quoted = !quoted;
    } else if (c == ',' && !quoted) {
      out.emplace_back();
    } else {
      out.back() += c;
    }
  }
  return out;
}

// --plot: the objective (with --optimize) and the metrics of the cases that succeeded, from
// STUDY/summary.csv, against the one varied parameter (docs/sweeps.md, "Optimal control").
void plot_summary(const Options& opt, const Study& s) {
  const auto column = [&](const std::string& name) {
    return static_cast<size_t>(std::find(s.header.begin(), s.header.end(), name) -
                               s.header.begin());
  };
  std::vector<std::string> names{s.header.at(1)};
  std::vector<size_t> ys;
  if (opt.optimize) {
    names.emplace_back("objective");
    ys.push_back(column("objective"));
  }
  for (const auto& m : s.plan.metrics) {
    names.push_back(m.name);
    ys.push_back(column(sweep::csv_field(m.name)));
  }
  if (ys.empty()) {
    fmt::print(stderr, "warning: --plot: nothing to plot (no metric)\n");
    return;
  }
  const size_t status = column("status");
  std::ifstream in(fs::path(opt.study) / "summary.csv");
  std::string line;
  std::getline(in, line);  // the header
  std::vector<double> table;
  while (std::getline(in, line)) {
    const std::vector<std::string> f = csv_fields(line);
    if (f.size() != s.header.size()) continue;
    table.push_back(std::strtod(f[1].c_str(), nullptr));
    for (const size_t y : ys)
      table.push_back(f[status] == "ok" ? std::strtod(f[y].c_str(), nullptr) : std::nan(""));
  }
  const std::string title =
      opt.optimize
          ? fmt::format("{}: {} {}", s.prepared.model->name,
                        s.prepared.model->optimal_control->maximize ? "maximize" : "minimize",
                        s.prepared.model->optimal_control->objective_text)
          : s.prepared.model->name;
  plot_columns(names, table, opt.plot, title);
}

// An optimisation study (docs/sweeps.md, "Optimal control"): the cases solved one after
// another in one process, each started from the nearest solution found before it.
int run_optimal_sweep(const Options& opt) {
  Study s;
  set_up(opt, s);
  if (opt.jobs > 1)
    fmt::print(stderr,
               "warning: --optimize solves the cases one after another, each started from the "
               "nearest solved case (docs/sweeps.md, \"Optimal control\"): -j {} does not "
               "apply\n",
               opt.jobs);
  std::unique_ptr<StudyLock> lock;
  const KeepWorkOnInterrupt keep;  // Ctrl-C: the running case finishes, the rows are kept
  const auto summary = open_summary(opt, s, lock);
  choose_evaluation(opt, s, true);
  const size_t already = summary->done().size();
  Progress progress(opt, s.plan.cases.size(), already);
  OptimalStudy study;
  study.prepared = &s.prepared;
  study.options = optimize_options(opt);
  study.options.verbose = false;
  study.metrics = s.plan.metrics;
  study.guess_path = (fs::path(opt.study) / ".warm_start.csv").string();
  // A resumed study starts from the solutions an earlier run kept (--keep-trajectories).
  const std::vector<size_t> attempted(summary->done().begin(), summary->done().end());
  std::map<size_t, Trajectory> solved;
  for (const size_t i : attempted) {
    const fs::path kept = fs::path(opt.study) / fmt::format("case_{}.csv", i);
    if (!fs::exists(kept)) continue;
    try {
      Trajectory t = read_trajectory_csv(kept.string());
      if (t.status == Trajectory::Status::Complete) solved.emplace(i, std::move(t));
    } catch (const std::exception&) {
      // not a solution to start from: the case nearest it starts from another
    }
  }
  // The first case is the one nearest the model file's own values, which its guess is for.
  std::vector<double> origin;
  for (const auto& [name, value] : s.plan.cases.front().values)
    origin.push_back(s.prepared.model->parameters
                         .at(static_cast<size_t>(s.prepared.model->parameter_index(name)))
                         .value);
  const std::vector<size_t> order =
      warm_start_order(s.plan.cases, pending_cases(s, *summary), origin, attempted);
  Reading reading;
  const auto read = [&](size_t index) {
    if (std::optional<sweep::CaseRead> r = replayed_case(s, index)) return std::move(*r);
    const auto start = Clock::now();
    sweep::CaseRead r = read_case_inputs(s.from, s.plan.cases.at(index).values);
    ++reading.files;
    reading.seconds += seconds_since(start);
    return r;
  };
  const auto done = [&](const OptimalCaseResult& r, const Trajectory& traj) {
    if (opt.keep_trajectories && traj.rows() > 0)
      write_trajectory_csv(traj,
                           (fs::path(opt.study) / fmt::format("case_{}.csv", r.index)).string());
    const sweep::Case& c = s.plan.cases[r.index];
    std::vector<std::string> row{std::to_string(c.index)};
    for (const auto& [name, value] : c.values) row.push_back(sweep::csv_field(value));
    row.emplace_back(r.optimal ? "ok" : "failed");
    row.push_back(sweep::csv_field(reason_text(r)));
    for (const double x : {r.objective, r.horizon}) row.push_back(sweep::csv_field(x));
    row.push_back(std::to_string(r.iterations));
    row.push_back(sweep::csv_field(r.violation));
    row.push_back(r.started_from ? std::to_string(*r.started_from) : "");
    for (const double x : r.metrics) row.push_back(sweep::csv_field(x));
    row.push_back(fmt::format("{:.6f}", r.solve_seconds));
    row.push_back(fmt::format("{:.6f}", r.wall_seconds));
    summary->append(r.index, row);  // an improved case again: its new row replaces the first
    if (r.improved.empty()) progress.add(r.optimal);
  };
  run_optimal_cases(study, *s.prepared.dynamics, s.plan.cases, order, read, solved, done,
                    opt.interrupt);
  for (const std::string& f : {study.guess_path, study.guess_path + ".json"}) fs::remove(f);
  const int code = conclude(opt, s, *summary, progress, already,
                            "1 worker (each case started from the nearest solved one)", reading);
  if (code == 0 && !opt.plot.empty()) {
    plot_summary(opt, s);
    if (!opt.quiet) fmt::print("  plotted {}\n", opt.plot);
  }
  return code;
}

}  // namespace

int run_sweep(const Options& opt) {
  sweep::keep_freed_memory();
  if (opt.optimize && started_by_mpirun())
    throw UsageError(
        "--optimize solves the cases one after another, each started from a neighbour's "
        "solution: run it without mpirun");
#ifdef LAGRANGE_HAVE_MPI
  if (started_by_mpirun()) {
    const KeepWorkOnInterrupt keep;  // an interrupted study keeps its finished cases
    return run_sweep_mpi(opt);
  }
#else
  if (started_by_mpirun())
    throw UsageError(
        "sweep was started by mpirun with several ranks, but this lagrange was built without "
        "MPI: every rank would run the whole study. Run it without mpirun (it uses every core; "
        "-j N chooses), or build lagrange with OpenMPI (libopenmpi-dev) installed");
#endif
  if (opt.optimize) return end_process(run_optimal_sweep(opt));
  Study s;
  set_up(opt, s);
  std::unique_ptr<StudyLock> lock;
  // From here an interrupted study keeps its finished cases, and a compile under way is stopped
  // and cleaned up (a compiler left by _exit would stay behind, with its source in the cache);
  // before, while the study derives, Ctrl-C ends it at once with 130, as simulate (issue 37
  // item 10).
  const KeepWorkOnInterrupt keep;
  const auto summary = open_summary(opt, s, lock);
  choose_evaluation(opt, s, true);
  const size_t already = summary->done().size();
  Progress progress(opt, s.plan.cases.size(), already);
  Reading reading;       // counted as rows reach the summary
  std::mutex read_lock;  // one model read at a time: GiNaC is not thread-safe
  sweep::PoolOptions pool;
  pool.workers = opt.jobs > 0 ? opt.jobs : std::max(1u, std::thread::hardware_concurrency());
  pool.interrupt = opt.interrupt;
  pool.evaluation = s.evaluation;
  pool.workspace = s.prepared.dynamics.get();  // its evaluation chosen as the workers'
  pool.read = [&](size_t index) {
    if (std::optional<sweep::CaseRead> r = replayed_case(s, index)) return std::move(*r);
    const std::lock_guard<std::mutex> lock(read_lock);
    const auto start = Clock::now();
    sweep::CaseRead r = read_case_inputs(s.from, s.plan.cases.at(index).values);
    r.read_seconds = seconds_since(start);
    return r;
  };
  pool.done = [&](const sweep::CaseResult& r) {
    summary->append(r.index, row_fields(s.plan.cases[r.index], r));
    progress.add(r.status == Trajectory::Status::Complete);
    if (r.read_seconds >= 0.0) {
      ++reading.files;
      reading.seconds += r.read_seconds;
    }
  };
  if (opt.keep_trajectories)
    pool.keep = [&](size_t index, const Trajectory& traj) {
      write_trajectory_csv(traj,
                           (fs::path(opt.study) / fmt::format("case_{}.csv", index)).string());
    };
  // Worker processes (threads when one): docs/sweeps.md, "Speed".
  try {
    sweep::run_pool_processes(s.prepared.compiled, {}, pending_cases(s, *summary), s.plan.metrics,
                              pool);
  } catch (const sweep::WorkerDied& e) {
    return end_process(worker_died(opt, s, progress, e));
  }
  const int code =
      conclude(opt, s, *summary, progress, already,
               fmt::format("{} worker{}", pool.workers, pool.workers == 1 ? "" : "s"), reading);
  if (code == 0 && !opt.plot.empty()) {
    plot_summary(opt, s);
    if (!opt.quiet) fmt::print("  plotted {}\n", opt.plot);
  }
  return end_process(code);
}

}  // namespace lagrange::cli

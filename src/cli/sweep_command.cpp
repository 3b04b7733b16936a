// `lagrange sweep`: a parameter study (docs/sweeps.md). Everything the command line says is
// checked, and every case's model read, before the first case runs or anything is written; then a
// pool of workers shares the one compiled model, or, under mpirun, rank 0 hands the cases to the
// other ranks (cli/sweep_mpi.hpp).

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <thread>

#include "cli/commands.hpp"
#include "cli/interrupt.hpp"
#include "cli/prepare.hpp"
#include "lagrange/error.hpp"
#include "lagrange/io.hpp"
#include "lagrange/reader.hpp"
#include "lagrange/sweep.hpp"

#ifdef LAGRANGE_HAVE_MPI
#include "cli/sweep_mpi.hpp"
#include "lagrange/dynamics.hpp"
#endif

namespace lagrange::cli {

namespace {

using Clock = std::chrono::steady_clock;
namespace fs = std::filesystem;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

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

// Each case's inputs from the model file read with its values (parameters, initial state and
// settings may be expressions of them); a value the model rejects makes that case fail.
struct PreparedCase {
  std::optional<sweep::CaseInput> input;
  std::string rejected;  ///< why the model file rejects these values
};

std::vector<PreparedCase> prepare_cases(const Options& opt, const Prepared& p,
                                        const std::vector<sweep::Case>& cases) {
  const ParameterOverrides fixed = parse_sets(opt.sets);
  const RunSettings settings{opt.t_end, opt.output_step, opt.rtol,
                             opt.atol,  opt.step,        opt.integrator};
  std::vector<PreparedCase> out(cases.size());
  for (const auto& c : cases) {
    ParameterOverrides values = fixed;
    for (const auto& [name, value] : c.values) values[name] = value;
    try {
      const Model m = read_model_file(opt.model, values);
      SimulationOptions so = simulation_options(m, settings);
      so.jacobian_source = jacobian_source(p, so.integrator.method);  // derived once, shared
      out[c.index].input = sweep::case_input(m, *p.compiled, so);
    } catch (const ModelError& e) {
      out[c.index].rejected = fmt::format("the model does not accept these values: {} (at {})",
                                          e.detail(), e.loc().str());
    } catch (const UsageError& e) {
      out[c.index].rejected = e.what();
    } catch (const sweep::StudyError& e) {
      throw UsageError(fmt::format("case {}: {}", c.index, e.what()));
    }
  }
  return out;
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

// A case the model file rejects, as a failed case.
sweep::CaseResult rejected_case(size_t index, const std::string& why, size_t metrics) {
  sweep::CaseResult r;
  r.index = index;
  r.status = Trajectory::Status::Failed;
  r.reason = why;
  r.metrics.assign(metrics, std::nan(""));
  return r;
}

// Everything checked and read before a case runs: the plan, the model derived and compiled once,
// each case's inputs and the summary's columns.
struct Study {
  StudyPlan plan;
  Prepared prepared;
  std::vector<PreparedCase> cases;
  std::vector<std::string> header;
  double read_seconds = 0.0;
};

Study set_up(const Options& opt) {
  Study s;
  s.plan = plan(opt);
  s.prepared = prepare(opt.model, opt.sets, {}, "--initial", opt.dynamics);
  const Prepared& p = s.prepared;
  for (const auto& [name, value] : s.plan.cases.front().values)
    if (p.model->parameter_index(name) < 0) {
      std::string known;
      for (const auto& par : p.model->parameters) known += (known.empty() ? "" : ", ") + par.name;
      throw UsageError(fmt::format("no parameter '{}' in {} (parameters: {})", name, opt.model,
                                   known.empty() ? "none" : known));
    }
  try {
    s.plan.metrics = sweep::study_metrics(*p.model, *p.compiled, opt.metrics);
  } catch (const sweep::StudyError& e) {
    throw UsageError(e.what());
  }
  const auto t_read = Clock::now();
  s.cases = prepare_cases(opt, p, s.plan.cases);
  s.read_seconds = seconds_since(t_read);
  s.header = {"case"};
  for (const auto& [name, value] : s.plan.cases.front().values) s.header.push_back(name);
  for (const char* c : {"status", "reason", "failure_time"}) s.header.emplace_back(c);
  for (const auto& m : s.plan.metrics) s.header.push_back(sweep::csv_field(m.name));
  s.header.emplace_back("wall_s");
  return s;
}

// What decides a study's cases and rows, one option a line: STUDY/study.txt, which --resume
// compares so that it finishes the same study.
std::string description(const Options& opt) {
  std::string d = fmt::format("model: {}\n", opt.model);
  const auto list = [&](const char* option, const std::vector<std::string>& values) {
    for (const auto& v : values) d += fmt::format("{} {}\n", option, v);
  };
  const auto number = [&](const char* option, const std::optional<double>& value) {
    if (value) d += fmt::format("{} {:.17g}\n", option, *value);
  };
  list("--vary", opt.vary);
  list("--random", opt.random);
  if (!opt.random.empty()) d += fmt::format("--samples {}\n--seed {}\n", opt.samples, opt.seed);
  list("--set", opt.sets);
  list("--metric", opt.metrics);
  number("--t-end", opt.t_end);
  number("--output-step", opt.output_step);
  number("--rtol", opt.rtol);
  number("--atol", opt.atol);
  number("--step", opt.step);
  if (opt.integrator) d += fmt::format("--integrator {}\n", *opt.integrator);
  d += fmt::format("--dynamics {}\n", opt.dynamics);
  return d;
}

// The study directory's summary; a UsageError when it cannot be made, holds another study, or
// --resume is given for a study started with other options.
std::unique_ptr<sweep::SummaryFile> open_summary(const Options& opt, const Study& s) {
  const fs::path about = fs::path(opt.study) / "study.txt";
  const std::string text = description(opt);
  try {
    if (opt.resume && fs::exists(about)) {
      std::ifstream in(about, std::ios::binary);
      std::stringstream was;
      was << in.rdbuf();
      if (was.str() != text)
        throw UsageError(fmt::format(
            "--resume: {} was started with other options; the same command with --resume "
            "finishes it. It was:\n{}",
            opt.study, was.str()));
    }
    fs::create_directories(opt.study);
    auto summary = std::make_unique<sweep::SummaryFile>(
        (fs::path(opt.study) / "summary.csv").string(), s.header, opt.resume);
    write_file_atomically(about.string(), text);
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

// The cases still to run (not in the summary), after recording those the model file rejects.
std::vector<size_t> pending_cases(const Study& s, sweep::SummaryFile& summary, Progress& progress) {
  std::vector<size_t> pending;
  for (size_t i = 0; i < s.cases.size(); ++i) {
    if (summary.done().count(i)) continue;
    if (s.cases[i].input) {
      pending.push_back(i);
      continue;
    }
    summary.append(i, row_fields(s.plan.cases[i],
                                 rejected_case(i, s.cases[i].rejected, s.plan.metrics.size())));
    progress.add(false);
  }
  return pending;
}

// The end of a study on rank 0 or the one machine: 130 when interrupted, else the table sorted.
int conclude(const Options& opt, const Study& s, sweep::SummaryFile& summary,
             const Progress& progress, size_t already, const std::string& workers) {
  const fs::path path = fs::path(opt.study) / "summary.csv";
  const size_t total = s.cases.size();
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
    fmt::print(
        "  derive {:.3f} s and compile {:.3f} s once, read the cases' values {:.3f} s, run "
        "{:.3f} s ({:.1f} cases/s)\n",
        s.prepared.derive_seconds, s.prepared.compile_seconds, s.read_seconds, progress.seconds(),
        static_cast<double>(ran) / std::max(progress.seconds(), 1e-9));
    fmt::print("  wrote {}\n", path.string());
  }
  return 0;
}

#ifdef LAGRANGE_HAVE_MPI
// Under mpirun: every rank sets the study up (the same checks, so a mistake stops them all
// alike; rank 0 alone reports it); rank 0 hands out the cases and writes the summary.
int run_sweep_mpi(const Options& opt) {
  MpiSession mpi;
  if (mpi.rank() != 0) {
    std::optional<Study> s;
    try {
      s.emplace(set_up(opt));
    } catch (const std::exception&) {
      return 2;  // rank 0 meets the same mistake and reports it
    }
    Dynamics dyn(s->prepared.compiled, s->prepared.compiled->parameter_defaults);
    Trajectory traj;
    mpi_work([&](size_t index, std::vector<std::string>& fields) {
      sweep::CaseInput input = *s->cases.at(index).input;
      input.options.interrupt = opt.interrupt;
      sweep::CaseResult r =
          sweep::run_case(dyn, input, s->plan.metrics, opt.keep_trajectories ? &traj : nullptr);
      if (r.status == Trajectory::Status::Interrupted) return false;
      if (opt.keep_trajectories)
        write_trajectory_csv(traj,
                             (fs::path(opt.study) / fmt::format("case_{}.csv", index)).string());
      fields = row_fields(s->plan.cases[index], r);
      return true;
    });
    return 0;
  }
  const Study s = set_up(opt);
  std::unique_ptr<sweep::SummaryFile> summary;
  try {
    summary = open_summary(opt, s);
  } catch (const UsageError&) {
    mpi_hand_out(mpi, {}, opt.interrupt, {});  // the workers stop at once
    throw;
  }
  const size_t already = summary->done().size();
  Progress progress(opt, s.cases.size(), already);
  const std::vector<size_t> pending = pending_cases(s, *summary, progress);
  mpi_hand_out(mpi, pending, opt.interrupt,
               [&](size_t index, const std::vector<std::string>& fields) {
                 summary->append(index, fields);
                 progress.add(fields.at(s.header.size() - 1 - s.plan.metrics.size() - 3) == "ok");
               });
  return conclude(
      opt, s, *summary, progress, already,
      fmt::format("{} MPI ranks (1 handing out, {} running cases)", mpi.size(), mpi.size() - 1));
}
#endif

}  // namespace

int run_sweep(const Options& opt) {
  const KeepWorkOnInterrupt keep;  // an interrupted study keeps its finished cases
#ifdef LAGRANGE_HAVE_MPI
  if (started_by_mpirun()) return run_sweep_mpi(opt);
#else
  if (started_by_mpirun())
    throw UsageError(
        "sweep was started by mpirun with several ranks, but this lagrange was built without "
        "MPI: every rank would run the whole study. Run it without mpirun (it uses every core; "
        "-j N chooses), or build lagrange with OpenMPI (libopenmpi-dev) installed");
#endif
  const Study s = set_up(opt);
  const auto summary = open_summary(opt, s);
  const size_t already = summary->done().size();
  Progress progress(opt, s.cases.size(), already);
  const std::vector<size_t> pending = pending_cases(s, *summary, progress);
  std::vector<sweep::CaseInput> inputs(s.cases.size());
  for (const size_t i : pending) inputs[i] = *s.cases[i].input;
  sweep::PoolOptions pool;
  pool.workers = opt.jobs > 0 ? opt.jobs : std::max(1u, std::thread::hardware_concurrency());
  pool.interrupt = opt.interrupt;
  pool.done = [&](const sweep::CaseResult& r) {
    summary->append(r.index, row_fields(s.plan.cases[r.index], r));
    progress.add(r.status == Trajectory::Status::Complete);
  };
  if (opt.keep_trajectories)
    pool.keep = [&](size_t index, const Trajectory& traj) {
      write_trajectory_csv(traj,
                           (fs::path(opt.study) / fmt::format("case_{}.csv", index)).string());
    };
  sweep::run_pool(s.prepared.compiled, inputs, pending, s.plan.metrics, pool);
  return conclude(opt, s, *summary, progress, already,
                  fmt::format("{} worker{}", pool.workers, pool.workers == 1 ? "" : "s"));
}

}  // namespace lagrange::cli

// The `lagrange` command (README.md, "Command line"): derive, simulate, export, check, eval,
// report, linearize, trim, sweep, optimize.
// Exit codes: 0 ok, 1 model error, 2 usage error, 3 simulation failure.

#include <fmt/format.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <atomic>
#include <charconv>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <limits>

#include "cli/commands.hpp"
#include "cli/interrupt.hpp"
#include "cli/version.hpp"
#include "lagrange/analysis.hpp"
#include "lagrange/error.hpp"
#include "lagrange/integrator.hpp"
#include "lagrange/sweep.hpp"

namespace {

/// A whole number from 0 to `max` in decimal digits (no sign, no exponent): CLI11 reads "-1"
/// into an unsigned option as 2^64 − 1, and clamps 2^64 to it (issue 37 item 3).
CLI::Validator whole_number(std::uint64_t max) {
  return CLI::Validator(
      [max](std::string& text) -> std::string {
        std::uint64_t value = 0;
        const char* end = text.data() + text.size();
        const auto [stop, error] = std::from_chars(text.data(), end, value);
        if (text.empty() || error != std::errc() || stop != end || value > max)
          return fmt::format("expected a whole number from 0 to {}, got '{}'", max, text);
        return "";
      },
      fmt::format("UINT<={}", max));
}

/// A path that is not empty: `-o ""` once ran and wrote nothing, silently.
const CLI::Validator kFileName(
    [](std::string& text) -> std::string {
      return text.empty() ? "expected a file or directory name, got ''" : "";
    },
    "PATH");

}  // namespace

int main(int argc, char** argv) {
  // --package-path: where the report looks up a URDF's package:// meshes, before
  // $ROS_PACKAGE_PATH (docs/model-language.md, "How a model looks").
  std::vector<std::string> package_paths;
  const char* package_help =
      "folder holding ROS packages, for a URDF's package:// meshes in the report (repeatable; "
      "searched before $ROS_PACKAGE_PATH)";
  using namespace lagrange::cli;
  CLI::App app{"lagrange: Lagrangian modelling and simulation of mechanical systems"};
  app.require_subcommand(1);
  app.set_version_flag("--version", lagrange::cli::version_text(),
                       "print the version and the git revision it was built from");
  Options opt;

  auto* derive =
      app.add_subcommand("derive", "print T, U, L, the Euler-Lagrange equations, M and h + Q");
  derive->add_option("model", opt.model, "model file (YAML)")->required();
  derive->add_option("--format", opt.format, "text | latex | json")
      ->check(CLI::IsMember({"text", "latex", "json"}));
  derive->add_flag("--expand", opt.expand,
                   "print the full expansion even for large models (by default printed through "
                   "named common subexpressions)");
  derive
      ->add_option("--form", opt.form,
                   "lagrange (default) | manipulator: D(q), Christoffel symbols, C, g, tau | "
                   "recursive: the articulated-body algorithm of a joint tree")
      ->check(CLI::IsMember({"lagrange", "manipulator", "recursive"}));

  auto* sim = app.add_subcommand("simulate", "integrate the model and write the trajectory");
  sim->add_option("model", opt.model, "model file (YAML)")->required();
  sim->add_option("--t-end", opt.t_end, "end time (overrides simulate.t_end)");
  sim->add_option("--output-step", opt.output_step, "output grid step");
  sim->add_option("-o,--output", opt.csv, "CSV file to write (default: print a summary only)")
      ->check(kFileName);
  sim->add_option("--plot", opt.plot, "plot of the coordinates, .svg or .png (through gnuplot)")
      ->check(kFileName);
  sim->add_option("--plot-columns", opt.plot_columns, "columns to plot (default: coordinates)")
      ->delimiter(',');
  sim->add_option("--report", opt.report,
                  "self-contained HTML report: 3-D animation, plots, equations (.html)")
      ->check(kFileName);
  sim->add_option("--set", opt.sets, "parameter value, NAME=VALUE (repeatable)");
  sim->add_option("--package-path", package_paths, package_help);
  sim->add_option("--initial", opt.initial,
                  "initial value of a coordinate or a rate NAME_dot, NAME=VALUE (repeatable, or "
                  "comma-separated)")
      ->delimiter(',');
  sim->add_option("--integrator", opt.integrator,
                  "dop853 (default), arkode (its table per tolerance), arkode:<table>, cvode, "
                  "cvode:jacobian, auto, rk4, midpoint, ida, ida:jacobian")
      ->check(CLI::IsMember(lagrange::integrator_methods()));
  sim->add_option("--rtol", opt.rtol, "relative tolerance");
  sim->add_option("--atol", opt.atol, "absolute tolerance");
  sim->add_option("--max-order", opt.max_order, "highest order of cvode*, ida* (1-5)");
  sim->add_option(
      "--step", opt.step,
      "fixed step of rk4 and midpoint; set, it also fixes the step of dop853 and arkode");
  sim->add_option("--compile", opt.compile,
                  "auto (default): machine code from the cache, or compiled in the background "
                  "for large models | on: compile before the run | off: interpreter only")
      ->check(CLI::IsMember({"auto", "on", "off"}));
  sim->add_option("--dynamics", opt.dynamics,
                  "auto (default): recursive where it applies (joint trees) | lagrangian: "
                  "M and h from the energies | recursive: articulated-body algorithm, O(N)")
      ->check(CLI::IsMember({"auto", "lagrangian", "recursive"}));
  sim->add_flag("-q,--quiet", opt.quiet, "no progress line and no summary");

  auto* exp = app.add_subcommand("export", "write standalone C99 source of the dynamics");
  exp->add_option("model", opt.model, "model file (YAML)")->required();
  exp->add_option("--c", opt.c_dir, "directory for lagrange_model.h/.c")->check(kFileName);
  exp->add_option("--fmu", opt.fmu,
                  "FMI 2.0 FMU to write (FILE.fmu): the C of --c, an integrator, "
                  "modelDescription.xml and a linux64 binary built with cc (docs/fmu.md)")
      ->check(kFileName);
  exp->add_option("--fmi-type", opt.fmi_type,
                  "both (default): Co-Simulation and Model Exchange | cs | me")
      ->check(CLI::IsMember({"cs", "me", "both"}));
  exp->add_option("--form", opt.form,
                  "lagrange (default): forward dynamics | manipulator: D, C q_dot, g, inverse "
                  "and forward dynamics")
      ->check(CLI::IsMember({"lagrange", "manipulator"}));
  exp->add_option("--dynamics", opt.dynamics,
                  "auto (default): recursive where it applies (joint trees) | lagrangian | "
                  "recursive; as for simulate")
      ->check(CLI::IsMember({"auto", "lagrangian", "recursive"}));
  exp->add_flag("--jacobian", opt.jacobian,
                "also write lagrange_jacobian.h/.c: exact da/dq, da/dv, da/du with their sparsity "
                "(Lagrangian form)");

  auto* check =
      app.add_subcommand("check", "validate the model and the consistency of its initial state");
  check->add_option("model", opt.model, "model file (YAML)")->required();
  check->add_option("--set", opt.sets, "parameter value, NAME=VALUE (repeatable)");
  check->add_option("--initial", opt.initial, "initial value NAME=VALUE, as for simulate")
      ->delimiter(',');
  check
      ->add_option("--dynamics", opt.dynamics,
                   "auto (default) | lagrangian | recursive: the equations checked, as for "
                   "simulate")
      ->check(CLI::IsMember({"auto", "lagrangian", "recursive"}));

  auto* eval = app.add_subcommand(
      "eval", "print M, the bias forces, the accelerations and inverse dynamics at one state");
  eval->add_option("model", opt.model, "model file (YAML or URDF)")->required();
  eval->add_option("--state", opt.initial,
                   "coordinate or rate NAME_dot, NAME=VALUE (comma-separated; others keep the "
                   "model's initial values)")
      ->delimiter(',');
  eval->add_option("--tau", opt.tau,
                   "joint forces NAME=VALUE replacing the model's (manipulators; others 0)")
      ->delimiter(',');
  eval->add_option("--set", opt.sets, "parameter value, NAME=VALUE (repeatable)");
  eval->add_option("--format", opt.format, "text | json")->check(CLI::IsMember({"text", "json"}));

  auto* report = app.add_subcommand(
      "report", "write the HTML report (3-D animation, plots, equations) of a saved trajectory");
  report->add_option("model", opt.model, "model file (YAML)")->required();
  report->add_option("trajectory", opt.trajectory, "trajectory CSV written by simulate -o")
      ->required();
  report->add_option("-o,--output", opt.report, "HTML file to write")->required()->check(kFileName);
  report->add_option("--set", opt.sets, "parameter value the run used, NAME=VALUE (repeatable)");
  report->add_flag("-q,--quiet", opt.quiet, "no summary line");
  report->add_option("--package-path", package_paths, package_help);

  const auto trim_choices = [&](CLI::App* cmd) {
    cmd->add_option("--free", opt.free,
                    "coordinates (and rates held by --steady) Newton may vary (default: every "
                    "coordinate not moving at a held rate), comma-separated")
        ->delimiter(',');
    cmd->add_option("--fix", opt.fix, "coordinates held at their initial values")->delimiter(',');
    cmd->add_option("--steady", opt.steady,
                    "a steady state: rates NAME_dot held at their initial or --at values, "
                    "comma-separated (docs/theory.md §5.5)")
        ->delimiter(',');
    cmd->add_option("--tol", opt.tol,
                    fmt::format("tolerance on max |acceleration| (default {:g})", Options{}.tol));
  };
  auto* lin = app.add_subcommand(
      "linearize", "A, B, C, D and the modes at an operating point, on the constraint manifold");
  lin->add_option("model", opt.model, "model file (YAML or URDF)")->required();
  lin->add_option("--at", opt.initial,
                  "operating point: coordinate or rate NAME_dot, NAME=VALUE (comma-separated; "
                  "others keep the model's initial values)")
      ->delimiter(',');
  lin->add_option("--inputs", opt.inputs,
                  "columns of B and D: model inputs or parameters, comma-separated")
      ->delimiter(',');
  lin->add_option("--outputs", opt.outputs,
                  "rows of C and D: coordinates, velocities or model outputs (default: the state)")
      ->delimiter(',');
  lin->add_option("--format", opt.format, "text | json | csv")
      ->check(CLI::IsMember({"text", "json", "csv"}));
  lin->add_option("--discrete", opt.discrete, "zero-order-hold discretisation with this step");
  lin->add_option("--set", opt.sets, "parameter value, NAME=VALUE (repeatable)");
  lin->add_flag("--at-trim", opt.at_trim,
                "trim first (from the initial state or --at, with --free/--fix/--steady/--tol) "
                "and linearise at the equilibrium or steady state found");
  trim_choices(lin);

  auto* trim = app.add_subcommand(
      "trim",
      "find an equilibrium or steady state from the initial state (Newton on the exact "
      "Jacobian)");
  trim->add_option("model", opt.model, "model file (YAML or URDF)")->required();
  trim_choices(trim);
  trim->add_option("--at", opt.initial,
                   "start: coordinate or rate NAME_dot, NAME=VALUE (comma-separated)")
      ->delimiter(',');
  trim->add_option("--set", opt.sets, "parameter value, NAME=VALUE (repeatable)");

  auto* sweep = app.add_subcommand(
      "sweep",
      "run every case of a parameter grid or random sample, deriving once, on every core; one "
      "summary row per case (docs/sweeps.md)");
  sweep->add_option("model", opt.model, "model file (YAML)")->required();
  sweep->add_option("--vary", opt.vary,
                    "parameter values NAME=START:STOP:COUNT or NAME=V1,V2,... (repeatable; the "
                    "grid is every combination)");
  sweep->add_option("--random", opt.random,
                    "random parameter NAME=normal(MU,SIGMA) | uniform(LOW,HIGH) | "
                    "lognormal(MU,SIGMA) (repeatable; --samples draws per grid point)");
  sweep->add_option("--samples", opt.samples, "draws of the --random parameters")
      ->check(whole_number(lagrange::sweep::kMaxStudyCases));
  sweep->add_option("--seed", opt.seed, "seed of the random draws (default 1)")
      ->check(whole_number(std::numeric_limits<std::uint64_t>::max()));
  sweep->add_option(
      "--metric", opt.metrics,
      "NAME=AGG(COLUMN[, WINDOW]) with AGG max | min | mean | final | initial | drift, "
      "COLUMN a trajectory column or abs(COLUMN), WINDOW like 't > 60' "
      "(repeatable)");
  sweep->add_option("-o,--output", opt.study, "study directory: summary.csv (and case_N.csv)")
      ->required()
      ->check(kFileName);
  sweep->add_option("-j,--jobs", opt.jobs, "workers (default 0: every core)")
      ->check(whole_number(kMaxJobs));
  sweep->add_flag("--resume", opt.resume,
                  "finish an interrupted study: cases already in summary.csv are not run again");
  sweep->add_flag("--keep-trajectories", opt.keep_trajectories,
                  "write each case's trajectory to STUDY/case_N.csv");
  sweep->add_option("--set", opt.sets, "value of a parameter not varied, NAME=VALUE (repeatable)");
  sweep->add_option("--t-end", opt.t_end, "end time (overrides simulate.t_end)");
  sweep->add_option("--output-step", opt.output_step, "output grid step");
  sweep->add_option("--integrator", opt.integrator, "as for simulate")
      ->check(CLI::IsMember(lagrange::integrator_methods()));
  sweep->add_option("--rtol", opt.rtol, "relative tolerance");
  sweep->add_option("--atol", opt.atol, "absolute tolerance");
  sweep->add_option("--max-order", opt.max_order, "highest order of cvode*, ida* (1-5)");
  sweep->add_option("--step", opt.step, "fixed step, as for simulate");
  sweep
      ->add_option("--compile", opt.compile,
                   "auto (default), on: machine code compiled once for every case (the "
                   "interpreter if it cannot be had; on also warns) | off: interpreter only")
      ->check(CLI::IsMember({"auto", "on", "off"}));
  sweep->add_option("--dynamics", opt.dynamics, "auto (default) | lagrangian | recursive")
      ->check(CLI::IsMember({"auto", "lagrangian", "recursive"}));
  sweep->add_flag("--optimize", opt.optimize,
                  "each case solves the model's optimal_control problem, started from the "
                  "nearest case solved before it (a power curve over the wind speed)");
  sweep->add_option("--intervals", opt.intervals, "--optimize: collocation intervals N")
      ->check(CLI::Range(1, 100000));
  sweep->add_option("--degree", opt.degree, "--optimize: Radau IIA points per interval, 1-5")
      ->check(CLI::Range(1, 5));
  sweep->add_option("--ipopt", opt.ipopt, "--optimize: Ipopt option KEY=VALUE (repeatable)");
  sweep->add_option("--hessian", opt.hessian, "--optimize: exact, limited-memory or auto")
      ->check(CLI::IsMember({"auto", "exact", "limited-memory"}));
  sweep->add_option("--plot", opt.plot,
                    "FILE.svg or .png: the objective (--optimize) and the metrics against the "
                    "one --vary parameter, through gnuplot");
  sweep->add_flag("-q,--quiet", opt.quiet, "no progress line and no summary");

  auto* optimize = app.add_subcommand(
      "optimize",
      "solve the model's optimal_control problem: Radau collocation of the DAE, solved by Ipopt");
  optimize->add_option("model", opt.model, "model file (YAML) with an optimal_control section")
      ->required();
  optimize->add_option("-o,--output", opt.csv,
                       "CSV of the optimal trajectory (simulate's columns, then the controls and "
                       "the collocated multipliers)");
  optimize->add_option("--report", opt.report,
                       "one offline HTML file: the optimal motion in 3-D, plots, equations");
  optimize->add_option("--intervals", opt.intervals, "collocation intervals N (overrides the file)")
      ->check(CLI::Range(1, 100000));
  optimize->add_option("--degree", opt.degree, "Radau IIA points per interval, 1-5")
      ->check(CLI::Range(1, 5));
  optimize->add_option("--set", opt.sets, "parameter value, NAME=VALUE (repeatable)");
  optimize->add_flag("--verify", opt.verify,
                     "re-simulate the optimal controls at tight tolerance and report the gap");
  optimize->add_option("--ipopt", opt.ipopt, "Ipopt option KEY=VALUE (repeatable)");
  optimize
      ->add_option("--hessian", opt.hessian,
                   "exact, limited-memory, or auto (exact unless the equations are too large)")
      ->check(CLI::IsMember({"auto", "exact", "limited-memory"}));
  optimize->add_option("--compile", opt.compile,
                       "auto (default): the Hessian's second derivatives on machine code from the "
                       "cache, or compiled beside the solve | on: compile before it | off: "
                       "interpreter only");
  optimize->add_flag("-v,--verbose", opt.verbose, "print Ipopt's iteration log");
  optimize->add_flag("-q,--quiet", opt.quiet, "no summary");
  optimize->add_option("--package-path", package_paths, package_help);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int rc = app.exit(e);
    return rc == 0 ? 0 : 2;
  }
  if (!package_paths.empty()) {
    std::string path;
    for (const std::string& p : package_paths) path += p + ":";
    if (const char* ros = std::getenv("ROS_PACKAGE_PATH")) path += ros;
    setenv("ROS_PACKAGE_PATH", path.c_str(), 1);
  }
  opt.interrupt = install_sigint_handler();
  opt.terminal = isatty(fileno(stderr)) != 0;
  try {
    if (*derive) return run_derive(opt);
    if (*sim) return run_simulate(opt);
    if (*exp) return run_export(opt);
    if (*check) return run_check(opt);
    if (*report) return run_report(opt);
    if (*eval) return run_eval(opt);
    if (*lin) return run_linearize(opt);
    if (*trim) return run_trim(opt);
    if (*sweep) return run_sweep(opt);
    if (*optimize) return run_optimize(opt);
  } catch (const lagrange::AnalysisError& e) {
    fmt::print(stderr, "lagrange: {}\n", e.what());
    return 3;
  } catch (const lagrange::ModelError& e) {
    fmt::print(stderr, "{}\n", e.what());
    return 1;
  } catch (const UsageError& e) {
    fmt::print(stderr, "lagrange: {}\n", e.what());
    return 2;
  } catch (const lagrange::SimulationError& e) {
    fmt::print(stderr, "lagrange: {}\n", e.what());
    return 3;
  } catch (const std::exception& e) {
    fmt::print(stderr, "lagrange: error: {}\n", e.what());
    return 1;
  }
  return 2;
}

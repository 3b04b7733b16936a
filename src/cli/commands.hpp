#pragma once
// The subcommands of the `lagrange` CLI, each returning the process exit code.

#include <atomic>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace lagrange::cli {

/// A mistake in the command line (exit code 2).
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// The most workers `sweep -j` starts (each one a process; docs/sweeps.md).
constexpr std::uint64_t kMaxJobs = 1024;

/// Everything the command line can set; unset optionals leave the model file's values.
struct Options {
  std::string model;
  std::string format = "text";
  std::string form = "lagrange";  ///< derive: lagrange | manipulator
  std::optional<double> t_end, output_step, rtol, atol, step;
  std::optional<int> max_order;
  std::optional<std::string> integrator;
  std::string compile = "auto";  ///< simulate --compile: auto | on | off
  std::string dynamics =
      "auto";  ///< simulate, export, check --dynamics: auto | lagrangian | recursive
  std::string csv, plot, c_dir;
  std::string fmu;                ///< export --fmu: the FMU file to write
  std::string fmi_type = "both";  ///< export --fmi-type: cs | me | both
  std::string report;             ///< simulate --report, report -o: the HTML report to write
  std::string trajectory;         ///< report: the saved trajectory CSV
  std::vector<std::string> plot_columns, sets;
  std::vector<std::string> initial;    ///< --initial NAME=VALUE (coordinates, NAME_dot rates)
  std::vector<std::string> tau;        ///< eval --tau NAME=VALUE (joint forces)
  std::vector<std::string> inputs;     ///< linearize --inputs: model inputs or parameters
  std::vector<std::string> outputs;    ///< linearize --outputs: coordinates, velocities, outputs
  std::optional<double> discrete;      ///< linearize --discrete DT (zero-order hold)
  std::vector<std::string> free, fix;  ///< trim --free / --fix: tangent coordinates, held rates
  std::vector<std::string> steady;     ///< trim --steady: rates NAME_dot held at their values
  bool at_trim = false;                ///< linearize --at-trim: trim first, linearise there
  bool jacobian = false;               ///< export --jacobian: also the derivatives' C
  double tol = 1e-9;                   ///< trim --tol: on max |acceleration|
  std::vector<std::string> vary, random, metrics;  ///< sweep --vary, --random, --metric
  size_t samples = 0;                              ///< sweep --samples
  std::uint64_t seed = 1;                          ///< sweep --seed
  std::string study;                               ///< sweep -o: the study directory
  size_t jobs = 0;                                 ///< sweep -j (0: every core)
  bool resume = false, keep_trajectories = false;  ///< sweep --resume, --keep-trajectories
  bool optimize = false;           ///< sweep --optimize: each case solves optimal_control
  int intervals = 0, degree = 0;   ///< optimize --intervals, --degree (0: the problem's)
  bool verify = false;             ///< optimize --verify
  bool verbose = false;            ///< optimize -v: Ipopt's iteration log
  std::vector<std::string> ipopt;  ///< optimize --ipopt KEY=VALUE
  std::string hessian = "auto";    ///< optimize: auto, exact or limited-memory
  bool quiet = false;
  bool expand = false;  ///< derive: print the full expansion even for large models
  bool terminal = false;
  const std::atomic<bool>* interrupt = nullptr;
};

int run_derive(const Options& opt);
int run_simulate(const Options& opt);
int run_export(const Options& opt);
int run_check(const Options& opt);
/// The HTML report of a saved trajectory (src/cli/report_command.cpp).
int run_report(const Options& opt);
/// M, bias forces, accelerations and inverse dynamics at the state of --state (src/cli/eval.cpp).
int run_eval(const Options& opt);
/// A, B, C, D and the modes at an operating point (src/cli/linearize_command.cpp).
int run_linearize(const Options& opt);
/// An equilibrium by Levenberg–Marquardt (docs/theory.md §5.5), printed as an initial-state block
/// (src/cli/trim_command.cpp).
int run_trim(const Options& opt);
/// Every case of a parameter grid or random sample, one derivation shared by a pool of workers,
/// into STUDY/summary.csv (src/cli/sweep_command.cpp, docs/sweeps.md).
int run_sweep(const Options& opt);
/// The model file's optimal-control problem by direct collocation and Ipopt (docs/theory.md §10,
/// src/cli/optimize_command.cpp).
int run_optimize(const Options& opt);

}  // namespace lagrange::cli

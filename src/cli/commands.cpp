#include "cli/commands.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "cli/initial_state.hpp"
#include "cli/interrupt.hpp"
#include "cli/plot_check.hpp"
#include "cli/prepare.hpp"
#include "cli/report_command.hpp"
#include "lagrange/analysis.hpp"
#include "lagrange/compiled_model.hpp"
#include "lagrange/dynamics.hpp"
#include "lagrange/equations.hpp"
#include "lagrange/error.hpp"
#include "lagrange/io.hpp"
#include "lagrange/reader.hpp"
#include "lagrange/simulation.hpp"
#include "lagrange/sweep.hpp"
#include "support/seconds_since.hpp"

namespace lagrange::cli {

namespace fs = std::filesystem;

namespace {

using Clock = std::chrono::steady_clock;

SimulationOptions simulation_options(const Model& model, const Options& opt) {
  return simulation_options(model, RunSettings{opt.t_end, opt.output_step, opt.rtol, opt.atol,
                                               opt.step, opt.integrator, opt.max_order});
}

// --plot and --plot-columns, checked before the run: a known image format whose gnuplot terminal
// is installed, and columns the trajectory will have (default: the coordinates).
std::vector<std::string> checked_plot_columns(const Options& opt, const CompiledModel& cm) {
  if (opt.plot.empty() && !opt.plot_columns.empty())
    throw UsageError("--plot-columns chooses what --plot draws; give --plot FILE.svg too");
  if (opt.plot.empty()) return {};
  checked_plot_format(opt.plot, [](PlotFormat format) {
    return format == PlotFormat::Png ? "plot to an .svg file" : "plot to a .png file";
  });
  std::vector<std::string> cols = opt.plot_columns;
  if (cols.empty()) cols = cm.coordinate_names;
  const std::vector<std::string> known = trajectory_columns(cm);
  for (const auto& c : cols)
    if (std::find(known.begin(), known.end(), c) == known.end())
      throw UsageError("--plot-columns: no column '" + c + "' in the trajectory");
  return cols;
}

// Progress line on a terminal for runs longer than about a second.
std::function<void(double)> progress_line(const Options& opt, double t_end) {
  if (opt.quiet || !opt.terminal) return {};
  auto start = Clock::now();
  auto last = start;
  return [start, last, t_end](double t) mutable {
    const auto now = Clock::now();
    if (seconds_since(start) < 1.0 || std::chrono::duration<double>(now - last).count() < 0.2)
      return;
    last = now;
    fmt::print(stderr, "\r  t = {:.4g} / {:.4g} ({:.0f} %)   ", t, t_end, 100.0 * t / t_end);
  };
}

}  // namespace

int run_derive(const Options& opt) {
  const Model model = read_model_file(opt.model);
  if (opt.form == "recursive") {  // docs/theory.md §4.9
    if (const std::string why = recursive_unsuitable(model); !why.empty())
      throw UsageError(
          fmt::format("--form recursive: the articulated-body algorithm does not "
                      "apply to {}: {}",
                      model.file, why));
    fmt::print("{}", format_recursive(derive(model, Formulation::Recursive), opt.format));
    return 0;
  }
  const Equations eq = derive(model);
  if (opt.form == "manipulator") {
    fmt::print("{}", format_manipulator(manipulator_form(eq), opt.format, opt.expand));
    return 0;
  }
  fmt::print("{}", format_equations(eq, opt.format, opt.expand));
  return 0;
}

namespace {

// export --fmu: the forward dynamics of `eq` as an FMI 2.0 FMU (docs/fmu.md).
void write_fmu(const Model& model, const Equations& eq, const CompiledModel& cm,
               const Options& opt) {
  FmuOptions fo = fmu_options(model);
  fo.fmi_type = opt.fmi_type;
  fo.equations = eq.recursive ? format_recursive(eq, "text") : format_equations(eq, "text");
  export_fmu(cm, fo, opt.fmu);
  fmt::print("wrote {} (FMI 2.0 {}, {} states, {} parameters, {} inputs)\n", opt.fmu,
             opt.fmi_type == "both" ? "Co-Simulation and Model Exchange"
             : opt.fmi_type == "cs" ? "Co-Simulation"
                                    : "Model Exchange",
             cm.nq + cm.nv, cm.np, cm.k);
}

// The usage errors of export's outputs, before any work.
void check_export_outputs(const Options& opt) {
  if (opt.c_dir.empty() && opt.fmu.empty())
    throw UsageError("export: give --c DIR (C source), --fmu FILE.fmu (an FMU), or both");
  if (opt.fmu.empty() && opt.fmi_type != "both")
    throw UsageError("--fmi-type chooses the interfaces of --fmu; give --fmu FILE.fmu too");
  if (opt.fmu.empty()) return;
  if (opt.form == "manipulator" || opt.jacobian)
    throw UsageError(fmt::format("--fmu exports the forward dynamics; drop {}",
                                 opt.jacobian ? "--jacobian" : "--form manipulator"));
  if (fs::path(opt.fmu).extension() != ".fmu")
    throw UsageError(fmt::format("--fmu {}: expected a file name ending in .fmu", opt.fmu));
  if (!opt.c_dir.empty() && fs::path(opt.c_dir) == fs::path(opt.fmu))
    throw UsageError("--c and --fmu name the same path");
}

}  // namespace

int run_export(const Options& opt) {
  check_export_outputs(opt);
  const Model model = read_model_file(opt.model);
  if (opt.form == "manipulator") {
    if (opt.dynamics == "recursive")
      throw UsageError(
          "export --form manipulator: D, C and g come from the Lagrangian form; drop "
          "--dynamics recursive");
    export_manipulator_c(derive(model), opt.c_dir);
    fmt::print("wrote {0}/lagrange_manipulator.h, {0}/lagrange_manipulator.c and {0}/main.c\n",
               opt.c_dir);
    return 0;
  }
  if (opt.jacobian) {
    if (opt.dynamics == "recursive")
      throw UsageError(
          "export --jacobian: the derivatives come from the Lagrangian form; drop --dynamics "
          "recursive");
    const Equations eq = derive(model, Formulation::Lagrangian);
    const auto cm = compile(eq);
    const DynamicsJacobian jac(eq, cm, cm->input_names);
    export_c_jacobian(jac, opt.c_dir);
    fmt::print(
        "wrote {0}/lagrange_model.h, {0}/lagrange_model.c, {0}/lagrange_jacobian.h and "
        "{0}/lagrange_jacobian.c ({1} + {2} tape instructions, lagrangian, {3} derivative "
        "entries)\n",
        opt.c_dir, cm->dynamics.num_instructions(), jac.tape().num_instructions(), jac.nonzeros());
    return 0;
  }
  const Formulation form = formulation(model, opt.dynamics);
  const Equations eq = derive(model, form);
  const auto cm = compile(eq);
  if (!opt.c_dir.empty()) {
    export_c(*cm, opt.c_dir);
    fmt::print("wrote {0}/lagrange_model.h and {0}/lagrange_model.c ({1} tape instructions, {2})\n",
               opt.c_dir, cm->dynamics.num_instructions(),
               form == Formulation::Recursive ? "recursive" : "lagrangian");
  }
  if (!opt.fmu.empty()) write_fmu(model, eq, *cm, opt);
  return 0;
}

int run_check(const Options& opt) {
  // The formulation simulate takes (docs/theory.md §4.9): a joint tree is checked on its
  // articulated-body equations, which grow linearly with the links.
  const Prepared p = prepare(opt.model, opt.sets, opt.initial, "--initial", opt.dynamics);
  const CompiledModel& cm = *p.compiled;
  (void)sweep::study_metrics(*p.model, cm, {});  // `metrics:`, as simulate checks them (issue 37)
  // prepare() evaluated the dynamics at the initial state last; the recursive form never forms M.
  if (p.equations.recursive) require_positive_pivots(*p.model, p.equations, *p.dynamics);
  fmt::print("{}: {} coordinates, {} constraints, {} parameters, {} inputs — model ok\n",
             p.model->name, cm.nq, cm.m, cm.np, cm.k);
  for (size_t r = 0; r < cm.m; ++r)
    fmt::print("  constraint {:<16} C = {:+.3e}   Cdot = {:+.3e}\n", cm.constraint_names[r],
               p.initial.C0[r], p.initial.Cdot0[r]);
  if (!p.initial.was_consistent) {
    fmt::print("{}\n(simulate starts from this projected state)\n", p.initial.note());
    return 1;
  }
  if (cm.m > 0) fmt::print("initial state is consistent\n");
  fmt::print("mass matrix positive definite at the initial state\n");
  return 0;
}

int run_simulate(const Options& opt) {
  // Output locations are checked before the run, not found unwritable after it (issue 25).
  for (const auto& [path, option] : {std::pair{opt.csv, "-o"}, std::pair{opt.plot, "--plot"},
                                     std::pair{opt.report, "--report"}}) {
    if (path.empty()) continue;
    check_output(path, option);
    if (std::string(option) == "-o") check_output(path + ".json", option);
  }
  Prepared p = prepare(opt.model, opt.sets, opt.initial, "--initial", opt.dynamics);
  const Model& model = *p.model;
  const auto& cm = p.compiled;
  SimulationOptions so = simulation_options(model, opt);
  p.dynamics->set_baumgarte(baumgarte_rate(model.stabilization, so.integrator.method));
  const std::vector<std::string> plot_columns = checked_plot_columns(opt, *cm);
  // The model file's `metrics:`, checked before the run and printed with the summary.
  const std::vector<sweep::Metric> metrics = sweep::study_metrics(model, *cm, {});
  if (!opt.report.empty()) check_report(opt.report, model);
  if (!p.initial.was_consistent && !opt.quiet) fmt::print(stderr, "note: {}\n", p.initial.note());
  so.interrupt = opt.interrupt;
  so.progress = progress_line(opt, so.t_end);
  {
    // Ctrl-C while `--compile on` compiles stops the compiler, so that none is left running
    // with its source in the cache (issue 37 item 10); then the process ends with 130.
    const KeepWorkOnInterrupt keep;
    const auto interrupted = [&] { return opt.interrupt != nullptr && opt.interrupt->load(); };
    if (!choose_evaluation(*p.dynamics, opt.compile, interrupted) && !interrupted())
      fmt::print(stderr, "warning: machine code: {}; the tape interpreter runs instead\n",
                 p.dynamics->machine_code_error());
    if (interrupted()) {
      fmt::print(stderr, "\nlagrange: interrupted\n");
      return 130;
    }
  }
  // cvode:jacobian and auto integrate on the exact Jacobian, derived once per model; simulate()
  // builds it for its workspace (docs/theory.md §5.6).
  so.jacobian_source = jacobian_source(p, so.integrator.method);
  const KeepWorkOnInterrupt keep;  // from here Ctrl-C keeps the rows so far
  const auto t2 = Clock::now();
  Trajectory traj = simulate(*p.dynamics, so, p.q, p.v);
  const double t_sim = seconds_since(t2);
  if (so.progress) fmt::print(stderr, "\r{:60}\r", "");
  if (!opt.quiet)
    for (const auto& note : traj.notes) fmt::print(stderr, "note: {}\n", note);
  for (const auto& warning : traj.warnings) fmt::print(stderr, "warning: {}\n", warning);
  if (opt.compile == "auto" && !opt.quiet && !p.dynamics->machine_code_error().empty())
    fmt::print(stderr, "note: machine code: {}; the tape interpreter ran instead\n",
               p.dynamics->machine_code_error());

  if (!opt.csv.empty()) write_trajectory_csv(traj, opt.csv);
  if (!opt.plot.empty() && traj.rows() > 1)
    plot_trajectory(traj, plot_columns, opt.plot, model.name);
  // The summary comes before the report, whose equations section may take a while to build.
  if (!opt.quiet) {
    const size_t rows = traj.rows();
    fmt::print(
        "{}: {} coordinates, {} constraints, {} tape instructions (symbolic in the parameters)\n",
        model.name, cm->nq, cm->m, cm->dynamics.num_instructions());
    fmt::print(
        "  derive {:.3f} s, compile {:.3f} s, simulate {:.3f} s ({} steps, {} rhs evaluations, "
        "{})\n",
        p.derive_seconds, p.compile_seconds, t_sim, traj.stats.steps, traj.stats.rhs_evals,
        traj.stats.method.empty() ? so.integrator.method : traj.stats.method);
    fmt::print("  evaluation: {}{}\n", p.dynamics->evaluation_note(),
               p.equations.recursive ? ", recursive (articulated-body algorithm)" : "");
    if (rows > 0) {
      const double e0 = traj.at(0, "energy"), e1 = traj.at(rows - 1, "energy");
      // Relative to the starting energy, unless that is zero next to the energies exchanged
      // (|e0| <= 1e-9 max(|T| + |V|), e.g. a pendulum released at rest from V = 0): then the
      // quotient only measures rounding, and the absolute change is printed instead.
      const size_t kin = traj.column_index("kinetic"), pot = traj.column_index("potential");
      const size_t width = traj.columns.size();
      double exchanged = 0.0;
      for (size_t r = 0; r < rows; ++r)
        exchanged = std::max(
            exchanged, std::abs(traj.data[r * width + kin]) + std::abs(traj.data[r * width + pot]));
      const bool absolute = std::abs(e0) <= 1e-9 * exchanged;
      fmt::print(
          "  t = {:.6g} .. {:.6g}, {} samples; energy {:.10g} -> {:.10g} ({} change {:.2e})\n",
          traj.at(0, "t"), traj.at(rows - 1, "t"), rows, e0, e1, absolute ? "absolute" : "relative",
          absolute ? std::abs(e1 - e0) : std::abs(e1 - e0) / std::abs(e0));
      std::string last;
      const size_t shown = std::min<size_t>(cm->nq, 6);
      for (size_t i = 0; i < shown; ++i)
        last += fmt::format("{}{} = {:.6g}", i ? ", " : "", cm->coordinate_names[i],
                            traj.at(rows - 1, cm->coordinate_names[i]));
      if (shown < cm->nq) last += fmt::format(", … ({} more in the CSV)", cm->nq - shown);
      fmt::print("  final state: {}\n", last);
      std::string values;
      const sweep::RowAt row_at = sweep::rows_between_samples(*p.dynamics, so, traj);
      for (const sweep::Metric& m : metrics)
        values += fmt::format("{}{} = {:.10g}", values.empty() ? "" : ", ", m.name,
                              sweep::evaluate(m, traj, p.dynamics->parameters(), row_at));
      if (!values.empty()) fmt::print("  metrics: {}\n", values);
      if (!traj.stopped_by.empty()) {
        const StopSpec* fired = nullptr;
        for (const StopSpec& s : cm->stop_when)
          if (s.name == traj.stopped_by) fired = &s;
        fmt::print("  stopped at t = {:.10g}: stop_when '{}' ({}) became true\n", traj.stop_time,
                   traj.stopped_by, fired ? fired->text : "?");
      }
      if (cm->m > 0) {
        double worst = 0;
        for (size_t r = 0; r < rows; ++r)
          worst = std::max(worst, traj.at(r, "constraint_residual"));
        fmt::print("  max constraint residual {:.2e}\n", worst);
      }
    }
    if (!opt.csv.empty()) fmt::print("  wrote {} (+ .json status)\n", opt.csv);
    if (!opt.plot.empty()) fmt::print("  wrote {}\n", opt.plot);
  }
  if (!opt.report.empty() && traj.rows() > 0) {
    const ReportNotes notes = write_run_report(
        p, traj, traj.stats.method.empty() ? so.integrator.method : traj.stats.method, t_sim,
        opt.report);
    if (!opt.quiet) fmt::print("  wrote {}\n", opt.report);
    print_report_notes(notes, opt.report, opt.quiet);
  }
  if (traj.status == Trajectory::Status::Failed) {
    fmt::print(stderr, "lagrange: {}\n", traj.message);
    if (!opt.csv.empty())
      fmt::print(
          stderr,
          "lagrange: the trajectory up to t = {:.6g} was kept in {} (marked failed in {}.json)\n",
          traj.rows() ? traj.data[(traj.rows() - 1) * traj.columns.size()] : 0.0, opt.csv, opt.csv);
    return 3;
  }
  if (traj.status == Trajectory::Status::Interrupted) {
    fmt::print(stderr, "lagrange: {}; partial trajectory kept\n", traj.message);
    return 130;
  }
  return 0;
}

}  // namespace lagrange::cli

// `lagrange optimize MODEL [-o out.csv] [--report out.html] [--hessian H] [--intervals N] [--degree
// d] [--set …] [--verify] [--compile auto|on|off]
// [--ipopt KEY=VALUE …]` (docs/model-language.md, "Optimal control"; docs/theory.md §10).
// Exit codes: 0 optimal, 1 a mistake in the model file, 2 usage, 3 Ipopt failed or infeasible.

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <stdexcept>

#include "cli/commands.hpp"
#include "cli/optimize_options.hpp"
#include "cli/prepare.hpp"
#include "cli/report_command.hpp"
#include "lagrange/io.hpp"
#include "lagrange/optimize.hpp"

namespace lagrange::cli {

namespace {

// docs/theory.md §10, "Checks": H(T) − H(0) against each source's work, and what is left.
void print_energy_balance(const EnergyBalance& b) {
  if (!b.unsuitable.empty()) {
    fmt::print("  energy balance     not checked: {}\n", b.unsuitable);
    return;
  }
  fmt::print("  energy balance     H(T) - H(0) = {:.6g}, the work over [0, T]:\n", b.change);
  for (const auto& [name, work] : b.work)
    fmt::print("                     {:+.6g}  {}\n", work, name);
  fmt::print("                     residual {:.3g} ({:.2g} of the energy moved)\n", b.residual,
             b.relative_residual());
}

}  // namespace

int run_optimize(const Options& opt) {
  // Output locations are checked before the solve, not found unwritable after it (issue 37).
  for (const auto& [path, option] :
       {std::pair{opt.csv, "-o"},
        std::pair{opt.csv.empty() ? std::string() : opt.csv + ".json", "-o"},
        std::pair{opt.report, "--report"}})
    if (!path.empty()) check_output(path, option);
  Prepared p = prepare(opt.model, opt.sets, {}, "--initial", "lagrangian");
  if (!p.model->optimal_control)
    throw UsageError(
        fmt::format("{} has no optimal_control section (docs/model-language.md, "
                    "\"Optimal control\")",
                    opt.model));
  const OptimalControlSpec& spec = *p.model->optimal_control;
  if (!opt.report.empty()) check_report(opt.report, *p.model);
  OptimizeOptions o = optimize_options(opt);
  const SimulationOptions so = simulation_options(*p.model, RunSettings{});
  p.dynamics->set_baumgarte(baumgarte_rate(p.model->stabilization, so.integrator.method));
  if (!choose_evaluation(*p.dynamics, opt.compile, {}))
    fmt::print(stderr, "warning: machine code: {}; the tape interpreter runs instead\n",
               p.dynamics->machine_code_error());
  OptimizeResult r;
  try {
    r = optimize(p.equations, p.compiled, *p.dynamics, spec, p.q, p.v, o);
  } catch (const std::invalid_argument& e) {
    throw ModelError(spec.loc, e.what());
  }
  for (const std::string& w : r.warnings) fmt::print(stderr, "{}\n", w);
  if (!r.hessian_note.empty() && !opt.quiet) fmt::print(stderr, "note: {}\n", r.hessian_note);
  if (!opt.csv.empty()) write_trajectory_csv(r.trajectory, opt.csv);
  if (!opt.report.empty())
    print_report_notes(write_run_report(p, r.trajectory, "Radau IIA collocation (optimize)",
                                        r.setup_seconds + r.solve_seconds, opt.report),
                       opt.report, opt.quiet);
  if (!opt.quiet) {
    for (const StageResult& stage : r.stages)
      fmt::print("  stage {:<12} {} ({} iterations), objective {:.6g}{}, {:.2f} s\n", stage.name,
                 stage.status, stage.iterations, stage.objective,
                 stage.tracking > 0 ? fmt::format(", tracking {:.3g}", stage.tracking) : "",
                 stage.seconds);
    fmt::print("{}: {} ({} iterations)\n", p.model->name, r.status, r.iterations);
    fmt::print("  objective          {:.10g}\n", r.objective);
    fmt::print("  horizon            {:.10g}{}\n", r.horizon, spec.free_horizon ? " (free)" : "");
    fmt::print("  intervals, degree  {}, {} (Radau IIA), {} Hessian\n", r.intervals, r.degree,
               r.exact_hessian ? "exact" : "limited-memory");
    std::vector<std::string> polynomial;
    for (size_t c = 0; c < r.polynomial.size(); ++c)
      if (r.polynomial[c]) polynomial.push_back(r.control_names[c]);
    if (!polynomial.empty())
      fmt::print("  polynomial         {} (degree {} on each interval)\n",
                 fmt::join(polynomial, ", "), r.degree - 1);
    if (!r.active_bounds.empty())
      fmt::print("  active bounds      {}\n",
                 fmt::join(r.active_bounds, "\n                     "));
    print_energy_balance(r.energy_balance);
    fmt::print("  worst violation    {:.3g}{}\n", r.violation,
               r.worst_constraint.empty() ? "" : " (" + r.worst_constraint + ")");
    fmt::print(
        "  time               {:.3f} s set-up (derive, compile, transcribe), {:.3f} s "
        "solve ({:.4f} s in our functions)\n",
        p.derive_seconds + p.compile_seconds + r.setup_seconds, r.solve_seconds,
        r.function_seconds);
    if (!r.hessian_evaluation.empty())
      fmt::print("  hessian            {}\n", r.hessian_evaluation);
    fmt::print("  residual           {}\n", r.residual_evaluation);
  }
  if (opt.verify) {
    SimulationOptions tight = so;
    tight.integrator.rtol = 1e-10;
    tight.integrator.atol = 1e-12;
    const VerifyResult v = verify(*p.dynamics, spec, r, tight);
    if (!v.message.empty()) fmt::print("  verify             simulation failed: {}\n", v.message);
    fmt::print("  verify             final-state gap {:.3g}, largest gap at the mesh {:.3g}\n",
               v.final_gap, v.largest_gap);
  }
  if (!r.optimal) {
    fmt::print(stderr, "lagrange: optimize: {}; most violated: {} (by {:.3g})\n", r.status,
               r.worst_constraint.empty() ? "none" : r.worst_constraint, r.violation);
    return 3;
  }
  return 0;
}

}  // namespace lagrange::cli

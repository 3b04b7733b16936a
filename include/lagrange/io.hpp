#pragma once
// Output of results: trajectories (CSV + status sidecar), plots, equations, C source.

#include <string>
#include <vector>

#include "lagrange/compiled_model.hpp"
#include "lagrange/equations.hpp"
#include "lagrange/manipulator.hpp"
#include "lagrange/simulation.hpp"

namespace lagrange {

class DynamicsJacobian;  // lagrange/analysis.hpp

/// CSV with a header row and 17 significant digits, written to a temporary name and renamed
/// when complete; beside it `path.json` records status ("complete", "failed", "interrupted"),
/// the reason and run statistics.
void write_trajectory_csv(const Trajectory& traj, const std::string& path);

/// Image formats of plot_trajectory, chosen by the file's extension.
enum class PlotFormat { Svg, Png };
/// The format for `path` (.svg or .png, any case); std::invalid_argument otherwise.
PlotFormat plot_format(const std::string& path);
/// The gnuplot terminal that writes `format` (svg, pngcairo).
const char* gnuplot_terminal(PlotFormat format);
/// True when gnuplot runs and lists the terminal for `format` in `gnuplot -e "set terminal"`.
bool plot_format_available(PlotFormat format);
/// A plot of the chosen columns against t through gnuplot, SVG or PNG by the extension of
/// `path` (throws std::runtime_error when gnuplot is missing or fails).
void plot_trajectory(const Trajectory& traj, const std::vector<std::string>& columns,
                     const std::string& path, const std::string& title);
/// A plot of columns 1… of a row-major `table` against its column 0, points joined by lines,
/// SVG or PNG by the extension of `path`; a row whose value is not finite is left out of that
/// curve (a sweep's failed case). std::runtime_error when gnuplot is missing or fails.
void plot_columns(const std::vector<std::string>& names, const std::vector<double>& table,
                  const std::string& path, const std::string& title);

/// Expression-tree nodes up to which `derive` prints the equations in full (about 1 MB of text).
constexpr size_t kFullExpansionLimit = 100000;

/// Terms up to which Cramer's numerators and denominator may expand for `derive` to print the
/// solved accelerations (docs/theory.md §4.1); larger systems are shown as M and h + Q only.
constexpr size_t kSolvedAccelerationTerms = 2000;

/// Equations as human-readable text, LaTeX, or JSON (`format`: text | latex | json). Models
/// whose full expansion exceeds kFullExpansionLimit nodes are printed through the compiled
/// tape's named common subexpressions instead, unless `expand` is set.
std::string format_equations(const Equations& eq, const std::string& format, bool expand = false);

/// The recursive formulation (docs/theory.md §4.9) as text, LaTeX or JSON: every named
/// intermediate in evaluation order, then q̈ (`derive --form recursive`). format_equations of
/// such equations only says how they are computed.
std::string format_recursive(const Equations& eq, const std::string& format);

/// The manipulator form D, Christoffel symbols, C, g, τ (docs/theory.md §4.8) as text, LaTeX or
/// JSON (`format`: text | latex | json); through named common subexpressions when written out in
/// full it would exceed kFullExpansionLimit nodes, unless `expand` is set.
std::string format_manipulator(const ManipulatorForm& form, const std::string& format,
                               bool expand = false);

/// Standalone C99 source (header + implementation) evaluating the dynamics
/// a = f(t, q, v, u, p) with the KKT solve; files lagrange_model.h/.c written into `dir`.
void export_c(const CompiledModel& model, const std::string& dir);

/// export_c, and also the exact derivatives ∂a/∂q, ∂a/∂v, ∂a/∂u (u: the model's inputs) with
/// their CSC sparsity patterns, in lagrange_jacobian.h/.c (docs/theory.md §5.7). `jac` must
/// differentiate by the model's inputs in order and no outputs (std::invalid_argument).
void export_c_jacobian(const DynamicsJacobian& jac, const std::string& dir);

/// C99 of the manipulator form — D(q), C(q, q̇) q̇, g(q), inverse and forward dynamics — in
/// lagrange_manipulator.h/.c with an example main.c in `dir`. Throws std::invalid_argument for a
/// constrained model, free bodies, or D, C q̇, g depending on t or inputs.
void export_manipulator_c(const Equations& eq, const std::string& dir);

/// What `export --fmu` takes from the model besides its compiled form (docs/fmu.md).
struct FmuOptions {
  std::string fmi_type = "both";     ///< cs | me | both: the interfaces the FMU offers
  std::string model_name;            ///< modelName; its C identifier is the modelIdentifier
  double alpha = kDefaultBaumgarte;  ///< Baumgarte rate (the FMU parameter fmu.baumgarte_alpha)
  bool project = true;  ///< Co-Simulation keeps the constraints and rotations by projection
  double rtol = 1e-8, atol = 1e-10;         ///< fmi2DoStep's tolerances (fmu.rtol, fmu.atol)
  double t_end = 10.0, output_step = 0.01;  ///< the DefaultExperiment
  std::string equations;                    ///< documentation/equations.txt (derive's text)
  std::string compiler;  ///< empty: $LAGRANGE_CC, $CC or cc (lagrange/machine_code.hpp)
};

/// FmuOptions from a model file's settings: its name, `stabilization:` (α when set, else
/// kDefaultBaumgarte; projection) and `simulate:` (rtol, atol, t_end, output_step).
FmuOptions fmu_options(const Model& model);

/// An FMI 2.0 FMU at `path` (docs/fmu.md): modelDescription.xml, sources/ (export_c's C, the
/// FMU's C and the FMI headers), binaries/linux64/<id>.so compiled now by the system C compiler,
/// documentation/. std::invalid_argument for a bad fmi_type, std::runtime_error naming the cause
/// when the compiler fails; nothing is written at `path` then.
void export_fmu(const CompiledModel& model, const FmuOptions& options, const std::string& path);

/// Creates the directories above `path` that do not exist yet (std::runtime_error naming the
/// directory when that fails).
void create_parent_directories(const std::string& path);

/// Write `text` to `path` through a unique temporary file beside it, fsync and an atomic
/// rename, creating missing directories above it; errors name the file and errno's reason.
void write_file_atomically(const std::string& path, const std::string& text);

/// Publishes `text` at `path`, then `sidecar_text` at `path`.json, both as write_file_atomically;
/// the old sidecar is removed first, so a sidecar present always describes the file present.
void write_file_with_sidecar(const std::string& path, const std::string& text,
                             const std::string& sidecar_text);

/// Throws std::runtime_error (naming `path` and the reason) unless a new file can be created
/// at `path`: the check `simulate -o` makes before the run.
void check_writable(const std::string& path);

}  // namespace lagrange
